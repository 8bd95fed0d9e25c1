// Commands that edit: script (run a .lvs program) and play (replay a recording).
#include "Arguments.h"
#include "Commands.h"
#include "EditOutputs.h"
#include "ProgressBar.h"
#include "VolumeFiles.h"

#include "lvdif/Editor.h"
#include "lvdif/Error.h"
#include "lvdif/Recording.h"
#include "lvdif/Script.h"
#include "lvdif/StarterCanvas.h"

#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

int CommandScript(int argc, char** argv)
{
  Arguments args(argc, argv, 2, { "in", "out", "mesh", "png", "size", "max-steps" });
  if (args.positional().size() != 1)
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, CommandUsage("script"));
  const std::string path = args.positional()[0];
  // --size is the empty start canvas's: with --in the volume is the start (it
  // was ignored without a word)
  if (args.has("in") && args.has("size"))
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
      "--size (the size of an empty start canvas) cannot be used with --in (the script starts from that volume)");
  // the start canvas's size is refused before any output is checked or volume built
  const lvdif::Index3 size = args.has("in") ? lvdif::Index3{ 0, 0, 0 } : args.getCanvasDims("size", 128);
  // its chunk table against the memory limit, as a refused command line naming the option (--size 1048576
  // was the volume's "chunk table of a ... volume needs 768.00 TiB ...", status 1)
  if (!args.has("in"))
    RequireChunkTable(size, "--size " + args.get("size", "128") + " makes a canvas", "use a smaller --size");
  // a long script that is no endless loop (a loop over every voxel of 512^3 is 134M steps) could not run
  const long maxSteps = args.getInt("max-steps", static_cast<long>(lvdif::ScriptOptions().maxSteps), 1,
    std::numeric_limits<long>::max());
  CheckEditOutputs(args);
  AcceptEditCommandLine(args);
  ProgressBar progress;
  lvdif::ScriptOptions options;
  options.interrupter = &progress;
  options.maxSteps = static_cast<std::uint64_t>(maxSteps);
  options.maxStepsRaisedBy = "--max-steps N";
  // --size and a script's `canvas N` both size the canvas: refused, not "the script wins" (--size was ignored)
  if (args.has("size")) options.canvasSizeGivenBy = "--size " + args.get("size", "");
  // the output's rule on the result's dimensions, before the script runs (a .bv of a
  // non-cubic canvas failed only when saving, after the whole script)
  if (args.has("out"))
    options.resultRule = [out = args.get("out", "")](const lvdif::Index3& dims, const std::array<double, 3>& spacing) {
      return VolumeOutputDimsProblem(out, dims, spacing.data());
    };
  // file:line:column, the way compilers report, so editors can jump to it
  auto atScriptLine = [&](auto&& work) {
    try
    {
      work();
    }
    catch (const lvdif::ScriptError& e)
    {
      throw lvdif::Error(e.code(), path + ":" + std::to_string(e.line()) + ":" + std::to_string(e.column()) + ": " + e.detail());
    }
  };
  // the (small) script is read and its syntax checked before the (possibly large) volume is
  // loaded, as play reads its recording first (a missing script or a typo in it was found
  // only after --in was read)
  const std::string text = lvdif::readScriptFile(path);
  try
  {
    atScriptLine([&] { lvdif::checkScript(text); });
  }
  catch (const lvdif::Error& e)
  {
    // a recording given to script: said so (it was "unknown command 'LVDIF'")
    const std::size_t b = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
    if (text.compare(b, 15, "LVDIF-RECORDING") != 0)
      throw;
    throw lvdif::Error(e.code(), std::string(e.what()) + " (this is a recording: replay it with lvdif play " + path +
        ", on the canvas it names or with --in VOLUME)");
  }
  lvdif::ScriptRunner runner(options);
  std::shared_ptr<lvdif::DictionaryVolume> start;
  if (args.has("in"))
  {
    start = LoadAnyVolume(args.get("in", ""), progress);
  }
  else
  {
    // scripts without `canvas` edit an empty canvas of --size (default 128)
    lvdif::VolumeOptions o;
    o.dims = size;
    start = std::make_unique<lvdif::DictionaryVolume>(o);
  }
  runner.attach(*start);
  atScriptLine([&] { runner.run(text); });
  std::unique_ptr<lvdif::DictionaryVolume> made = runner.takeVolume();
  const lvdif::DictionaryVolume& result = made ? *made : *start;
  std::printf("%s: %llu edits, %llu steps\n", path.c_str(), (unsigned long long)runner.edits(),
    (unsigned long long)runner.steps());
  // as play's: a run without an output keeps nothing, said once (it was silent)
  if (!args.has("out") && !args.has("mesh") && !args.has("png"))
    std::fprintf(stderr, "warning: nothing written (no --out, --mesh or --png): the script's edits are not kept\n");
  WriteEditOutputs(result, args, { { "script", path } }, progress);
  return 0;
}

