// Recorder and player: record -> text -> read -> play is bit-exact; parse
// errors name the source, line and column; the original CSV imports with axis swap and scaling.
#include "EditTestUtil.h"
#include "ErrorTestUtil.h"
#include "lvdif/AnalyticFill.h"
#include "lvdif/Editor.h"
#include "lvdif/Error.h"
#include "lvdif/Recording.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>

using namespace lvdif;

namespace
{
/// readRecording's message for the text s (a ParseError; the test fails without one).
std::string recordingErrorOf(const std::string& s)
{
  std::istringstream in(s);
  return errortest::errorMessageOf([&] { readRecording(in); }, ErrorCode::ParseError);
}

/// A volume of n^3 voxels holding a sphere, a copy of it as it was (the start
/// of every playback) and an editor on it that records.
struct RecordedSphere
{
  DictionaryVolume v;
  std::unique_ptr<DictionaryVolume> start;
  Editor e;
  RecordedSphere(std::int64_t n, const SdfFunction& sphere)
    : v(edittest::options(n, 16))
    , start((fillFromFunction(v, sphere), v.clone()))
    , e(v)
  {
    this->e.startRecording();
  }
};
} // namespace

TEST(Recording, RecordWriteReadPlayIsBitExact)
{
  RecordedSphere setup(64, sphereSdf(30, 34, 31, 17));
  DictionaryVolume& v = setup.v;
  Editor& e = setup.e;
  const std::unique_ptr<DictionaryVolume>& start = setup.start;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> pos(3, 61), rad(1.5, 8);
  for (int i = 0; i < 10; ++i)
  {
    e.brush.op = static_cast<BrushOp>(i % 3);
    e.brush.blend = i % 3 == 1 ? 2.7 : 0;
    e.brush.color = Rgba{ 10, static_cast<std::uint8_t>(25 * i), 200, 255 };
    if (i % 3 == 0)
      e.dab(Dab{ i % 2 ? BrushShape::Cube : BrushShape::Sphere, { pos(rng), pos(rng), pos(rng) }, rad(rng), {} });
    else
    {
      e.stroke.kind = static_cast<BrushKind>(1 + i % 3);
      e.stroke.radius = rad(rng);
      std::vector<BrushSample> s(4);
      for (auto& p : s)
      {
        p.position = { pos(rng), pos(rng), pos(rng) };
        p.pressure = (i % 2) ? 0.3 + 0.1 * i / 10 : -1;
        p.buttons = 1;
      }
      s.back().buttons = 0;
      ReplayDevice dev(s);
      e.pump(dev);
    }
    if (i == 5)
    {
      e.undo();
      e.undo();
      e.redo();
    }
  }
  e.applyDabs({ Dab{ BrushShape::Capsule, { 5, 5, 5 }, 3, { 40, 20, 10 } } }, BrushKind::Basic);
  const Recording rec = e.stopRecording();
  std::stringstream text;
  writeRecording(text, rec);
  const std::string first = text.str();
  EXPECT_EQ(first.rfind("LVDIF-RECORDING 2\n", 0), 0u);
  const Recording back = readRecording(text);
  std::stringstream again;
  writeRecording(again, back);
  EXPECT_EQ(again.str(), first);

  Editor player(*start);
  player.play(back);
  EXPECT_EQ(edittest::countDifferences(*start, v), 0);
}

