#include "LVDIFOpenVDB.h"

#include "lvdif/ByteStream.h"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/SignedFloodFill.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <unistd.h>

namespace lvdif
{
namespace vdb
{
namespace
{

openvdb::Coord coord(std::int64_t x, std::int64_t y, std::int64_t z)
{
  return openvdb::Coord(static_cast<openvdb::Int32>(x), static_cast<openvdb::Int32>(y), static_cast<openvdb::Int32>(z));
}

std::string gridList(const std::vector<GridSummary>& grids)
{
  std::ostringstream s;
  for (std::size_t i = 0; i < grids.size(); ++i)
  {
    s << (i ? ", " : "") << "'" << grids[i].name << "' (" << grids[i].type << ", " << grids[i].gridClass << ")";
  }
  return grids.empty() ? std::string("none") : s.str();
}

std::vector<GridSummary> summarize(const openvdb::GridPtrVec& grids)
{
  std::vector<GridSummary> out;
  for (const auto& g : grids)
  {
    out.push_back({ g->getName(), g->valueType(), openvdb::GridBase::gridClassToString(g->getGridClass()) });
  }
  return out;
}

/// Opens a file, turning OpenVDB's exceptions into lvdif::Error.
void openFile(openvdb::io::File& file, const std::string& path)
{
  // the project's own open first: a missing file, a folder or a FIFO gets the
  // message every reader gives ("cannot open 'F': No such file or directory";
  // OpenVDB said "IoError: could not open file F")
  FileSource{ path };
  try
  {
    file.open(/*delayLoad=*/false);
  }
  catch (const std::exception& e)
  {
    throw Error(ErrorCode::IoFailure, "OpenVDB cannot open '" + path + "': " + e.what());
  }
}

/// Voxel size and world origin of index (0,0,0) of a linear, axis-aligned,
/// uniformly scaled, non-reflecting transform; Error(CorruptData) otherwise.
double checkTransform(const openvdb::math::Transform& xf, const std::string& gridName)
{
  if (!xf.isLinear() || !xf.hasUniformScale())
  {
    throw Error(ErrorCode::CorruptData,
      "grid '" + gridName + "' has a non-linear or non-uniform transform (" + xf.mapType() + "); only uniform voxels are supported");
  }
  const openvdb::Vec3d o = xf.indexToWorld(openvdb::Vec3d(0, 0, 0));
  const double vs = xf.voxelSize()[0];
  for (int a = 0; a < 3; ++a)
  {
    openvdb::Vec3d e(0, 0, 0);
    e[a] = 1;
    const openvdb::Vec3d d = xf.indexToWorld(e) - o;
    for (int b = 0; b < 3; ++b)
    {
      const double expected = a == b ? vs : 0.0;
      if (std::fabs(d[b] - expected) > 1e-9 * vs)
      {
        throw Error(ErrorCode::CorruptData, "grid '" + gridName + "' has a rotated or reflected transform; only axis-aligned grids are supported");
      }
    }
  }
  if (!(vs > 0) || !std::isfinite(vs))
  {
    throw Error(ErrorCode::CorruptData, "grid '" + gridName + "' has an invalid voxel size");
  }
  return vs;
}

} // namespace

std::vector<GridSummary> listGrids(const std::string& path)
{
  openvdb::initialize();
  openvdb::io::File file(path);
  openFile(file, path);
  auto grids = file.readAllGridMetadata();
  file.close();
  return summarize(*grids);
}

double exportHalfWidth(const DictionaryVolume& volume, double asked)
{
  const double band = volume.bandWidth();
  const double hw = asked > 0 ? asked : (std::isfinite(band) ? band : DefaultHalfWidth);
  // Saturated distances (|d| = band) are not distances: never make them active.
  return std::min(hw, band);
}

void checkHalfWidth(double halfWidth, const std::string& name)
{
  if (halfWidth != 0 && !(halfWidth >= MinHalfWidth && halfWidth <= MaxHalfWidth)) // NaN too
  {
    std::ostringstream msg;
    msg << name << " must be 0 (the volume's band) or a number of voxels in [1, 10000], not " << halfWidth;
    throw Error(ErrorCode::InvalidArgument, msg.str());
  }
}

void checkImportPadding(int padding, const std::string& name)
{
  require(padding >= 0 && padding <= MaxImportPadding,
    name + " must be a number of voxels in [0, " + std::to_string(MaxImportPadding) + "], not " + std::to_string(padding));
}

void checkExportSpacing(const double spacing[3])
{
  const double vs = spacing[0];
  for (int a = 1; a < 3; ++a)
  {
    require(std::fabs(spacing[a] - vs) <= 1e-9 * vs,
      "OpenVDB export needs isotropic spacing (a level set has one distance unit); the volume has spacing " +
        std::to_string(spacing[0]) + ", " + std::to_string(spacing[1]) + ", " + std::to_string(spacing[2]));
  }
}

void checkExport(const DictionaryVolume& volume, const ExportOptions& options)
{
  checkExportSpacing(volume.options().spacing.data());
  checkHalfWidth(options.halfWidth, "OpenVDB export: the half width");
  require(!options.sdfName.empty(), "OpenVDB export: empty grid name");
}

void exportLevelSet(
  const DictionaryVolume& volume, const std::string& path, const ExportOptions& options, Interrupter& interrupter)
{
  checkExport(volume, options);
  const VolumeOptions& o = volume.options();
  const double vs = o.spacing[0];
  const double hw = exportHalfWidth(volume, options.halfWidth);

  const std::uint64_t voxels = checkedMultiply(static_cast<std::uint64_t>(volume.expandedChunkCount()) + 1,
    static_cast<std::uint64_t>(volume.chunkEdge()) * volume.chunkEdge() * volume.chunkEdge(), "OpenVDB export");
  // Leaf nodes: 4-byte value + masks per voxel, per grid.
  requireMemory(checkedMultiply(voxels, options.withColor ? 10 : 5, "OpenVDB export"), "OpenVDB grids of the export");

  openvdb::initialize();
  auto xf = openvdb::math::Transform::createLinearTransform(vs);
  xf->postTranslate(openvdb::Vec3d(o.origin[0], o.origin[1], o.origin[2]));
  auto sdf = openvdb::FloatGrid::create(static_cast<float>(hw * vs));
  sdf->setName(options.sdfName);
  sdf->setGridClass(openvdb::GRID_LEVEL_SET);
  sdf->setTransform(xf);
  sdf->setCreator("LVDIF");
  sdf->insertMeta("lvdif_distance_unit", openvdb::StringMetadata("world (voxel distance x voxel size)"));
  sdf->insertMeta("lvdif_half_width_voxels", openvdb::DoubleMetadata(hw));
  auto rgba = openvdb::Int32Grid::create(0);
  rgba->setName(options.colorName);
  rgba->setTransform(xf->copy());
  rgba->setCreator("LVDIF");
  rgba->insertMeta("lvdif_packing", openvdb::StringMetadata("r | g<<8 | b<<16 | a<<24"));

  auto sa = sdf->getAccessor();
  auto ca = rgba->getAccessor();
  interrupter.start("OpenVDB export");
  const std::int64_t n = volume.chunkCount();
  for (std::int64_t id = 0; id < n; ++id)
  {
    if ((id & 63) == 0)
    {
      interrupter.checkInterrupt();
      interrupter.progress(0.9 * double(id) / double(n));
    }
    if (volume.isUniform(id) && !(std::fabs(volume.decode(volume.uniformValue(id).sdf)) < hw))
    {
      continue; // beyond the band: background, signed by the flood fill
    }
    const VoxelBox b = volume.chunkBox(id);
    for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
      for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
        for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
        {
          const Voxel v = volume.get(x, y, z);
          const double d = volume.decode(v.sdf);
          if (std::fabs(d) < hw)
          {
            sa.setValue(coord(x, y, z), static_cast<float>(d * vs));
            if (options.withColor)
            {
              ca.setValue(coord(x, y, z), static_cast<std::int32_t>(volume.colors()[v.color].packed()));
            }
          }
        }
  }
  openvdb::tools::signedFloodFill(sdf->tree());
  interrupter.checkInterrupt();

  openvdb::GridPtrVec grids{ sdf };
  if (options.withColor)
  {
    grids.push_back(rgba);
  }
  // Crash-safe as every save of the project (saveAtomicallyByName: a temporary file renamed over the
  // old one, its mode kept, synced; this writer had a rename of its own). OpenVDB does not check its
  // writes: under a full disk or a file size limit the cut file was renamed over the old one and the
  // save succeeded, so the file is read back and its grids' active voxels counted first.
  saveAtomicallyByName(path, [&](const std::string& tmp) {
    try
    {
      {
        openvdb::io::File file(tmp);
        file.write(grids);
        file.close();
      }
      bool whole = false;
      try
      {
        openvdb::io::File back(tmp);
        back.open(/*delayLoad=*/false);
        const openvdb::GridPtrVecPtr read = back.getGrids();
        back.close();
        whole = read && read->size() == grids.size();
        for (std::size_t i = 0; whole && i < grids.size(); ++i)
          whole = (*read)[i] && (*read)[i]->activeVoxelCount() == grids[i]->activeVoxelCount();
      }
      catch (const std::exception&)
      {
        // (OpenVDB's words about a cut file quote its garbage)
      }
      if (!whole)
        throw std::runtime_error("the file written does not hold the grids whole (the disk full, or a file size limit?); "
                                 "the old file is kept");
    }
    catch (const std::exception& e)
    {
      throw Error(ErrorCode::IoFailure, "OpenVDB cannot write '" + path + "': " + e.what());
    }
  });
  interrupter.progress(1.0);
}

std::unique_ptr<DictionaryVolume> importLevelSet(
  const std::string& path, const ImportOptions& options, Interrupter& interrupter)
{
  checkImportPadding(options.padding, "OpenVDB import: the padding");
  openvdb::initialize();
  openvdb::io::File file(path);
  openFile(file, path);
  try
  {
    const auto all = summarize(*file.readAllGridMetadata());
    std::string name = options.gridName;
    if (name.empty())
    {
      for (const auto& g : all)
      {
        if (g.type == openvdb::typeNameAsString<float>() &&
          g.gridClass == openvdb::GridBase::gridClassToString(openvdb::GRID_LEVEL_SET))
        {
          name = g.name;
          break;
        }
      }
      if (name.empty())
      {
        throw Error(ErrorCode::CorruptData, "'" + path + "' has no float level-set grid; its grids: " + gridList(all));
      }
    }
    auto it = std::find_if(all.begin(), all.end(), [&](const GridSummary& g) { return g.name == name; });
    if (it == all.end())
    {
      throw Error(ErrorCode::CorruptData, "'" + path + "' has no grid named '" + name + "'; its grids: " + gridList(all));
    }
    if (it->type != openvdb::typeNameAsString<float>())
    {
      throw Error(ErrorCode::CorruptData, "grid '" + name + "' holds " + it->type + " values, not float");
    }
    auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(name));
    if (!grid)
    {
      throw Error(ErrorCode::CorruptData, "grid '" + name + "' is not a FloatGrid");
    }
    const double vs = checkTransform(grid->transform(), name);
    const float bg = grid->background();
    if (!(bg > 0) || !std::isfinite(bg))
    {
      throw Error(ErrorCode::CorruptData, "grid '" + name + "' has background " + std::to_string(bg) +
          "; a level set's background is its positive half band width");
    }
    openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
    if (box.empty())
    {
      throw Error(ErrorCode::CorruptData, "grid '" + name + "' has no active voxels");
    }
    box.expand(options.padding);

    VolumeOptions vo;
    const openvdb::Coord dim = box.dim();
    vo.dims = { dim.x(), dim.y(), dim.z() };
    vo.chunkEdge = options.chunkEdge;
    const openvdb::Vec3d origin = grid->transform().indexToWorld(box.min());
    vo.origin = { origin.x(), origin.y(), origin.z() };
    vo.spacing = { vs, vs, vs };
    vo.bandWidth = static_cast<float>(bg / vs);
    vo.memoryLimit = options.memoryLimit;
    auto volume = std::make_unique<DictionaryVolume>(vo); // validates and refuses absurd sizes
    volume->colors().setPolicy(ColorDictionary::FullPolicy::Nearest);
    const SdfKey outsideKey = volume->outsideVoxel().sdf;
    const openvdb::Coord lo = box.min();
    const auto local = [&](const openvdb::Coord& c) {
      return Index3{ std::int64_t(c.x()) - lo.x(), std::int64_t(c.y()) - lo.y(), std::int64_t(c.z()) - lo.z() };
    };

    interrupter.start("OpenVDB import");
    const openvdb::FloatTree& tree = grid->tree();
    // Tiles (above the leaf level): whole chunks by fillChunk, the rest voxel by voxel.
    auto tiles = tree.cbeginValueAll();
    tiles.setMaxDepth(openvdb::FloatTree::ValueAllCIter::LEAF_DEPTH - 1);
    for (; tiles; ++tiles)
    {
      const SdfKey key = volume->encode(static_cast<float>(*tiles / vs));
      openvdb::CoordBBox tb;
      if (key == outsideKey || !tiles.getBoundingBox(tb))
      {
        continue;
      }
      tb.intersect(box);
      if (tb.empty())
      {
        continue;
      }
      interrupter.checkInterrupt();
      VoxelBox vb;
      vb.lo = local(tb.min());
      vb.hi = local(tb.max());
      volume->forEachChunkInBox(vb, [&](std::int64_t id) {
        const VoxelBox cb = volume->chunkBox(id);
        const VoxelBox part = cb.intersect(vb);
        if (part.voxelCount() == cb.voxelCount())
        {
          volume->fillChunk(id, Voxel{ key, 0 });
          return;
        }
        for (std::int64_t z = part.lo[2]; z <= part.hi[2]; ++z)
          for (std::int64_t y = part.lo[1]; y <= part.hi[1]; ++y)
            for (std::int64_t x = part.lo[0]; x <= part.hi[0]; ++x)
              volume->set(x, y, z, Voxel{ key, 0 });
      });
    }
    const double leaves = std::max<double>(1.0, double(tree.leafCount()));
    std::int64_t done = 0;
    for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf, ++done)
    {
      if ((done & 255) == 0)
      {
        interrupter.checkInterrupt();
        interrupter.progress(0.9 * done / leaves);
      }
      for (auto v = leaf->cbeginValueAll(); v; ++v)
      {
        const openvdb::Coord c = v.getCoord();
        if (!box.isInside(c))
        {
          continue;
        }
        const SdfKey key = volume->encode(static_cast<float>(*v / vs));
        const Index3 p = local(c);
        if (key != outsideKey || volume->get(p[0], p[1], p[2]).sdf != outsideKey)
        {
          volume->set(p[0], p[1], p[2], Voxel{ key, 0 });
        }
      }
    }

