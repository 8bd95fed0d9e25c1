#include "ErrorTestUtil.h"
#include "lvdif/ColorDictionary.h"
#include "lvdif/Error.h"

#include <gtest/gtest.h>

#include <map>
#include <random>

using namespace lvdif;

static Rgba colourOf(std::uint32_t i)
{
  return Rgba::unpack(i * 2654435761u | 0xff000000u);
}

TEST(ColorDictionary, DeduplicatesAndKeepsDefault)
{
  ColorDictionary d(Rgba{ 10, 20, 30, 255 });
  EXPECT_EQ(d.size(), 1u);
  EXPECT_EQ(d.add(Rgba{ 10, 20, 30, 255 }), 0);
  const ColorKey red = d.add(Rgba{ 255, 0, 0, 255 });
  EXPECT_EQ(red, 1);
  EXPECT_EQ(d.add(Rgba{ 255, 0, 0, 255 }), red);
  EXPECT_EQ(d.add(Rgba{ 255, 0, 0, 128 }), 2); // alpha distinguishes colours
  EXPECT_EQ(d.size(), 3u);
  ColorKey k = 99;
  EXPECT_TRUE(d.find(Rgba{ 255, 0, 0, 255 }, k));
  EXPECT_EQ(k, red);
  EXPECT_FALSE(d.find(Rgba{ 1, 2, 3, 4 }, k));
  EXPECT_THROW(d.color(3), Error);
}

TEST(ColorDictionary, CapacityAndFullError)
{
  ColorDictionary d(Rgba{ 0, 0, 0, 0 });
  std::uint32_t i = 1;
  while (!d.full())
  {
    d.add(Rgba::unpack(i++));
  }
  EXPECT_EQ(d.size(), ColorDictionary::Capacity);
  EXPECT_EQ(d.color(65534).packed(), 65534u);
  // an existing colour still resolves
  EXPECT_EQ(d.add(Rgba::unpack(77)), 77);
  const std::string full = errortest::errorMessageOf([&] { d.add(Rgba{ 1, 2, 3, 200 }); }, ErrorCode::DictionaryFull);
  EXPECT_NE(full.find("full"), std::string::npos) << full;
  EXPECT_EQ(d.size(), ColorDictionary::Capacity);
}

TEST(ColorDictionary, NearestPolicyWhenFull)
{
  ColorDictionary d(Rgba{ 0, 0, 0, 255 }, ColorDictionary::FullPolicy::Nearest);
  for (std::uint32_t i = 1; d.size() < ColorDictionary::Capacity; ++i)
  {
    d.add(colourOf(i));
  }
  const Rgba probe{ 3, 1, 2, 255 };
  ColorKey dummy;
  ASSERT_FALSE(d.find(probe, dummy));
  const ColorKey k = d.add(probe);
  // brute-force nearest as the oracle
  long best = 1L << 40;
  ColorKey bestKey = 0;
  for (std::size_t i = 0; i < d.size(); ++i)
  {
    const Rgba c = d[static_cast<ColorKey>(i)];
    const long dr = c.r - 3, dg = c.g - 1, db = c.b - 2, da = c.a - 255;
    const long dist = dr * dr + dg * dg + db * db + da * da;
    if (dist < best)
    {
      best = dist;
      bestKey = static_cast<ColorKey>(i);
    }
  }
  EXPECT_EQ(k, bestKey);
  EXPECT_EQ(d.size(), ColorDictionary::Capacity);
}

TEST(ColorDictionary, AssignValidates)
{
  ColorDictionary d;
  EXPECT_THROW(d.assign({}), Error);
  EXPECT_THROW(d.assign({ Rgba{ 1, 1, 1, 1 }, Rgba{ 1, 1, 1, 1 } }), Error);
  d.assign({ Rgba{ 1, 1, 1, 1 }, Rgba{ 2, 2, 2, 2 } });
  EXPECT_EQ(d.size(), 2u);
  EXPECT_EQ(d.add(Rgba{ 2, 2, 2, 2 }), 1);
}

TEST(ColorDictionary, MatchesAMapOnRandomColours)
{
  // oracle: a std::map from packed colour to the key it got first; colours are
  // drawn from a small set (many repeats) and differ in one channel at a time
  // so that every byte of the packed value matters to the index
  std::mt19937 rng(11);
  for (int round = 0; round < 4; ++round)
  {
    ColorDictionary d(Rgba{ 0, 0, 0, 255 });
    std::map<std::uint32_t, ColorKey> oracle{ { Rgba{ 0, 0, 0, 255 }.packed(), 0 } };
    const int span = round == 0 ? 4 : 64;
    for (int i = 0; i < 40000; ++i)
    {
      Rgba c{ std::uint8_t(rng() % span), std::uint8_t(rng() % span), std::uint8_t(rng() % span),
        std::uint8_t(255 - rng() % span) };
      ColorKey found = 0;
      const auto it = oracle.find(c.packed());
      ASSERT_EQ(d.find(c, found), it != oracle.end()) << i;
      if (it != oracle.end())
        ASSERT_EQ(found, it->second);
      const ColorKey key = d.add(c);
      if (it == oracle.end())
      {
        ASSERT_EQ(key, oracle.size()) << i;
        oracle.emplace(c.packed(), key);
      }
      else
        ASSERT_EQ(key, it->second) << i;
    }
    ASSERT_EQ(d.size(), oracle.size());
    for (const auto& [packed, key] : oracle)
      ASSERT_EQ(d[key].packed(), packed);
    // after assign() (index built by the first add): some colours found by
    // find(), then every one added again keeps its key, then all found
    ColorDictionary e;
    e.assign(d.colors());
    int probed = 0;
    for (const auto& [packed, key] : oracle)
    {
      if (probed++ % 97 != 0)
        continue;
      ColorKey found = 0;
      ASSERT_TRUE(e.find(Rgba::unpack(packed), found));
      ASSERT_EQ(found, key);
    }
    ColorKey found = 0;
    EXPECT_FALSE(e.find(Rgba{ 255, 255, 255, 0 }, found));
    for (const auto& [packed, key] : oracle)
      ASSERT_EQ(e.add(Rgba::unpack(packed)), key);
    ASSERT_EQ(e.size(), oracle.size());
    for (const auto& [packed, key] : oracle)
    {
      ASSERT_TRUE(e.find(Rgba::unpack(packed), found));
      ASSERT_EQ(found, key);
    }
    EXPECT_FALSE(e.find(Rgba{ 255, 255, 255, 0 }, found));
    EXPECT_EQ(e.add(Rgba{ 255, 255, 255, 0 }), oracle.size()); // a new colour after the index is built
  }
}

TEST(ColorDictionary, AssignNamesTheFirstRepeatedKey)
{
  std::vector<Rgba> colours;
  for (std::uint32_t i = 0; i < 5000; ++i)
    colours.push_back(colourOf(i));
  colours[4321] = colours[1234];
  colours[4500] = colours[17];
  ColorDictionary d;
  const std::string repeated = errortest::errorMessageOf([&] { d.assign(colours); }, ErrorCode::CorruptData);
  EXPECT_NE(repeated.find("duplicate colour at key 4321"), std::string::npos) << repeated;
  EXPECT_EQ(d.size(), 1u); // unchanged
  ColorKey k = 0;
  EXPECT_TRUE(d.find(d[0], k));
}
