// The outputs shared by the editing commands: --out VOLUME, --mesh FILE, --png FILE.
#pragma once

#include "Arguments.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"

#include <map>
#include <string>

void WriteEditOutputs(const lvdif::DictionaryVolume& volume, const Arguments& args,
  const std::map<std::string, std::string>& metadata, lvdif::Interrupter& progress);
