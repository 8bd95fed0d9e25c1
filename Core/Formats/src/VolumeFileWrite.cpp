// Writing the volume file: header, dictionaries and metadata, then the chunk
// payloads streamed in batches (compressed in parallel with OpenMP, written in
// order, so memory stays bounded by one batch), then the table and footer.
#include "VolumeFileFormat.h"

#include "lvdif/Memory.h"
#include "lvdif/VolumeFile.h"

#include <zstd.h>

#include <algorithm>
#ifdef _OPENMP
#include <omp.h>
#else // the fuzz build runs without OpenMP
static int omp_get_max_threads() { return 1; }
static int omp_get_thread_num() { return 0; }
#endif

namespace lvdif
{

namespace
{
using namespace detail::volumefile;

std::vector<std::uint8_t> dictionarySection(const DictionaryVolume& volume, const VolumeMetadata& metadata)
{
  LeWriter w;
  for (const Rgba& c : volume.colors().colors())
  {
    w.u8(c.r);
    w.u8(c.g);
    w.u8(c.b);
    w.u8(c.a);
  }
  for (const auto& kv : metadata)
  {
    w.u32(static_cast<std::uint32_t>(kv.first.size()));
    w.raw(kv.first.data(), kv.first.size());
    w.u32(static_cast<std::uint32_t>(kv.second.size()));
    w.raw(kv.second.data(), kv.second.size());
  }
  w.u64(checksum64(w.bytes.data(), w.bytes.size()));
  return w.bytes;
}

std::uint64_t metadataBytes(const VolumeMetadata& metadata)
{
  std::uint64_t n = 0;
  for (const auto& kv : metadata)
  {
    n += 8 + kv.first.size() + kv.second.size();
  }
  return n;
}

struct ZstdContext
{
  ZSTD_CCtx* ctx = ZSTD_createCCtx();
  ~ZstdContext() { ZSTD_freeCCtx(ctx); }
};
} // namespace

void checkCompressionLevel(int level, const std::string& name)
{
  require(level >= 1 && level <= 19, name + " must be a zstd level in [1, 19], not " + std::to_string(level));
}

void writeVolume(const DictionaryVolume& volume, ByteSink& sink, const VolumeFileWriteOptions& options,
  Interrupter& interrupter)
{
  checkCompressionLevel(options.compressionLevel);
  require(options.metadata.size() <= volume_file::MaxMetadataEntries &&
      metadataBytes(options.metadata) <= volume_file::MaxMetadataBytes,
    "metadata too large (at most 65536 entries and 16 MiB)");

  FileHeader h;
  h.version = volume_file::Version;
  h.options = volume.options();
  h.colorCount = static_cast<std::uint32_t>(volume.colors().size());
  h.metadataCount = static_cast<std::uint32_t>(options.metadata.size());
  h.metadataBytes = metadataBytes(options.metadata);
  h.chunkCount = static_cast<std::uint64_t>(volume.chunkCount());
  h.compressionLevel = static_cast<std::uint32_t>(options.compressionLevel);

  interrupter.start("save volume");
  const std::vector<std::uint8_t> header = encodeHeader(h);
  sink.write(header.data(), header.size());
  const std::vector<std::uint8_t> dict = dictionarySection(volume, options.metadata);
  sink.write(dict.data(), dict.size());

  const int edge = volume.chunkEdge();
  const std::size_t raw = static_cast<std::size_t>(edge) * edge * edge * sizeof(Voxel);
  const std::size_t bound = ZSTD_compressBound(raw);
  const std::int64_t n = volume.chunkCount();
  std::vector<TableEntry> table(static_cast<size_t>(n));

  // A batch holds up to 64 chunks per thread: enough to keep every core busy,
  // small enough that its buffers stay a few tens of MiB.
  const int threads = std::max(1, omp_get_max_threads());
  const std::int64_t batch = 64 * threads;
  requireMemory(checkedMultiply(static_cast<std::uint64_t>(batch), bound + raw, "save buffers"),
    "the save's compression"); // "the save's compression needs N bytes, more than the limit"
  std::vector<std::vector<std::uint8_t>> out(static_cast<size_t>(batch));
  std::vector<ZstdContext> contexts(static_cast<size_t>(threads));
  std::uint64_t offset = sink.bytesWritten();

  for (std::int64_t first = 0; first < n; first += batch)
  {
    interrupter.checkInterrupt();
    const std::int64_t last = std::min(n, first + batch);
    bool failed = false;
    std::string failure;
#pragma omp parallel num_threads(threads) if (last - first > 16)
    {
      std::vector<std::uint8_t> planes(raw);
      ZSTD_CCtx* cctx = contexts[static_cast<size_t>(omp_get_thread_num())].ctx;
#pragma omp for schedule(dynamic, 1)
      for (std::int64_t id = first; id < last; ++id)
      {
        try // no exception may leave an OpenMP region
        {
          std::vector<std::uint8_t>& buf = out[static_cast<size_t>(id - first)];
          const Voxel* data = volume.chunkData(id);
          if (!data)
          {
            buf.clear();
            continue;
          }
          const std::int64_t voxels = static_cast<std::int64_t>(edge) * edge * edge;
          ColorKey maxColor = 0;
          for (std::int64_t i = 0; i < voxels; ++i) maxColor = std::max(maxColor, data[i].color);
          if (maxColor >= h.colorCount)
          {
#pragma omp critical(lvdif_save_failure)
            {
              failed = true;
              failure = "chunk " + std::to_string(id) + " uses colour key " + std::to_string(maxColor) +
                ", which is not in the colour dictionary (" + std::to_string(h.colorCount) + " colours)";
            }
            continue;
          }
          encodeChunkPlanes(data, edge, planes.data());
          buf.resize(bound);
          const std::size_t size =
            cctx ? ZSTD_compressCCtx(cctx, buf.data(), bound, planes.data(), raw, options.compressionLevel) : 0;
          if (!cctx || ZSTD_isError(size))
          {
#pragma omp critical(lvdif_save_failure)
            {
              failed = true;
              failure = std::string("zstd failed on chunk ") + std::to_string(id) + ": " +
                (cctx ? ZSTD_getErrorName(size) : "no context");
            }
            buf.clear();
            continue;
          }
          buf.resize(size);
        }
        catch (const std::exception& e)
        {
#pragma omp critical(lvdif_save_failure)
          {
            failed = true;
            failure = "chunk " + std::to_string(id) + ": " + e.what();
          }
        }
      }
    }
    if (failed)
    {
      throw Error(ErrorCode::InvalidArgument, failure);
    }
    for (std::int64_t id = first; id < last; ++id)
    {
      TableEntry& e = table[static_cast<size_t>(id)];
      const std::vector<std::uint8_t>& buf = out[static_cast<size_t>(id - first)];
      if (volume.isUniform(id) || buf.empty())
      {
        e.uniform = packVoxel(volume.uniformValue(id));
        if (volume.uniformValue(id).color >= h.colorCount)
        {
          throw Error(ErrorCode::InvalidArgument, "chunk " + std::to_string(id) + " uses colour key " +
              std::to_string(volume.uniformValue(id).color) + ", which is not in the colour dictionary");
        }
        continue;
      }
      e.offset = offset;
      e.size = static_cast<std::uint32_t>(buf.size());
      e.checksum = checksum64(buf.data(), buf.size());
      sink.write(buf.data(), buf.size());
      offset += buf.size();
    }
    interrupter.progress(static_cast<double>(last) / static_cast<double>(n));
  }

  // table, then the footer that locates it
  LeWriter t;
  t.bytes.reserve(static_cast<size_t>(n) * volume_file::TableEntryBytes);
  for (const TableEntry& e : table)
  {
    t.u64(e.offset);
    t.u32(e.size);
    t.u32(e.uniform);
    t.u64(e.checksum);
  }
  const std::uint64_t tableOffset = offset;
  sink.write(t.bytes.data(), t.bytes.size());
  LeWriter f;
  f.u64(tableOffset);
  f.u64(tableOffset + t.bytes.size() + volume_file::FooterBytes);
  f.u64(checksum64(t.bytes.data(), t.bytes.size()));
  f.raw(FooterMagic, 8);
  sink.write(f.bytes.data(), f.bytes.size());
  interrupter.end();
}

void saveVolume(const DictionaryVolume& volume, const std::string& path, const VolumeFileWriteOptions& options,
  Interrupter& interrupter)
{
  saveAtomically(path, [&](ByteSink& sink) { writeVolume(volume, sink, options, interrupter); });
}

} // namespace lvdif
