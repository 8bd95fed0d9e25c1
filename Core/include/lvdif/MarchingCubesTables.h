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
// (the choice of VTK's vtkMarchingCubes table: same triangle count in all 256
// cases: checked against VTK 9.1 on all 256 single-cell images during
// development; the VTK-side test of vtkChunkedMarchingCubes checks whole images).
// Because the choice depends only on the face's four corners, neighbouring
// cells always agree and the surface has no cracks. Segments are chained into
// closed loops on the cube boundary (one per surface sheet in the cell), each
// loop is triangulated without a diagonal lying in a cube face (a fan could
// put one there, and the neighbour cell may draw the same one: non-manifold). Loops are oriented so that triangles are
// counter-clockwise seen from the above (outside) side: the geometric normal
// points toward increasing values, i.e. along the SDF gradient.
#pragma once

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

} // namespace lvdif