// A Basic stroke applied as it goes (the Qt editor's Basic: the surface
// changes under the cursor, as a Drill stroke's) is recorded as kind=basic,
// the kind the user chose: the editor set Drill for it, and its recordings said
// kind=drill. It is applied as it goes and leaves the volume a Drill stroke
// through the same samples leaves, bit for bit, and its replay gives it again
// with the same kind.
TEST(Recording, ABasicStrokeAppliedAsItGoesIsRecordedAsBasic)
{
  const std::vector<std::array<double, 3>> path{ { 10, 12, 30 }, { 16, 14, 31 }, { 24, 20, 33 }, { 30, 30, 32 },
    { 36, 34, 30 } };
  auto stroke = [&](DictionaryVolume& v, BrushKind kind, bool asItGoes, std::size_t* appliedBeforeTheEnd) {
    Editor e(v);
    e.stroke.kind = kind;
    e.stroke.applyAsItGoes = asItGoes;
    e.stroke.radius = 4;
    e.startRecording();
    e.beginStroke();
    for (const auto& p : path)
    {
      BrushSample s;
      s.position = p;
      s.buttons = 1;
      *appliedBeforeTheEnd += e.addSample(s).changedChunks.size();
    }
    e.endStroke();
    return e.stopRecording();
  };
  DictionaryVolume basic(edittest::options(48, 16)), drill(edittest::options(48, 16));
  fillFromFunction(basic, sphereSdf(24, 24, 24, 14));
  fillFromFunction(drill, sphereSdf(24, 24, 24, 14));
  const std::unique_ptr<DictionaryVolume> start = basic.clone();
  std::size_t basicLive = 0, drillLive = 0;
  const Recording rb = stroke(basic, BrushKind::Basic, true, &basicLive);
  const Recording rd = stroke(drill, BrushKind::Drill, false, &drillLive);
  EXPECT_GT(basicLive, 0u); // applied while the stroke was open
  EXPECT_EQ(basicLive, drillLive);
  EXPECT_EQ(edittest::countDifferences(basic, drill), 0);
  ASSERT_EQ(rb.records.size(), 1u);
  EXPECT_EQ(rb.records[0].kind, BrushKind::Basic);
  EXPECT_EQ(rd.records[0].kind, BrushKind::Drill);
  std::stringstream text;
  writeRecording(text, rb);
  EXPECT_NE(text.str().find(" kind=basic "), std::string::npos) << text.str();
  // replayed: the same volume, and recorded again as basic
  const Recording back = readRecording(text);
  Editor player(*start);
  player.startRecording();
  player.play(back);
  EXPECT_EQ(edittest::countDifferences(*start, basic), 0);
  EXPECT_EQ(player.stopRecording().records.at(0).kind, BrushKind::Basic);
  // without applyAsItGoes a Basic stroke still waits for its end
  DictionaryVolume waits(edittest::options(48, 16));
  fillFromFunction(waits, sphereSdf(24, 24, 24, 14));
  std::size_t waitLive = 0;
  stroke(waits, BrushKind::Basic, false, &waitLive);
  EXPECT_EQ(waitLive, 0u);
  EXPECT_EQ(edittest::countDifferences(waits, basic), 0);
}

TEST(Recording, AnUndoWithNothingToUndoStopsPlayback)
{
  // The recording starts after an edit and undoes it: played on the volume it
  // started from, the undo has nothing to act on. It was skipped, and the
  // playback gave a model with the edit the session had undone.
  DictionaryVolume v(edittest::options(48, 16));
  fillFromFunction(v, sphereSdf(24, 24, 24, 12));
  Editor e(v);
  e.dab(Dab{ BrushShape::Sphere, { 24, 24, 38 }, 5, {} }); // before the recording
  auto start = v.clone();
  e.startRecording();
  e.undo();
  e.dab(Dab{ BrushShape::Sphere, { 24, 10, 24 }, 4, {} });
  const Recording rec = e.stopRecording();
  ASSERT_EQ(rec.records.size(), 2u);

  auto played = start->clone();
  Editor p(*played);
  const std::string undoRefused = errortest::errorMessageOf([&] { p.play(rec); }, ErrorCode::InvalidArgument);
  EXPECT_NE(undoRefused.find("record 1 of 2 ('undo') has nothing to undo"), std::string::npos) << undoRefused;
  EXPECT_EQ(edittest::countDifferences(*played, *start), 0); // nothing was applied before it

  // a redo with nothing to redo, after an edit that stays applied
  std::istringstream text("LVDIF-RECORDING 1\n"
                          "edit time=0 op=add shape=sphere kind=single spacing=1.6 blend=0 coloroffset=1.5 "
                          "color=1,2,3,255 dabs=1\nd 24 24 10 4\nredo time=1\n");
  Editor q(*played);
  EXPECT_THROW(q.play(readRecording(text)), Error);
  EXPECT_EQ(q.undoCount(), 1u);
  EXPECT_TRUE(q.undo());
  EXPECT_EQ(edittest::countDifferences(*played, *start), 0);
}

