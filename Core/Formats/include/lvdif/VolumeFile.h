// The dictionary volume file (.lvdv), documented byte by byte in docs/FORMAT.md.
//
//   header (160 B, checksummed) | colours + metadata (checksummed) |
//   chunk payloads (zstd frames) | chunk table (24 B per chunk) | footer (32 B)
//
// The table sits after the payloads (as a zip central directory does) so the
// writer streams chunks in bounded memory; the footer locates it. A uniform
// chunk is one 4-byte value in its table entry; any other chunk is a zstd
// frame of chunkEdge^3 little-endian voxels with a 64-bit checksum.
//
// Reading validates every field against the file length, the memory limit
// and the other fields before allocating or trusting it, and fails with one
// Error(CorruptData) naming the problem (never a partly filled volume).
// Partial reads decompress only the chunks that overlap a VoxelBox.
#pragma once

#include "lvdif/ByteStream.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Interrupter.h"

#include <map>
#include <memory>
#include <string>

namespace lvdif
{

/// Free-form key/value metadata (name, source mesh, creation parameters).
using VolumeMetadata = std::map<std::string, std::string>;

struct VolumeFileWriteOptions
{
  /// zstd level for non-uniform chunks (1..19). The default 3 is justified by
  /// bench_volume_file (docs/FORMAT.md): ratio close to level 9 at a fraction of its time.
  int compressionLevel = 3;
  VolumeMetadata metadata;
};

/// The one rule of a compression level (every writer's, checked before any
/// work): a zstd level in [1, 19]; anything else throws lvdif::Error
/// (InvalidArgument) naming `name` ("NAME must be a zstd level in [1, 19], not 25").
void checkCompressionLevel(int level, const std::string& name = "compression level");

struct VolumeFileReadOptions
{
  /// With wholeVolume false, only chunks overlapping `region` are read.
  /// Chunks outside it keep their stored value if uniform in the file, else
  /// the outside voxel: only voxels inside the box are meaningful then.
  VoxelBox region;
  bool wholeVolume = true; // false: honour `region`
  /// Bytes the returned volume may use; 0 = memoryLimitBytes().
  std::uint64_t memoryLimit = 0;
};

/// What a file holds, from its header, dictionaries and table (no payload read).
struct VolumeFileInfo
{
  std::uint32_t version = 0;
  VolumeOptions options; // dims, chunk edge, origin, spacing, band, SDF dictionary
  std::vector<Rgba> colors;
  VolumeMetadata metadata;
  std::int64_t chunkCount = 0;
  std::int64_t uniformChunks = 0;
  std::uint64_t payloadBytes = 0;
  std::uint64_t fileBytes = 0;
};

/// Format constants (see docs/FORMAT.md).
namespace volume_file
{
constexpr std::uint32_t Version = 1;
constexpr std::size_t HeaderBytes = 160;
constexpr std::size_t FooterBytes = 32;
constexpr std::size_t TableEntryBytes = 24;
constexpr std::uint64_t MaxMetadataBytes = 16u << 20;
constexpr std::uint32_t MaxMetadataEntries = 65536;
} // namespace volume_file

/// Serializes into any sink (no crash safety; use saveVolume for files).
void writeVolume(const DictionaryVolume& volume, ByteSink& sink,
  const VolumeFileWriteOptions& options = VolumeFileWriteOptions(),
  Interrupter& interrupter = nullInterrupter());

/// Writes a file crash-safely (temporary file, fsync, rename, fsync directory).
void saveVolume(const DictionaryVolume& volume, const std::string& path,
  const VolumeFileWriteOptions& options = VolumeFileWriteOptions(),
  Interrupter& interrupter = nullInterrupter());

/// Reads and validates the header, dictionaries, metadata and chunk table.
VolumeFileInfo readVolumeInfo(ByteSource& source);
VolumeFileInfo readVolumeInfo(const std::string& path);

/// Reads the header, dictionaries and table, then checks every stored chunk
/// the way readVolume does (checksum, zstd frame, colour keys), one chunk per
/// thread in memory, never the whole volume. Throws Error(CorruptData) naming
/// the first damaged part, Error(Cancelled) when interrupted.
VolumeFileInfo verifyVolume(ByteSource& source, Interrupter& interrupter = nullInterrupter());
VolumeFileInfo verifyVolume(const std::string& path, Interrupter& interrupter = nullInterrupter());

/// Reads a volume (or the chunks overlapping options.region). Throws
/// Error(CorruptData) for any invalid content, Error(OutOfMemory) when the
/// volume would exceed the limit, Error(Cancelled) when interrupted.
std::unique_ptr<DictionaryVolume> readVolume(ByteSource& source,
  const VolumeFileReadOptions& options = VolumeFileReadOptions(), Interrupter& interrupter = nullInterrupter(),
  VolumeFileInfo* info = nullptr);
std::unique_ptr<DictionaryVolume> loadVolume(const std::string& path,
  const VolumeFileReadOptions& options = VolumeFileReadOptions(), Interrupter& interrupter = nullInterrupter(),
  VolumeFileInfo* info = nullptr);

/// The 64-bit checksum of the format: FNV-1a (Fowler, Noll, Vo; IETF draft
/// draft-eastlake-fnv) applied to little-endian 64-bit words (tail bytes
/// zero-padded, length mixed in), then the splitmix64 finalizer (Steele, Lea,
/// Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014) to
/// spread every input bit. Each step is a bijection of the state, so any
/// change of a single word always changes the result.
std::uint64_t checksum64(const void* data, std::size_t n);

} // namespace lvdif
