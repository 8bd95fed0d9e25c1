// Hostile numbers and sizes for every edit input: each is refused before any
// work with one line naming the value, the volume stays bit-identical, and
// long edits can be cancelled. Inputs are generated (random extremes), the
// oracle is the untouched copy of the volume or the unbatched Core call.
#include "EditTestUtil.h"
#include "ErrorTestUtil.h"
#include "SocketTestUtil.h"
#include "lvdif/AnalyticFill.h"
#include "lvdif/Editor.h"
#include "lvdif/Error.h"
#include "lvdif/InputDevice.h"
#include "lvdif/Memory.h"
#include "lvdif/Recording.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <sys/socket.h>
#include <sys/stat.h>
#include <fstream>
#include <thread>
#include <unistd.h>

using namespace lvdif;
using sockettest::connectTo;

namespace
{
double seconds(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Runs f, expects one InvalidArgument (or OutOfMemory) line, and returns it.
template <typename F>
std::string refused(F&& f)
{
  try
  {
    f();
  }
  catch (const Error& e)
  {
    EXPECT_TRUE(e.code() == ErrorCode::InvalidArgument || e.code() == ErrorCode::OutOfMemory) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_FALSE(std::string(e.what()).empty());
    return e.what();
  }
  ADD_FAILURE() << "not refused";
  return {};
}

std::vector<double> hostileNumbers(std::mt19937& rng)
{
  std::vector<double> v{ std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity(), 1e308, -1e308, 1e300, 2e7, -2e9 };
  std::uniform_real_distribution<double> e(7.5, 300);
  for (int i = 0; i < 8; ++i)
    v.push_back((i % 2 ? -1 : 1) * std::pow(10.0, e(rng)));
  return v;
}
} // namespace

TEST(EditLimits, HostileBrushNumbersAreRefusedAndChangeNothing)
{
  DictionaryVolume v(edittest::options(48, 16));
  fillFromFunction(v, sphereSdf(24, 24, 24, 12));
  const auto before = v.clone();
  Editor e(v);
  std::mt19937 rng(18);
  for (double x : hostileNumbers(rng))
  {
    SCOPED_TRACE(x);
    e.brush = BrushSettings();
    e.brush.blend = x;
    refused([&] { e.dab(Dab{ BrushShape::Sphere, { 24, 24, 24 }, 5, {} }); });
    e.brush = BrushSettings();
    e.brush.rounding = x;
    SCOPED_TRACE("rounding");
    refused([&] { e.dab(Dab{ BrushShape::Cube, { 24, 24, 24 }, 5, {} }); });
    e.brush = BrushSettings();
    if (!(std::fabs(x) <= EditLimits::MaxCoordinate))
      refused([&] { e.dab(Dab{ BrushShape::Sphere, { 24, x, 24 }, 5, {} }); });
    else
      EXPECT_NO_THROW(e.dab(Dab{ BrushShape::Sphere, { 24, x, 24 }, 5, {} })); // far away: changes nothing
    if (!(std::fabs(x) <= EditLimits::MaxSize))
      refused([&] { e.dab(Dab{ BrushShape::Sphere, { 24, 24, 24 }, x, {} }); });
    e.stroke = StrokeSettings();
    e.stroke.spacing = x > 0 && x < 1 ? x : -x;
    if (!(e.stroke.spacing >= EditLimits::MinSpacing && e.stroke.spacing <= EditLimits::MaxSize))
      refused([&] { e.beginStroke(); });
    e.stroke = StrokeSettings();
    e.stroke.radius = x;
    if (!(x > 0 && x <= EditLimits::MaxSize))
      refused([&] { e.strokeThrough({ BrushSample(), BrushSample() }); });
  }
  e.stroke = StrokeSettings();
  EXPECT_FALSE(e.strokeOpen());
  EXPECT_EQ(edittest::countDifferences(v, *before), 0);
  // the message names the value
  e.brush.blend = 1e300;
  EXPECT_NE(refused([&] { e.dab(Dab{}); }).find("blend"), std::string::npos);
  // the largest allowed blend still works (and touches the whole small volume)
  e.brush.blend = EditLimits::MaxSize;
  EXPECT_NO_THROW(e.dab(Dab{ BrushShape::Sphere, { 24, 24, 24 }, 5, {} }));
}

TEST(EditLimits, RunawayStrokesAreRefusedBeforeTheWork)
{
  DictionaryVolume v(edittest::options(64, 16));
  fillFromFunction(v, sphereSdf(32, 32, 32, 20));
  const auto before = v.clone();
  Editor e(v);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> len(1e4, 1e8);
  const std::uint64_t rss0 = residentMemoryBytes();
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < 20; ++i)
  {
    const double far = len(rng);
    // a line with a tiny spacing
    e.stroke.spacing = EditLimits::MinSpacing * (1 + i);
    BrushSample a, b;
    a.position = { 1, 2, 3 };
    b.position = { 1 + far, 2, 3 };
    const std::string m = refused([&] { e.strokeThrough({ a, b }); });
    EXPECT_NE(m.find("more than the limit"), std::string::npos) << m;
    // an interactive (socket-like) stroke to a far-away coordinate, every kind
    e.stroke.spacing = 1.6;
    e.stroke.kind = static_cast<BrushKind>(1 + i % 3);
    e.beginStroke();
    e.addSample(a);
    BrushSample c;
    c.position = { 10, 10, far };
    refused([&] { e.addSample(c); });
    e.endStroke(); // the stroke stays usable: it ends with what it had
  }
  EXPECT_LT(seconds(t0), 10.0);
  const std::uint64_t rss1 = residentMemoryBytes();
  if (rss0 > 0)
    EXPECT_LT(rss1, rss0 + (256ull << 20));
  // the volume only holds the dabs at the first samples (one per stroke)
  EXPECT_LE(e.dabsApplied(), 20u);
  (void)before;
}