TEST(Recording, AnotherCanvasIsRefusedBeforePlaying)
{
  // A recording carries its canvas: played on a volume of other dimensions it
  // used to run (rc 0) with its dabs elsewhere or outside, a different model.
  DictionaryVolume v(edittest::options(48, 16));
  Editor e(v);
  e.startRecording();
  e.dab(Dab{ BrushShape::Sphere, { 40, 24, 24 }, 5, {} });
  const Recording rec = e.stopRecording();
  std::stringstream text;
  writeRecording(text, rec);
  EXPECT_EQ(text.str().rfind("LVDIF-RECORDING 2\ncanvas 48 48 48\nedit ", 0), 0u) << text.str();
  const Recording back = readRecording(text);
  EXPECT_EQ(back.canvas, (Index3{ 48, 48, 48 }));

  VolumeOptions o = edittest::options(48, 16);
  o.dims = { 48, 48, 32 };
  DictionaryVolume other(o);
  auto untouched = other.clone();
  Editor p(other);
  EXPECT_EQ(errortest::errorMessageOf([&] { p.play(back); }, ErrorCode::InvalidArgument),
    "the recording was made on a 48 x 48 x 48 canvas; this volume is 48 x 48 x 32 (nothing was played)");
  EXPECT_EQ(edittest::countDifferences(other, *untouched), 0);
  EXPECT_FALSE(p.canUndo());

  // the same canvas plays; a recording without the line (older files, CSV imports) plays anywhere
  DictionaryVolume same(edittest::options(48, 16));
  Editor q(same);
  q.play(back);
  EXPECT_EQ(edittest::countDifferences(same, v), 0);
  Recording old = back;
  old.canvas = { 0, 0, 0 };
  p.play(old);
  EXPECT_TRUE(p.canUndo());

  const auto errorOf = recordingErrorOf;
  EXPECT_EQ(errorOf("LVDIF-RECORDING 1\ncanvas 48 48\n"), "recording:2:1: expected 'canvas NX NY NZ'");
  EXPECT_EQ(errorOf("LVDIF-RECORDING 1\ncanvas 48 0 48\n"),
    "recording:2:11: canvas dimensions must be whole numbers 1..1048576, got '0'");
  EXPECT_EQ(errorOf("LVDIF-RECORDING 1\ncanvas 48 4.5 48\n"),
    "recording:2:11: canvas dimensions must be whole numbers 1..1048576, got '4.5'");
  EXPECT_EQ(errorOf("LVDIF-RECORDING 1\ncanvas 8 8 8\ncanvas 8 8 8\n"),
    "recording:3:1: the canvas line must come once, right after the version line");
  EXPECT_EQ(errorOf("LVDIF-RECORDING 1\nundo time=0\ncanvas 8 8 8\n"),
    "recording:3:1: the canvas line must come once, right after the version line");
}

// A recording of a non-cubic canvas is version 4: the editors' starter shape on such a canvas
// became a rounded box in session 24 (a sphere before), and a version 2 file cannot say which
// one it was recorded on (the editor played old ones on the box). The version read is kept.
TEST(Recording, NonCubicCanvasIsVersion4AndTheVersionReadIsKept)
{
  auto written = [](Index3 canvas, bool fill) {
    Recording r;
    r.canvas = canvas;
    if (fill)
    {
      r.records.emplace_back();
      r.records.back().type = EditRecord::Type::Fill;
    }
    std::stringstream text;
    writeRecording(text, r);
    const std::string head = text.str().substr(0, text.str().find('\n'));
    EXPECT_EQ(readRecording(text).version, head.back() - '0') << head;
    return head;
  };
  EXPECT_EQ(written({ 48, 48, 48 }, false), "LVDIF-RECORDING 2");
  EXPECT_EQ(written({ 48, 48, 48 }, true), "LVDIF-RECORDING 3");
  EXPECT_EQ(written({ 0, 0, 0 }, false), "LVDIF-RECORDING 2");
  EXPECT_EQ(written({ 64, 16, 24 }, false), "LVDIF-RECORDING 4");
  EXPECT_EQ(written({ 48, 48, 16 }, true), "LVDIF-RECORDING 4");
  std::istringstream v1("LVDIF-RECORDING 1\ncanvas 64 16 24\n");
  EXPECT_EQ(readRecording(v1).version, 1);
}

