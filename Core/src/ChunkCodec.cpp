// Chunk codec 1 of the volume file: a lossless transform that makes a chunk
// compress well with zstd.
//
// SDF keys are ordered like distances and a signed distance field is close to
// linear locally, so each key is predicted from its already-coded neighbours
// with the planar predictor a + b - c of lossless JPEG (ITU T.81, predictor 7
// in Annex H: left + up - up-left), which is exact for a linear field, and only
// the residual is stored. Residuals of a quantized smooth field are a few keys,
// so they are zigzag-mapped (small magnitude -> small number) and the low and
// high bytes are stored in separate planes, as Blosc's shuffle filter does for
// typed arrays; colour keys (mostly constant) get two planes of their own.
// Keys wrap modulo 2^16 in both directions, so any input round-trips exactly.
#include "VolumeFileFormat.h"

namespace lvdif
{
namespace detail
{

namespace
{
inline std::uint16_t predict(const std::uint16_t* k, int x, int y, int z, std::int64_t i, int edge)
{
  const std::int64_t row = edge, slab = static_cast<std::int64_t>(edge) * edge;
  int p;
  if (x > 0 && y > 0)
  {
    p = int(k[i - 1]) + int(k[i - row]) - int(k[i - row - 1]);
  }
  else if (x > 0)
  {
    p = x >= 2 ? 2 * int(k[i - 1]) - int(k[i - 2]) : int(k[i - 1]);
  }
  else if (y > 0)
  {
    p = y >= 2 ? 2 * int(k[i - row]) - int(k[i - 2 * row]) : int(k[i - row]);
  }
  else
  {
    p = z > 0 ? int(k[i - slab]) : 0;
  }
  return static_cast<std::uint16_t>(p);
}

inline std::uint16_t zigzag(std::uint16_t residual)
{
  const std::int16_t r = static_cast<std::int16_t>(residual);
  return static_cast<std::uint16_t>((static_cast<std::uint16_t>(r) << 1) ^ static_cast<std::uint16_t>(r >> 15));
}

inline std::uint16_t unzigzag(std::uint16_t z)
{
  return static_cast<std::uint16_t>((z >> 1) ^ static_cast<std::uint16_t>(-(z & 1)));
}
} // namespace

void encodeChunkPlanes(const Voxel* voxels, int edge, std::uint8_t* planes)
{
  const std::int64_t n = static_cast<std::int64_t>(edge) * edge * edge;
  std::vector<std::uint16_t> keys(static_cast<size_t>(n));
  for (std::int64_t i = 0; i < n; ++i)
  {
    keys[i] = voxels[i].sdf;
  }
  std::uint8_t *lo = planes, *hi = planes + n, *clo = planes + 2 * n, *chi = planes + 3 * n;
  std::int64_t i = 0;
  for (int z = 0; z < edge; ++z)
    for (int y = 0; y < edge; ++y)
      for (int x = 0; x < edge; ++x, ++i)
      {
        const std::uint16_t r = zigzag(static_cast<std::uint16_t>(keys[i] - predict(keys.data(), x, y, z, i, edge)));
        lo[i] = static_cast<std::uint8_t>(r & 0xff);
        hi[i] = static_cast<std::uint8_t>(r >> 8);
        clo[i] = static_cast<std::uint8_t>(voxels[i].color & 0xff);
        chi[i] = static_cast<std::uint8_t>(voxels[i].color >> 8);
      }
}

void decodeChunkPlanes(const std::uint8_t* planes, int edge, Voxel* voxels)
{
  const std::int64_t n = static_cast<std::int64_t>(edge) * edge * edge;
  std::vector<std::uint16_t> keys(static_cast<size_t>(n));
  const std::uint8_t *lo = planes, *hi = planes + n, *clo = planes + 2 * n, *chi = planes + 3 * n;
  std::int64_t i = 0;
  for (int z = 0; z < edge; ++z)
    for (int y = 0; y < edge; ++y)
      for (int x = 0; x < edge; ++x, ++i)
      {
        const std::uint16_t r = unzigzag(static_cast<std::uint16_t>(lo[i] | (hi[i] << 8)));
        keys[i] = static_cast<std::uint16_t>(predict(keys.data(), x, y, z, i, edge) + r);
        voxels[i].sdf = keys[i];
        voxels[i].color = static_cast<ColorKey>(clo[i] | (chi[i] << 8));
      }
}

} // namespace detail
} // namespace lvdif
