// The one rule for a grid of points stored as pieces (a .lvdvp index's
// pieces, a .vti's <Piece> elements): the pieces must tile the whole extent.
// Neighbouring pieces share one boundary layer of points (VTK's extent
// translator and vtkPDictionaryVolumeWriter write them so); anything more is
// an overlap whose points two pieces would both claim, and a point no piece
// holds would be made up by the reader.
#pragma once

#include "lvdif/DictionaryVolume.h"

#include <string>
#include <vector>

namespace lvdif
{

/// "x0 x1 y0 y1 z0 z1": an extent in the order of VTK's and the index's files.
std::string extentText(const VoxelBox& box);

/// "" when `pieces` tile `whole`, else the first problem in words, naming the
/// extents: a piece empty or outside the whole extent; two pieces with the same
/// extent, or sharing more than one boundary layer of points (a layer is shared
/// when it is the last of one piece and the first of the other on some axis of
/// more than one point); points of the whole extent that no piece holds (for
/// one piece: "the whole extent W is larger than its piece's extent E").
/// `what` names a piece in the messages ("piece"). With `overlapsAllowed`
/// only pieces outside and holes are problems (a .vti: VTK's writer repeats the
/// whole extent in every piece when its input cannot be split, and its reader
/// takes the last piece's values).
/// Works on the grid of the pieces' distinct boundaries (refused above 2^23
/// cells): each cell held by each piece once, every two pieces holding a cell
/// compared, so the work is about the grid's size for pieces that tile.
std::string pieceTilingProblem(const VoxelBox& whole, const std::vector<VoxelBox>& pieces,
  const std::string& what = "piece", bool overlapsAllowed = false);

} // namespace lvdif