TEST(Recording, ParseErrorsNameTheLine)
{
  const auto errorOf = recordingErrorOf;
  EXPECT_EQ(errorOf("hello\n"), "recording:1:1: expected the version line 'LVDIF-RECORDING 2'");
  EXPECT_EQ(errorOf("LVDIF-RECORDING 5\n"), "recording:1:17: unsupported recording version '5'");
  const std::string head = "LVDIF-RECORDING 1\n";
  const std::string edit =
    "edit time=0 op=add shape=sphere kind=basic spacing=1.6 blend=0 coloroffset=1.5 color=1,2,3,255 dabs=2\n";
  EXPECT_EQ(errorOf(head + edit + "d 1 2 3 4\n"), "recording:3:1: recording ends 1 dab lines early");
  EXPECT_EQ(errorOf(head + edit + "d 1 2 3 4\nd 1 2 x 4\n"), "recording:4:7: dab position is not a finite number: 'x'");
  // a value out of the dabs' range is named at it (a huge radius was named at x, column 3)
  EXPECT_EQ(errorOf(head + edit + "d 1 2 3 1e300\n").rfind("recording:3:9: dab 0 radius must be a finite number in ", 0), 0u)
    << errorOf(head + edit + "d 1 2 3 1e300\n");
  EXPECT_EQ(errorOf(head + edit + "d 1 2e30 3 4\n").rfind("recording:3:3: dab 0 position must be a finite number in ", 0), 0u)
    << errorOf(head + edit + "d 1 2e30 3 4\n");
  EXPECT_EQ(errorOf(head + edit + "d 1 2 3 4\nd:capsule 1 2 3 4 5 6 7e30\n")
              .rfind("recording:4:19: dab 1 capsule end must be a finite number in ", 0),
    0u)
    << errorOf(head + edit + "d 1 2 3 4\nd:capsule 1 2 3 4 5 6 7e30\n");
  EXPECT_EQ(errorOf(head + "\n# c\nedit time=0 op=melt\n"), "recording:4:16: unknown op 'melt'");
  EXPECT_EQ(errorOf(head + "bogus time=1\n"), "recording:2:1: unknown record 'bogus'");
  // an empty file: line 1, as every position is 1-based (it said "recording:0:1")
  EXPECT_EQ(errorOf(""), "recording:1:1: empty recording (no version line)");
  EXPECT_EQ(errorOf("# only a comment\n"), "recording:1:1: empty recording (no version line)");
}

TEST(Recording, BrushValuesAreNamedAtTheirColumn)
{
  // A brush value out of its range is named at the value, as the dab values and the spacing are
  // (they were all named at column 1, the record's start: "recording:2:1: brush blend radius ...").
  const std::string head = "LVDIF-RECORDING 1\n";
  for (const std::string& field : { std::string("blend=-1"), std::string("coloroffset=-1"), std::string("rounding=-1"),
         std::string("strength=2"), std::string("strength=0"), std::string("mirrory=2e9"), std::string("mirrorz=-2e9") })
  {
    const std::string line = "edit time=0 op=add shape=sphere kind=basic spacing=1.6 " +
      std::string(field.rfind("blend", 0) == 0 ? "" : "blend=0 ") +
      (field.rfind("coloroffset", 0) == 0 ? "" : "coloroffset=1.5 ") + field + " color=1,2,3,255 dabs=1";
    const std::size_t column = line.find(field) + field.find('=') + 2; // 1-based, the value's first character
    const std::string error = recordingErrorOf(head + line + "\nd 1 2 3 4\n");
    EXPECT_EQ(error.rfind("recording:2:" + std::to_string(column) + ": ", 0), 0u) << field << ": " << error;
  }
}

