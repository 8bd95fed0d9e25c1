// `lvdif demo`: the README's main job on an embedded default. Builds a
// coloured volume, meshes it with the chunked marching cubes, writes the
// mesh and a PNG, and prints a summary.
#include "Arguments.h"
#include "Commands.h"
#include "DemoScene.h"
#include "MeshOutput.h"
#include "ProgressBar.h"
#include "VolumeFiles.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include "vtkPolyData.h"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <cstdio>
#include <sys/stat.h>
#include <unistd.h>

int CommandDemo(int argc, char** argv)
{
  Arguments args(argc, argv, 2, { "out", "size" });
  const std::string out = args.get("out", "out");
  // before the output folder is made
  const long size = args.getCanvasSize("size", 128);
  RequireChunkTable({ size, size, size }, "--size " + std::to_string(size) + " makes a canvas", "use a smaller --size");
  // a folder this command makes is removed again if the command then fails
  // (e.g. a --size over the memory limit, found only by the build)
  const bool made = ::mkdir(out.c_str(), 0755) == 0;
  // why the folder is unusable, in its own words (a failed mkdir was swallowed:
  // --out /proc/x said "the folder '/proc/x' does not exist", --out FILE named FILE/demo.ply)
  struct stat st;
  if (!made && errno != EEXIST)
    throw lvdif::Error(lvdif::ErrorCode::IoFailure, "cannot create the output folder '" + out + "': " + std::strerror(errno));
  if (!made && (::stat(out.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)))
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "--out '" + out + "' exists and is not a folder");
  CommandLineAccepted();
  const std::string plyPath = out + "/demo.ply", pngPath = out + "/demo.png", volumePath = out + "/demo.lvdv";
  DemoResult demo;
  vtkSmartPointer<vtkPolyData> mesh;
  double tBuild = 0, tMesh = 0;
  ProgressBar progress;
  const auto t0 = std::chrono::steady_clock::now();
  auto seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  try
  {
    CheckMeshOutput(plyPath);
    CheckPngOutput(pngPath);
    RequireDisplay(pngPath);
    demo = BuildDemoVolume(size, out, progress);
    tBuild = seconds();
    mesh = MeshVolume(*demo.volume, progress);
    tMesh = seconds() - tBuild;
    WriteMesh(mesh, plyPath);
    RenderPng(mesh, pngPath);
  }
  catch (...)
  {
    if (made)
    {
      // only the files this command writes (each saved atomically: none is partial); a
      // folder someone else filled meanwhile is not emptied (rmdir fails on it)
      for (const std::string& f : { volumePath, plyPath, pngPath }) ::unlink(f.c_str());
      ::rmdir(out.c_str());
    }
    throw;
  }

  const auto& d = demo.volume->dims();
  std::printf("LVDIF demo\n");
  std::printf("  source      %s\n", demo.source.c_str());
  std::printf("  volume      %lld x %lld x %lld voxels, chunk %d, band %.1f\n", (long long)d[0], (long long)d[1],
    (long long)d[2], demo.volume->chunkEdge(), demo.volume->bandWidth());
  std::printf("  memory      %s (%lld of %lld chunks expanded; dense would be %s)\n",
    lvdif::formatBytes(demo.volume->memoryBytes()).c_str(), (long long)demo.volume->expandedChunkCount(),
    (long long)demo.volume->chunkCount(), lvdif::formatBytes(4ull * demo.volume->voxelCount()).c_str());
  std::printf("  colours     %zu in the dictionary\n", demo.volume->colors().size());
  if (!demo.savedPath.empty()) std::printf("  saved       %s\n", demo.savedPath.c_str());
  std::printf("  mesh        %lld triangles, %lld points -> %s\n", (long long)mesh->GetNumberOfPolys(),
    (long long)mesh->GetNumberOfPoints(), plyPath.c_str());
  std::printf("  picture     %s\n", pngPath.c_str());
  std::printf("  time        build %.2f s, mesh %.2f s, total %.2f s\n", tBuild, tMesh, seconds());
  return 0;
}
