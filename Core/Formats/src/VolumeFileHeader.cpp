// The fixed header of the volume file and the format's checksum.
#include "VolumeFileFormat.h"

#include "lvdif/VolumeFile.h"

#include <cmath>
#include <sstream>

namespace lvdif
{

std::uint64_t checksum64(const void* data, std::size_t n)
{
  // FNV-1a over 64-bit little-endian words (offset basis and prime of FNV-64)
  constexpr std::uint64_t basis = 0xcbf29ce484222325ull, prime = 0x100000001b3ull;
  const auto* p = static_cast<const std::uint8_t*>(data);
  std::uint64_t h = basis;
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
  {
    std::uint64_t w = 0;
    for (int b = 0; b < 8; ++b) w |= static_cast<std::uint64_t>(p[i + b]) << (8 * b);
    h = (h ^ w) * prime;
  }
  std::uint64_t tail = 0;
  for (int b = 0; i < n; ++i, ++b) tail |= static_cast<std::uint64_t>(p[i]) << (8 * b);
  h = (h ^ tail) * prime;
  h = (h ^ static_cast<std::uint64_t>(n)) * prime; // "ab" + zero tail != "ab\0"
  // splitmix64 finalizer
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ull;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebull;
  h ^= h >> 31;
  return h;
}

namespace detail::volumefile
{

std::vector<std::uint8_t> encodeHeader(const FileHeader& h)
{
  LeWriter w;
  w.raw(HeaderMagic, 8);
  w.u32(h.version);
  w.u32(ByteOrderTag);
  for (int a = 0; a < 3; ++a) w.u64(static_cast<std::uint64_t>(h.options.dims[a]));
  for (int a = 0; a < 3; ++a) w.f64(h.options.origin[a]);
  for (int a = 0; a < 3; ++a) w.f64(h.options.spacing[a]);
  w.u32(static_cast<std::uint32_t>(h.options.chunkEdge));
  w.f32(h.options.bandWidth);
  w.f64(h.options.dictionary.groupALimit);
  w.f64(h.options.dictionary.stepA);
  w.f64(h.options.dictionary.stepB);
  w.u32(h.colorCount);
  w.u32(h.metadataCount);
  w.u64(h.metadataBytes);
  w.u64(h.chunkCount);
  w.u32(h.compressionLevel);
  w.u32(h.codec);
  w.u64(checksum64(w.bytes.data(), w.bytes.size()));
  return w.bytes;
}

namespace
{
[[noreturn]] void bad(const std::string& what)
{
  throw Error(ErrorCode::CorruptData, "header: " + what);
}
} // namespace

FileHeader decodeHeader(const std::uint8_t* bytes, std::size_t n)
{
  if (n < volume_file::HeaderBytes)
  {
    bad("file too short for the header");
  }
  if (std::memcmp(bytes, HeaderMagic, 8) != 0)
  {
    bad("bad magic: not an LVDIF volume file");
  }
  LeReader r(bytes, volume_file::HeaderBytes, "header");
  r.raw(8);
  FileHeader h;
  h.version = r.u32();
  const std::uint32_t order = r.u32();
  if (order != ByteOrderTag)
  {
    bad(order == 0x04030201u ? "big-endian byte order is not supported" : "bad byte order tag");
  }
  if (h.version != volume_file::Version)
  {
    bad("unsupported format version " + std::to_string(h.version) + " (this reader knows version " +
      std::to_string(volume_file::Version) + ")");
  }
  const std::uint64_t stored = [&] {
    LeReader c(bytes + volume_file::HeaderBytes - 8, 8, "header");
    return c.u64();
  }();
  if (stored != checksum64(bytes, volume_file::HeaderBytes - 8))
  {
    bad("checksum mismatch (the header is damaged)");
  }
  VolumeOptions& o = h.options;
  for (int a = 0; a < 3; ++a) o.dims[a] = static_cast<std::int64_t>(r.u64());
  for (int a = 0; a < 3; ++a) o.origin[a] = r.f64();
  for (int a = 0; a < 3; ++a) o.spacing[a] = r.f64();
  const std::uint32_t edge = r.u32();
  o.bandWidth = r.f32();
  o.dictionary.groupALimit = r.f64();
  o.dictionary.stepA = r.f64();
  o.dictionary.stepB = r.f64();
  h.colorCount = r.u32();
  h.metadataCount = r.u32();
  h.metadataBytes = r.u64();
  h.chunkCount = r.u64();
  h.compressionLevel = r.u32();
  h.codec = r.u32();

  std::ostringstream msg;
  for (int a = 0; a < 3; ++a)
  {
    if (o.dims[a] < 1 || o.dims[a] > DictionaryVolume::MaxDimension)
    {
      msg << "dimensions " << o.dims[0] << " x " << o.dims[1] << " x " << o.dims[2] << " out of range 1.."
          << DictionaryVolume::MaxDimension;
      bad(msg.str());
    }
  }
  const std::string geometry = DictionaryVolume::checkGeometry(o);
  if (!geometry.empty())
  {
    bad(geometry);
  }
  if (edge < 4 || edge > 256 || (edge & (edge - 1)) != 0)
  {
    bad("chunk edge " + std::to_string(edge) + " is not a power of two in [4, 256]");
  }
  o.chunkEdge = static_cast<int>(edge);
  if (!(o.bandWidth > 0))
  {
    bad("band width is not positive");
  }
  if (h.colorCount < 1 || h.colorCount > ColorDictionary::Capacity)
  {
    bad("colour dictionary count " + std::to_string(h.colorCount) + " out of range 1.." +
      std::to_string(ColorDictionary::Capacity));
  }
  if (h.metadataCount > volume_file::MaxMetadataEntries || h.metadataBytes > volume_file::MaxMetadataBytes)
  {
    bad("metadata of " + std::to_string(h.metadataCount) + " entries / " + std::to_string(h.metadataBytes) +
      " bytes exceeds the limits");
  }
  std::uint64_t chunks = 1;
  for (int a = 0; a < 3; ++a)
  {
    chunks *= static_cast<std::uint64_t>((o.dims[a] + o.chunkEdge - 1) / o.chunkEdge); // < 2^60, no overflow
  }
  if (h.chunkCount != chunks)
  {
    bad("chunk count " + std::to_string(h.chunkCount) + " does not match the dimensions (expected " +
      std::to_string(chunks) + ")");
  }
  if (h.codec != ChunkCodec)
  {
    bad("unknown chunk codec " + std::to_string(h.codec));
  }
  return h;
}

} // namespace detail::volumefile
} // namespace lvdif
