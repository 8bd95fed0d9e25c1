#include "DemoScene.h"

#include "DemoScript.h"
#include "VolumeFiles.h"

#include "lvdif/Error.h"
#include "lvdif/Script.h"

#include <regex>

DemoResult BuildDemoVolume(long size, const std::string& outDir, lvdif::Interrupter& progress)
{
  // The dice script (paper Fig. 9b) sizes everything from `n = 128`; the
  // demo's --size replaces that first assignment.
  const std::string script =
    std::regex_replace(DemoScript, std::regex("^n = [0-9]+", std::regex::multiline), "n = " + std::to_string(size),
      std::regex_constants::format_first_only);
  lvdif::ScriptOptions options;
  options.interrupter = &progress;
  lvdif::ScriptRunner runner(options);
  try
  {
    runner.run(script);
  }
  catch (const lvdif::ScriptError& e)
  {
    // the embedded script's line and column mean nothing to the user: name the option
    if (e.code() == lvdif::ErrorCode::Cancelled) throw;
    throw lvdif::Error(e.code(), "--size " + std::to_string(size) + ": " + e.detail());
  }
  DemoResult r;
  r.volume = runner.takeVolume();
  if (!r.volume)
  {
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "the embedded demo script made no canvas");
  }
  r.source = "embedded script Data/scripts/dice.lvs (n = " + std::to_string(size) + ", " +
    std::to_string(runner.edits()) + " edits)";
  r.savedPath = outDir + "/demo.lvdv";
  SaveAnyVolume(*r.volume, r.savedPath, { { "name", "LVDIF demo dice" }, { "script", "Data/scripts/dice.lvs" } },
    progress);
  return r;
}
