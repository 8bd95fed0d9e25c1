// Internal helpers of the volume file (docs/FORMAT.md): little-endian field
// encoding, the fixed header, table entries and the chunk codec (a byte-plane
// transform applied before zstd). Not installed; used by VolumeFile*.cpp.
#pragma once

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace lvdif
{
namespace detail::volumefile
{

constexpr char HeaderMagic[8] = { 'L', 'V', 'D', 'I', 'F', 'V', 'O', 'L' };
constexpr char FooterMagic[8] = { 'L', 'V', 'D', 'I', 'F', 'E', 'N', 'D' };
constexpr std::uint32_t ByteOrderTag = 0x01020304u;
/// Chunk codec 1: SDF keys as zigzag residuals of a planar predictor, split
/// into byte planes, then zstd (see ChunkCodec.cpp).
constexpr std::uint32_t ChunkCodec = 1;

/// Appends little-endian fields to a byte vector (independent of host order).
struct LeWriter
{
  std::vector<std::uint8_t> bytes;
  void u8(std::uint8_t v) { bytes.push_back(v); }
  void u32(std::uint32_t v)
  {
    for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void u64(std::uint64_t v)
  {
    for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void f32(float v)
  {
    std::uint32_t u;
    std::memcpy(&u, &v, 4);
    u32(u);
  }
  void f64(double v)
  {
    std::uint64_t u;
    std::memcpy(&u, &v, 8);
    u64(u);
  }
  void raw(const void* p, std::size_t n)
  {
    const auto* b = static_cast<const std::uint8_t*>(p);
    bytes.insert(bytes.end(), b, b + n);
  }
};

/// Reads little-endian fields from a buffer; running past its end throws
/// Error(CorruptData) naming the section.
struct LeReader
{
  const std::uint8_t* p;
  std::size_t n;
  std::size_t pos = 0;
  const char* section;
  LeReader(const std::uint8_t* data, std::size_t size, const char* sectionName)
    : p(data)
    , n(size)
    , section(sectionName)
  {
  }
  void need(std::size_t k) const
  {
    if (k > n - pos)
    {
      throw Error(ErrorCode::CorruptData, std::string(section) + ": ends before its fields do");
    }
  }
  std::uint32_t u32()
  {
    need(4);
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(p[pos + i]) << (8 * i);
    pos += 4;
    return v;
  }
  std::uint64_t u64()
  {
    need(8);
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(p[pos + i]) << (8 * i);
    pos += 8;
    return v;
  }
  float f32()
  {
    const std::uint32_t u = u32();
    float v;
    std::memcpy(&v, &u, 4);
    return v;
  }
  double f64()
  {
    const std::uint64_t u = u64();
    double v;
    std::memcpy(&v, &u, 8);
    return v;
  }
  const std::uint8_t* raw(std::size_t k)
  {
    need(k);
    const std::uint8_t* r = p + pos;
    pos += k;
    return r;
  }
};

inline std::uint32_t packVoxel(Voxel v)
{
  return static_cast<std::uint32_t>(v.sdf) | (static_cast<std::uint32_t>(v.color) << 16);
}
inline Voxel unpackVoxel(std::uint32_t u)
{
  return Voxel{ static_cast<SdfKey>(u & 0xffffu), static_cast<ColorKey>(u >> 16) };
}

struct TableEntry
{
  std::uint64_t offset = 0; // payload offset (0 for a uniform chunk)
  std::uint32_t size = 0;   // compressed bytes; 0 = uniform chunk
  std::uint32_t uniform = 0; // packed voxel of a uniform chunk
  std::uint64_t checksum = 0; // checksum64 of the compressed bytes (0 for uniform)
};

/// The fixed 160-byte header (layout in docs/FORMAT.md).
struct FileHeader
{
  std::uint32_t version = 0;
  VolumeOptions options;
  std::uint32_t colorCount = 0;
  std::uint32_t metadataCount = 0;
  std::uint64_t metadataBytes = 0;
  std::uint64_t chunkCount = 0;
  std::uint32_t compressionLevel = 0;
  std::uint32_t codec = ChunkCodec;
};

std::vector<std::uint8_t> encodeHeader(const FileHeader& h);
/// Validates magic, version, byte order, checksum and every field; throws
/// Error(CorruptData) with a message starting "header: ".
FileHeader decodeHeader(const std::uint8_t* bytes, std::size_t n);

/// Chunk codec 1 (lossless). `planes` holds 4*n bytes: the low bytes of the
/// SDF residuals, their high bytes, the colour keys' low bytes, high bytes.
void encodeChunkPlanes(const Voxel* voxels, int edge, std::uint8_t* planes);
void decodeChunkPlanes(const std::uint8_t* planes, int edge, Voxel* voxels);

} // namespace detail::volumefile
} // namespace lvdif
