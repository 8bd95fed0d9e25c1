// Legacy .bv import/export. Their dictionary is checked against the values
// the spec lists (original-code-spec.md 3.2/3.3); imports are checked on
// hand-written records; export -> import must be exact.
#include "lvdif/AnalyticFill.h"
#include "lvdif/LegacyBv.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace lvdif;

namespace
{
using Bytes = std::vector<std::uint8_t>;

Bytes record(std::uint16_t key, std::uint16_t colour)
{
  return { std::uint8_t(key & 0xff), std::uint8_t(key >> 8), std::uint8_t(colour & 0xff), std::uint8_t(colour >> 8) };
}

void expectCorrupt(const Bytes& b, const std::string& name, const std::string& needle)
{
  MemorySource src(b.data(), b.size());
  try
  {
    readLegacyBv(src, name);
    ADD_FAILURE() << "accepted " << name;
  }
  catch (const Error& e)
  {
    EXPECT_EQ(e.code(), ErrorCode::CorruptData) << e.what();
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}
} // namespace

TEST(LegacyBv, TheirTableHasTheSpecsValues)
{
  using legacy_bv::decodeKey;
  EXPECT_EQ(decodeKey(0), -1e-7f);
  EXPECT_EQ(decodeKey(1), 0.0f);
  EXPECT_EQ(decodeKey(2), 0.001f);
  EXPECT_EQ(decodeKey(3), -0.001f);
  EXPECT_EQ(decodeKey(2000), 1.0f);
  EXPECT_EQ(decodeKey(2001), -1.0f);
  EXPECT_EQ(decodeKey(8002), 4.001f);
  EXPECT_EQ(decodeKey(8003), -4.001f);
  EXPECT_EQ(decodeKey(8004), 4.1f);
  EXPECT_EQ(decodeKey(8005), -4.1f);
  EXPECT_EQ(decodeKey(65534), 2880.6f);
  EXPECT_EQ(decodeKey(65535), -2880.6f);
  // every other key: positive on even keys, negative on odd keys, |v| grows with the key pair
  for (int k = 4; k < 65536; ++k)
  {
    ASSERT_EQ(decodeKey(std::uint16_t(k)) > 0, k % 2 == 0) << k;
    ASSERT_GT(std::fabs(decodeKey(std::uint16_t(k))), std::fabs(decodeKey(std::uint16_t(k - 2)))) << k;
  }
}

TEST(LegacyBv, TheirEncoderFixedKeepsParityAndSaturates)
{
  using legacy_bv::encodeValue;
  EXPECT_EQ(encodeValue(1.0), 2000);  // spec 3.4: the keys of +-1.0
  EXPECT_EQ(encodeValue(-1.0), 2001);
  EXPECT_EQ(encodeValue(0.0), 0);     // zero and tiny values -> key 0 (-1e-7), as theirs
  EXPECT_EQ(encodeValue(0.0004), 0);
  EXPECT_EQ(encodeValue(-0.0004), 0);
  EXPECT_EQ(encodeValue(-0.511), 1023); // their truncation would give -0.510 (key 1021)
  EXPECT_EQ(encodeValue(4.1), 8004);
  EXPECT_EQ(encodeValue(-4.1), 8005);
  EXPECT_EQ(encodeValue(1e9), 65534);  // saturates positive (theirs wraps to 65535 = -2880.6)
  EXPECT_EQ(encodeValue(2880.66), 65534);
  EXPECT_EQ(encodeValue(-1e9), 65535);
  EXPECT_EQ(encodeValue(std::nan("")), 0);
  // every dictionary value encodes to its own key (key 1 = 0.0 -> key 0)
  for (int k = 2; k < 65536; ++k)
    ASSERT_EQ(encodeValue(legacy_bv::decodeKey(std::uint16_t(k))), k) << k;
  EXPECT_EQ(encodeValue(legacy_bv::decodeKey(1)), 0);
}

TEST(LegacyBv, ImportConvertsSignAxesAndColours)
{
  const std::int64_t n = 4;
  Bytes file;
  for (int i = 0; i < n * n * n; ++i)
  {
    const Bytes r = record(0, 0); // empty
    file.insert(file.end(), r.begin(), r.end());
  }
  auto put = [&](int x, int y, int z, std::uint16_t key, std::uint16_t colour) {
    const Bytes r = record(key, colour);
    std::copy(r.begin(), r.end(), file.begin() + 4 * (x + n * (y + n * z)));
  };
  put(1, 2, 3, 2000, 3);  // their +1.0 = one unit INSIDE, palette colour 3
  put(3, 0, 0, 2001, 12); // their -1.0 = outside, index past the default palette
  put(0, 1, 0, 8004, 0);  // their +4.1 (inside)
  put(2, 2, 2, 65535, 0); // their -2880.6 (far outside)
  MemorySource src(file.data(), file.size());
  auto v = readLegacyBv(src, "dir_x/SDF_4_test.bv");
  // X and Z swapped, sign negated, band 8 clamps
  EXPECT_FLOAT_EQ(v->sdf(3, 2, 1), -1.0f);
  EXPECT_EQ(v->get(3, 2, 1).color, 3);
  EXPECT_EQ(v->colors().color(3), legacy_bv::defaultPalette()[3]);
  EXPECT_FLOAT_EQ(v->sdf(0, 0, 3), 1.0f);
  EXPECT_EQ(v->get(0, 0, 3).color, 12);
  EXPECT_FLOAT_EQ(v->sdf(0, 1, 0), -4.1f);
  EXPECT_FLOAT_EQ(v->sdf(2, 2, 2), 8.0f);
  EXPECT_EQ(v->sdf(0, 0, 0), 0.0f); // their -1e-7 "empty" is our zero key
  EXPECT_EQ(v->colors().size(), 13u);
  LegacyBvOptions keep;
  keep.swapXZ = false;
  MemorySource src2(file.data(), file.size());
  EXPECT_FLOAT_EQ(readLegacyBv(src2, "", keep)->sdf(1, 2, 3), -1.0f);
}

TEST(LegacyBv, ImportOfExportIsExact)
{
  for (std::int64_t n : { std::int64_t(48), std::int64_t(37) })
  {
    VolumeOptions o;
    o.dims = { n, n, n };
    o.chunkEdge = 16;
    o.bandWidth = 9.5f;
    DictionaryVolume v(o);
    fillFromFunction(v, sphereSdf(0.4 * n, 0.5 * n, 0.6 * n, 0.3 * n));
    std::mt19937 rng(4);
    for (int i = 0; i < 20; ++i)
      v.colors().add(Rgba{ std::uint8_t(rng()), std::uint8_t(rng()), std::uint8_t(rng()), 255 });
    for (int i = 0; i < 3000; ++i)
    {
      const std::int64_t x = rng() % n, y = rng() % n, z = rng() % n;
      Voxel w = v.get(x, y, z);
      w.color = ColorKey(rng() % v.colors().size());
      v.set(x, y, z, w);
    }
    MemorySink sink;
    LegacyBvOptions lo;
    lo.palette = v.colors().colors();
    lo.bandWidth = 9.5f;
    lo.chunkEdge = 8; // another chunking on purpose
    writeLegacyBv(v, sink, lo);
    ASSERT_EQ(sink.buffer().size(), std::size_t(4 * n * n * n));
    MemorySource src(sink.buffer().data(), sink.buffer().size());
    auto back = readLegacyBv(src, legacy_bv::fileName(n, "sphere"), lo);
    std::int64_t bad = 0;
    for (std::int64_t z = 0; z < n; ++z)
      for (std::int64_t y = 0; y < n; ++y)
        for (std::int64_t x = 0; x < n; ++x)
          bad += back->get(x, y, z) != v.get(x, y, z);
    EXPECT_EQ(bad, 0) << "n = " << n;
    EXPECT_TRUE(back->colors() == v.colors());
    // inside is their positive: the centre voxel is on an even key
    const Bytes& b = sink.buffer();
    const std::int64_t cx = std::int64_t(0.4 * n), cy = std::int64_t(0.5 * n), cz = std::int64_t(0.6 * n);
    const std::size_t at = 4 * (cz + n * (cy + n * cx)); // X and Z swapped in the file
    EXPECT_EQ(b[at] % 2, 0);
    EXPECT_GT(legacy_bv::decodeKey(std::uint16_t(b[at] | (b[at + 1] << 8))), 0.0f);
  }
}

TEST(LegacyBv, BadSizesAndNamesAreClearErrors)
{
  expectCorrupt(Bytes(), "x.bv", "not 4*N^3");
  expectCorrupt(Bytes(4 * 27 + 2, 0), "x.bv", "not 4*N^3");
  expectCorrupt(Bytes(4 * 26, 0), "x.bv", "not 4*N^3");
  expectCorrupt(Bytes(4 * 27, 0), "/a/SDF_128_dragon.bv", "N = 128 but its size gives N = 3");
  EXPECT_EQ(legacy_bv::edgeFromName("/x/SDF_128_dragon_vrip_res2.bv"), 128);
  EXPECT_EQ(legacy_bv::edgeFromName("my_volume.bv"), -1);
  VolumeOptions o;
  o.dims = { 8, 8, 9 };
  o.chunkEdge = 4;
  DictionaryVolume notCubic(o);
  MemorySink sink;
  EXPECT_THROW(writeLegacyBv(notCubic, sink), Error);
  o.dims = { 8, 8, 8 };
  DictionaryVolume cubic(o);
  EXPECT_THROW(saveLegacyBv(cubic, ::testing::TempDir() + "SDF_16_wrong.bv"), Error);
}
