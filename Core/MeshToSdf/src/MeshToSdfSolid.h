// Whether a prepared mesh is the boundary of a solid, as the pseudo-normal
// sign's theorem needs it: then that sign equals the winding number's, and
// a PseudoNormal call takes the faster winding path (MeshToSdf.cpp).
//
// Baerentzen and Aanaes (IEEE TVCG 11(3), 2005) prove that the sign of
// (p - c) . n, n the angle-weighted pseudo-normal of the feature holding the
// closest point c, is the inside/outside of p for a closed, orientable
// 2-manifold without self-intersections. For such a mesh whose winding
// number is 0 or 1 everywhere, "inside" is winding >= 1/2: the two signs are
// one function. The check is conservative: whatever it cannot prove (within
// its rounding allowance) makes it false, and the call keeps the pseudo-normal
// path (docs/MESH_TO_SDF.md, "Pseudo-normal signs of solids").
#pragma once

#include "MeshToSdfInternal.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf
{

/// The connected parts of a mesh: each welded vertex's part (parts faces
/// joined by welded vertices), numbered 0..count-1 in vertex order; unused
/// vertices get NoPart.
struct MeshParts
{
  static constexpr std::uint32_t NoPart = 0xffffffffu;
  std::vector<std::uint32_t> partOfVertex;
  std::uint32_t count = 0;
};

struct SolidBoundary
{
  bool solid = false;
  std::string why; // what failed (for --trace), empty when solid
  /// Closed, manifold, embedded parts whose faces point into the solid
  /// (winding number -1 behind them, 0 in front): for the normal and
  /// pseudo-normal signs' warning. Counted only when steps 1 and 2 pass.
  std::size_t inwardParts = 0;
  std::size_t parts = 0;
};

/// The mesh is a solid's boundary when, over its non-degenerate triangles:
/// 1. every edge has exactly two faces running it in opposite directions
///    (closed, consistently oriented) and every vertex's faces form one fan
///    (a 2-manifold);
/// 2. no two triangles meet except at the vertices and edges they share
///    (embedded; pairs closer than the rounding allowance count as meeting);
/// 3. on the front side of every part the winding number of the whole mesh
///    is 0 (by a ray's signed crossings; then it is 0 or 1 everywhere: outer
///    shells face out, cavities in).
/// bvh: the mesh's tree over mesh.tris.
SolidBoundary checkSolidBoundary(const PreparedMesh& mesh, const Bvh& bvh, const MeshParts& parts);

} // namespace detail::meshtosdf
} // namespace lvdif
