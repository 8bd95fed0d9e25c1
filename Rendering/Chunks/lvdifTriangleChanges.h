// The triangles by which two meshes differ, for vtkChunkActorManager's changed
// boxes and points (vtkPartialRedrawCuller). Not a VTK class: a private header
// of the module.
#pragma once

#include "vtkType.h"

#include <cstdint>
#include <utility>
#include <vector>

class vtkPolyData;

namespace lvdif
{
namespace render
{

/// A mesh's triangle hashes with their triangles' indices, sorted by hash.
using SortedTriangleHashes = std::vector<std::pair<std::uint64_t, vtkIdType>>;

/// Per triangle: a hash of its three points (position and point arrays, the
/// cyclic order kept, starting at the smallest) and its cell arrays; false if
/// the mesh holds other cells.
bool triangleHashes(vtkPolyData* pd, std::vector<std::uint64_t>& out);

/// triangleHashes' list sorted, each with its triangle's index.
SortedTriangleHashes sortedWithIndex(const std::vector<std::uint64_t>& order);

/// The box of the triangles of either mesh whose hash count differs between
/// them (sb, sa: sortedWithIndex of each mesh's triangleHashes), and, if
/// points is given, those triangles' points (x, y, z); false if none differ.
bool changedBoundsOf(vtkPolyData* before, const SortedTriangleHashes& sb, vtkPolyData* after,
  const SortedTriangleHashes& sa, double bounds[6], std::vector<double>* points = nullptr);

/// Whether two meshes are equal value for value: points, every point and
/// cell array (names, types, attribute roles, bytes), and every cell array's
/// offsets and connectivity; no field data. False whenever it cannot tell
/// cheaply (an array without the standard memory layout, different storage
/// types): a conservative test, never true for meshes that draw differently.
bool sameMesh(vtkPolyData* a, vtkPolyData* b);

/// The union of both meshes' bounds (either may be null or empty); false if both are empty.
bool unionBounds(vtkPolyData* before, vtkPolyData* after, double bounds[6]);

} // namespace render
} // namespace lvdif
