// Loading and saving volumes for the CLI: by extension through the one file
// registry (IO/Files/LVDIFFiles.h), shared with the editor and checked
// against the ParaView plugin.
#pragma once

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"

#include <map>
#include <memory>
#include <string>

std::shared_ptr<lvdif::DictionaryVolume> LoadAnyVolume(const std::string& path, lvdif::Interrupter& progress);
void SaveAnyVolume(const lvdif::DictionaryVolume& volume, const std::string& path,
  const std::map<std::string, std::string>& metadata, lvdif::Interrupter& progress);
std::string Extension(const std::string& path);