TEST(Recording, MalformedFieldsAreRefusedNotGuessed)
{
  // Each of these was read as something else before: "1.5,..." as the colour
  // 1,5,190,255, a fifth component or other separators ignored, a misspelt
  // optional key ignored (the edit played with strength 1), the last of two
  // op= keys used, invert=0.5 as 1, and stray dab lines named "expected key=value".
  const auto errorOf = recordingErrorOf;
  const std::string head = "LVDIF-RECORDING 1\n";
  auto edit = [](const std::string& color, const std::string& more) {
    return "edit time=0 op=add shape=sphere kind=basic spacing=1.6 blend=0 coloroffset=1.5 color=" + color + more +
      " dabs=1\nd 1 2 3 4\n";
  };
  const std::string bad = "color must be r,g,b,a (four whole numbers 0..255), got '";
  EXPECT_EQ(errorOf(head + edit("1.5,190,255,255", "")), "recording:2:86: " + bad + "1.5,190,255,255'");
  EXPECT_EQ(errorOf(head + edit("1,2,3,4,5", "")), "recording:2:86: " + bad + "1,2,3,4,5'");
  EXPECT_EQ(errorOf(head + edit("1;2;3;4", "")), "recording:2:86: " + bad + "1;2;3;4'");
  EXPECT_EQ(errorOf(head + edit("1,2,3", "")), "recording:2:86: " + bad + "1,2,3'");
  EXPECT_EQ(errorOf(head + edit("-1,2,3,4", "")), "recording:2:86: " + bad + "-1,2,3,4'");
  EXPECT_EQ(errorOf(head + edit("1,2,3,256", "")), "recording:2:86: color components must be 0..255, got '1,2,3,256'");
  EXPECT_EQ(errorOf(head + edit("1,2,3,4", " strenght=0.5")), "recording:2:94: unknown key 'strenght' in a 'edit' record");
  EXPECT_EQ(errorOf(head + edit("1,2,3,4", " op=subtract")), "recording:2:94: key 'op' given twice");
  EXPECT_EQ(errorOf(head + edit("1,2,3,4", " invert=0.5")), "recording:2:101: invert must be 0 or 1 (got 0.5)");
  EXPECT_EQ(errorOf(head + "undo time=1 dabs=2\n"), "recording:2:13: unknown key 'dabs' in a 'undo' record");
  EXPECT_EQ(errorOf(head + edit("1,2,3,4", "") + "d 5 6 7 8\n"),
    "recording:4:1: dab line outside an edit (the edit's dabs= count is already read)");
  EXPECT_EQ(errorOf(head + "d 5 6 7 8\n"), "recording:2:1: dab line outside an edit (the edit's dabs= count is already read)");
  // the writer's own output still reads, every optional key included
  std::istringstream ok(head + edit("0,0,0,0", " rounding=2 strength=0.5 falloff=smooth invert=1 mirrorx=3 mirrory=4 mirrorz=5"));
  const Recording r = readRecording(ok);
  ASSERT_EQ(r.records.size(), 1u);
  EXPECT_EQ(r.records[0].brush.strength, 0.5);
  EXPECT_TRUE(r.records[0].brush.invert);
}

// The fill record (a script's `canvas fill|clear`, version 3) is read strictly,
// as every record; its playback is checked against the script run directly
// (Script.CanvasFillAndClearArePlayedBackFromARecording).
TEST(Recording, FillRecordsNeedVersion3AndTheirKeys)
{
  const auto errorOf = recordingErrorOf;
  EXPECT_EQ(errorOf("LVDIF-RECORDING 2\nfill time=0 sdf=1 color=1,2,3,4\nend records=1\n"),
    "recording:2:1: a fill record needs version 3 ('LVDIF-RECORDING 3'), this file says version 2");
  const std::string head = "LVDIF-RECORDING 3\n";
  EXPECT_EQ(errorOf(head + "fill time=0 sdf=1\n"), "recording:2:18: missing color=");
  EXPECT_EQ(errorOf(head + "fill time=0 sdf=x color=1,2,3,4\n"), "recording:2:17: sdf is not a finite number: 'x'");
  EXPECT_EQ(errorOf(head + "fill time=0 sdf=1 color=1,2,3\n"),
    "recording:2:25: color must be r,g,b,a (four whole numbers 0..255), got '1,2,3'");
  EXPECT_EQ(errorOf(head + "fill time=0 sdf=1 color=1,2,3,4 dabs=1\n"),
    "recording:2:33: unknown key 'dabs' in a 'fill' record");
  std::istringstream in(head + "canvas 8 8 8\nfill time=2.5 sdf=-0.75 color=1,2,3,4\nend records=1\n");
  const Recording r = readRecording(in);
  ASSERT_EQ(r.records.size(), 1u);
  EXPECT_EQ(r.records[0].type, EditRecord::Type::Fill);
  EXPECT_EQ(r.records[0].time, 2.5);
  EXPECT_EQ(r.records[0].sdf, -0.75);
  EXPECT_EQ(r.records[0].brush.color, (Rgba{ 1, 2, 3, 4 }));
  std::ostringstream out;
  writeRecording(out, r);
  EXPECT_EQ(out.str(), head + "canvas 8 8 8\nfill time=2.5 sdf=-0.75 color=1,2,3,4\nend records=1\n");
}

