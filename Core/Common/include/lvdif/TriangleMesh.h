// A triangle mesh as the core consumes it: shared points, index triples and
// optional per-point normals. Readers (IO/) and the VTK layer (which
// triangulates polygons) produce it; mesh-to-SDF and the tests consume it.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace lvdif
{

using Vec3f = std::array<float, 3>;

struct TriangleMesh
{
  std::vector<Vec3f> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<Vec3f> normals; // empty, or one per point

  /// Throws Error(InvalidArgument) naming the first problem: no triangles,
  /// an index out of range, a NaN or infinite coordinate, normals of the wrong count.
  void validate() const;
  /// Axis-aligned bounds {min, max}; requires at least one point.
  std::array<Vec3f, 2> bounds() const;
  /// Number of triangles with (numerically) zero area.
  std::size_t degenerateCount() const;
};

/// A closed UV sphere (for tests and demos), outward-facing, counter-clockwise.
TriangleMesh makeSphereMesh(float cx, float cy, float cz, float radius, int rings = 32, int segments = 64);
/// A closed axis-aligned box made of 12 triangles, outward-facing.
TriangleMesh makeBoxMesh(Vec3f lo, Vec3f hi);

} // namespace lvdif
