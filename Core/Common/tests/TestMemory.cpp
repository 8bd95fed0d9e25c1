#include "lvdif/Memory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>
#include <memory>
#include <vector>

using namespace lvdif;

// resizeLarge is resize() with a hint to the kernel: the same elements
// (value-initialized, old ones kept) whatever the kernel does with the hint.
TEST(Memory, ResizeLargeIsResize)
{
  struct Rec
  {
    std::array<double, 5> v{};
    std::uint32_t id = 7;
  };
  for (std::size_t n : { std::size_t(0), std::size_t(3), std::size_t(1) << 20 }) // 0, tiny, 48 MB
  {
    std::vector<Rec> a, b;
    resizeLarge(a, n);
    b.resize(n);
    ASSERT_EQ(a.size(), n);
    for (std::size_t i = 0; i < n; i += 4099)
    {
      EXPECT_EQ(a[i].id, b[i].id);
      EXPECT_EQ(a[i].v, b[i].v);
    }
  }
  std::vector<std::uint64_t> grow = { 1, 2, 3 };
  resizeLarge(grow, std::size_t(3) << 20); // 24 MB: reallocates, keeps the old ones
  ASSERT_EQ(grow.size(), std::size_t(3) << 20);
  EXPECT_EQ(grow[0], 1u);
  EXPECT_EQ(grow[2], 3u);
  EXPECT_EQ(grow[3], 0u);
  EXPECT_EQ(grow.back(), 0u);
  resizeLarge(grow, 2); // shrinking is resize too
  EXPECT_EQ(grow.size(), 2u);
  adviseHugePages(nullptr, 0); // nothing to advise: no effect
}

// A LargeVector's resizeLarge constructs the new elements on the threads:
// every one equals a value-initialized element (default member initializers
// that are not zero included), whatever the storage held before; the old
// ones are kept; every other way to grow it constructs as std::vector does.
TEST(Memory, LargeVectorResizeLargeConstructsEveryNewElement)
{
  struct Rec
  {
    std::array<double, 5> v{};
    std::int32_t left = -1;
    std::uint32_t id = 7;
  };
  const Rec fresh{};
  for (std::size_t n : { std::size_t(0), std::size_t(3), std::size_t(65537), std::size_t(1) << 20 })
  {
    LargeVector<Rec> a;
    // storage that held other bytes before: reserve, fill, shrink to 0
    a.resize(n, Rec{ { 1, 2, 3, 4, 5 }, 9, 9 });
    a.clear();
    resizeLarge(a, n);
    ASSERT_EQ(a.size(), n);
    for (std::size_t i = 0; i < n; ++i)
    {
      ASSERT_EQ(a[i].v, fresh.v) << i;
      ASSERT_EQ(a[i].left, -1) << i;
      ASSERT_EQ(a[i].id, 7u) << i;
    }
  }
  LargeVector<std::uint64_t> grow = { 1, 2, 3 };
  grow.reserve(std::size_t(4) << 20);
  std::fill(grow.data() + 3, grow.data() + grow.capacity(), ~std::uint64_t(0)); // garbage past the end
  resizeLarge(grow, std::size_t(3) << 20); // within the capacity: the garbage must be overwritten
  ASSERT_EQ(grow.size(), std::size_t(3) << 20);
  EXPECT_EQ(grow[0], 1u);
  EXPECT_EQ(grow[2], 3u);
  for (std::size_t i = 3; i < grow.size(); ++i) ASSERT_EQ(grow[i], 0u) << i;
  resizeLarge(grow, std::size_t(5) << 20); // reallocates, keeps the old ones
  EXPECT_EQ(grow[1], 2u);
  EXPECT_EQ(grow.back(), 0u);
  // plain resize and push_back construct as usual
  LargeVector<Rec> plain;
  plain.resize(5);
  plain.push_back(Rec{});
  for (const Rec& r : plain)
  {
    EXPECT_EQ(r.left, -1);
    EXPECT_EQ(r.id, 7u);
  }
  resizeLarge(grow, 2); // shrinking is resize too
  EXPECT_EQ(grow.size(), 2u);
}

TEST(Memory, PrefaultLargeMapsTheBlockOnTheThreads)
{
  // a fresh 64 MiB block is not resident until touched; after prefaultLarge
  // it is (the resident set grows by about its size), and its bytes are zero
  constexpr std::size_t n = std::size_t(64) << 20;
  std::unique_ptr<char[]> block(new char[n]); // not value-initialized: untouched
  const std::uint64_t before = residentMemoryBytes();
  prefaultLarge(block.get(), n);
  const std::uint64_t after = residentMemoryBytes();
  if (before == 0) GTEST_SKIP() << "no /proc/self/statm";
  EXPECT_GE(after, before + n * 9 / 10);
  for (std::size_t b = 0; b < n; b += 4096) ASSERT_EQ(block[b], 0);
  prefaultLarge(nullptr, 0); // nothing to touch: no effect
}

// LVDIF_MEMORY_LIMIT as a user types it: sizes with a suffix, a number too
// large for 64 bits (no limit), and text that is no size (ignored, with one
// notice). "nan", "inf" and 1e30 were cast to an integer (undefined; on x86
// 2^63 bytes), and "abc" was ignored without a word.
TEST(Memory, LimitFromTheEnvironment)
{
  const char* saved = std::getenv("LVDIF_MEMORY_LIMIT");
  const std::string keep = saved ? saved : "";
  ::unsetenv("LVDIF_MEMORY_LIMIT");
  const std::uint64_t fallback = memoryLimitBytes();
  auto with = [](const char* v) {
    ::setenv("LVDIF_MEMORY_LIMIT", v, 1);
    return memoryLimitBytes();
  };
  EXPECT_EQ(with("2G"), std::uint64_t(2) << 30);
  EXPECT_EQ(with("1.5k"), 1536u);
  EXPECT_EQ(with("1e30"), std::numeric_limits<std::uint64_t>::max());
  testing::internal::CaptureStderr();
  for (const char* bad : { "nan", "inf", "-inf", "abc", "-5", "0" })
  {
    const std::uint64_t v = with(bad);
    // the machine's own limit (its available memory changes a little between calls)
    EXPECT_LT(v, std::uint64_t(1) << 56) << bad;
    EXPECT_GT(v, fallback / 2) << bad;
  }
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("LVDIF_MEMORY_LIMIT"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err; // one notice per process
  if (saved)
    ::setenv("LVDIF_MEMORY_LIMIT", keep.c_str(), 1);
  else
    ::unsetenv("LVDIF_MEMORY_LIMIT");
}