TEST(EditLimits, TotalDabsAndChunkVisitsAreBudgeted)
{
  DictionaryVolume v(edittest::options(64, 8));
  Editor e(v);
  e.limits.maxTotalDabs = 500;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> p(5, 59);
  std::uint64_t refusedCount = 0;
  for (int i = 0; i < 40; ++i)
  {
    std::vector<Dab> dabs(static_cast<std::size_t>(1 + rng() % 60));
    for (auto& d : dabs)
      d = Dab{ BrushShape::Sphere, { p(rng), p(rng), p(rng) }, 2, {} };
    try
    {
      e.applyDabs(dabs, BrushKind::Basic);
    }
    catch (const Error& x)
    {
      EXPECT_EQ(x.code(), ErrorCode::InvalidArgument);
      ++refusedCount;
    }
  }
  EXPECT_LE(e.dabsApplied(), 500u);
  EXPECT_GT(refusedCount, 0u);
  // many dabs with a radius reaching every chunk of a large volume
  DictionaryVolume big(edittest::options(1024, 8));
  Editor eb(big);
  std::vector<Dab> huge(5000, Dab{ BrushShape::Sphere, { 512, 512, 512 }, 600, {} });
  const auto t0 = std::chrono::steady_clock::now();
  const std::string m = refused([&] { eb.applyDabs(huge, BrushKind::Basic); });
  EXPECT_NE(m.find("chunks"), std::string::npos) << m;
  EXPECT_LT(seconds(t0), 5.0);
  EXPECT_EQ(big.expandedChunkCount(), 0);
}

TEST(EditLimits, LongEditsCancelBetweenBatchesAndUndoRestores)
{
  // a thin band keeps each dab's reach small, so 10,000 dabs stay quick
  DictionaryVolume v(edittest::options(128, 16, 2.0f));
  fillFromFunction(v, sphereSdf(64, 64, 64, 40));
  const auto original = v.clone();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> p(4, 124);
  std::vector<Dab> dabs(10000);
  for (auto& d : dabs)
    d = Dab{ BrushShape::Sphere, { p(rng), p(rng), p(rng) }, 1.5, {} };
  // batching is bit-identical to one Core call (the oracle)
  {
    auto ref = v.clone();
    BrushSettings b;
    applyDabs(*ref, dabs, b);
    auto w = v.clone();
    Editor e(*w);
    e.applyDabs(dabs, BrushKind::Basic);
    EXPECT_EQ(edittest::countDifferences(*w, *ref), 0);
  }
  struct AfterN : Interrupter
  {
    mutable std::atomic<int> left;
    explicit AfterN(int n) : left(n) {}
    bool wasInterrupted() const override { return --this->left < 0; }
  };
  // cancelled once n batches are in (the batches' own chunk checks pass until then)
  struct AfterBatches : Interrupter
  {
    const Editor* editor = nullptr;
    std::uint64_t dabs = 0;
    bool wasInterrupted() const override { return this->editor->dabsApplied() >= this->dabs; }
  };
  for (int n : { 0, 1 })
  {
    Editor e(v);
    AfterBatches stop;
    stop.editor = &e;
    stop.dabs = std::uint64_t(n) * 4096u;
    e.interrupter = &stop;
    errortest::errorMessageOf([&] { e.applyDabs(dabs, BrushKind::Basic); }, ErrorCode::Cancelled);
    EXPECT_EQ(e.dabsApplied(), std::uint64_t(n) * 4096u);
    if (n > 0)
    {
      EXPECT_TRUE(e.undo());
    }
    EXPECT_EQ(edittest::countDifferences(v, *original), 0);
  }
  // playback of one 10,000-dab record cancels inside the record
  Recording r;
  EditRecord rec;
  rec.dabs = dabs;
  r.records.push_back(rec);
  AfterN stop(1);
  Editor e(v);
  EXPECT_THROW(e.play(r, stop), Error);
  EXPECT_LT(e.dabsApplied(), dabs.size());
  EXPECT_EQ(e.interrupter, nullptr);
}

