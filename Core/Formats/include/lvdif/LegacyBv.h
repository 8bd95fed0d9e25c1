// Import and export of the original LVDIF's `.bv` volume files
// (original-code-spec.md section 3): N^3 little-endian records
// {uint16 SDF key, uint16 colour index}, x fastest, no header; the edge N
// comes from the file size (4 N^3 bytes) and, when the name has the form
// `SDF_<N>_<name>.bv`, must agree with it.
//
// Their SDF dictionary differs from ours (section 3.2): INSIDE-POSITIVE
// values, positive on even keys and negative on odd keys, key 0 = -1e-7
// ("empty"). Import decodes their key with their table, negates it, scales it
// and re-encodes it with our dictionary (band-clamped); export does the
// reverse with their key formula (section 3.3) fixed as the spec suggests:
// the nearest dictionary value (no float truncation error on ~21 negative
// values) and saturation at +-2880.6 (never their wrap of large positive
// values onto key 65535). With the default options, import(export(v)) == v
// exactly for keys and colour indices.
//
// Axis order: the original's mesh-to-SDF stores the mesh with X and Z
// exchanged (section 0.2), so by default import and export swap X and Z:
// a .bv made from a mesh imports in the mesh's own orientation, and a volume
// exported here looks in the original as its own mesh-derived volumes do.
//
// Colour: their file stores palette indices only (the palette lives in Unity
// and is not saved, section 3.5); our colour key i is their index i, and the
// colours come from LegacyBvOptions::palette (default: the Mouse scene's 11
// colours, then distinct synthetic colours for higher indices).
#pragma once

#include "lvdif/ByteStream.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"

#include <memory>
#include <string>

namespace lvdif
{

struct LegacyBvOptions
{
  /// Exchange X and Z (see above).
  bool swapXZ = true;
  /// Our voxel units per their grid unit. Their distances are in "grid units"
  /// (padded bounding-box diagonal mapped to N*sqrt(3), spec 1.3), which equal
  /// voxel units only for a cubic box, and N/(N-4) too large even then; the
  /// box is not stored, so the default keeps the numbers as they are.
  double distanceScale = 1.0;
  /// Import: chunk edge and band width of the new volume.
  int chunkEdge = 32;
  float bandWidth = 8.0f;
  /// Import: colour of each palette index (empty = the Mouse scene palette).
  std::vector<Rgba> palette;
  /// Import: bytes the volume may use; 0 = memoryLimitBytes().
  std::uint64_t memoryLimit = 0;
};

namespace legacy_bv
{
/// Their dictionary value of a key (spec 3.2, float32 as their table holds it).
float decodeKey(std::uint16_t key);
/// Their key of an inside-positive value: the nearest dictionary value, on
/// the key of the right parity (spec 3.3), 0 for |value| < 0.0005,
/// saturating at +-2880.6. NaN gives key 0 (empty).
std::uint16_t encodeValue(double value);
/// N from a `SDF_<N>_...` file name (directories ignored), or -1 if absent.
std::int64_t edgeFromName(const std::string& path);
/// N of a file of `bytes` bytes named `name` (may be empty): the one size rule
/// (4 N^3 bytes, and the N of a SDF_<N>_ name), used by the import and by
/// vtkLegacyBvReader before it reads. Throws Error(CorruptData) saying why not.
std::int64_t edgeFromSize(std::uint64_t bytes, const std::string& name);
/// The same for a file on disk (opened as the import opens it: Error(IoFailure)
/// naming the path when it cannot be).
std::int64_t edgeOfFile(const std::string& path);
/// The original's naming: SDF_<N>_<name>.bv
std::string fileName(std::int64_t edge, const std::string& name);
/// The Mouse scene's default palette (spec 3.5), as 8-bit RGBA.
std::vector<Rgba> defaultPalette();
} // namespace legacy_bv

/// Imports from any source; `name` (may be empty) is checked for the N token.
/// Throws Error(CorruptData) when the size is not 4 N^3 or disagrees with the
/// name, Error(OutOfMemory) past the limit, Error(Cancelled) when interrupted.
std::unique_ptr<DictionaryVolume> readLegacyBv(ByteSource& source, const std::string& name,
  const LegacyBvOptions& options = LegacyBvOptions(), Interrupter& interrupter = nullInterrupter());
std::unique_ptr<DictionaryVolume> loadLegacyBv(const std::string& path,
  const LegacyBvOptions& options = LegacyBvOptions(), Interrupter& interrupter = nullInterrupter());

/// "" if a volume of these dimensions can be saved to `path` as .bv (cubic,
/// and the edge a SDF_<N>_ name states), else the reason: the writers' rule,
/// for callers that know the dimensions before the volume exists (lvdif
/// mesh-to-sdf checks it before the work). An empty path checks the shape only.
std::string checkLegacyBvDims(const Index3& dims, const std::string& path = std::string());
/// Exports a cubic volume (Error(InvalidArgument) otherwise).
void writeLegacyBv(const DictionaryVolume& volume, ByteSink& sink, const LegacyBvOptions& options = LegacyBvOptions(),
  Interrupter& interrupter = nullInterrupter());
/// Crash-safe; refuses a path whose SDF_<N>_ token disagrees with the volume.
void saveLegacyBv(const DictionaryVolume& volume, const std::string& path,
  const LegacyBvOptions& options = LegacyBvOptions(), Interrupter& interrupter = nullInterrupter());

} // namespace lvdif
