// The meshes of the far-block tests (CPU: TestMeshToSdfFarBlocks.cpp, CUDA:
// TestMeshToSdfCuda.cpp): clean, sharp, open, flipped, duplicated (some
// reversed), non-manifold, intersecting, a soup, and slivers.
#pragma once

#include "MeshToSdfOracle.h"
#include "lvdif/TriangleMesh.h"

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace farcases
{

struct Case
{
  std::string name;
  lvdif::TriangleMesh mesh;
};

inline std::vector<Case> meshes()
{
  using lvdif::TriangleMesh;
  std::vector<Case> cs;
  const TriangleMesh sphere = lvdif::makeSphereMesh(0.05f, -0.03f, 0.02f, 1.0f, 12, 24);
  cs.push_back({ "closed sphere", sphere });
  cs.push_back({ "closed box", lvdif::makeBoxMesh({ -0.9f, -0.7f, -0.8f }, { 0.8f, 0.9f, 0.6f }) });
  {
    TriangleMesh h = sphere; // holes: the polar cap and scattered faces
    std::vector<std::array<std::uint32_t, 3>> kept;
    for (std::size_t t = 0; t < h.triangles.size(); ++t)
      if (t >= 24 * 3 && t % 29 != 5) kept.push_back(h.triangles[t]);
    h.triangles = kept;
    cs.push_back({ "sphere with holes", h });
  }
  {
    TriangleMesh f = sphere;
    std::mt19937 rng(7);
    for (auto& t : f.triangles)
      if (rng() % 5 == 0) std::swap(t[1], t[2]); // ~20 % flipped
    cs.push_back({ "20% faces flipped", f });
  }
  {
    TriangleMesh d = sphere; // duplicates, every other one reversed (they cancel)
    for (std::size_t t = 0; t < sphere.triangles.size(); t += 3)
    {
      auto x = sphere.triangles[t];
      if (t % 2) std::swap(x[1], x[2]);
      d.triangles.push_back(x);
    }
    cs.push_back({ "duplicated faces, half reversed", d });
  }
  {
    // a box with a fin on one edge (three faces there) and a second box on that edge
    TriangleMesh m = lvdif::makeBoxMesh({ -0.8f, -0.7f, -0.6f }, { 0.3f, 0.4f, 0.5f });
    const std::uint32_t b = static_cast<std::uint32_t>(m.points.size());
    m.points.push_back({ 0.3f, 0.4f, -0.6f });
    m.points.push_back({ 0.3f, 0.4f, 0.5f });
    m.points.push_back({ 1.0f, 1.1f, 0.0f });
    m.triangles.push_back({ b, b + 1, b + 2 });
    cs.push_back({ "non-manifold boxes + fin",
      oracle::merge(m, lvdif::makeBoxMesh({ 0.3f, 0.4f, -0.6f }, { 1.1f, 1.0f, 0.5f })) });
  }
  cs.push_back({ "two intersecting spheres", oracle::merge(lvdif::makeSphereMesh(-0.35f, 0, 0, 0.8f, 8, 16),
                                               lvdif::makeSphereMesh(0.4f, 0.1f, 0.05f, 0.75f, 8, 16)) });
  cs.push_back({ "random soup", oracle::randomSoup(40, 5) });
  {
    // slivers (ill-shaped: the far test leaves boxes near them to the voxels)
    // beside a sphere, and a needle fan
    TriangleMesh m = lvdif::makeSphereMesh(-0.2f, 0.1f, 0, 0.7f, 10, 20);
    const std::uint32_t b = static_cast<std::uint32_t>(m.points.size());
    m.points.push_back({ 0.6f, -0.9f, 0.1f });
    m.points.push_back({ 1.2f, -0.9f, 0.1f });
    m.points.push_back({ 0.9f, -0.89999f, 0.1f });
    m.points.push_back({ 0.9f, -0.9f, 0.9f });
    m.points.push_back({ 0.90001f, -0.9f, -0.5f });
    m.triangles.push_back({ b, b + 1, b + 2 });
    m.triangles.push_back({ b + 3, b + 4, b + 1 });
    m.triangles.push_back({ b + 3, b + 1, b + 4 }); // the same sliver reversed
    cs.push_back({ "sphere + slivers", m });
  }
  return cs;
}

/// A dense mesh for coarse grids (19,600 triangles): a bumpy ellipsoid, so
/// that no point is equidistant from a whole ring of triangles (as a sphere's
/// centre is) and a query deep inside has one nearest region.
inline lvdif::TriangleMesh denseMesh()
{
  lvdif::TriangleMesh m = lvdif::makeSphereMesh(0, 0, 0, 1.0f, 70, 140);
  for (lvdif::Vec3f& v : m.points)
  {
    const float bump = 1.0f + 0.06f * std::sin(7.0f * v[0]) * std::cos(5.0f * v[1] + 1.0f);
    v = { 1.1f * bump * v[0] + 0.03f, 0.75f * bump * v[1] - 0.02f, 0.5f * bump * v[2] + 0.01f };
  }
  return m;
}

} // namespace farcases
