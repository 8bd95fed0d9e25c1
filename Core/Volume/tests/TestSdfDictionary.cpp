#include "lvdif/Error.h"
#include "lvdif/SdfDictionary.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace lvdif;

TEST(SdfDictionary, PaperGroupsAndRange)
{
  const SdfDictionary& d = defaultSdfDictionary();
  EXPECT_FLOAT_EQ(d.decode(d.zeroKey()), 0.0f);
  // Group A: 8003 values -4.001..4.001, Group B starts at +-4.1.
  EXPECT_FLOAT_EQ(d.decode(d.zeroKey() + 4001), 4.001f);
  EXPECT_FLOAT_EQ(d.decode(d.zeroKey() - 4001), -4.001f);
  EXPECT_FLOAT_EQ(d.decode(d.zeroKey() + 4002), 4.1f);
  EXPECT_FLOAT_EQ(d.decode(d.zeroKey() - 4002), -4.1f);
  EXPECT_FLOAT_EQ(d.minValue(), -2880.6f);
  EXPECT_FLOAT_EQ(d.maxValue(), 2880.7f);
  EXPECT_EQ(d.zeroKey(), 28766 + 4001);
}

TEST(SdfDictionary, EveryKeyRoundTripsAndOrderFollowsValues)
{
  const SdfDictionary& d = defaultSdfDictionary();
  for (int k = 0; k < SdfDictionary::KeyCount; ++k)
  {
    const SdfKey key = static_cast<SdfKey>(k);
    ASSERT_EQ(d.encode(d.decode(key)), key) << "key " << k << " value " << d.decode(key);
    if (k > 0)
    {
      ASSERT_LT(d.decode(static_cast<SdfKey>(k - 1)), d.decode(key)) << "key " << k;
    }
  }
}

TEST(SdfDictionary, KeysBelowSplitsTheKeysAtTheValue)
{
  // against counting every key: key values, values between keys, the ends, beyond them
  const SdfDictionary& d = defaultSdfDictionary();
  std::vector<float> values{ 0.0f, -0.0f, 0.0005f, -0.0005f, 4.05f, -4.05f, 2.5f, -1234.56f, d.minValue(), d.maxValue(),
    -1e9f, 1e9f, std::nextafter(d.maxValue(), 1e9f) };
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> key(0, SdfDictionary::KeyCount - 1);
  for (int i = 0; i < 20; ++i)
    values.push_back(d.decode(static_cast<SdfKey>(key(rng))));
  for (float v : values)
  {
    std::int32_t below = 0;
    for (int k = 0; k < SdfDictionary::KeyCount; ++k)
      below += d.decode(static_cast<SdfKey>(k)) < v ? 1 : 0;
    EXPECT_EQ(d.keysBelow(v), below) << "value " << v;
  }
  EXPECT_EQ(d.keysBelow(std::numeric_limits<float>::quiet_NaN()), SdfDictionary::KeyCount);
}

TEST(SdfDictionary, DenseSweepWithinDocumentedBound)
{
  const SdfDictionary& d = defaultSdfDictionary();
  const double gapBound = 0.5 * (d.firstGroupBValue() - 4.001);
  // Every 1e-4 over the whole range (about 58 million values) is too slow for a
  // unit test; a step of 3.7e-4 (incommensurate with the dictionary steps)
  // still puts ~15 samples into every Group B interval and straddles every
  // Group A tie.
  for (double x = -2881.0; x <= 2881.0; x += 3.7e-4)
  {
    const float xf = static_cast<float>(x);
    const float back = d.decode(d.encode(xf));
    const double a = std::fabs(static_cast<double>(xf));
    double bound;
    if (a <= 4.001 + 5e-4)
      bound = 5e-4;
    else if (a < d.firstGroupBValue())
      bound = gapBound;
    else if (xf >= d.minValue() && xf <= d.maxValue())
      bound = 0.05;
    else
    {
      // saturation: same sign, extreme value
      ASSERT_EQ(back, xf < 0 ? d.minValue() : d.maxValue()) << x;
      continue;
    }
    // float rounding of the decoded value adds at most a few ulps
    const double ulps = 4.0 * std::numeric_limits<float>::epsilon() * std::max(1.0, a);
    ASSERT_LE(std::fabs(back - static_cast<double>(xf)), bound + ulps) << "x=" << x;
    // sign is never lost (0 encodes to exactly 0)
    if (xf > 5e-4f) ASSERT_GT(back, 0.0f) << x;
    if (xf < -5e-4f) ASSERT_LT(back, 0.0f) << x;
  }
}

