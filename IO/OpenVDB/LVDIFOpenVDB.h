// Conversion between lvdif::DictionaryVolume and an OpenVDB level set file
// (docs/FORMAT.md, "OpenVDB interop"). The interface names no OpenVDB type, so
// the VTK classes and their Python wrappers never include OpenVDB's headers.
//
// Export: a FloatGrid `sdf` of class GRID_LEVEL_SET with a linear transform
// (voxel size = spacing, index (0,0,0) at the origin), holding WORLD-unit
// distances (our voxel distance x voxel size, negative inside, as OpenVDB's
// level sets are). Active voxels: |d| < half width; background = half width x
// voxel size; the rest is signed by flood fill (inside = -background). A
// colour grid Int32Grid `rgba` (r | g<<8 | b<<16 | a<<24, as
// lvdif::Rgba::packed) is active on the same voxels. Only isotropic spacing
// can be exported: a level set's distances have one unit.
//
// Import: any FloatGrid (by name; default the first grid of class level set)
// with a linear, axis-aligned, uniformly scaled transform. The volume covers
// the grid's active bounding box (plus `padding` voxels); distances are
// divided by the voxel size and the band width is background / voxel size.
// An Int32Grid of the colour grid's name with the same transform colours the
// voxels it has active (other voxels get colour key 0).
#pragma once

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"
#include "lvdifIOOpenVDBModule.h"

#include <memory>
#include <string>
#include <vector>

namespace lvdif
{
namespace vdb
{

struct ExportOptions
{
  /// Half width of the narrow band in voxels: 0 = the volume's band width
  /// (3, OpenVDB's default, when the volume's band is infinite), else 1 to 10000
  /// (checkHalfWidth). Never wider than the volume's band (exportHalfWidth).
  double halfWidth = 0.0;
  bool withColor = true;
  std::string sdfName = "sdf";
  std::string colorName = "rgba";
};

struct ImportOptions
{
  /// Grid to read; empty = the first FloatGrid of class level set.
  std::string gridName;
  /// Int32Grid holding packed colours; empty = no colour.
  std::string colorName = "rgba";
  /// Voxels added around the active bounding box on every side.
  int padding = 0;
  int chunkEdge = 32;
  /// Bytes the volume may use; 0 = memoryLimitBytes().
  std::uint64_t memoryLimit = 0;
};

struct GridSummary
{
  std::string name, type, gridClass;
};

/// OpenVDB's own default narrow-band half width (voxels): what an unlimited
/// band, or an image without a band, is written with when none is asked.
constexpr double DefaultHalfWidth = 3.0;

/// The narrow band's half width (voxels) that exportLevelSet writes for a half
/// width asked (0: the volume's band): never wider than the volume's band
/// (saturated distances are not distances), and 3, OpenVDB's default, for an
/// unlimited band with 0 (a level set's background is finite).
LVDIFIOOPENVDB_EXPORT double exportHalfWidth(const DictionaryVolume& volume, double asked);

/// The half widths an export takes: 0 (the volume's band) or 1 to 10000 voxels
/// (a level set needs at least one active voxel on each side of its surface).
/// Else Error(InvalidArgument) naming `name` and the value; the writer's
/// HalfWidth is refused by this rule (it was clamped).
constexpr double MinHalfWidth = 1.0, MaxHalfWidth = 1.0e4;
LVDIFIOOPENVDB_EXPORT void checkHalfWidth(double halfWidth, const std::string& name = "half width");

/// The most voxels an import adds around the active box (index coordinates stay
/// within int); more is Error(InvalidArgument) naming `name` and the value.
constexpr int MaxImportPadding = 1 << 16;
LVDIFIOOPENVDB_EXPORT void checkImportPadding(int padding, const std::string& name = "padding");

/// What exportLevelSet refuses before any work, with its words: anisotropic
/// spacing, a half width out of range, an empty grid name (Error(InvalidArgument)).
/// The writer checks it before it says anything about the band (it warned of a
/// narrower band and then refused the volume).
LVDIFIOOPENVDB_EXPORT void checkExport(const DictionaryVolume& volume, const ExportOptions& options);
/// The spacing rule of checkExport alone (one distance unit: isotropic); throws Error.
LVDIFIOOPENVDB_EXPORT void checkExportSpacing(const double spacing[3]);

/// Writes the .vdb (Error(InvalidArgument) for anisotropic spacing,
/// Error(IoFailure) when OpenVDB cannot write, Error(Cancelled)). Returns the
/// active voxels of the level set written: 0 for a volume with no voxel within
/// the band (no surface), whose file importLevelSet refuses ("no active voxels").
LVDIFIOOPENVDB_EXPORT std::uint64_t exportLevelSet(const DictionaryVolume& volume, const std::string& path,
  const ExportOptions& options = ExportOptions(), Interrupter& interrupter = nullInterrupter());

/// Reads a level set (Error(IoFailure) for a file OpenVDB cannot open,
/// Error(CorruptData) for a missing grid, wrong type or unsupported transform,
/// Error(OutOfMemory) past the limit, Error(Cancelled)).
LVDIFIOOPENVDB_EXPORT std::unique_ptr<DictionaryVolume> importLevelSet(const std::string& path,
  const ImportOptions& options = ImportOptions(), Interrupter& interrupter = nullInterrupter());

/// The grids of a file (name, value type, class), for error messages and UIs.
LVDIFIOOPENVDB_EXPORT std::vector<GridSummary> listGrids(const std::string& path);

} // namespace vdb
} // namespace lvdif
