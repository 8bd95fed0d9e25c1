// lvdif mesh-to-sdf: a mesh file (OBJ, OFF, STL, PLY) to a volume file
// (.lvdv or the original's .bv) through Core's meshToSdf, written chunk slab
// by chunk slab straight into the dictionary volume (no full float grid).
#include "Arguments.h"
#include "Commands.h"
#include "ProgressBar.h"
#include "VolumeFiles.h"

#include "LVDIFVolumeBridge.h"

#include "lvdif/CNumbers.h"
#include "lvdif/Cuda.h"
#include "lvdif/Error.h"
#include "lvdif/MeshFile.h"
#include "lvdif/MeshToSdf.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

namespace
{
/// A number as the shortest text that reads back as the same double (std::to_string
/// rounds to 6 decimals: --padding 0.1234567 was recorded as 0.123457).
std::string exactNumber(double v)
{
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

lvdif::Device deviceFromName(const std::string& s)
{
  if (s == "cpu")
    return lvdif::Device::Cpu;
  if (s == "cuda")
    return lvdif::Device::Cuda;
  if (s == "auto")
    return lvdif::Device::Auto;
  throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "--device must be cpu, cuda or auto, not '" + s + "'");
}
} // namespace

int CommandMeshToSdf(int argc, char** argv)
{
  Arguments args(argc, argv, 2, { "dims", "padding", "sign", "band", "device" }, { "svf", "reorient" });
  if (args.positional().size() != 2)
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, CommandUsage("mesh-to-sdf"));
  const std::string in = args.positional()[0], out = args.positional()[1];
  // --dims 7x300x2 (script's --size, the editor's --new take NXxNYxNZ) was "expects an integer": say why one
  {
    const std::string v = args.get("dims", "");
    const auto x1 = v.find('x'), x2 = x1 == std::string::npos ? x1 : v.find('x', x1 + 1);
    if (x2 != std::string::npos && v.find('x', x2 + 1) == std::string::npos && x1 > 0 && x2 > x1 + 1 && x2 + 1 < v.size() &&
      v.find_first_not_of("0123456789x") == std::string::npos)
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "option --dims expects one integer, the voxels along the mesh's "
          "longest axis (the other axes follow the mesh's proportions), got '" + v + "'");
  }
  // every fitted grid's and canvas's range (lvdif-editor --mesh-resolution, --new, script --size, vtkMeshToSDF)
  const long dims =
    args.getInt("dims", 128, lvdif::DictionaryVolume::MinCanvasDimension, lvdif::DictionaryVolume::MaxDimension);
  // (more padding than voxels is refused below, naming both options)
  const double padding = args.getDouble("padding", 2.0, 0, double(lvdif::DictionaryVolume::MaxDimension));
  const double band = args.getDouble("band", 8.0); // its range: the filters' rule below
  if (static_cast<double>(dims) - 1.0 - 2.0 * padding < 1.0)
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "--dims " + std::to_string(dims) + " leaves no voxel for the mesh inside --padding " +
        args.get("padding", "2") + " on every side: use --dims of at least 2 x padding + 2, or less padding");
  // the filters' and writers' rule (0 = no band, negative or NaN refused), before the mesh is read
  const float bandWidth = LVDIFVolumeBridge::CheckVolumeSettings(lvdif::VolumeOptions().chunkEdge, band, "--band");
  lvdif::MeshToSdfOptions options;
  options.sign = lvdif::signModeFromName(args.get("sign", "winding"), "--sign");
  options.device = deviceFromName(args.get("device", "auto"));
  // winding sign of the consistently re-oriented mesh (unreliable face orientation)
  options.reorientFaces = args.has("reorient");
  if (options.reorientFaces && options.sign != lvdif::SignMode::WindingNumber)
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "--reorient needs --sign winding");
  if (args.has("svf"))
    options.svfFilters = lvdif::SvfAll; // SVF1..SVF4, the paper's cleanup (meant for --sign normal)

  // a grid's chunk table alone past the memory limit, named with --dims (it was the volume's own words,
  // "chunk table of a 1000000 x 1000000 x 1000000 volume needs 666.13 TiB ...", with no option to change)
  auto requireTable = [&](const lvdif::Index3& d, const std::string& whose) {
    RequireChunkTable(d, "--dims " + std::to_string(dims) + " makes " + whose, "use fewer --dims");
  };
  // a cubic-only format's grid is --dims on every axis, whatever the mesh: its rules (the N of an
  // SDF_<N>_ name) and its chunk table before the mesh is read, as a refused command line (the mesh
  // was read first, and the refusal said "the grid fitted to the mesh", status 1)
  if (VolumeOutputIsCubicOnly(out))
  {
    const std::string refused = VolumeOutputDimsProblem(out, { dims, dims, dims });
    if (!refused.empty())
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, refused + " (--dims " + std::to_string(dims) + " on every axis)");
    requireTable({ dims, dims, dims }, "the cubic grid");
  }
  CheckVolumeOutput(out);
  CommandLineAccepted();
  ProgressBar progress;
  const lvdif::TriangleMesh mesh = [&] {
    try
    {
      return lvdif::loadMesh(in);
    }
    catch (const lvdif::Error& e)
    {
      // the reader's message says where in the file; this says which file
      const std::string what = e.what();
      throw lvdif::Error(e.code(), what.rfind("cannot ", 0) == 0 ? what : "cannot read '" + in + "': " + what);
    }
  }();
  // errors about the mesh itself (zero-size bounds, no triangle of non-zero
  // area) say which file, as the reader's do
  auto namingTheMesh = [&](auto&& work) {
    try
    {
      return work();
    }
    catch (const lvdif::Error& e)
    {
      if (e.code() != lvdif::ErrorCode::InvalidArgument) throw;
      throw lvdif::Error(e.code(), "mesh '" + in + "': " + e.what());
    }
  };
  // a mesh of one point as read: its coordinates may differ in the file only beyond float's precision
  // (a unit cube at 1e29 was "fit grid: the mesh bounds have zero size")
  {
    const auto b = mesh.bounds();
    if (b[0] == b[1])
    {
      std::string p = "(";
      for (int a = 0; a < 3; ++a)
      {
        char c[40];
        lvdif::formatDoubleC(c, sizeof c, "%.9g", double(b[0][a]));
        p += std::string(a ? ", " : "") + c;
      }
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "mesh '" + in + "': all its " +
          std::to_string(mesh.points.size()) + " points are the one point " + p + ")" +
          " as read, so it has no size (coordinates are read as 32-bit floats, about 7 significant digits: "
          "points that differ only beyond that, such as 1e29 and 1e29 + 1, are one point)");
    }
  }
  // a format of cubic volumes only (.bv, the original's N^3): the fitted grid made cubic, --dims on
  // every axis around the same centre and voxels (every mesh but a cube's was refused, with no
  // option that could make its grid cubic)
  auto gridWith = [&](double pad) {
    lvdif::GridGeometry g = namingTheMesh([&] { return lvdif::fitGridToMesh(mesh, dims, pad); });
    if (VolumeOutputIsCubicOnly(out))
    {
      for (int a = 0; a < 3; ++a)
      {
        g.origin[a] -= 0.5 * static_cast<double>(dims - g.dims[a]) * g.spacing[a];
        g.dims[a] = dims;
      }
    }
    return g;
  };
  lvdif::GridGeometry grid = gridWith(padding);
  lvdif::VolumeOptions vo = lvdif::volumeOptionsOn(grid);
  vo.bandWidth = bandWidth;
  // a mesh inside the world range whose padded grid is not, or so small that its
  // voxels are below the smallest spacing: named with the options (the volume's
  // own words are about an origin the user never gave; a mesh 1e-30 across was
  // said to take the grid beyond +-1e+30)
  const double finest = std::min({ grid.spacing[0], grid.spacing[1], grid.spacing[2] });
  if (!(finest >= lvdif::DictionaryVolume::MinSpacing))
  {
    const auto b = mesh.bounds();
    double extent = 0;
    for (int a = 0; a < 3; ++a) extent = std::max(extent, double(b[1][a]) - double(b[0][a]));
    char e[40], sp[40], limit[40];
    lvdif::formatDoubleC(e, sizeof e, "%g", extent);
    lvdif::formatDoubleC(sp, sizeof sp, "%g", finest);
    lvdif::formatDoubleC(limit, sizeof limit, "%g", lvdif::DictionaryVolume::MinSpacing);
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, std::string("the mesh is ") + e + " across, so --dims " +
        std::to_string(dims) + " gives voxels of " + sp + ", below the volumes' smallest spacing of " + limit +
        ": scale the mesh up or use fewer --dims");
  }
  if (!lvdif::DictionaryVolume::checkGeometry(vo).empty())
  {
    const auto b = mesh.bounds();
    double reach = 0;
    for (int a = 0; a < 3; ++a) reach = std::max({ reach, std::fabs(double(b[0][a])), std::fabs(double(b[1][a])) });
    char r[40], limit[40];
    lvdif::formatDoubleC(r, sizeof r, "%g", reach);
    lvdif::formatDoubleC(limit, sizeof limit, "%g", lvdif::MaxWorldCoordinate);
    // less padding helps only where the grid without it fits (with --padding 0, or a mesh at the
    // world range's edge, "use less padding" was advice that could not work)
    const bool lessPaddingFits =
      padding > 0 && lvdif::DictionaryVolume::checkGeometry(lvdif::volumeOptionsOn(gridWith(0))).empty();
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, std::string("the mesh reaches ") + r + " and --padding " +
        args.get("padding", "2") + " around it takes the grid beyond +-" + limit + " (the volumes' world range): " +
        (lessPaddingFits ? "use less padding (--padding 0 fits) or scale the mesh down"
                         : "scale the mesh down (less padding cannot help: even --padding 0 takes the grid beyond it)"));
  }
  requireTable(grid.dims, "this mesh's grid");
  lvdif::DictionaryVolume volume(vo);
  const lvdif::MeshToSdfStats stats = namingTheMesh([&] { return lvdif::meshToSdf(mesh, volume, options, progress); });
  SaveAnyVolume(volume, out,
    { { "source mesh", in },
      { "creation parameters", "lvdif mesh-to-sdf --dims " + std::to_string(dims) + " --padding " +
          exactNumber(padding) + " --sign " + lvdif::signModeName(options.sign) + (args.has("svf") ? " --svf" : "") +
          (options.reorientFaces ? " --reorient" : "") + " --band " + exactNumber(band) } },
    progress);
  // what stats.boundaryEdges counts, in the warnings' words: the edges whose oriented uses do not cancel, which
  // are holes' rims and the edges of reversed or duplicated faces alike ("8 boundary edges" called a closed box
  // with two faces doubled open; the warnings then say which it is)
  std::printf("%zu triangles (%zu degenerate skipped, %zu edges of non-zero net multiplicity: holes' rims or the edges "
              "of reversed or duplicated faces) -> %lld x %lld x %lld voxels, sign %s, "
              "device %s, %lld sign flips by the filters -> %s\n",
    stats.triangles, stats.degenerateSkipped, stats.boundaryEdges, (long long)grid.dims[0], (long long)grid.dims[1],
    (long long)grid.dims[2], lvdif::signModeName(options.sign), lvdif::toString(stats.device), (long long)stats.svfFlips,
    out.c_str());
  for (const std::string& w : stats.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  return 0;
}