    if (!options.colorName.empty() && file.hasGrid(options.colorName))
    {
      auto base = file.readGrid(options.colorName);
      auto colors = openvdb::gridPtrCast<openvdb::Int32Grid>(base);
      if (!colors)
      {
        throw Error(ErrorCode::CorruptData, "colour grid '" + options.colorName + "' holds " + base->valueType() +
            " values, not int32 (packed RGBA); choose another colour grid name or none");
      }
      if (!(colors->transform() == grid->transform()))
      {
        throw Error(ErrorCode::CorruptData, "colour grid '" + options.colorName + "' does not share grid '" + name + "''s transform");
      }
      for (auto v = colors->cbeginValueOn(); v; ++v)
      {
        openvdb::CoordBBox vb;
        v.getBoundingBox(vb);
        vb.intersect(box);
        if (vb.empty())
        {
          continue;
        }
        const ColorKey ck = volume->colors().add(Rgba::unpack(static_cast<std::uint32_t>(*v)));
        for (auto c = vb.begin(); c; ++c)
        {
          const Index3 p = local(*c);
          volume->set(p[0], p[1], p[2], Voxel{ volume->get(p[0], p[1], p[2]).sdf, ck });
        }
      }
    }
    file.close();
    volume->collapseUniformChunks();
    volume->takeDirtyChunks();
    interrupter.progress(1.0);
    return volume;
  }
  catch (const Error&)
  {
    throw;
  }
  catch (const std::exception& e)
  {
    throw Error(ErrorCode::CorruptData, "OpenVDB cannot read '" + path + "': " + e.what());
  }
}

} // namespace vdb
} // namespace lvdif
