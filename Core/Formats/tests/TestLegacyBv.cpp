// Legacy .bv import/export. Their dictionary is checked against the values
// the spec lists (original-code-spec.md 3.2/3.3); imports are checked on
// hand-written records; export -> import must be exact.
#include "ErrorTestUtil.h"
#include "lvdif/AnalyticFill.h"
#include "lvdif/LegacyBv.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

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
  const std::string message = errortest::errorMessageOf([&] { readLegacyBv(src, name); }, ErrorCode::CorruptData);
  EXPECT_NE(message.find(needle), std::string::npos) << name << ": " << message;
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

namespace
{
/// The palette rule as first written (LegacyBv.h: index i past the given
/// palette gets (i & 255, i >> 8, 128, 255), blue stepped past every colour
/// taken earlier), by brute force over a set of every colour: the oracle for
/// the import's cheaper construction.
std::vector<Rgba> referencePalette(std::vector<Rgba> palette, std::size_t count)
{
  std::set<std::uint32_t> used;
  for (const Rgba& c : palette)
    used.insert(c.packed());
  for (std::size_t i = palette.size(); i < count; ++i)
  {
    Rgba c{ std::uint8_t(i & 0xff), std::uint8_t((i >> 8) & 0xff), 128, 255 };
    while (used.count(c.packed()))
      c.b = std::uint8_t(c.b + 1);
    used.insert(c.packed());
    palette.push_back(c);
  }
  return palette;
}
} // namespace

TEST(LegacyBv, ImportedPaletteMatchesTheRuleOnGeneratedFiles)
{
  std::mt19937 rng(18);
  for (int round = 0; round < 24; ++round)
  {
    const std::int64_t n = 2 + rng() % 5;
    // colour indices: small ones, and in half the rounds one near the top
    const std::uint32_t top = round % 2 ? 65534 - rng() % 300 : 1 + rng() % 2000;
    std::vector<std::uint16_t> index;
    for (std::int64_t i = 0; i < n * n * n; ++i)
      index.push_back(std::uint16_t(rng() % 4 == 0 ? rng() % (top + 1) : rng() % 12));
    index[rng() % index.size()] = std::uint16_t(top);
    Bytes file;
    for (const std::uint16_t colour : index)
    {
      const Bytes r = record(std::uint16_t(rng()), colour);
      file.insert(file.end(), r.begin(), r.end());
    }
    const std::uint32_t maxIndex = *std::max_element(index.begin(), index.end());
    LegacyBvOptions o;
    o.swapXZ = false;
    o.chunkEdge = 4;
    if (round % 3 != 0)
    {
      // a given palette that sits on synthetic colours: some indices past it
      // must step their blue once or several times
      const std::size_t size = 1 + rng() % 40;
      auto give = [&](Rgba c) {
        if (std::find(o.palette.begin(), o.palette.end(), c) == o.palette.end())
          o.palette.push_back(c);
      };
      while (o.palette.size() < size)
      {
        // an index's own blue and up to three after it, with or without a gap
        const std::uint32_t at = std::max<std::uint32_t>(rng() % (maxIndex + 1), std::uint32_t(size));
        const int run = 1 + rng() % 4, gap = rng() % 3 == 0 ? 1 : 0;
        for (int b = 0; b < run; ++b)
          give(Rgba{ std::uint8_t(at & 0xff), std::uint8_t(at >> 8), std::uint8_t(128 + b + (b ? gap : 0)), 255 });
        give(Rgba{ std::uint8_t(rng()), std::uint8_t(rng()), std::uint8_t(rng()), std::uint8_t(rng()) });
      }
    }
    MemorySource src(file.data(), file.size());
    auto v = readLegacyBv(src, "", o);
    const std::vector<Rgba> base = o.palette.empty() ? legacy_bv::defaultPalette() : o.palette;
    const std::vector<Rgba> want = referencePalette(base, std::max<std::size_t>(base.size(), maxIndex + 1));
    ASSERT_TRUE(v->colors().colors() == want) << "round " << round;
    for (std::int64_t i = 0; i < n * n * n; ++i)
      ASSERT_EQ(v->get(i % n, (i / n) % n, i / (n * n)).color, index[i]) << "round " << round;
  }
}

TEST(LegacyBv, PaletteFindsAColourWhenEveryBlueIsTaken)
{
  // a given palette holding (0, 1, b, 255) for every b: index 256 has no free
  // blue at full alpha (the first construction looped forever here)
  LegacyBvOptions o;
  o.swapXZ = false;
  for (int b = 0; b < 256; ++b)
    o.palette.push_back(Rgba{ 0, 1, std::uint8_t(b), 255 });
  const std::int64_t n = 3;
  Bytes file;
  for (std::int64_t i = 0; i < n * n * n; ++i)
  {
    const Bytes r = record(0, i == 5 ? 300 : 0);
    file.insert(file.end(), r.begin(), r.end());
  }
  MemorySource src(file.data(), file.size());
  auto v = readLegacyBv(src, "", o);
  ASSERT_EQ(v->colors().size(), 301u);
  const Rgba c = v->colors()[256];
  EXPECT_EQ(c.r, 0);
  EXPECT_EQ(c.g, 1);
  EXPECT_EQ(c.a, 254); // the next alpha down, blue back at its start
  EXPECT_EQ(c.b, 128);
  EXPECT_EQ(v->colors()[300], (Rgba{ 44, 1, 128, 255 })); // the others as usual
  EXPECT_EQ(v->get(2, 1, 0).color, 300);
}
