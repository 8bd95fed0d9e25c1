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

/// Largest |world coordinate| of any mesh point or voxel: meshes have float
/// vertices and volumes derive positions from origin + index x spacing, so
/// every position stays far inside float range (3.4e38): a mesh at 3e38 was
/// read and then failed as "volume origin ... on axis x" when its grid was fitted.
constexpr double MaxWorldCoordinate = 1e30;
/// The one per-coordinate rule of meshes: finite and within +-MaxWorldCoordinate
/// as a float (a file's "1e30" reads as 1.00000002e30 and passes).
inline bool isWorldCoordinate(float c)
{
  constexpr float limit = static_cast<float>(MaxWorldCoordinate);
  return c >= -limit && c <= limit; // false for NaN and infinities
}

struct TriangleMesh
{
  std::vector<Vec3f> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<Vec3f> normals; // empty, or one per point

  /// Throws Error(InvalidArgument) naming the first problem: no triangles,
  /// an index out of range, a NaN or infinite coordinate, coordinates beyond
  /// +-MaxWorldCoordinate (the message gives the mesh's bounds), normals of the wrong count.
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
