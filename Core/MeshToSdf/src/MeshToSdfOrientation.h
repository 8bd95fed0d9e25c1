// Consistent re-orientation of a triangle soup for the winding-number sign
// (MeshToSdfWinding.cpp): M+ = M with a set F of faces reversed and a set R
// of duplicated faces removed, so that w_M = w_{M+} + 2 w_F + w_R, and the
// boundary chain of M+ (what still needs a cone to close it).
#pragma once

#include "MeshToSdfGeometry.h"

#include <array>
#include <cstdint>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf
{

struct Tri;

struct OrientedMesh
{
  enum State : std::uint8_t
  {
    Keep = 0,    // in M+ as it is
    Reverse = 1, // in M+ reversed: w_M = w_{M+} + 2 w_t
    Remove = 2   // not in M+ (an exact duplicate of another face): w_M = w_{M+} + w_t
  };
  /// Per triangle (index into the prepared triangles).
  std::vector<std::uint8_t> state;
  std::size_t flippedCount = 0;     // faces reversed
  std::size_t removedCount = 0;     // duplicate faces removed
  std::size_t opposedDuplicates = 0; // faces cancelled by a duplicate of opposite orientation (group size - |net|)
  std::size_t components = 0;       // connected over manifold edges
  std::size_t nonManifoldEdges = 0; // edges with 1 or more than 2 faces are not crossed by the BFS
  std::size_t conflicts = 0;        // manifold edges left inconsistent (non-orientable parts)
  /// The boundary chain of M+ as directed segments a -> b, repeated per unit
  /// of |net multiplicity|; sorted so the result does not depend on threads.
  std::vector<std::array<V3, 2>> boundary;
};

/// Faces with the same three vertices as another face are reduced first to
/// their net multiplicity (one face of the majority orientation; when they
/// cancel, one face all the same, oriented by the search below, so M+ has no
/// hole there); the others are removed. Then it orients every connected component (faces joined by edges with exactly two
/// faces) by a breadth-first search, keeps the orientation of the majority of
/// each component's faces, and lists the reversed minority F. Any choice of F
/// gives the same w_M: only the speed depends on F being small and M+ having
/// little boundary. Non-manifold edges are not crossed; a non-orientable
/// component keeps the first orientation the BFS reached (its conflicting
/// edges become boundary of M+, closed by the cone).
/// `welded`: per triangle, its corners' vertex ids welded by exact position
/// (PreparedMesh::welded). Sorts on OpenMP threads; the result does not
/// depend on the thread count.
OrientedMesh orientMesh(const TriList& tris, const LargeVector<std::array<std::uint32_t, 3>>& welded);

/// The faces keyed by their corner set, { sorted welded ids, face }, in sorted
/// order, so that exact duplicates (the same three corners) are adjacent; the
/// one grouping of duplicates (orientMesh, and the warnings' count). Sorts on
/// OpenMP threads; the order does not depend on the thread count.
std::vector<std::array<std::uint32_t, 4>> facesByCornerSet(const LargeVector<std::array<std::uint32_t, 3>>& welded);

/// +1 when `corners` (a face's welded ids) run the sorted ids of its key in
/// cyclic order (an even permutation), else -1: a duplicate's orientation.
inline int cornerParity(const std::array<std::uint32_t, 3>& corners, const std::array<std::uint32_t, 4>& key)
{
  const std::uint32_t a = corners[0], b = corners[1];
  return (a == key[0] && b == key[1]) || (a == key[1] && b == key[2]) || (a == key[2] && b == key[0]) ? 1 : -1;
}

} // namespace detail::meshtosdf
} // namespace lvdif
