// The caps of the solid on the faces of the volume's box, for display only.
// Marching cubes meshes the surface inside the box: a solid that reaches a
// face (a Full canvas, a model cut by the box) is left open there, and a Full
// canvas showed nothing at all until carved. The editor closes it with caps:
// on each face, the region where the face's voxels are inside (marching
// squares, the same linear crossing as marching cubes' vertices on that face),
// facing out of the box. They are added to the meshes of the chunks whose
// cells touch a face, so an edit that re-meshes a chunk renews its caps; the
// volume, its marching cubes (Core) and the exported mesh are unchanged.
#pragma once

#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdif/DictionaryVolume.h"

namespace BoxCaps
{
/// Whether a chunk's cells reach a face of a box of `dims` points.
bool touchesBox(const lvdif::VoxelBox& cells, const lvdif::Index3& dims);

/// Appends to `mesh` (a chunk's marching cubes mesh of `volume`, empty or not)
/// the caps on the box faces its cells reach, with the arrays the mesh has
/// (all of them when it is empty): points, normals (out of the box), colours,
/// corner colours and cells (of the boundary cell each cap lies on). Returns
/// whether any triangle was added.
bool append(lvdif::ChunkMesh& mesh, const lvdif::DictionaryVolume& volume, float iso);
}
