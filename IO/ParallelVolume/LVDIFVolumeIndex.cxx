#include "LVDIFVolumeIndex.h"

#include "lvdif/ByteStream.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"
#include "lvdif/PieceTiling.h"

#include <algorithm>
#include <cstdio>
#include <locale>
#include <iomanip>
#include <set>
#include <sstream>

namespace lvdifvtk
{
namespace
{
const char* MAGIC = "LVDIF-PVOLUME";

[[noreturn]] void fail(int line, const std::string& what)
{
  // the reader's one guard names the file ("cannot read 'x.lvdvp': line 3: ..."): a
  // message that named it ("index 'x.lvdvp', line 3: ...") lost that prefix
  throw lvdif::Error(lvdif::ErrorCode::CorruptData, (line > 0 ? "line " + std::to_string(line) + ": " : std::string()) + what);
}

lvdif::VoxelBox extentBox(const int e[6])
{
  lvdif::VoxelBox b;
  for (int a = 0; a < 3; ++a)
  {
    b.lo[a] = e[2 * a];
    b.hi[a] = e[2 * a + 1];
  }
  return b;
}

bool contains(const int outer[6], const int inner[6])
{
  for (int a = 0; a < 3; ++a)
    if (inner[2 * a] < outer[2 * a] || inner[2 * a + 1] > outer[2 * a + 1])
      return false;
  return true;
}
} // namespace

std::string directoryOf(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

namespace
{
/// "dir/name.lvdvp" -> "name"
std::string setStem(const std::string& indexPath)
{
  std::string name = indexPath.substr(directoryOf(indexPath).size());
  const auto dot = name.find_last_of('.');
  if (dot != std::string::npos && dot > 0)
    name.resize(dot);
  return name;
}
}

std::string pieceFileName(const std::string& indexPath, int piece, int generation)
{
  return setStem(indexPath) + "_" + std::to_string(piece) + (generation == 1 ? ".g1" : "") + ".lvdv";
}

bool isPieceFileName(const std::string& indexPath, const std::string& file, int* piece)
{
  const std::string stem = setStem(indexPath) + "_";
  if (file.compare(0, stem.size(), stem) != 0)
    return false;
  std::size_t i = stem.size(), digits = 0;
  long p = 0;
  for (; i < file.size() && file[i] >= '0' && file[i] <= '9' && digits < 9; ++i, ++digits)
    p = 10 * p + (file[i] - '0');
  const std::string rest = file.substr(i);
  if (digits == 0 || (digits > 1 && file[stem.size()] == '0') || (rest != ".lvdv" && rest != ".g1.lvdv"))
    return false;
  if (piece)
    *piece = static_cast<int>(p);
  return true;
}

VolumeIndex readVolumeIndex(const std::string& path)
{
  // the project's file check: a FIFO blocked std::ifstream, a folder read as an empty file
  lvdif::FileSource source(path);
  {
    // the magic line first: a garbage file of gigabytes was read whole (memory and
    // time) before its first line was found not to be an index
    std::string head(static_cast<std::size_t>(std::min<std::uint64_t>(source.size(), 65536)), '\0');
    if (!head.empty())
      source.read(0, &head[0], head.size());
    std::istringstream h(head.substr(head.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0)); // a UTF-8 byte order mark
    std::string line;
    for (int n = 1; std::getline(h, line); ++n)
    {
      if (h.eof() && head.size() < source.size())
        break; // a line cut by the head: judged below, with the whole file
      if (!line.empty() && line.back() == '\r')
        line.pop_back();
      if (line.empty() || line[0] == '#')
        continue;
      std::istringstream ls(line);
      std::string key;
      ls >> key;
      if (key != MAGIC)
        fail(n, std::string("not an LVDIF volume index (expected '") + MAGIC + " <version>')");
      break;
    }
  }
  lvdif::requireMemory(source.size(), "reading the index " + path);
  std::string text(static_cast<std::size_t>(source.size()), '\0');
  if (!text.empty())
    source.read(0, &text[0], text.size());
  std::istringstream in(text.substr(text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0));
  VolumeIndex index;
  std::string line;
  int lineNo = 0, declaredPieces = -1;
  bool haveMagic = false, haveWhole = false, haveOrigin = false, haveSpacing = false;
  std::set<std::string> seen;
  while (std::getline(in, line))
  {
    ++lineNo;
    if (!line.empty() && line.back() == '\r')
      line.pop_back(); // CRLF (an index edited on Windows): the piece's file name ended in '\r'
    if (line.empty() || line[0] == '#')
      continue;
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    // every line but a piece holds its values only (a stray one was ignored)
    auto complete = [&] {
      std::string extra;
      if (ls >> extra)
        fail(lineNo, key + " has a value too many: '" + extra.substr(0, 40) + "'");
    };
    if (!haveMagic)
    {
      // the first line that is not a comment (comments before it skipped the check)
      if (key != MAGIC || !(ls >> index.version))
        fail(lineNo, std::string("not an LVDIF volume index (expected '") + MAGIC + " <version>')");
      if (index.version != 1)
        fail(lineNo, "unsupported index version " + std::to_string(index.version) + " (this reader knows 1)");
      complete();
      haveMagic = true;
      continue;
    }
    if (key != "piece" && !seen.insert(key).second)
      fail(lineNo, key + " given twice"); // the last one silently won
    if (key == "whole_extent")
    {
      for (int& v : index.wholeExtent)
        if (!(ls >> v))
          fail(lineNo, "whole_extent needs 6 integers");
      complete();
      if (!extentIsValid(index.wholeExtent))
        fail(lineNo, "empty whole_extent");
      haveWhole = true;
    }
    else if (key == "origin" || key == "spacing")
    {
      double* v = key == "origin" ? index.origin : index.spacing;
      for (int a = 0; a < 3; ++a)
        if (!(ls >> v[a]))
          fail(lineNo, key + " needs 3 numbers");
      complete();
      (key == "origin" ? haveOrigin : haveSpacing) = true;
    }
    else if (key == "pieces")
    {
      if (!(ls >> declaredPieces) || declaredPieces < 1 || declaredPieces > (1 << 20))
        fail(lineNo, "pieces needs a count in 1..1048576");
      complete();
    }
    else if (key == "piece")
    {
      VolumeIndexPiece p;
      for (int& v : p.extent)
        if (!(ls >> v))
          fail(lineNo, "piece needs 6 integers and a file name");
      std::getline(ls >> std::ws, p.file);
      if (p.file.empty() || p.file.find('/') != std::string::npos)
        fail(lineNo, "piece file must be a plain file name beside the index");
      if (!extentIsValid(p.extent) || !haveWhole || !contains(index.wholeExtent, p.extent))
        fail(lineNo, "piece extent empty or outside whole_extent (whole_extent must come first)");
      index.pieces.push_back(p);
    }
    else
    {
      fail(lineNo, "unknown key '" + key.substr(0, 40) + "'");
    }
  }
  if (!haveMagic)
    fail(0, lineNo == 0 ? "empty file" : std::string("no '") + MAGIC + " <version>' line");
  if (!haveWhole || !haveOrigin || !haveSpacing)
    fail(0, "whole_extent, origin and spacing are required");
  // the volume's one geometry rule (finite, spacing >= 1e-30, every point within +-1e30), on the grid
  // the reader makes (origin at the whole extent's first point): "spacing -1 1 1" or "0 1 1" passed,
  // the pipeline was told that grid, and the read failed later in the volume's own words
  {
    lvdif::VolumeOptions grid;
    for (int a = 0; a < 3; ++a)
    {
      grid.dims[a] = static_cast<std::int64_t>(index.wholeExtent[2 * a + 1]) - index.wholeExtent[2 * a] + 1;
      grid.origin[a] = index.origin[a] + index.spacing[a] * index.wholeExtent[2 * a];
      grid.spacing[a] = index.spacing[a];
    }
    const std::string geometry = lvdif::DictionaryVolume::checkGeometry(grid);
    if (!geometry.empty())
      fail(0, "origin and spacing: " + geometry);
  }
  if (declaredPieces != static_cast<int>(index.pieces.size()))
    fail(0, "declares " + std::to_string(declaredPieces) + " pieces, lists " + std::to_string(index.pieces.size()));
  // the pieces tile the whole extent: a duplicate or overlapping piece (two
  // claims on the same points) and a hole were accepted
  std::vector<lvdif::VoxelBox> boxes;
  for (const auto& p : index.pieces)
    boxes.push_back(extentBox(p.extent));
  const std::string problem = lvdif::pieceTilingProblem(extentBox(index.wholeExtent), boxes, "piece");
  if (!problem.empty())
    fail(0, problem + " (pieces counted in the order listed)");
  return index;
}

void writeVolumeIndex(const VolumeIndex& index, const std::string& path)
{
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out << MAGIC << " " << index.version << "\n";
  out << "# distributed LVDIF dictionary volume: the pieces are .lvdv files beside this index (docs/FORMAT.md)\n";
  out << "whole_extent";
  for (int v : index.wholeExtent)
    out << " " << v;
  out << "\n" << std::setprecision(17);
  out << "origin " << index.origin[0] << " " << index.origin[1] << " " << index.origin[2] << "\n";
  out << "spacing " << index.spacing[0] << " " << index.spacing[1] << " " << index.spacing[2] << "\n";
  out << "pieces " << index.pieces.size() << "\n";
  for (const auto& p : index.pieces)
  {
    out << "piece";
    for (int v : p.extent)
      out << " " << v;
    out << " " << p.file << "\n";
  }
  const std::string text = out.str();
  // the project's one crash-safe save (it wrote "<index>.tmp" with an ofstream)
  lvdif::saveAtomically(path, [&](lvdif::ByteSink& sink) { sink.write(text.data(), text.size()); });
}
}