TEST(EditLimits, RecordingsRefuseBadNumbersWithNameLineAndColumn)
{
  const std::string head = "LVDIF-RECORDING 1\n";
  const std::string edit = "edit time=0 op=add shape=sphere kind=basic spacing=1.6 blend=0 coloroffset=1.5 "
                           "color=1,2,3,255 dabs=1\n";
  auto errorOf = [](const std::string& text) {
    std::istringstream in(text);
    return errortest::errorMessageOf([&] { readRecording(in, "x.lvr"); }, ErrorCode::ParseError);
  };
  EXPECT_EQ(errorOf(head + edit + "d 1 2 3 -4\n"), "x.lvr:3:9: dab radius must be >= 0 (got -4)");
  EXPECT_EQ(errorOf(head + edit + "d 1 2 3e300 4\n"), "x.lvr:3:3: dab 0 position must be a finite number in "
                                                       "[-1e+09, 1e+09] (got 3e+300)");
  std::string big = edit;
  big.replace(big.find("blend=0"), 7, "blend=1e300");
  // at the value's column (since session 26; it was the edit line's column 1)
  const std::string blendAt = "x.lvr:2:" + std::to_string(big.find("blend=") + 7) + ": brush blend radius";
  EXPECT_NE(errorOf(head + big + "d 1 2 3 4\n").find(blendAt), std::string::npos) << errorOf(head + big + "d 1 2 3 4\n");
  std::string tiny = edit;
  tiny.replace(tiny.find("spacing=1.6"), 11, "spacing=1e-9");
  const std::string at = "x.lvr:2:" + std::to_string(tiny.find("spacing=") + 9) + ": spacing must be";
  EXPECT_EQ(errorOf(head + tiny).substr(0, at.size()), at);
  std::string many = edit;
  many.replace(many.find("dabs=1"), 6, "dabs=99999999999");
  EXPECT_NE(errorOf(head + many).find("dabs must be a count"), std::string::npos);
  EXPECT_EQ(errorOf(head + std::string(100000, 'x')), "x.lvr:2:4097: line longer than 4096 bytes");
  // random garbage lines after a good header: always one ParseError line, never a crash
  std::mt19937 rng(5);
  for (int i = 0; i < 300; ++i)
  {
    std::string g = head + edit;
    const int n = static_cast<int>(rng() % 40);
    for (int k = 0; k < n; ++k)
      g += "d -.e+1 x:=\t9"[rng() % 13];
    const std::string m = errorOf(g);
    EXPECT_EQ(m.rfind("x.lvr:", 0), 0u) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos);
  }
}

