// Mesh to SDF helpers without the engine: the fitted grid and the names of
// the modes (moved out of MeshToSdf.cpp to keep it small).
#include "lvdif/MeshToSdf.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace lvdif
{

GridGeometry fitGridToMesh(const TriangleMesh& mesh, std::int64_t maxDim, double paddingVoxels)
{
  mesh.validate();
  require(maxDim >= 2 && maxDim <= DictionaryVolume::MaxDimension,
    "fit grid: maximum dimension " + std::to_string(maxDim) + " out of range [2, " +
      std::to_string(DictionaryVolume::MaxDimension) + "]");
  require(std::isfinite(paddingVoxels) && paddingVoxels >= 0, "fit grid: padding must be finite and >= 0");
  require(static_cast<double>(maxDim) - 1 - 2 * paddingVoxels >= 1,
    "fit grid: padding leaves no voxel for the mesh (maxDim - 1 - 2 * padding < 1)");
  const auto b = mesh.bounds();
  double ext[3], longest = 0;
  int axis = 0;
  for (int a = 0; a < 3; ++a)
  {
    ext[a] = static_cast<double>(b[1][a]) - b[0][a];
    if (ext[a] > longest)
    {
      longest = ext[a];
      axis = a;
    }
  }
  require(longest > 0, "fit grid: the mesh bounds have zero size");
  const double h = longest / (static_cast<double>(maxDim) - 1 - 2 * paddingVoxels);
  GridGeometry g;
  for (int a = 0; a < 3; ++a)
  {
    // at least one cell on every axis (a flat mesh without padding got 1
    // point: a volume nothing meshes, not even the unsigned shell of a sheet)
    g.dims[a] = a == axis ? maxDim : std::clamp<std::int64_t>(
      static_cast<std::int64_t>(std::ceil(ext[a] / h + 2 * paddingVoxels - 1e-9)) + 1,
      DictionaryVolume::MinCanvasDimension, maxDim);
    g.spacing[a] = h;
    const double centre = 0.5 * (static_cast<double>(b[0][a]) + b[1][a]);
    g.origin[a] = centre - 0.5 * static_cast<double>(g.dims[a] - 1) * h;
  }
  return g;
}

const char* toString(SignMode mode)
{
  switch (mode)
  {
    case SignMode::Normal: return "normal";
    case SignMode::PseudoNormal: return "pseudonormal";
    case SignMode::WindingNumber: return "winding";
    case SignMode::Unsigned: return "unsigned";
  }
  return "?";
}

namespace
{
// both ways, so that a command line written from a mode (the CLI's "creation
// parameters") runs again
const std::pair<const char*, SignMode> SignNames[] = { { "normal", SignMode::Normal },
  { "pseudo", SignMode::PseudoNormal }, { "winding", SignMode::WindingNumber } };
}

SignMode signModeFromName(const std::string& name, const std::string& option)
{
  for (const auto& n : SignNames)
    if (name == n.first)
      return n.second;
  throw Error(ErrorCode::InvalidArgument, option + " must be normal, pseudo or winding, not '" + name + "'");
}

const char* signModeName(SignMode mode)
{
  for (const auto& n : SignNames)
    if (mode == n.second)
      return n.first;
  return toString(mode);
}

const char* toString(MeshToSdfAccel accel)
{
  switch (accel)
  {
    case MeshToSdfAccel::Bvh: return "bvh";
    case MeshToSdfAccel::Faithful: return "faithful";
    case MeshToSdfAccel::BruteForce: return "bruteforce";
  }
  return "?";
}

} // namespace lvdif
