// Legacy .bv import/export (see LegacyBv.h and original-code-spec.md section 3).
#include "lvdif/LegacyBv.h"

#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace lvdif
{

namespace legacy_bv
{

float decodeKey(std::uint16_t k)
{
  // spec 3.2: positive values on even keys, negative on odd keys
  if (k == 0)
    return -1e-7f; // MinVoxel, "empty"
  if (k == 1)
    return 0.0f;
  if (k <= 8003)
    return (k % 2 == 0) ? static_cast<float>(0.001 * (k / 2)) : static_cast<float>(-0.001 * ((k - 1) / 2));
  return (k % 2 == 0) ? static_cast<float>(4.0 + 0.1 * ((k - 8002) / 2))
                      : static_cast<float>(-(4.0 + 0.1 * ((k - 8003) / 2)));
}

std::uint16_t encodeValue(double q)
{
  if (!(q == q))
    return 0;
  const double a = std::fabs(q);
  const int sign = q < 0 ? 1 : 0; // odd keys hold negative values (the parity rule)
  std::int64_t k;
  // Group A (multiples of 0.001 up to 4.001) and Group B (4.1, 4.2, ...):
  // the nearest value, with the gap between 4.001 and 4.1 split at its middle.
  if (a <= 0.5 * (4.001 + 4.1))
  {
    const std::int64_t m = std::min<std::int64_t>(std::llround(a * 1000.0), 4001);
    if (m == 0)
      return 0; // |q| < 0.0005 -> key 0 (-1e-7), as their encoder does
    k = 2 * m + sign;
  }
  else
  {
    const double j = std::min(std::max(std::round((a - 4.0) * 10.0), 1.0), 28766.0); // saturate, never wrap
    k = 8002 + 2 * static_cast<std::int64_t>(j) + sign;
  }
  return static_cast<std::uint16_t>(k);
}

std::int64_t edgeFromName(const std::string& path)
{
  const auto slash = path.find_last_of('/');
  const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  if (base.rfind("SDF_", 0) != 0)
    return -1;
  const auto end = base.find('_', 4);
  const std::string token = base.substr(4, end == std::string::npos ? std::string::npos : end - 4);
  if (token.empty() || token.size() > 9 || !std::all_of(token.begin(), token.end(), ::isdigit))
    return -1;
  return std::stoll(token);
}

std::string fileName(std::int64_t edge, const std::string& name)
{
  return "SDF_" + std::to_string(edge) + "_" + name + ".bv";
}

std::vector<Rgba> defaultPalette()
{
  const float p[11][4] = { { 0, .580f, .882f, 1 }, { .749f, .875f, .962f, 1 }, { .980f, .718f, .122f, 1 },
    { .627f, .796f, .231f, 1 }, { .925f, .322f, .596f, 1 }, { .882f, .973f, .859f, 1 }, { .067f, .655f, .592f, 1 },
    { .851f, .322f, .149f, 1 }, { .780f, .388f, .761f, 1 }, { 1, .871f, .965f, 1 }, { .392f, .392f, .392f, 1 } };
  std::vector<Rgba> out;
  for (const auto& c : p)
  {
    auto b = [](float f) { return static_cast<std::uint8_t>(std::lround(f * 255.0f)); };
    out.push_back(Rgba{ b(c[0]), b(c[1]), b(c[2]), b(c[3]) });
  }
  return out;
}

} // namespace legacy_bv

namespace
{
[[noreturn]] void corrupt(const std::string& what)
{
  throw Error(ErrorCode::CorruptData, ".bv: " + what);
}

/// Palette entries for indices 0..count-1: the given palette, then for each
/// index i past it the synthetic colour (i & 255, i >> 8, 128, 255) with blue
/// stepped up (mod 256) past colours taken earlier (the dictionary needs
/// unique colours). Two synthetic colours never meet (red and green spell
/// the index, count <= 65,536), so only a given colour of full alpha can be
/// in the way, and only of the index its red and green spell: those indices
/// step, the others take their colour as it is. (A hash set of every colour
/// made an import of a file naming index 65,534 cost 65,535 node
/// allocations.) Where all 256 blues are taken (a given palette of 256 such
/// colours), alpha steps down, so every index gets a colour.
std::vector<Rgba> paletteFor(std::vector<Rgba> palette, std::size_t count)
{
  const std::size_t given = palette.size();
  std::vector<std::uint32_t> sorted;
  std::vector<std::size_t> blocked; // indices past the palette whose colour may be taken
  for (const Rgba& c : palette)
  {
    sorted.push_back(c.packed());
    const std::size_t i = c.r | (std::size_t(c.g) << 8);
    if (c.a == 255 && i >= given && i < count)
      blocked.push_back(i);
  }
  std::sort(sorted.begin(), sorted.end());
  palette.resize(std::max(given, count));
  for (std::size_t i = given; i < count; ++i)
    palette[i] = Rgba{ static_cast<std::uint8_t>(i & 0xff), static_cast<std::uint8_t>(i >> 8), 128, 255 };
  for (const std::size_t i : blocked)
  {
    Rgba& c = palette[i];
    for (int step = 1; std::binary_search(sorted.begin(), sorted.end(), c.packed()); ++step)
    {
      c.b = static_cast<std::uint8_t>(c.b + 1);
      if (step % 256 == 0)
        c.a = static_cast<std::uint8_t>(c.a - 1);
    }
  }
  return palette;
}
} // namespace

std::int64_t legacy_bv::edgeFromSize(std::uint64_t bytes, const std::string& name)
{
  const std::uint64_t records = bytes / 4;
  std::int64_t n = static_cast<std::int64_t>(std::llround(std::cbrt(static_cast<double>(records))));
  while (n > 0 && std::uint64_t(n) * n * n > records) --n;
  while (std::uint64_t(n + 1) * (n + 1) * (n + 1) <= records) ++n;
  if (bytes == 0 || bytes % 4 != 0 || std::uint64_t(n) * n * n != records)
  {
    corrupt("size of " + std::to_string(bytes) + " bytes is not 4*N^3 (N^3 records of 4 bytes)");
  }
  const std::int64_t token = legacy_bv::edgeFromName(name);
  if (token >= 0 && token != n)
  {
    corrupt("file name says N = " + std::to_string(token) + " but its size gives N = " + std::to_string(n));
  }
  return n;
}

std::int64_t legacy_bv::edgeOfFile(const std::string& path)
{
  FileSource src(path);
  return legacy_bv::edgeFromSize(src.size(), path);
}

std::unique_ptr<DictionaryVolume> readLegacyBv(
  ByteSource& source, const std::string& name, const LegacyBvOptions& options, Interrupter& interrupter)
{
  require(options.distanceScale > 0 && std::isfinite(options.distanceScale), "distance scale must be finite and > 0");
  const std::uint64_t bytes = source.size();
  const std::int64_t n = legacy_bv::edgeFromSize(bytes, name);
  const std::uint64_t records = bytes / 4;
  VolumeOptions vo;
  vo.dims = { n, n, n };
  vo.chunkEdge = options.chunkEdge;
  vo.bandWidth = options.bandWidth;
  vo.memoryLimit = options.memoryLimit;
  auto volume = std::make_unique<DictionaryVolume>(vo);

  // their key -> our key: negate (inside-positive -> negative inside), scale, re-encode;
  // a table of all 65,536 keys once the file has more records than that
  auto convert = [&](std::uint16_t k) {
    return volume->encode(static_cast<float>(-options.distanceScale * legacy_bv::decodeKey(k)));
  };
  std::vector<SdfKey> lut(records > 65536 ? 65536 : 0);
  for (std::size_t k = 0; k < lut.size(); ++k)
    lut[k] = convert(static_cast<std::uint16_t>(k));

  const int edge = volume->chunkEdge();
  const std::uint64_t slabBytes = checkedMultiply(std::uint64_t(n) * n * 4, std::uint64_t(edge), ".bv slab");
  requireMemory(slabBytes, ".bv read buffer", volume->memoryLimit());
  std::vector<std::uint8_t> slab(static_cast<size_t>(std::min<std::uint64_t>(slabBytes, bytes)));
  interrupter.start("import .bv");
  std::uint32_t maxColor = 0;
  for (std::int64_t z0 = 0; z0 < n; z0 += edge)
  {
    interrupter.checkInterrupt();
    const std::int64_t slices = std::min<std::int64_t>(edge, n - z0);
    source.read(std::uint64_t(z0) * n * n * 4, slab.data(), static_cast<size_t>(std::uint64_t(slices) * n * n * 4));
    // the file's z-slab is our z-slab, or our x-slab when X and Z are swapped
    VoxelBox box = volume->bounds();
    const int axis = options.swapXZ ? 0 : 2;
    box.lo[axis] = z0;
    box.hi[axis] = z0 + slices - 1;
    const std::vector<std::int64_t> ids = volume->chunksInBox(box);
    std::uint32_t slabMax = 0;
    bool failed = false;
    Error failure(ErrorCode::OutOfMemory, "");
#pragma omp parallel for schedule(dynamic, 1) reduction(max : slabMax)
    for (std::size_t c = 0; c < ids.size(); ++c)
    {
      const std::int64_t id = ids[c];
      const VoxelBox b = volume->chunkBox(id);
      Voxel* d;
      try
      {
        d = volume->expandChunk(id);
      }
      catch (const Error& e)
      {
#pragma omp critical(lvdif_bv_failure)
        {
          failed = true;
          failure = e;
        }
        continue;
      }
      for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
        for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
          for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
          {
            const std::int64_t fx = options.swapXZ ? z : x, fz = options.swapXZ ? x : z;
            const std::uint8_t* r = slab.data() + 4 * (((fz - z0) * n + y) * n + fx);
            const std::uint32_t color = r[2] | (std::uint32_t(r[3]) << 8);
            slabMax = std::max(slabMax, color);
            const std::uint16_t key = static_cast<std::uint16_t>(r[0] | (r[1] << 8));
            d[volume->localIndex(x, y, z)] = Voxel{ lut.empty() ? convert(key) : lut[key], static_cast<ColorKey>(color) };
          }
      volume->tryCollapseChunk(id);
    }
    if (failed)
    {
      throw failure;
    }
    maxColor = std::max(maxColor, slabMax);
    interrupter.progress(static_cast<double>(z0 + slices) / static_cast<double>(n));
  }
  if (maxColor >= ColorDictionary::Capacity)
  {
    corrupt("colour index " + std::to_string(maxColor) + " exceeds the " + std::to_string(ColorDictionary::Capacity) +
      " colours a dictionary holds");
  }
  const std::vector<Rgba> base = options.palette.empty() ? legacy_bv::defaultPalette() : options.palette;
  const std::vector<Rgba> palette = paletteFor(base, std::max<std::size_t>(base.size(), maxColor + 1));
  try
  {
    volume->colors().assign(palette);
  }
  catch (const Error& e)
  {
    throw Error(ErrorCode::InvalidArgument, std::string("palette: ") + e.what());
  }
  volume->takeDirtyChunks();
  interrupter.end();
  return volume;
}

std::unique_ptr<DictionaryVolume> loadLegacyBv(
  const std::string& path, const LegacyBvOptions& options, Interrupter& interrupter)
{
  FileSource src(path);
  return readLegacyBv(src, path, options, interrupter);
}

std::string checkLegacyBvDims(const Index3& d, const std::string& path)
{
  if (d[0] != d[1] || d[1] != d[2])
    return ".bv holds only cubic volumes; this one is " + std::to_string(d[0]) + " x " + std::to_string(d[1]) + " x " +
      std::to_string(d[2]);
  const std::int64_t token = path.empty() ? -1 : legacy_bv::edgeFromName(path);
  if (token >= 0 && token != d[0])
    return "file name says N = " + std::to_string(token) + " but the volume's edge is " + std::to_string(d[0]);
  return std::string();
}

void writeLegacyBv(const DictionaryVolume& volume, ByteSink& sink, const LegacyBvOptions& options,
  Interrupter& interrupter)
{
  const Index3& d = volume.dims();
  const std::string notCubic = checkLegacyBvDims(d);
  require(notCubic.empty(), notCubic);
  require(options.distanceScale > 0 && std::isfinite(options.distanceScale), "distance scale must be finite and > 0");
  const std::int64_t n = d[0];
  std::vector<std::uint16_t> lut(65536);
  for (int k = 0; k < 65536; ++k)
    lut[k] = legacy_bv::encodeValue(-static_cast<double>(volume.decode(SdfKey(k))) / options.distanceScale);
  const std::uint64_t sliceBytes = std::uint64_t(n) * n * 4;
  requireMemory(sliceBytes, ".bv write buffer");
  std::vector<std::uint8_t> slice(static_cast<size_t>(sliceBytes));
  interrupter.start("export .bv");
  for (std::int64_t fz = 0; fz < n; ++fz)
  {
    interrupter.checkInterrupt();
#pragma omp parallel for schedule(static)
    for (std::int64_t fy = 0; fy < n; ++fy)
    {
      std::uint8_t* r = slice.data() + 4 * fy * n;
      for (std::int64_t fx = 0; fx < n; ++fx, r += 4)
      {
        const Voxel v = options.swapXZ ? volume.get(fz, fy, fx) : volume.get(fx, fy, fz);
        const std::uint16_t k = lut[v.sdf];
        r[0] = static_cast<std::uint8_t>(k & 0xff);
        r[1] = static_cast<std::uint8_t>(k >> 8);
        r[2] = static_cast<std::uint8_t>(v.color & 0xff);
        r[3] = static_cast<std::uint8_t>(v.color >> 8);
      }
    }
    sink.write(slice.data(), slice.size());
    if ((fz & 15) == 15)
      interrupter.progress(static_cast<double>(fz + 1) / static_cast<double>(n));
  }
  interrupter.progress(1.0);
  interrupter.end();
}

void saveLegacyBv(
  const DictionaryVolume& volume, const std::string& path, const LegacyBvOptions& options, Interrupter& interrupter)
{
  const std::string problem = checkLegacyBvDims(volume.dims(), path);
  require(problem.empty(), problem);
  saveAtomically(
    path, [&](ByteSink& sink) { writeLegacyBv(volume, sink, options, interrupter); });
}

} // namespace lvdif
