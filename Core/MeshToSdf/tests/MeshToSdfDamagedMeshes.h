// The damaged meshes of the winding-sign tests that compare the GPU's
// construction with the CPU's (TestMeshToSdfDipoleDecide.cpp on the CPU,
// TestMeshToSdfCuda.cpp on the GPU): a bumpy sphere (no symmetry that could
// hide an error) damaged by the benchmarks' seeded functions (one definition).
#pragma once

#include "../../../Testing/Benchmarks/Core/SignQualityMeshes.h"
#include "lvdif/TriangleMesh.h"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace oracle
{

/// A sphere with bumps, 40 x 80 (6k triangles).
inline lvdif::TriangleMesh bumpySphere()
{
  lvdif::TriangleMesh m = lvdif::makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 40, 80);
  for (auto& p : m.points)
  {
    const double x = p[0] - 0.05, y = p[1] + 0.03, z = p[2] - 0.02;
    const double s = 1 + 0.12 * std::sin(3 * x + 1) * std::cos(2 * y) + 0.08 * std::sin(4 * z);
    p = { static_cast<float>(0.05 + s * x), static_cast<float>(-0.03 + s * y), static_cast<float>(0.02 + s * z) };
  }
  return m;
}

/// 10 % and 30 % reversed in patches, 10 % scattered, 20 % duplicated (half
/// reversed), 40 holes, 60 non-manifold fins, a self-intersecting pair,
/// patches with holes, scattered reversals with holes.
inline std::vector<std::pair<std::string, lvdif::TriangleMesh>> damagedMeshes()
{
  const lvdif::TriangleMesh m = bumpySphere();
  std::vector<std::pair<std::string, lvdif::TriangleMesh>> out;
  for (const char* d : { "patch10", "patch30", "flip10", "duprev20", "holes40", "fins60", "pair" })
    out.emplace_back(d, signquality::damaged(m, d));
  out.emplace_back("patch10+holes", signquality::damaged(signquality::damaged(m, "patch10"), "holes"));
  out.emplace_back("flip20+holes", signquality::damaged(signquality::damaged(m, "holes"), "flip20"));
  return out;
}

} // namespace oracle