TEST(EditLimits, SocketDeviceIsBounded)
{
  for (std::size_t oversize : { SocketDevice::MaxLine + 1, std::size_t(10) << 20 })
  {
    SocketDevice dev(0);
    const int fd = connectTo(dev.port());
    ASSERT_GE(fd, 0);
    std::thread writer([&] {
      const std::string big(oversize, 'x');
      const std::string msg = "{\"pos\":[1,2,3]}\n" + big + "\n{\"pos\":[4,5,6]}\n{\"pos\":[1e300,0,0]}\n";
      std::size_t at = 0;
      while (at < msg.size())
      {
        const ssize_t n = ::send(fd, msg.data() + at, msg.size() - at, 0);
        if (n <= 0)
          break;
        at += static_cast<std::size_t>(n);
      }
      ::close(fd);
    });
    std::vector<BrushSample> got;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!dev.finished() && std::chrono::steady_clock::now() < until)
    {
      BrushSample s;
      const auto t0 = std::chrono::steady_clock::now();
      if (dev.poll(s, 20))
        got.push_back(s);
      EXPECT_LT(seconds(t0), 1.0); // one poll is bounded
      if (got.size() == 2 && dev.errorCount() >= 2)
        break;
    }
    writer.join();
    ASSERT_EQ(got.size(), 2u);
    EXPECT_EQ(got[1].position[0], 4.0);
    EXPECT_EQ(dev.errorCount(), 2u) << dev.lastError(); // one for the long line, one for 1e300
  }
  // a flood: the queue never passes its bound, and each poll returns quickly
  SocketDevice dev(0);
  const int fd = connectTo(dev.port());
  ASSERT_GE(fd, 0);
  std::thread writer([&] {
    std::string line;
    for (int i = 0; i < 2000; ++i)
      line += "{\"pos\":[1,2,3]}\n";
    for (int k = 0; k < 100; ++k)
      if (::send(fd, line.data(), line.size(), 0) <= 0)
        break;
    ::close(fd);
  });
  std::size_t n = 0;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (n < 200000 && std::chrono::steady_clock::now() < until)
  {
    BrushSample s;
    const auto t0 = std::chrono::steady_clock::now();
    n += dev.poll(s, 20) ? 1 : 0;
    EXPECT_LT(seconds(t0), 1.0);
  }
  writer.join();
  EXPECT_EQ(n, 200000u);
  EXPECT_EQ(dev.errorCount(), 0u);
}

TEST(EditLimits, LoadRecordingRefusesNonRegularFilesAndGarbageFirst)
{
  char t[] = "/tmp/lvdif-rec-XXXXXX";
  const std::string dir = ::mkdtemp(t);
  const std::string fifo = dir + "/r.lvr", big = dir + "/big.lvr";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  for (const std::string& p : { fifo, dir, std::string("/dev/zero") })
  {
    const std::string refused = errortest::errorMessageOf([&] { loadRecording(p); }, ErrorCode::IoFailure);
    EXPECT_NE(refused.find("not a regular file"), std::string::npos) << p << ": " << refused;
  }
  {
    std::ofstream f(big);
    f << "garbage that is not a recording\n";
  }
  ASSERT_EQ(::truncate(big.c_str(), off_t(3) << 30), 0); // 3 GiB, sparse
  const auto t0 = std::chrono::steady_clock::now();
  const std::string garbage = errortest::errorMessageOf([&] { loadRecording(big); }, ErrorCode::ParseError);
  EXPECT_EQ(garbage.rfind(big + ":1:1: expected the version line", 0), 0u) << garbage;
  EXPECT_LT(seconds(t0), 2.0);
  ::unlink(fifo.c_str());
  ::unlink(big.c_str());
  ::rmdir(dir.c_str());
}

TEST(EditLimits, OneLargeDabCancelsBetweenChunksAndUndoRestores)
{
  // one dab over most of the volume: the cancel is seen between its chunks
  DictionaryVolume v(edittest::options(128, 8, 3.0f));
  fillFromFunction(v, sphereSdf(64, 64, 64, 30));
  const auto original = v.clone();
  const Dab big{ BrushShape::Sphere, { 60, 70, 64 }, 50, {} };
  // the oracle of a finished dab: everything it would change
  auto full = v.clone();
  applyDabs(*full, { big }, BrushSettings());
  const std::int64_t allChanged = edittest::countDifferences(*full, *original);
  ASSERT_GT(allChanged, 10000);
  struct AfterN : Interrupter
  {
    mutable std::atomic<int> left;
    explicit AfterN(int n) : left(n) {}
    bool wasInterrupted() const override { return --this->left < 0; }
  };
  for (int n : { 0, 800 })
  {
    AfterN stop(n);
    Editor e(v);
    e.interrupter = &stop;
    errortest::errorMessageOf([&] { e.dab(big); }, ErrorCode::Cancelled);
    const std::int64_t written = edittest::countDifferences(v, *original);
    EXPECT_LT(written, allChanged) << "the dab ran to its end";
    if (n == 0)
      EXPECT_EQ(written, 0);
    else
    {
      EXPECT_GT(written, 0);
      // every chunk it wrote is whole: the voxels it changed are the finished dab's there
      EXPECT_EQ(edittest::countDifferences(v, *full) + written, allChanged);
      EXPECT_TRUE(e.undo());
    }
    EXPECT_EQ(edittest::countDifferences(v, *original), 0);
  }
}
