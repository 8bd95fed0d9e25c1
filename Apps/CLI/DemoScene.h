// The demo's volume: built from the embedded example, saved when the file
// format is available.
#pragma once

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"

#include <memory>
#include <string>

struct DemoResult
{
  std::unique_ptr<lvdif::DictionaryVolume> volume;
  std::string source;    // what it was built from
  std::string savedPath; // empty if not saved
};

DemoResult BuildDemoVolume(long size, const std::string& outDir, lvdif::Interrupter& progress);