int CommandPlay(int argc, char** argv)
{
  Arguments args(argc, argv, 2, { "in", "out", "mesh", "png", "fill" });
  if (args.positional().size() != 1)
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, CommandUsage("play"));
  // without --in the recording plays on its own canvas, new as the editor makes it (`lvdif-editor
  // --script R.lvr` without --new or --open): a recording made on the editor's starter canvas
  // could not be replayed here at all (--in was required and nothing made that canvas)
  const bool ownCanvas = !args.has("in");
  if (args.has("fill") && !ownCanvas)
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
      "--fill fills the recording's own canvas (without --in): not with --in (the replay starts from that volume)");
  const lvdif::CanvasFill fill = lvdif::canvasFillFromName(args.get("fill", "sphere"), "--fill");
  CheckEditOutputs(args);
  AcceptEditCommandLine(args);
  ProgressBar progress;
  const std::string& path = args.positional()[0];
  // the (small) recording is read and checked before the (possibly large) volume is loaded
  const lvdif::Recording recording = [&] {
    try
    {
      return lvdif::loadRecording(path);
    }
    catch (const lvdif::Error& e)
    {
      // a script given to play: said so (it was only "expected the version line")
      const bool script = path.size() > 4 && path.compare(path.size() - 4, 4, ".lvs") == 0;
      if (!script || std::string(e.what()).find(": expected the version line") == std::string::npos)
        throw;
      throw lvdif::Error(e.code(), std::string(e.what()) + " (this is a script: run it with lvdif script " + path + ")");
    }
  }();
  if (!recording.warning.empty()) // a version 1 recording: no end record to tell a cut one
    std::fprintf(stderr, "warning: %s\n", recording.warning.c_str());
  std::shared_ptr<lvdif::DictionaryVolume> volume;
  std::string startName;
  if (ownCanvas)
  {
    const lvdif::Index3& c = recording.canvas;
    if (c[0] == 0)
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, path + " does not say the canvas it was made on (no "
          "'canvas' line: an old recording or an imported CSV): give the volume to play it on with --in VOLUME");
    const std::string problem = lvdif::DictionaryVolume::checkCanvasDimensions(c);
    if (!problem.empty())
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, path + ": its canvas: " + problem);
    RequireChunkTable(c, path + "'s canvas", "nothing was played");
    startName = "its own " + std::to_string(c[0]) + " x " + std::to_string(c[1]) + " x " + std::to_string(c[2]) +
      " canvas (--fill " + args.get("fill", "sphere") + ")";
    // the output's rule on the dimensions before the canvas is made and played
    const std::string refused = args.has("out") ? VolumeOutputDimsProblem(args.get("out", ""), c) : std::string();
    if (!refused.empty())
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, refused + " (the recording's canvas)");
    // the starter shape it was made on, by its version, as the editor's (a version 2 recording of a
    // non-cubic canvas cannot say which: refused, nothing played)
    volume = lvdif::makeCanvas(c, fill == lvdif::CanvasFill::Sphere ? lvdif::recordedStarter(recording, c, "--in VOLUME") : fill);
  }
  else
  {
    startName = args.get("in", "");
    // a replay keeps the dimensions: the output's rule on them before replaying, from a .lvdv's
    // header before loading it
    std::string refused = args.has("out") ? VolumeOutputProblemForInput(args.get("out", ""), args.get("in", "")) : std::string();
    if (!refused.empty())
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, refused + " (the volume of --in)");
    volume = LoadAnyVolume(args.get("in", ""), progress);
    refused = args.has("out")
      ? VolumeOutputDimsProblem(args.get("out", ""), volume->dims(), volume->options().spacing.data())
      : std::string();
    if (!refused.empty())
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, refused + " (the volume of --in)");
  }
  lvdif::Editor editor(*volume);
  editor.play(recording, progress);
  // a replay said nothing at all, and without an output it keeps nothing: both said
  std::printf("%s: %zu records replayed on %s\n", path.c_str(), recording.records.size(), startName.c_str());
  if (!args.has("out") && !args.has("mesh") && !args.has("png"))
    std::fprintf(stderr, "warning: nothing written (no --out, --mesh or --png): the replay only checked the recording\n");
  WriteEditOutputs(*volume, args, { { "recording", path } }, progress);
  return 0;
}
