// Commands on saved volumes: info, mesh, convert.
#include "Arguments.h"
#include "Commands.h"
#include "MeshOutput.h"
#include "ProgressBar.h"
#include "VolumeFiles.h"

#include "LVDIFFiles.h"

#include "lvdif/Error.h"
#include "lvdif/Memory.h"
#include "lvdif/VolumeFile.h"

#include "vtkPolyData.h"

#include <cstdio>
#include <string>

int CommandInfo(int argc, char** argv)
{
  Arguments args(argc, argv, 2, {}, { "header-only" });
  if (args.positional().size() != 1)
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, CommandUsage("info"));
  const std::string& path = args.positional()[0];
  const bool headerOnly = args.has("header-only");
  // another volume format is not "a damaged .lvdv" (it said "header: bad magic")
  const LVDIFFiles::Format* format = LVDIFFiles::Find(path, LVDIFFiles::Kind::Volume);
  if (format && format->extension != "lvdv")
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "info describes .lvdv files, '" + path + "' is a ." +
        format->extension + " file: convert it first (lvdif convert " + path + " OUT.lvdv)");
  CommandLineAccepted();
  lvdif::VolumeFileInfo info;
  try
  {
    // by default every stored chunk is checked as `lvdif mesh` would read it
    // (one chunk at a time, not the volume): a damaged file is never "fine"
    ProgressBar progress;
    info = headerOnly ? lvdif::readVolumeInfo(path) : lvdif::verifyVolume(path, progress);
  }
  catch (const lvdif::Error& e)
  {
    // the format's messages name the damaged part, not the file
    if (std::string(e.what()).find(path) != std::string::npos) throw;
    throw lvdif::Error(e.code(), "cannot read '" + path + "': " + e.what());
  }
  const auto& o = info.options;
  std::printf("file        %s (%s, format version %u)\n", args.positional()[0].c_str(),
    lvdif::formatBytes(info.fileBytes).c_str(), info.version);
  std::printf("dimensions  %lld x %lld x %lld, chunk edge %d, band %g\n", (long long)o.dims[0], (long long)o.dims[1],
    (long long)o.dims[2], o.chunkEdge, o.bandWidth);
  std::printf("origin      %g %g %g, spacing %g %g %g\n", o.origin[0], o.origin[1], o.origin[2], o.spacing[0],
    o.spacing[1], o.spacing[2]);
  std::printf("dictionary  Group A +-%g step %g, Group B step %g\n", o.dictionary.groupALimit, o.dictionary.stepA,
    o.dictionary.stepB);
  std::printf("chunks      %lld (%lld uniform), compressed payload %s\n", (long long)info.chunkCount,
    (long long)info.uniformChunks, lvdif::formatBytes(info.payloadBytes).c_str());
  std::printf("colours     %zu\n", info.colors.size());
  for (const auto& kv : info.metadata) std::printf("meta        %s = %s\n", kv.first.c_str(), kv.second.c_str());
  std::printf("checked     %s\n", headerOnly ? "header, dictionaries and chunk table only (--header-only)"
                                              : "every chunk's checksum and content");
  return 0;
}

int CommandMesh(int argc, char** argv)
{
  Arguments args(argc, argv, 2, { "png" });
  if (args.positional().size() != 2)
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, CommandUsage("mesh"));
  CheckMeshOutput(args.positional()[1]);
  if (args.has("png")) CheckPngOutput(args.get("png", ""));
  CommandLineAccepted();
  if (args.has("png")) RequireDisplay(args.get("png", ""));
  ProgressBar progress;
  auto volume = LoadAnyVolume(args.positional()[0], progress);
  vtkSmartPointer<vtkPolyData> mesh = MeshVolume(*volume, progress);
  WriteMesh(mesh, args.positional()[1]);
  if (args.has("png")) RenderPng(mesh, args.get("png", ""));
  std::printf("%lld triangles -> %s\n", (long long)mesh->GetNumberOfPolys(), args.positional()[1].c_str());
  return 0;
}

int CommandConvert(int argc, char** argv)
{
  Arguments args(argc, argv, 2, {});
  if (args.positional().size() != 2)
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, CommandUsage("convert"));
  CheckVolumeOutput(args.positional()[1]);
  CommandLineAccepted();
  // a .lvdv's dimensions from its header against the output's rule (.bv: cubic), before reading it whole
  // (a non-cubic volume to .bv was read, then refused by the writer)
  const std::string refused = VolumeOutputProblemForInput(args.positional()[1], args.positional()[0]);
  if (!refused.empty())
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, refused + " (the volume of " + args.positional()[0] + ")");
  ProgressBar progress;
  auto volume = LoadAnyVolume(args.positional()[0], progress);
  SaveAnyVolume(*volume, args.positional()[1], { { "converted_from", args.positional()[0] } }, progress);
  std::printf("%s -> %s\n", args.positional()[0].c_str(), args.positional()[1].c_str());
  return 0;
}
