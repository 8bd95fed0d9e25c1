// Loading and saving volumes by file extension for the CLI:
// .lvdv (the dictionary volume format) and .bv (the original LVDIF's raw files).
#pragma once

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"

#include <map>
#include <memory>
#include <string>

std::unique_ptr<lvdif::DictionaryVolume> LoadAnyVolume(const std::string& path, lvdif::Interrupter& progress);
/// A known volume extension and a writable place, checked before the work.
void CheckVolumeOutput(const std::string& path);
void SaveAnyVolume(const lvdif::DictionaryVolume& volume, const std::string& path,
  const std::map<std::string, std::string>& metadata, lvdif::Interrupter& progress);
std::string Extension(const std::string& path);
