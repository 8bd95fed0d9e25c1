// The outputs shared by the editing commands: --out VOLUME, --mesh FILE, --png FILE.
#pragma once

#include "Arguments.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"

#include <map>
#include <string>

/// --out, --mesh and --png checked before the work (extension, writable place).
void CheckEditOutputs(const Arguments& args);
/// The end of an editing command's check (CommandLineAccepted), then the X
/// display that --png needs, opened before the work.
void AcceptEditCommandLine(const Arguments& args);
void WriteEditOutputs(const lvdif::DictionaryVolume& volume, const Arguments& args,
  const std::map<std::string, std::string>& metadata, lvdif::Interrupter& progress);