// A recording saved with a UTF-8 byte order mark (as Windows editors save) was
// refused ("expected the version line"); scripts skip the mark, so do recordings.
TEST(Recording, AByteOrderMarkBeforeTheVersionLineIsSkipped)
{
  const std::string text = "LVDIF-RECORDING 2\nundo time=0\nend records=1\n";
  const std::string path = ::testing::TempDir() + "/bom.lvr";
  for (const std::string& before : { std::string(), std::string("# made by hand\n") })
  {
    std::ofstream(path, std::ios::binary) << "\xEF\xBB\xBF" << before << text;
    EXPECT_EQ(loadRecording(path).records.size(), 1u) << before;
    std::istringstream in("\xEF\xBB\xBF" + before + text);
    EXPECT_EQ(readRecording(in).records.size(), 1u) << before;
  }
  // only before the text: elsewhere it is the stray bytes it is
  EXPECT_EQ(recordingErrorOf("LVDIF-RECORDING 2\n\xEF\xBB\xBFundo time=0\n"),
    "recording:2:1: unknown record '\xEF\xBB\xBFundo'");
  std::remove(path.c_str());
}

TEST(Recording, ImportsTheOriginalCsvWithAxisSwapAndScaling)
{
  // synthetic rows in the original's format: kernel order (z, y, x), '-' separators
  const std::string csv =
    "time stamp,frame ID, input method, brush shape, input radius, eraser mode, color type, start time, end "
    "time,cursorVoxelPos\r\n"
    "\"2022_01_01-01:00:00.000000\",0,0,1,10,0,2,\"2022_01_01-01:00:00.000000\",\"2022_01_01-01:00:00.000000\","
    "30.000-40.000-50.000-10.000\r\n"
    "broken,row\r\n"
    "\"2022_01_01-01:00:01.000000\",1,2,0,2,1,0,\"a\",\"b\",10.500-20.000-30.000-2.000_11.000-20.000-30.000-1.000\r\n";
  std::istringstream in(csv);
  CsvImportOptions o;
  o.originalSize = 128;
  o.targetSize = 64;
  const CsvImportResult r = importOriginalCsv(in, o);
  EXPECT_EQ(r.skippedRows, 1u);
  EXPECT_EQ(r.firstProblem.rfind("line 3:", 0), 0u);
  ASSERT_EQ(r.recording.records.size(), 2u);
  const EditRecord& a = r.recording.records[0];
  EXPECT_EQ(a.kind, BrushKind::Single);
  EXPECT_EQ(a.brush.op, BrushOp::Add);
  EXPECT_EQ(a.brush.color, defaultCsvPalette()[2]);
  ASSERT_EQ(a.dabs.size(), 1u);
  EXPECT_EQ(a.dabs[0].shape, BrushShape::Cube);
  EXPECT_EQ(a.dabs[0].center, (std::array<double, 3>{ 25, 20, 15 })); // (x, y, z) = (50, 40, 30) / 2
  EXPECT_EQ(a.dabs[0].radius, 5.0);
  const EditRecord& b = r.recording.records[1];
  EXPECT_EQ(b.kind, BrushKind::Dynamic);
  EXPECT_EQ(b.brush.op, BrushOp::Subtract);
  ASSERT_EQ(b.dabs.size(), 2u);
  EXPECT_EQ(b.dabs[1].center, (std::array<double, 3>{ 15, 10, 5.5 }));
  EXPECT_EQ(b.dabs[1].radius, 0.5);
  // and it plays: the cube is there, the eraser cut a hole
  DictionaryVolume v(edittest::options(64));
  Editor e(v);
  e.play(r.recording);
  EXPECT_LT(v.sdf(25, 20, 15), 0.0f);
  EXPECT_EQ(v.colors()[v.get(25, 20, 15).color], defaultCsvPalette()[2]);
}

