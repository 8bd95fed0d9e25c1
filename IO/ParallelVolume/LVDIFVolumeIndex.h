// The .lvdvp index of a distributed dictionary volume (docs/FORMAT.md,
// "Distributed volumes"): plain text, one .lvdv file per piece beside it.
#ifndef LVDIFVolumeIndex_h
#define LVDIFVolumeIndex_h

#include <string>
#include <vector>

namespace lvdifvtk
{
struct VolumeIndexPiece
{
  int extent[6];    // point extent of the piece in the whole volume's indices
  std::string file; // relative to the index's directory
};

struct VolumeIndex
{
  int version = 1;
  int wholeExtent[6] = { 0, -1, 0, -1, 0, -1 };
  double origin[3] = { 0, 0, 0 };  // world position of index (0, 0, 0)
  double spacing[3] = { 1, 1, 1 };
  std::vector<VolumeIndexPiece> pieces;
};

/// Parses an index; throws lvdif::Error (InvalidArgument / IoFailure) naming the line and the problem.
VolumeIndex readVolumeIndex(const std::string& path);
/// Writes it crash-safely (temporary file, then rename).
void writeVolumeIndex(const VolumeIndex& index, const std::string& path);
/// "dir/name.lvdvp" -> "name_<piece>.lvdv" (the piece file's name, relative to the
/// index) of generation 0, "name_<piece>.g1.lvdv" of generation 1: a write puts its
/// pieces under the generation the current index does not list, so the old set
/// stays whole until the new index replaces the old one.
std::string pieceFileName(const std::string& indexPath, int piece, int generation = 0);
/// Whether `file` (a name beside the index) is a piece file name of that index's set
/// (either generation); `piece` is then its piece number.
bool isPieceFileName(const std::string& indexPath, const std::string& file, int* piece = nullptr);
/// The directory part of a path, with its trailing '/', or "".
std::string directoryOf(const std::string& path);
/// True if the piece extent is not empty.
inline bool extentIsValid(const int e[6])
{
  return e[0] <= e[1] && e[2] <= e[3] && e[4] <= e[5];
}
}

#endif
