// Mesh health report for triangle soups (OpenMesh for mesh
// processing). Private to LVDIF::IOMesh so that OpenMesh stays out of Core/
// and out of public (Python-wrapped) headers.
//
// Definitions (each a count):
// - degenerate faces: two equal corner indices (after welding) or an exactly
//   zero cross product in double precision; skipped;
// - duplicated faces: the same three vertices as an earlier kept face, in any
//   order or orientation; skipped;
// - boundary / non-manifold edges: undirected edges used by exactly one / more
//   than two of the kept faces;
// - refused faces: kept faces OpenMesh's add_face refuses (a complex edge or
//   vertex: the face cannot join a 2-manifold halfedge structure);
// - non-manifold vertices: vertices of the OpenMesh mesh with more than one
//   outgoing boundary halfedge (e.g. two fans meeting at one vertex),
//   OpenMesh's is_manifold(vh);
// - components: connected components (through shared vertices) of the faces
//   OpenMesh accepted.
// Welding merges vertices closer than the tolerance (chained: a-b and b-c
// close puts a, b and c together), with a hash grid of cell = tolerance.
#pragma once

#include "lvdif/TriangleMesh.h"

#include <cstdint>
#include <string>

namespace lvdif_mesh_check
{
struct Report
{
  std::int64_t inputVertices = 0, inputFaces = 0;
  std::int64_t vertices = 0; // after welding
  std::int64_t weldedVertices = 0; // input vertices merged into another
  std::int64_t degenerateFaces = 0, duplicatedFaces = 0;
  std::int64_t boundaryEdges = 0, nonManifoldEdges = 0;
  std::int64_t refusedFaces = 0, nonManifoldVertices = 0;
  std::int64_t components = 0;
  /// One line: "V vertices, F faces: ... ".
  std::string summary() const;
};

/// Welds `mesh` in place when tolerance > 0 (points and indices renumbered,
/// normals dropped), then reports. The mesh must be valid (TriangleMesh::validate).
Report check(lvdif::TriangleMesh& mesh, double weldTolerance);
}