// A recording cut short (a copy stopped early, a full disk) at a line boundary,
// or inside the last number, played without an error: the format had no end.
// Version 2 recordings end with `end records=N`: every cut of one is refused
// naming where the end was due, and the whole file reads and plays bit for bit
// as the edits did (oracle: the volume the edits made). A version 1 file (no end
// record) plays the same, with one warning.
TEST(Recording, ACutRecordingIsRefused)
{
  RecordedSphere setup(48, sphereSdf(24, 24, 24, 10));
  DictionaryVolume& v = setup.v;
  Editor& e = setup.e;
  const std::unique_ptr<DictionaryVolume>& start = setup.start;
  for (int i = 0; i < 11; ++i)
    e.dab(Dab{ BrushShape::Sphere, { 10.25 + 2.5 * i, 24.5, 30.125 }, 3.5 + 0.125 * i, {} });
  e.undo();
  const Recording rec = e.stopRecording();
  ASSERT_EQ(rec.records.size(), 12u);
  std::stringstream out;
  writeRecording(out, rec);
  const std::string text = out.str();
  const std::string endLine = "end records=12\n";
  ASSERT_GE(text.size(), endLine.size());
  EXPECT_EQ(text.substr(text.size() - endLine.size()), endLine);

  std::istringstream whole(text);
  const Recording back = readRecording(whole, "whole.lvr");
  EXPECT_EQ(back.warning, "");
  auto played = start->clone();
  Editor p(*played);
  p.play(back);
  EXPECT_EQ(edittest::countDifferences(*played, v), 0);

  // every cut: at each line boundary, and one character short of each line's end
  // (inside the last number of a dab line, inside the end record's count)
  int cuts = 0;
  for (std::size_t at = text.find('\n') + 1; at < text.size(); ++at)
  {
    if (text[at] != '\n' && text[at - 1] != '\n')
      continue;
    const std::string cut = text.substr(0, text[at] == '\n' ? at - 1 : at);
    if (cut.empty() || cut.back() == ' ')
      continue;
    std::istringstream in(cut);
    const std::string error =
      errortest::errorMessageOf([&] { readRecording(in, "cut.lvr"); }, ErrorCode::ParseError);
    const bool named = error.find("the recording is cut short: no 'end records=N' line") != std::string::npos ||
      error.find("the end record counts '1' records, the recording has 12") != std::string::npos ||
      error.find("expected 'end records=N'") != std::string::npos ||
      error.find("dab lines early") != std::string::npos;
    // (a cut inside an edit line's last value is refused by that value's rule)
    const std::string last = cut.substr(cut.find_last_of('\n', cut.size() - 2) + 1);
    if (last.rfind("edit ", 0) != 0 && last.rfind("canvas ", 0) != 0)
      EXPECT_TRUE(named) << "cut at " << cut.size() << ": " << error;
    ++cuts;
  }
  EXPECT_GT(cuts, 40);
  // the exact words for a cut at the line before the end record
  EXPECT_EQ(recordingErrorOf(text.substr(0, text.size() - endLine.size())),
    "recording:26:1: the recording is cut short: no 'end records=N' line (a version 2 recording ends with one)");

  // the same records as version 1 (no end record): played as before, one warning
  std::string old = text.substr(0, text.size() - endLine.size());
  old.replace(0, std::string("LVDIF-RECORDING 2").size(), "LVDIF-RECORDING 1");
  std::istringstream oldIn(old);
  const Recording oldBack = readRecording(oldIn, "old.lvr");
  EXPECT_EQ(oldBack.warning, "old.lvr: a version 1 recording has no end record, so a cut file cannot be told from "
                             "a whole one; its 12 records are played as they are");
  auto playedOld = start->clone();
  Editor q(*playedOld);
  q.play(oldBack);
  EXPECT_EQ(edittest::countDifferences(*playedOld, v), 0);

  // the end record's own rules
  EXPECT_EQ(recordingErrorOf(old + "end records=12\n"),
    "recording:26:1: an end record needs version 2 ('LVDIF-RECORDING 2'), this file says version 1");
  EXPECT_EQ(recordingErrorOf(text + "undo time=9\n"),
    "recording:27:1: 'undo' after the end record (the end record is the last line)");
  std::istringstream commented(text + "# a comment\n\n");
  EXPECT_NO_THROW(readRecording(commented));
  EXPECT_EQ(recordingErrorOf("LVDIF-RECORDING 2\nend records=x\n"),
    "recording:2:13: the end record counts 'x' records, the recording has 0 (the file was cut or edited)");
}
