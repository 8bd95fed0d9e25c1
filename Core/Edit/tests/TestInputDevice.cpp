// Input devices: the JSON line protocol, the loopback socket, replay and script
// devices driving the editor.
#include "EditTestUtil.h"
#include "SocketTestUtil.h"
#include "lvdif/Editor.h"
#include "lvdif/InputDevice.h"

#include <gtest/gtest.h>

#include <chrono>
#include <sys/socket.h>
#include <unistd.h>

using namespace lvdif;

TEST(InputDevice, ParsesTheJsonLineProtocol)
{
  BrushSample s;
  std::string err;
  ASSERT_TRUE(parseSampleJson(
    R"( {"position": [1.5, -2, 3e1], "orientation":[2,0,0,0], "pressure":0.25, "buttons":3, "time":12.5, "extra":"x"} )",
    s, &err))
    << err;
  EXPECT_EQ(s.position, (std::array<double, 3>{ 1.5, -2, 30 }));
  EXPECT_EQ(s.orientation, (std::array<double, 4>{ 1, 0, 0, 0 })); // normalised
  EXPECT_EQ(s.pressure, 0.25);
  EXPECT_EQ(s.buttons, 3u);
  EXPECT_EQ(s.time, 12.5);
  ASSERT_TRUE(parseSampleJson(R"({"pos":[0,0,0]})", s));
  EXPECT_LT(s.pressure, 0); // absent
}

TEST(InputDevice, RejectsGarbageWithAColumn)
{
  BrushSample s;
  std::string err;
  EXPECT_FALSE(parseSampleJson("hello", s, &err));
  EXPECT_EQ(err, "column 1: expected '{'");
  EXPECT_FALSE(parseSampleJson(R"({"position":[1,2]})", s, &err));
  EXPECT_NE(err.find("3 numbers"), std::string::npos);
  EXPECT_FALSE(parseSampleJson(R"({"position":[1,2,3]} trailing)", s, &err));
  EXPECT_EQ(err, "column 22: text after the object");
  EXPECT_FALSE(parseSampleJson(R"({"position":[1,2,3],"a":{"b":1}})", s, &err));
  EXPECT_FALSE(parseSampleJson(R"({"position":[1,2,1e999]})", s, &err));
  EXPECT_FALSE(parseSampleJson(R"({"position":[1,2,3],"buttons":-1})", s, &err));
  EXPECT_FALSE(parseSampleJson(R"({"position":[1,2,3],)", s, &err));
  EXPECT_FALSE(parseSampleJson("", s, &err));
}

namespace
{
using sockettest::connectTo;

void sendAll(int fd, const std::string& s)
{
  ASSERT_EQ(::send(fd, s.data(), s.size(), 0), static_cast<ssize_t>(s.size()));
}
} // namespace

TEST(InputDevice, SocketDeviceReadsLinesAndSkipsGarbage)
{
  SocketDevice dev(0);
  ASSERT_GT(dev.port(), 0);
  const int fd = connectTo(dev.port());
  ASSERT_GE(fd, 0);
  sendAll(fd, "{\"position\":[1,2,3],\"buttons\":1}\nnot json\n{\"posi");
  sendAll(fd, "tion\":[4,5,6]}\r\n\n" + std::string(SocketDevice::MaxLine + 10, 'x') + "\n{\"pos\":[7,8,9]}\n");
  ::close(fd);
  std::vector<BrushSample> got;
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (got.size() < 3 && std::chrono::steady_clock::now() < until)
  {
    BrushSample s;
    if (dev.poll(s, 50))
      got.push_back(s);
  }
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[0].position, (std::array<double, 3>{ 1, 2, 3 }));
  EXPECT_EQ(got[0].buttons, 1u);
  EXPECT_EQ(got[1].position, (std::array<double, 3>{ 4, 5, 6 }));
  EXPECT_EQ(got[2].position, (std::array<double, 3>{ 7, 8, 9 }));
  EXPECT_EQ(dev.errorCount(), 2u); // "not json" and the over-long line
  // a second client can connect after the first left
  const int fd2 = connectTo(dev.port());
  ASSERT_GE(fd2, 0);
  sendAll(fd2, "{\"pos\":[0,0,1]}\n");
  BrushSample s;
  bool ok = false;
  for (int i = 0; i < 100 && !ok; ++i)
    ok = dev.poll(s, 50);
  ::close(fd2);
  ASSERT_TRUE(ok);
  EXPECT_EQ(s.position[2], 1.0);
}

TEST(InputDevice, ReplayDeviceDrivesStrokesLikeTheDirectCall)
{
  DictionaryVolume a(edittest::options(48)), b(edittest::options(48));
  std::vector<BrushSample> samples;
  for (int i = 0; i <= 20; ++i)
  {
    BrushSample s;
    s.position = { 8.0 + i, 20 + 0.3 * i, 24 };
    s.buttons = i < 20 ? 1u : 0u; // released on the last sample
    samples.push_back(s);
  }
  Editor ea(a), eb(b);
  ReplayDevice dev(samples);
  EXPECT_EQ(ea.pump(dev), samples.size());
  EXPECT_FALSE(ea.strokeOpen());
  EXPECT_EQ(ea.undoStack().undoCount(), 1u);
  eb.strokeThrough(samples);
  EXPECT_EQ(edittest::countDifferences(a, b), 0);
  EXPECT_LT(a.sdf(18, 23, 24), 0.0f);
}

TEST(InputDevice, ScriptDeviceDrillAppliesWhileTheButtonIsHeld)
{
  DictionaryVolume v(edittest::options(48));
  Editor e(v);
  e.stroke.kind = BrushKind::Drill;
  ScriptDevice dev([](std::uint64_t i, BrushSample& s) {
    if (i > 30)
      return false;
    s.position = { 5.0 + i, 24, 24 };
    s.buttons = 1;
    return true;
  });
  e.pump(dev, 10); // ten samples: the drill has already cut
  EXPECT_TRUE(e.strokeOpen());
  EXPECT_LT(v.sdf(10, 24, 24), 0.0f);
  e.pump(dev, 1000);
  EXPECT_FALSE(e.strokeOpen()); // device finished closes the stroke
  EXPECT_LT(v.sdf(35, 24, 24), 0.0f);
  EXPECT_EQ(e.undoStack().undoCount(), 1u);
}
