// The warnings of a mesh-to-SDF call (MeshToSdfStats::warnings): a field with
// nothing inside, parts smaller than a voxel, duplicated faces, faces reversed
// against their neighbours. Each names the cause and the option that helps
// (docs/MESH_TO_SDF.md, "Warnings").
#pragma once

#include "lvdif/MeshToSdf.h"

#include <cstdint>

namespace lvdif
{
namespace detail::meshtosdf
{

/// How deep inside a voxel must lie to count for warnIfNothingInside: 1 voxel
/// (`oneVoxel` in output units), or half the band when the band is narrower.
float deepInsideLimit(float oneVoxel, float band);

/// stats.warnings when a signed field over the whole grid has no voxel inside
/// deeper than deepInsideLimit (`inside`: their count), or when some parts of
/// the mesh vanish; true when its warning named the mesh's duplicate faces.
bool warnIfNothingInside(const MeshToSdfPrepared& mesh, const GridGeometry& grid, const MeshToSdfOptions& options,
  std::int64_t inside, MeshToSdfStats& stats);

/// stats.warnings for exact duplicate faces of a mesh with boundary edges,
/// unless warnIfNothingInside named them (`said`) or the call keeps each once.
void warnIfFacesDuplicated(
  const MeshToSdfPrepared& mesh, const MeshToSdfOptions& options, MeshToSdfStats& stats, bool said);

/// stats.warnings when the faces' orientation is inconsistent and the sign
/// cannot be what the user means.
void warnIfFacesReversed(const MeshToSdfPrepared& mesh, const MeshToSdfOptions& options, MeshToSdfStats& stats);

} // namespace detail::meshtosdf
} // namespace lvdif