TEST(SdfDictionary, EncodeIsMonotone)
{
  const SdfDictionary& d = defaultSdfDictionary();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-3000.0f, 3000.0f);
  for (int i = 0; i < 200000; ++i)
  {
    float a = u(rng), b = u(rng);
    if (a > b) std::swap(a, b);
    ASSERT_LE(d.encode(a), d.encode(b)) << a << " " << b;
  }
}

TEST(SdfDictionary, SaturatesNeverWraps)
{
  const SdfDictionary& d = defaultSdfDictionary();
  // The original code flips +2880.65 to -2880.6; we saturate.
  EXPECT_GT(d.decode(d.encode(2880.65f)), 2880.0f);
  EXPECT_EQ(d.encode(2880.8f), SdfDictionary::KeyCount - 1);
  EXPECT_EQ(d.encode(-2880.7f), 0);
  EXPECT_EQ(d.encode(1e30f), SdfDictionary::KeyCount - 1);
  EXPECT_EQ(d.encode(std::numeric_limits<float>::infinity()), SdfDictionary::KeyCount - 1);
  EXPECT_EQ(d.encode(-1e30f), 0);
  EXPECT_EQ(d.encode(-std::numeric_limits<float>::infinity()), 0);
  EXPECT_EQ(d.encode(std::numeric_limits<float>::quiet_NaN()), SdfDictionary::KeyCount - 1);
  EXPECT_GT(d.decode(d.encode(5000.0f)), 0.0f);
}

TEST(SdfDictionary, ZeroAndTinyValuesKeepTheirSign)
{
  const SdfDictionary& d = defaultSdfDictionary();
  EXPECT_EQ(d.encode(0.0f), d.zeroKey());
  EXPECT_EQ(d.encode(-0.0f), d.zeroKey());
  EXPECT_EQ(d.encode(0.0006f), d.zeroKey() + 1);
  EXPECT_EQ(d.encode(-0.0006f), d.zeroKey() - 1);
  // the negative values the original re-encoded one step toward zero are stable here
  for (float v : { -0.251f, -0.253f, -0.502f, -0.511f, -1.004f, -2.001f })
  {
    EXPECT_FLOAT_EQ(d.decode(d.encode(v)), v);
  }
}

TEST(SdfDictionary, AdjustableGroupA)
{
  SdfDictionaryParams p;
  p.groupALimit = 8.0;
  p.stepA = 0.002;
  p.stepB = 0.25;
  SdfDictionary d(p);
  EXPECT_FLOAT_EQ(d.decode(d.encode(7.0f)), 7.0f);
  EXPECT_NEAR(d.decode(d.encode(3.0013f)), 3.0013f, 0.001 + 1e-6);
  EXPECT_FLOAT_EQ(static_cast<float>(d.firstGroupBValue()), 8.25f);
  EXPECT_NEAR(d.decode(d.encode(100.1f)), 100.1f, 0.125 + 1e-4);
}

TEST(SdfDictionary, RejectsBadParameters)
{
  SdfDictionaryParams p;
  p.stepA = 0;
  EXPECT_THROW(SdfDictionary{ p }, Error);
  p = SdfDictionaryParams();
  p.groupALimit = 100.0; // 200,001 keys for Group A alone
  EXPECT_THROW(SdfDictionary{ p }, Error);
  p = SdfDictionaryParams();
  p.stepB = 0.0001; // smaller than stepA
  EXPECT_THROW(SdfDictionary{ p }, Error);
  p = SdfDictionaryParams();
  p.stepB = std::nan("");
  EXPECT_THROW(SdfDictionary{ p }, Error);
}
