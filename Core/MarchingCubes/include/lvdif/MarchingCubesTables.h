// The marching cubes case table (Lorensen & Cline, SIGGRAPH 1987), generated
// at first use from a documented rule instead of being typed in.
//
// Conventions (ours, used by every marching cubes path of the project):
// * Corner c of a cell sits at offset (c & 1, (c >> 1) & 1, (c >> 2) & 1).
// * Case index: bit c is set when corner c is "above": value >= iso. With the
//   project's negative-inside SDF, "above" means outside.
// * Edge e = 4 * axis + 2 * bu + bv runs along `axis` from its lower corner;
//   bu, bv are the offsets along the two other axes u = axis+1, v = axis+2 (mod 3).
//
// Generation rule: on every cube face the contour segments separate "below"
// corners from "above" ones; on an ambiguous face (two diagonal corners above,
// two below) the ABOVE corners are separated and the below corners connect
// (the choice of VTK's vtkMarchingCubes table: the same contour loops, hence the
// same triangle counts, as VTK's table in all 256 cases, checked against VTK
// 9.1 at run time by Filters/Meshing/Testing). Because the choice depends only
// on the face's four corners, neighbouring cells always agree and the surface
// has no cracks. Segments are chained into closed loops on the cube boundary
// (one per surface sheet in the cell), each loop is triangulated without a
// diagonal lying in a cube face (a fan could put one there, and the neighbour
// cell may draw the same one: non-manifold). Loops are oriented so that
// triangles are counter-clockwise seen from the above (outside) side: the
// geometric normal points toward increasing values, i.e. along the SDF gradient.
//
// The diagonals inside loops of 4 to 7 vertices (the first valid choice of the
// recursive search in MarchingCubesTables.cpp) are not VTK's in 162 of the 256
// cases. VTK's table is hand-made (Lorensen & Cline's base cases spread by
// symmetry): no simple rule we tried reproduces it (fans from the loop vertex
// with the smallest/largest edge id in either numbering, either loop direction,
// with the search in either order: at most 57 of VTK's 214 non-triangle loops;
// shortest-diagonal or smallest-area rules: ties everywhere). Callers that need
// VTK's exact surface pass VTK's table (marchingCubesTablesWith below; the VTK
// filter does, reading vtkMarchingCubesTriangleCases at run time).
#pragma once

#include <array>
#include <cstdint>

namespace lvdif
{

struct MarchingCubesTables
{
  /// Triangles of each case (0..5).
  std::uint8_t triangleCount[256];
  /// Edge ids, 3 per triangle, then -1.
  std::int8_t triangles[256][16];
  /// The two corners of each edge, lower one first.
  std::uint8_t edgeCorners[12][2];
  std::uint8_t edgeAxis[12];
};

/// The table (built once, thread-safe).
const MarchingCubesTables& marchingCubesTables();

/// A caller's triangles per case: edge ids (our numbering above), 3 per
/// triangle, then -1 up to the end of the row.
using MarchingCubesTriangleTable = std::array<std::array<std::int8_t, 16>, 256>;

/// Our table with its triangles replaced by `triangles`, after checking that in
/// every case they triangulate exactly our contour loops: only this case's cut
/// edges, each triangle within one loop, n-2 triangles for a loop of n vertices,
/// no directed edge used twice, and the same directed loop segments as ours (so
/// the same orientation: counter-clockwise seen from the above side). These
/// conditions make each loop's triangles a disk bounded by the loop (Euler
/// characteristic 1 with one boundary), so only the diagonals inside a loop may
/// differ from ours; cracks between cells cannot appear, as loop segments on
/// cube faces are unchanged. Throws Error(InvalidArgument) naming the first
/// offending case. The VTK filter passes VTK's own table this way.
MarchingCubesTables marchingCubesTablesWith(const MarchingCubesTriangleTable& triangles);

/// Our own triangles as a MarchingCubesTriangleTable.
MarchingCubesTriangleTable marchingCubesTriangleTable();

} // namespace lvdif
