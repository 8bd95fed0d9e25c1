// Reading the volume file. Every field is validated against the file length,
// the memory limit and the other fields before it is used (order: header,
// footer, dictionaries and metadata, table, then payloads); the volume is
// returned only when every chunk asked for decoded and validated.
#include "VolumeFileFormat.h"

#include "lvdif/Memory.h"
#include "lvdif/VolumeFile.h"

#include <zstd.h>

#include <algorithm>

namespace lvdif
{

namespace
{
using namespace detail::volumefile;

[[noreturn]] void corrupt(const std::string& what)
{
  throw Error(ErrorCode::CorruptData, what);
}

struct ParsedFile
{
  FileHeader header;
  VolumeFileInfo info;
  std::vector<TableEntry> table;
};

ParsedFile parse(ByteSource& src, std::uint64_t memoryLimit)
{
  ParsedFile pf;
  const std::uint64_t fileBytes = src.size();
  if (fileBytes < volume_file::HeaderBytes + volume_file::FooterBytes)
  {
    corrupt("file of " + std::to_string(fileBytes) + " bytes is too short for an LVDIF volume (at least " +
      std::to_string(volume_file::HeaderBytes + volume_file::FooterBytes) + ")");
  }
  std::uint8_t hb[volume_file::HeaderBytes];
  src.read(0, hb, sizeof(hb));
  pf.header = decodeHeader(hb, sizeof(hb));
  const FileHeader& h = pf.header;

  // footer
  std::uint8_t fb[volume_file::FooterBytes];
  src.read(fileBytes - volume_file::FooterBytes, fb, sizeof(fb));
  if (std::memcmp(fb + 24, FooterMagic, 8) != 0)
  {
    corrupt("footer: end marker missing (file truncated or overwritten at its end)");
  }
  LeReader fr(fb, sizeof(fb), "footer");
  const std::uint64_t tableOffset = fr.u64();
  const std::uint64_t storedSize = fr.u64();
  const std::uint64_t tableChecksum = fr.u64();
  if (storedSize != fileBytes)
  {
    corrupt("footer: file should be " + std::to_string(storedSize) + " bytes but is " + std::to_string(fileBytes));
  }
  const std::uint64_t colourBytes = std::uint64_t(h.colorCount) * 4;
  const std::uint64_t payloadStart = volume_file::HeaderBytes + colourBytes + h.metadataBytes + 8;
  const std::uint64_t spaceForTable = fileBytes - volume_file::FooterBytes;
  if (h.chunkCount > spaceForTable / volume_file::TableEntryBytes ||
    tableOffset != spaceForTable - h.chunkCount * volume_file::TableEntryBytes || tableOffset < payloadStart)
  {
    corrupt("footer: chunk table of " + std::to_string(h.chunkCount) + " chunks does not fit the file (table offset " +
      std::to_string(tableOffset) + ", file " + std::to_string(fileBytes) + " bytes)");
  }

  // colours and metadata (bounded by the header's limits: at most ~16.3 MiB)
  std::vector<std::uint8_t> dict(static_cast<size_t>(colourBytes + h.metadataBytes + 8));
  src.read(volume_file::HeaderBytes, dict.data(), dict.size());
  {
    LeReader c(dict.data() + dict.size() - 8, 8, "dictionaries");
    if (c.u64() != checksum64(dict.data(), dict.size() - 8))
    {
      corrupt("colour dictionary / metadata: checksum mismatch");
    }
  }
  VolumeFileInfo& info = pf.info;
  info.version = h.version;
  info.options = h.options;
  info.colors.resize(h.colorCount);
  for (std::uint32_t i = 0; i < h.colorCount; ++i)
  {
    const std::uint8_t* p = dict.data() + 4 * i;
    info.colors[i] = Rgba{ p[0], p[1], p[2], p[3] };
  }
  try
  {
    ColorDictionary check;
    check.assign(info.colors); // rejects duplicates
  }
  catch (const Error& e)
  {
    corrupt(std::string("colour dictionary: ") + e.what());
  }
  LeReader m(dict.data() + colourBytes, static_cast<size_t>(h.metadataBytes), "metadata");
  for (std::uint32_t i = 0; i < h.metadataCount; ++i)
  {
    std::string kv[2];
    for (std::string& s : kv)
    {
      const std::uint32_t len = m.u32();
      const std::uint8_t* p = m.raw(len);
      s.assign(reinterpret_cast<const char*>(p), len);
    }
    if (!info.metadata.emplace(kv[0], kv[1]).second)
    {
      corrupt("metadata: duplicate key '" + kv[0] + "'");
    }
  }
  if (m.pos != m.n)
  {
    corrupt("metadata: " + std::to_string(m.n - m.pos) + " bytes left after the last entry");
  }
  try
  {
    // every 16-bit SDF key is a valid entry of any dictionary, so keys need no
    // check; a key beyond the band is legal (DictionaryVolume::set allows it)
    SdfDictionary check(h.options.dictionary);
  }
  catch (const Error& e)
  {
    corrupt(std::string("SDF dictionary parameters: ") + e.what());
  }

  // the volume's own rules on its options (DictionaryVolume::tableBytes checks
  // them all), as the header's: a band narrower than the dictionary's first step
  // passed decodeHeader and was refused here as an InvalidArgument naming no file
  // part ("band width ... is below ..."), a command line's fault to the CLI
  std::uint64_t volumeTable = 0;
  try
  {
    volumeTable = DictionaryVolume::tableBytes(h.options);
  }
  catch (const Error& e)
  {
    corrupt(std::string("header: ") + e.what());
  }
  // table: its size is bounded by the file; refuse it if the volume's own
  // table would not fit in memory anyway
  requireMemory(volumeTable + h.chunkCount * volume_file::TableEntryBytes, "chunk table of the file", memoryLimit);
  std::vector<std::uint8_t> tb(static_cast<size_t>(h.chunkCount * volume_file::TableEntryBytes));
  src.read(tableOffset, tb.data(), tb.size());
  if (checksum64(tb.data(), tb.size()) != tableChecksum)
  {
    corrupt("chunk table: checksum mismatch");
  }
  const int edge = h.options.chunkEdge;
  const std::uint64_t bound = ZSTD_compressBound(static_cast<size_t>(edge) * edge * edge * sizeof(Voxel));
  pf.table.resize(static_cast<size_t>(h.chunkCount));
  LeReader t(tb.data(), tb.size(), "chunk table");
  for (std::uint64_t id = 0; id < h.chunkCount; ++id)
  {
    TableEntry& e = pf.table[id];
    e.offset = t.u64();
    e.size = t.u32();
    e.uniform = t.u32();
    e.checksum = t.u64();
    const std::string where = "chunk " + std::to_string(id) + ": ";
    if (e.size == 0)
    {
      const Voxel v = unpackVoxel(e.uniform);
      if (v.color >= h.colorCount)
      {
        corrupt(where + "uniform colour key " + std::to_string(v.color) + " is not in the colour dictionary (" +
          std::to_string(h.colorCount) + " colours)");
      }
      ++info.uniformChunks;
      continue;
    }
    if (e.size > bound || e.offset < payloadStart || e.offset > tableOffset || e.size > tableOffset - e.offset)
    {
      corrupt(where + "payload of " + std::to_string(e.size) + " bytes at offset " + std::to_string(e.offset) +
        " lies outside the payload area [" + std::to_string(payloadStart) + ", " + std::to_string(tableOffset) + ")");
    }
    info.payloadBytes += e.size;
  }
  info.chunkCount = static_cast<std::int64_t>(h.chunkCount);
  info.fileBytes = fileBytes;
  return pf;
}

/// Decompresses one chunk into dst, validating checksum, size and keys.
void decodeChunk(ByteSource& src, const ParsedFile& pf, std::int64_t id, ZSTD_DCtx* dctx,
  std::vector<std::uint8_t>& packed, std::vector<std::uint8_t>& planes, Voxel* dst)
{
  const TableEntry& e = pf.table[static_cast<size_t>(id)];
  const std::string where = "chunk " + std::to_string(id) + ": ";
  packed.resize(e.size);
  src.read(e.offset, packed.data(), e.size);
  if (checksum64(packed.data(), packed.size()) != e.checksum)
  {
    corrupt(where + "checksum mismatch (payload damaged)");
  }
  const std::size_t raw = planes.size();
  const unsigned long long declared = ZSTD_getFrameContentSize(packed.data(), packed.size());
  if (declared != raw)
  {
    corrupt(where + "compressed frame does not declare the chunk size of " + std::to_string(raw) + " bytes");
  }
  const std::size_t got = ZSTD_decompressDCtx(dctx, planes.data(), raw, packed.data(), packed.size());
  if (ZSTD_isError(got) || got != raw)
  {
    corrupt(where + "cannot decompress (" + (ZSTD_isError(got) ? ZSTD_getErrorName(got) : "wrong size") + ")");
  }
  const int edge = pf.header.options.chunkEdge;
  decodeChunkPlanes(planes.data(), edge, dst);
  const std::int64_t n = static_cast<std::int64_t>(edge) * edge * edge;
  for (std::int64_t i = 0; i < n; ++i)
  {
    if (dst[i].color >= pf.header.colorCount)
    {
      corrupt(where + "colour key " + std::to_string(dst[i].color) + " is not in the colour dictionary");
    }
  }
}

/// Decodes and validates the chunks `wanted` (checksum, zstd frame, colour keys:
/// decodeChunk) on OpenMP threads, into `volume`'s expanded chunks, or, with
/// no volume (verifyVolume), into one scratch chunk per thread that is then
/// dropped. Throws the first failure; a cancel throws Error(Cancelled).
void decodeChunks(ByteSource& source, const ParsedFile& pf, const std::vector<std::int64_t>& wanted,
  Interrupter& interrupter, DictionaryVolume* volume)
{
  const int edge = pf.header.options.chunkEdge;
  const std::size_t voxels = static_cast<std::size_t>(edge) * edge * edge;
  const std::uint64_t raw = voxels * sizeof(Voxel);
  bool failed = false;
  Error failure(ErrorCode::CorruptData, "");
  std::int64_t done = 0;
  const std::int64_t total = static_cast<std::int64_t>(wanted.size());
#pragma omp parallel if (total > 16) // a thread team costs more than a few small chunks
  {
    ZSTD_DCtx* dctx = ZSTD_createDCtx();
    std::vector<std::uint8_t> packed, planes(static_cast<size_t>(raw));
    std::vector<Voxel> scratch(volume ? 0 : voxels);
#pragma omp for schedule(dynamic, 4)
    for (std::int64_t i = 0; i < total; ++i)
    {
      if (failed)
      {
        continue;
      }
      try
      {
        if (!dctx)
        {
          throw Error(ErrorCode::OutOfMemory, "cannot create a zstd decompression context");
        }
        const std::int64_t id = wanted[static_cast<size_t>(i)];
        decodeChunk(source, pf, id, dctx, packed, planes, volume ? volume->expandChunk(id) : scratch.data());
      }
      catch (const Error& e)
      {
#pragma omp critical(lvdif_load_failure)
        if (!failed)
        {
          failed = true;
          failure = e;
        }
      }
      catch (const std::exception& e)
      {
#pragma omp critical(lvdif_load_failure)
        if (!failed)
        {
          failed = true;
          failure = Error(ErrorCode::OutOfMemory, e.what());
        }
      }
#pragma omp critical(lvdif_load_progress)
      {
        ++done;
        if (interrupter.wasInterrupted())
        {
          failed = true;
          failure = Error(ErrorCode::Cancelled, "operation cancelled");
        }
        else if ((done & 63) == 0)
        {
          interrupter.progress(static_cast<double>(done) / static_cast<double>(total));
        }
      }
    }
    ZSTD_freeDCtx(dctx);
  }
  if (failed)
  {
    throw failure; // the caller frees a partly filled volume
  }
}
} // namespace

VolumeFileInfo readVolumeInfo(ByteSource& source)
{
  return parse(source, memoryLimitBytes()).info;
}

VolumeFileInfo readVolumeInfo(const std::string& path)
{
  FileSource src(path);
  return readVolumeInfo(src);
}

VolumeFileInfo verifyVolume(ByteSource& source, Interrupter& interrupter)
{
  interrupter.start("verify volume");
  ParsedFile pf = parse(source, memoryLimitBytes());
  std::vector<std::int64_t> stored; // the chunks with a payload: all the table's checksums
  for (std::size_t id = 0; id < pf.table.size(); ++id)
  {
    if (pf.table[id].size)
    {
      stored.push_back(static_cast<std::int64_t>(id));
    }
  }
  decodeChunks(source, pf, stored, interrupter, nullptr);
  interrupter.progress(1.0);
  interrupter.end();
  return pf.info;
}

VolumeFileInfo verifyVolume(const std::string& path, Interrupter& interrupter)
{
  FileSource src(path);
  return verifyVolume(src, interrupter);
}

std::unique_ptr<DictionaryVolume> readVolume(
  ByteSource& source, const VolumeFileReadOptions& options, Interrupter& interrupter, VolumeFileInfo* info)
{
  interrupter.start("load volume");
  const std::uint64_t limit = options.memoryLimit ? options.memoryLimit : memoryLimitBytes();
  ParsedFile pf = parse(source, limit);
  VolumeOptions vo = pf.header.options;
  vo.memoryLimit = limit;
  const int edge = vo.chunkEdge;
  const std::uint64_t raw = static_cast<std::uint64_t>(edge) * edge * edge * sizeof(Voxel);

  // which chunks to decode, and the memory they need, before allocating any
  std::vector<std::int64_t> wanted;
  {
    Index3 counts;
    for (int a = 0; a < 3; ++a) counts[a] = (vo.dims[a] + edge - 1) / edge;
    VoxelBox all;
    all.hi = { vo.dims[0] - 1, vo.dims[1] - 1, vo.dims[2] - 1 };
    const VoxelBox box = options.wholeVolume ? all : options.region.intersect(all);
    if (!box.empty())
    {
      for (std::int64_t cz = box.lo[2] / edge; cz <= box.hi[2] / edge; ++cz)
        for (std::int64_t cy = box.lo[1] / edge; cy <= box.hi[1] / edge; ++cy)
          for (std::int64_t cx = box.lo[0] / edge; cx <= box.hi[0] / edge; ++cx)
          {
            const std::int64_t id = cx + counts[0] * (cy + counts[1] * cz);
            if (pf.table[static_cast<size_t>(id)].size)
            {
              wanted.push_back(id);
            }
          }
    }
  }
  requireMemory(DictionaryVolume::tableBytes(vo) + checkedMultiply(wanted.size(), raw, "volume data"),
    "the volume read from the file", vo.memoryLimit);

  auto volume = std::make_unique<DictionaryVolume>(vo);
  volume->colors().assign(pf.info.colors);
  for (std::int64_t id = 0; id < volume->chunkCount(); ++id)
  {
    const TableEntry& e = pf.table[static_cast<size_t>(id)];
    // uniform chunks are set whether in the region or not (they cost nothing)
    volume->fillChunk(id, e.size ? volume->outsideVoxel() : unpackVoxel(e.uniform));
  }

  decodeChunks(source, pf, wanted, interrupter, volume.get());
  volume->takeDirtyChunks(); // a freshly read volume has nothing to re-mesh incrementally
  interrupter.progress(1.0);
  interrupter.end();
  if (info)
  {
    *info = pf.info;
  }
  return volume;
}

std::unique_ptr<DictionaryVolume> loadVolume(
  const std::string& path, const VolumeFileReadOptions& options, Interrupter& interrupter, VolumeFileInfo* info)
{
  FileSource src(path);
  return readVolume(src, options, interrupter, info);
}

} // namespace lvdif
