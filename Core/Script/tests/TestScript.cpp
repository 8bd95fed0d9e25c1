// The scripting language: expressions, control flow, exact error positions,
// step limit and cancellation, and the two shipped example scripts checked
// against analytic geometry.
#include "EditTestUtil.h"
#include "ErrorTestUtil.h"
#include "lvdif/Brush.h"
#include "lvdif/Script.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>

using namespace lvdif;

namespace
{
double valueOf(const std::string& src, const char* var = "x")
{
  ScriptRunner r;
  r.run(src);
  return r.variable(var);
}

struct Where
{
  int line = 0, column = 0;
  std::string detail;
  ErrorCode code = ErrorCode::InvalidArgument;
};

Where errorOf(const std::string& src, ScriptOptions o = ScriptOptions())
{
  ScriptRunner r(o);
  try
  {
    r.run(src);
  }
  catch (const ScriptError& e)
  {
    return Where{ e.line(), e.column(), e.detail(), e.code() };
  }
  return Where{ 0, 0, "no error", ErrorCode::InvalidArgument };
}

std::string readScript(const char* name)
{
  std::ifstream in(std::string(LVDIF_SOURCE_DIR) + "/Data/scripts/" + name);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs the bundled script Data/scripts/<name>; the canvas it made.
DictionaryVolume& runBundled(ScriptRunner& r, const char* name)
{
  const std::string src = readScript(name);
  EXPECT_FALSE(src.empty()) << name;
  r.run(src);
  if (!r.volume())
    throw std::runtime_error(std::string(name) + " made no canvas");
  return *r.volume();
}
} // namespace

TEST(Script, ArithmeticPrecedenceAndFunctions)
{
  EXPECT_EQ(valueOf("x = 1 + 2 * 3 - -4 / 2"), 9);
  EXPECT_EQ(valueOf("x = (1 + 2) * 3"), 9);
  EXPECT_EQ(valueOf("x = 7 % 3"), 1);
  EXPECT_EQ(valueOf("x = -7 % 3"), 2);
  EXPECT_EQ(valueOf("x = 2 < 3 and not (1 == 2) or 0"), 1);
  EXPECT_EQ(valueOf("x = 1 >= 2"), 0);
  EXPECT_NEAR(valueOf("x = sin(pi / 2) + cos(0) + sqrt(16) + abs(-2) + floor(2.7) + min(3, 1, 2) + max(1, 5)"),
    1 + 1 + 4 + 2 + 2 + 1 + 5, 1e-12);
  EXPECT_EQ(valueOf("let x = 2.5e1; x = x + .5"), 25.5);
}

TEST(Script, LoopsAndConditionals)
{
  EXPECT_EQ(valueOf("x = 0\nfor i in 0..5 { x = x + i }"), 10); // half-open range
  EXPECT_EQ(valueOf("x = 0\nfor i in 3..3 { x = 99 }"), 0);
  EXPECT_EQ(valueOf("x = 1\nwhile x < 100 { x = x * 2 }"), 128);
  EXPECT_EQ(valueOf("y = 5\nif y < 3 { x = 1 } else if y < 6 { x = 2 } else { x = 3 }"), 2);
  EXPECT_EQ(valueOf("y = 9\nif y < 3 {\n x = 1\n}\nelse {\n x = 3\n}"), 3);
  EXPECT_EQ(valueOf("x = 0\nif 1 { x = 4 }\nx = x + 1"), 5);
  EXPECT_EQ(valueOf("x = 0\nfor i in 0..3 { for j in 0..4 { x = x + 1 } }"), 12);
}

TEST(Script, SyntaxErrorsGiveLineAndColumn)
{
  // script, line and column of the error (0: not checked), the message
  struct Case
  {
    const char* script;
    int line, column;
    const char* detail;
  };
  const Case cases[] = {
    { "x = 1 +\n", 1, 8, "expected a value, found the end of the line" },
    { "canvas 64\n  dab 1 2\n", 2, 3, "'dab' takes 3 arguments, got 2" },
    { "color 10 20\n", 1, 1, "'color' takes 3 or 4 arguments, got 2" }, // it said "3 to 4"
    { "for i in 0..3 {\n  dab 1 2 3\n", 1, 15, "this '{' is never closed" },
    { "brush cylinder", 1, 7, "'brush' expects one of: cube, sphere; found 'cylinder'" },
    { "\n\nx = 3 $ 4", 3, 7, "unexpected character '$'" },
    { "x = 1\n   explode 1 2", 2, 4, "unknown command 'explode'" },
    { "if 1 < 2 < 3 { }", 0, 10, "comparisons cannot be chained; use 'and'" },
    { "x = (1 + 2", 1, 11, "expected ')', found the end of the script" },
    { "for in 0..3 { }", 0, 5, "'in' is a reserved word and cannot be a variable" },
    { "x = 12abc", 0, 7, "unexpected 'a' after a number" },
    { "}", 0, 0, "unexpected '}' without a matching '{'" },
    // a minus that subtracts where an argument was meant is named (it said only "takes 4 arguments, got 3")
    { "sphere 1 1 1 -1", 1, 1, "'sphere' takes 4 arguments, got 3 (the '-' at column 14, with a space before it and "
                               "none after, subtracts: separate the arguments with commas when one starts with a minus, "
                               "as in 'dab 10, -2, 5')" },
    { "sphere 1 1 1 - 1", 1, 1, "'sphere' takes 4 arguments, got 3" },
    { "sphere 1 1 1", 1, 1, "'sphere' takes 4 arguments, got 3" },
  };
  for (const Case& c : cases)
  {
    const Where w = errorOf(c.script);
    EXPECT_EQ(w.code, ErrorCode::ParseError) << c.script;
    if (c.line)
      EXPECT_EQ(w.line, c.line) << c.script;
    if (c.column)
      EXPECT_EQ(w.column, c.column) << c.script;
    EXPECT_EQ(w.detail, c.detail) << c.script;
  }
}

// A token of 100,000 characters (a number, a name) is quoted as the mesh readers quote file text:
// 40 characters then "..." (lvdif/QuotedText.h); the whole token was in the message, a 100 kB line.
TEST(Script, LongTokensAreQuotedShort)
{
  const std::string ones(100000, '1'), name(100000, 'a');
  const std::string ones40 = "'" + ones.substr(0, 40) + "...'", name40 = "'" + name.substr(0, 40) + "...'";
  EXPECT_EQ(errorOf("sphere 1 1 1 " + ones).detail, "number " + ones40 + " is out of range");
  EXPECT_EQ(errorOf("x = 1\n" + name + " 1 2").detail, "unknown command " + name40);
  EXPECT_EQ(errorOf("x = " + name).detail, "undefined variable " + name40);
  EXPECT_EQ(errorOf("x = " + name + "(1)").detail, "unknown function " + name40);
  EXPECT_EQ(errorOf("x = (1 " + name).detail, "expected ')', found " + name40);
}

TEST(Script, RunTimeErrorsGiveLineAndColumn)
{
  Where w = errorOf("x = 1\ny = x + zz");
  EXPECT_EQ(w.code, ErrorCode::InvalidArgument);
  EXPECT_EQ(w.line, 2);
  EXPECT_EQ(w.column, 9);
  EXPECT_EQ(w.detail, "undefined variable 'zz'");
  w = errorOf("y = 0\nx = 3 / y");
  EXPECT_EQ(w.line, 2);
  EXPECT_EQ(w.column, 7);
  EXPECT_EQ(w.detail, "division by zero");
  w = errorOf("x = sqrt(-1)");
  EXPECT_EQ(w.column, 5);
  // clamp's bounds reversed are named at lo (clamp(x, 10, 0) gave 10 for every x without a word)
  w = errorOf("x = 3\ny = clamp(x, 10, 0)");
  EXPECT_EQ(w.line, 2);
  EXPECT_EQ(w.column, 14);
  EXPECT_EQ(w.detail, "'clamp' takes (x, lo, hi) with lo <= hi, got lo 10 above hi 0");
  {
    std::string printed; // lo == hi is the one value
    ScriptOptions o;
    o.print = [&](const std::string& t) { printed += t + "\n"; };
    ScriptRunner equal(o);
    equal.run("print clamp(-4, 2, 2), clamp(1, 0, 3), clamp(9, 0, 3)");
    EXPECT_EQ(printed, "2 1 3\n");
  }
  w = errorOf("dab 1 2 3");
  EXPECT_EQ(w.detail, "no canvas: start with 'canvas N' (or attach a volume)");
  // an absurd canvas is refused by every volume's rule, the chunk table's memory before
  // allocating, at the statement; a caller's own bound (maxCanvasVoxels) in its words
  w = errorOf("canvas 100000 100000 100000");
  EXPECT_EQ(w.line, 1);
  EXPECT_EQ(w.detail.rfind("chunk table of a 100000 x 100000 x 100000 volume needs ", 0), 0u) << w.detail;
  ScriptOptions bounded;
  bounded.maxCanvasVoxels = 64 * 64 * 64;
  EXPECT_EQ(errorOf("canvas 65 64 64", bounded).detail,
    "canvas of 65 x 64 x 64 voxels exceeds the limit of 262144 voxels (ScriptOptions::maxCanvasVoxels)");
  // the canvas every editor makes (--new 2048, lvdif script --size 2048): a script made no
  // canvas of more than 2^32 voxels ("canvas of 2048 x 2048 x 2048 voxels exceeds the limit of 4294967296")
  {
    ScriptRunner big;
    big.run("canvas 2048\nradius 4\ndab 1000, 1000, 1000");
    const std::unique_ptr<DictionaryVolume> v = big.takeVolume();
    ASSERT_TRUE(v);
    EXPECT_EQ(v->dims(), (Index3{ 2048, 2048, 2048 }));
    EXPECT_LT(v->sdf(1000, 1000, 1000), 0.f);
    EXPECT_GT(v->sdf(1010, 1000, 1000), 0.f);
  }
  // the editors' one smallest canvas (DictionaryVolume::checkCanvasDimensions), same words
  w = errorOf("canvas 1 1 1");
  EXPECT_EQ(w.detail, DictionaryVolume::checkCanvasDimensions({ 1, 1, 1 }));
  EXPECT_NE(w.detail.find("each axis needs 2.."), std::string::npos) << w.detail;
  w = errorOf("canvas 8 0 8");
  EXPECT_EQ(w.detail, DictionaryVolume::checkCanvasDimensions({ 8, 0, 8 }));
  // the numbers asked for, not clamped ones (it said "-1 x -1 x -1" and "1048577")
  EXPECT_NE(errorOf("canvas -5").detail.find("a canvas of -5 x -5 x -5 voxels"), std::string::npos)
    << errorOf("canvas -5").detail;
  EXPECT_NE(errorOf("canvas 64, 3000000, -3").detail.find("a canvas of 64 x 3000000 x -3 voxels"), std::string::npos)
    << errorOf("canvas 64, 3000000, -3").detail;
  w = errorOf("canvas 2.5");
  EXPECT_EQ(w.detail, "canvas dimensions must be whole numbers");
  EXPECT_EQ(errorOf("canvas 2 2 2").detail, "no error");
  w = errorOf("canvas 16\nradius -2");
  EXPECT_EQ(w.line, 2);
  EXPECT_EQ(w.detail, "radius must be a finite number in (0, 1e+07] (got -2)");
  // one rule with one message at both ends and for every size argument (0 and
  // -2 said "must be > 0", 2e7 "must be a finite number in [0, 1e+07]")
  for (const char* bad : { "radius 0", "radius 2e7", "sphere 1 2 3 0", "sphere 1 2 3 2e7", "cube 1, 2, 3, -1" })
  {
    w = errorOf(std::string("canvas 16\n") + bad);
    EXPECT_EQ(w.line, 2) << bad;
    EXPECT_NE(w.detail.find("must be a finite number in (0, 1e+07] (got "), std::string::npos) << bad << ": " << w.detail;
  }
  w = errorOf("canvas 16\nbegin\npoint 1 2 3");
  EXPECT_EQ(w.line, 2);
  EXPECT_EQ(w.column, 1);
  // a bad value is named at its column, not the statement's ('color 300 0 0' said column 1)
  w = errorOf("canvas 16\n  color 10, 300, 0");
  EXPECT_EQ(w.line, 2);
  EXPECT_EQ(w.column, 13);
  EXPECT_EQ(w.detail, "colour components must be in 0..255, got 300");
  EXPECT_EQ(errorOf("canvas 16\ncolor 0 0 0 -1").column, 13);
  EXPECT_EQ(errorOf("canvas 16\nradius -2").column, 8);
  EXPECT_EQ(errorOf("canvas 16\nsphere 1 2 3 0").column, 14);
  EXPECT_EQ(errorOf("canvas 16\nblend -1").column, 7);
  EXPECT_EQ(errorOf("canvas 16\nspacing 0").column, 9);
}

TEST(Script, StepLimitStopsEndlessLoops)
{
  ScriptOptions o;
  o.maxSteps = 10000;
  const Where w = errorOf("x = 0\nwhile 1 { x = x + 1 }", o);
  EXPECT_EQ(w.line, 2);
  EXPECT_NE(w.detail.find("step limit of 10000 exceeded"), std::string::npos);
  EXPECT_EQ(w.detail, "step limit of 10000 exceeded (an endless loop?)");
  // a caller that lets the user raise the limit names how (`lvdif script --max-steps N`): a long script
  // that is no endless loop was stopped with nothing to do about it
  o.maxStepsRaisedBy = "--max-steps N";
  EXPECT_EQ(errorOf("x = 0\nwhile 1 { x = x + 1 }", o).detail,
    "step limit of 10000 exceeded (an endless loop? If not, raise the limit with --max-steps N)");
  o.maxSteps = 100000; // and the raised limit is the one that holds
  ScriptRunner r(o);
  r.run("x = 0\nfor i in 0..20000 { x = x + 1 }");
  EXPECT_EQ(r.variable("x"), 20000);
}

// A for loop from past 2^53 never advanced (i + 1 rounds back to i): 'for i in 1e16..1e16+4' ran its
// body on the same i until the step limit (`lvdif script` printed "1e+16" 25 million times). Now the
// loop stops at the first i that adding 1 does not change, named at the for; oracle: 2^53 + 1 == 2^53
// in double arithmetic, and a loop just below it counts.
TEST(Script, ForLoopPastTwoToThe53IsAClearError)
{
  ScriptOptions o;
  o.maxSteps = 1000000;
  int prints = 0;
  o.print = [&](const std::string&) { ++prints; };
  const Where w = errorOf("canvas 16\nx = 1\nfor i in 1e16..1e16 + 4 { print i }", o);
  EXPECT_EQ(w.line, 3);
  EXPECT_EQ(w.column, 1);
  EXPECT_EQ(w.detail, "the loop cannot count past 10000000000000000: adding 1 gives the same number (doubles are "
                      "whole steps apart only below 2^53 = 9007199254740992)");
  EXPECT_EQ(prints, 0);
  // from 2^53 - 2 it counts to 2^53, where 2^53 + 1 is 2^53
  prints = 0;
  EXPECT_EQ(errorOf("for i in 9007199254740990..9007199254740999 { print i }", o).detail.rfind(
              "the loop cannot count past 9007199254740992:", 0), 0u);
  EXPECT_EQ(prints, 2);
  ScriptRunner r(o);
  r.run("x = 0\nfor i in 9007199254740980..9007199254740990 { x = x + 1 }");
  EXPECT_EQ(r.variable("x"), 10);
}

TEST(Script, CancelStopsTheScript)
{
  struct CancelAfter : Interrupter
  {
    int calls = 0;
    bool wasInterrupted() const override { return true; }
  } cancel;
  ScriptOptions o;
  o.interrupter = &cancel;
  ScriptRunner r(o);
  errortest::errorMessageOf([&] { r.run("x = 0\nwhile 1 { x = x + 1 }"); }, ErrorCode::Cancelled);
  EXPECT_LT(r.steps(), 5000u);
}

// `undo` and `redo` with nothing to act on are errors at the statement, as in a
// recording (they did nothing without a word, so one `undo` too many, or one
// after `canvas fill`, ran on and kept the edits it was meant to drop)
TEST(Script, UndoAndRedoWithNothingToActOnAreErrors)
{
  Where w = errorOf("canvas 16\nsphere 8 8 8 3\nundo\nundo");
  EXPECT_EQ(w.line, 4);
  EXPECT_EQ(w.column, 1);
  EXPECT_EQ(w.detail, "'undo' has nothing to undo: no edit since the start or the last 'canvas'");
  w = errorOf("canvas 16\nsphere 8 8 8 3\ncanvas fill\nundo");
  EXPECT_EQ(w.line, 4);
  EXPECT_EQ(w.detail, "'undo' has nothing to undo: no edit since the start or the last 'canvas'");
  w = errorOf("canvas 16\nsphere 8 8 8 3\nredo");
  EXPECT_EQ(w.line, 3);
  EXPECT_EQ(w.detail, "'redo' has nothing to redo: no edit was undone since the last edit");
  // what can be undone and redone still runs: the volume is the one edit's (the oracle: an editor's)
  ScriptRunner r;
  r.run("canvas 16\ncolor 255 0 0\nsphere 8 8 8 3\nundo\nredo\nundo\nredo");
  DictionaryVolume v(edittest::options(16, 32));
  Editor e(v);
  e.brush.color = Rgba{ 255, 0, 0, 255 };
  e.dab(Dab{ BrushShape::Sphere, { 8, 8, 8 }, 3, {} });
  EXPECT_EQ(edittest::countDifferences(*r.volume(), v), 0);
}

// Every edit command is one undoable step (docs/SCRIPTING.md), also one that
// changes no voxel: the editor keeps no step for it, so `undo` after it undid
// the edit before it (`sphere` then a `sphere` beside the canvas then `undo` left
// an empty canvas). The oracle is an editor that made only the edits meant to stay.
TEST(Script, AnEditThatChangesNothingIsAStepOfItsOwn)
{
  DictionaryVolume sphereOnly(edittest::options(32, 32));
  {
    Editor e(sphereOnly);
    e.dab(Dab{ BrushShape::Sphere, { 16, 16, 16 }, 6, {} });
  }
  const DictionaryVolume empty(edittest::options(32, 32));
  const std::string sphere = "canvas 32\nsphere 16 16 16 6\n";
  auto volumeAfter = [](const std::string& src) {
    auto r = std::make_unique<ScriptRunner>();
    r->run(src);
    return r;
  };
  // a dab beside the canvas, a paint away from the surface, a line and a stroke beside the canvas: undone alone
  for (const char* noop : { "sphere 1000 1000 1000 3", "op paint\nsphere 3 3 3 1", "line 900 900 900 950 900 900",
         "begin\npoint 900 900 900\npoint 950 900 900\nend" })
  {
    const auto r = volumeAfter(sphere + noop + "\nundo");
    EXPECT_EQ(edittest::countDifferences(*r->volume(), sphereOnly), 0) << noop;
    // the next undo is the sphere's, and the one after has nothing left
    EXPECT_EQ(edittest::countDifferences(*volumeAfter(sphere + noop + "\nundo\nundo")->volume(), empty), 0) << noop;
    const Where w = errorOf(sphere + noop + "\nundo\nundo\nundo");
    EXPECT_EQ(w.detail, "'undo' has nothing to undo: no edit since the start or the last 'canvas'") << noop;
  }
  // redo of the step that changed nothing, then undo: the sphere stays
  EXPECT_EQ(edittest::countDifferences(
              *volumeAfter(sphere + "sphere 1000 1000 1000 3\nundo\nredo\nundo")->volume(), sphereOnly), 0);
  // undo of both, then redo of both in order
  EXPECT_EQ(edittest::countDifferences(
              *volumeAfter(sphere + "sphere 1000 1000 1000 3\nundo\nundo\nredo\nredo")->volume(), sphereOnly), 0);
  // a new edit, even one that changes nothing, drops what was undone (the sphere came back by `redo`)
  Where w = errorOf(sphere + "undo\nsphere 1000 1000 1000 3\nredo");
  EXPECT_EQ(w.line, 5);
  EXPECT_EQ(w.detail, "'redo' has nothing to redo: no edit was undone since the last edit");
  // a script driving an editor: its `undo` past its own steps undoes the editor's edits before the run
  DictionaryVolume v(edittest::options(32, 32));
  Editor ed(v);
  ed.dab(Dab{ BrushShape::Sphere, { 16, 16, 16 }, 6, {} });
  ScriptRunner r;
  r.attach(ed);
  r.run("sphere 1000 1000 1000 3\nundo");
  EXPECT_EQ(edittest::countDifferences(v, sphereOnly), 0);
  r.run("sphere 1000 1000 1000 3\nundo\nundo");
  EXPECT_EQ(edittest::countDifferences(v, empty), 0);
}

// `canvas fill` and `canvas clear` run while recording were missing from the
// recording (the format had no record for them): the playback gave another
// model. They are fill records now (version 3), played back as fills.
// Oracle: the same script run directly on the same start volume.
TEST(Script, CanvasFillAndClearArePlayedBackFromARecording)
{
  const std::string src = "sphere 8 8 8 4\ncanvas clear\ncolor 255 0 0\nsphere 20 20 20 5\ncanvas fill\n"
                          "op subtract\nsphere 16 16 16 6\nundo\nredo\ncolor 0 0 255\nop add\nsphere 4 4 4 3\n";
  DictionaryVolume start(edittest::options(32, 16));
  auto direct = start.clone(), recorded = start.clone(), played = start.clone();
  auto runOn = [&](DictionaryVolume& v, bool record) {
    Editor ed(v);
    if (record)
      ed.startRecording();
    ScriptRunner r;
    r.attach(ed);
    r.run(src);
    return record ? ed.stopRecording() : Recording();
  };
  runOn(*direct, false);
  std::stringstream text;
  writeRecording(text, runOn(*recorded, true));
  EXPECT_EQ(text.str().rfind("LVDIF-RECORDING 3\n", 0), 0u) << text.str();
  EXPECT_NE(text.str().find("\nfill time=1 sdf=8 color=200,200,200,255\n"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("\nfill time=3 sdf=-8 color=255,0,0,255\n"), std::string::npos) << text.str();
  Editor player(*played);
  player.play(readRecording(text));
  EXPECT_EQ(edittest::countDifferences(*played, *recorded), 0);
  EXPECT_EQ(edittest::countDifferences(*played, *direct), 0);
  EXPECT_EQ(played->colors(), direct->colors());
}

// A UTF-8 byte order mark before the text (Windows editors write one) is
// skipped, as the mesh readers skip it: a script saved so failed at once with
// "line 1, column 1: unexpected character byte 239".
TEST(Script, AByteOrderMarkBeforeTheTextIsSkipped)
{
  ScriptRunner a, b;
  a.run("\xEF\xBB\xBF" "canvas 16\nsphere 8 8 8 3\n");
  b.run("canvas 16\nsphere 8 8 8 3\n");
  EXPECT_EQ(a.edits(), 1u);
  EXPECT_EQ(edittest::countDifferences(*a.volume(), *b.volume()), 0);
  // positions on the first line are counted after it
  Where w = errorOf("\xEF\xBB\xBF" "frob 1");
  EXPECT_EQ(w.line, 1);
  EXPECT_EQ(w.column, 1);
  EXPECT_EQ(w.detail, "unknown command 'frob'");
  w = errorOf("\xEF\xBB\xBF" "print 1 +");
  EXPECT_EQ(w.column, 10);
  // only before the text: elsewhere it is still a character no script has
  w = errorOf("print 1\n\xEF\xBB\xBF" "print 2");
  EXPECT_EQ(w.line, 2);
  EXPECT_EQ(w.column, 1);
  EXPECT_NE(w.detail.find("unexpected character"), std::string::npos) << w.detail;
}

// A character outside ASCII (text copied from a web page or a word processor)
// is named whole with its code point, and a look-alike of a space or a minus
// with what to type: a no-break space between arguments was "unexpected
// character byte 194", at the right place but with nothing to recognise it by.
TEST(Script, CharactersOutsideAsciiAreNamed)
{
  Where w = errorOf("canvas 16\nsphere 8,\xC2\xA0" "8, 8, 3");
  EXPECT_EQ(w.line, 2);
  EXPECT_EQ(w.column, 10);
  EXPECT_EQ(w.detail, "unexpected character U+00A0 (a no-break or other wide space: type a plain space)");
  w = errorOf("print 3 \xE2\x88\x92 1");
  EXPECT_EQ(w.column, 9);
  EXPECT_EQ(w.detail, "unexpected character '\xE2\x88\x92' U+2212 (a dash or minus sign: type '-')");
  w = errorOf("print 3 \xE2\x80\x93 1");
  EXPECT_EQ(w.detail, "unexpected character '\xE2\x80\x93' U+2013 (a dash or minus sign: type '-')");
  w = errorOf("r\xC3\xA9" "sultat = 1");
  EXPECT_EQ(w.column, 2);
  EXPECT_EQ(w.detail, "unexpected character '\xC3\xA9' U+00E9 (scripts are ASCII outside comments)");
  // in a comment any text is fine; a byte that starts no UTF-8 character, or a cut one, is a byte
  EXPECT_EQ(errorOf("# r\xC3\xA9sultat \xE2\x88\x92 \xC2\xA0\nprint 1").detail, "no error");
  EXPECT_EQ(errorOf("print \xFF").detail, "unexpected character byte 255");
  EXPECT_EQ(errorOf("print \xC3").detail, "unexpected character byte 195");
  EXPECT_EQ(errorOf("print \xE2\x88 1").detail, "unexpected character byte 226");
}

TEST(Script, CommandsDriveTheSameEditsAsTheEditor)
{
  ScriptRunner r;
  r.run("canvas 40\ncolor 255 0 0\nradius 4\nbrush cube\ndab 20 20 20\nop subtract\nsphere 24, 20, 20, 3\n"
        "op add\nbrush sphere\nblend 2\nline 5 5 5 15 5 5\n");
  DictionaryVolume v(edittest::options(40, 32));
  Editor e(v);
  e.brush.color = Rgba{ 255, 0, 0, 255 };
  e.dab(Dab{ BrushShape::Cube, { 20, 20, 20 }, 4, {} });
  e.brush.op = BrushOp::Subtract;
  e.dab(Dab{ BrushShape::Sphere, { 24, 20, 20 }, 3, {} });
  e.brush.op = BrushOp::Add;
  e.brush.blend = 2;
  e.stroke.radius = 4;
  BrushSample a, b;
  a.position = { 5, 5, 5 };
  b.position = { 15, 5, 5 };
  e.strokeThrough({ a, b });
  EXPECT_EQ(edittest::countDifferences(*r.volume(), v), 0);
  EXPECT_EQ(r.edits(), 3u);
}

TEST(Script, DiceMatchesTheAnalyticRoundedCubeMinusPips)
{
  ScriptRunner r;
  DictionaryVolume& v = runBundled(r, "dice.lvs");
  const double n = 128, c = 64, h = 0.4 * n, round = 0.06 * n, pr = 0.1 * n;
  std::vector<std::array<double, 3>> pips{ { c, c, c - h }, { c, c + h, c } };
  for (int i = 0; i < 4; ++i)
    pips.push_back({ (0.3 + 0.4 * (i % 2)) * n, c + h, (0.3 + 0.4 * (i / 2)) * n });
  for (int k = 0; k < 3; ++k)
    pips.push_back({ c + h, (0.3 + 0.2 * k) * n, (0.3 + 0.2 * k) * n });
  std::int64_t material = 0, expected = 0, signMismatch = 0;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    // rounded box by the closest-point construction, in double
    const double q[3] = { std::fabs(x - c) - (h - round), std::fabs(y - c) - (h - round), std::fabs(z - c) - (h - round) };
    double out = 0, in = -1e30;
    for (double a : q)
    {
      out += a > 0 ? a * a : 0;
      in = std::max(in, a);
    }
    double d = std::sqrt(out) + std::min(in, 0.0) - round;
    for (const auto& p : pips)
      d = std::max(d, pr - std::sqrt((x - p[0]) * (x - p[0]) + (y - p[1]) * (y - p[1]) + (z - p[2]) * (z - p[2])));
    const bool solid = v.sdf(x, y, z) < 0;
    material += solid;
    expected += d < 0;
    if (std::fabs(d) > 0.06 && solid != (d < 0))
      ++signMismatch;
  });
  EXPECT_EQ(signMismatch, 0);
  EXPECT_NEAR(double(material), double(expected), 0.002 * expected);
  // colours: the pip floor shows the red interior, the face the white body
  const Rgba red{ 220, 30, 40, 255 }, white{ 235, 235, 240, 255 };
  EXPECT_EQ(v.colors()[v.get(64, 64, 26).color], red);   // floor of the one-pip dimple (z = 25.6)
  EXPECT_EQ(v.colors()[v.get(84, 84, 13).color], white); // the same face away from the pip
  EXPECT_EQ(r.edits(), 11u);
}

TEST(Script, SpiralDrawsNineTaperedLinesInNineColours)
{
  ScriptRunner r;
  DictionaryVolume& v = runBundled(r, "spiral.lvs");
  EXPECT_EQ(r.edits(), 9u);
  EXPECT_EQ(r.editor()->undoStack().undoCount(), 9u);
  std::set<ColorKey> used;
  edittest::forEachVoxel(v, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    if (v.sdf(x, y, z) < 0)
      used.insert(v.get(x, y, z).color);
  });
  EXPECT_EQ(used.size(), 9u);
  EXPECT_EQ(v.colors().size(), 10u); // the default colour and nine line colours
  // each helix starts (i = 0, t = 0) at radius 0.03 n = 3.84: its start point is solid
  for (int j = 0; j < 9; ++j)
  {
    const double phi = j * 40 * M_PI / 180;
    const double x = 128 * (0.5 + 0.25 * std::sin(phi)), y = 128 * (0.5 + 0.25 * std::cos(phi)), z = 128 * 0.1;
    EXPECT_LT(v.sdf(std::lround(x), std::lround(y), std::lround(z)), 0.0f) << j;
  }
  // the helix axis itself is empty
  EXPECT_GT(v.sdf(64, 64, 64), 0.0f);
}

// Hostile shapes of scripts: chains of any length evaluate without recursion
// (checked against a sum computed here), nesting beyond the limit is one
// parse error at the token that crossed it.
TEST(Script, LongChainsRunWithoutRecursion)
{
  std::mt19937 rng(18);
  for (int n : { 2, 3, 1000, 100000 })
  {
    std::string src = "x = 7";
    double expect = 7;
    for (int i = 0; i < n; ++i)
    {
      const int v = static_cast<int>(rng() % 9) + 1;
      const bool minus = rng() % 2 != 0;
      src += (minus ? "-" : "+") + std::to_string(v);
      expect += minus ? -v : v;
    }
    EXPECT_EQ(valueOf(src), expect) << n << " terms";
  }
  // products, 'and' and 'or' chains, and mixed levels
  std::string prod = "x = 1", all = "x = 1", any = "x = 0";
  for (int i = 0; i < 50000; ++i)
  {
    prod += i % 2 ? "*2" : "/2";
    all += " and 1";
    any += " or 0";
  }
  EXPECT_EQ(valueOf(prod), 1.0);
  EXPECT_EQ(valueOf(all), 1.0);
  EXPECT_EQ(valueOf(any + " or 3"), 1.0);
  EXPECT_EQ(valueOf("x = 2 + 3 * 4 - 10 / 5 * 2 + 7 % 4"), 2 + 12 - 4 + 3);
  EXPECT_EQ(valueOf("x = 1 < 2 and 3 > 2 or 0"), 1.0);
  EXPECT_EQ(valueOf("x = (1 + 2) * (3 + 4) - (10 - 2 - 3)"), 21 - 5);
  // errors inside a chain point at their own operator
  const Where w = errorOf("x = 1 + 2 + 3 / 0 + 4");
  EXPECT_EQ(w.line, 1);
  EXPECT_EQ(w.column, 15);
  EXPECT_EQ(w.detail, "division by zero");
}

TEST(Script, LongElseIfChainsPickTheRightClause)
{
  for (int n : { 1, 2, 30000 })
    for (int pick : { 0, n / 2, n - 1, n })
    {
      std::string src = "k = " + std::to_string(pick) + "\nif k == 0 { x = 0 }";
      for (int i = 1; i < n; ++i)
        src += " else if k == " + std::to_string(i) + " { x = " + std::to_string(i) + " }";
      src += "\nelse { x = -1 }";
      EXPECT_EQ(valueOf(src), pick < n ? pick : -1) << n << " clauses, pick " << pick;
    }
}

TEST(Script, NestingBeyondTheLimitIsOneParseError)
{
  const auto check = [](const std::string& src, int column, const char* what) {
    const Where w = errorOf(src);
    EXPECT_EQ(w.code, ErrorCode::ParseError) << what;
    EXPECT_EQ(w.line, 1) << what;
    EXPECT_EQ(w.column, column) << what;
    EXPECT_NE(w.detail.find("nested too deeply"), std::string::npos) << what << ": " << w.detail;
    EXPECT_EQ(w.detail.find('\n'), std::string::npos);
  };
  for (int n : { ScriptMaxNesting + 1, 100000 })
  {
    const std::string open(static_cast<std::size_t>(n), '(');
    // 'x = ' is 4 characters; the parenthesis that crosses the limit is the (ScriptMaxNesting + 1)-th
    // character after it (the statement's own expression is the first level)
    check("x = " + open + "1" + std::string(static_cast<std::size_t>(n), ')'), 5 + ScriptMaxNesting, "parentheses");
    std::string neg;
    for (int i = 0; i < n; ++i)
      neg += "-";
    check("x = " + neg + "1", 4 + ScriptMaxNesting, "unary minus");
    std::string nots;
    for (int i = 0; i < n; ++i)
      nots += "not ";
    check("x = " + nots + "1", 5 + 4 * (ScriptMaxNesting - 1), "not");
    std::string calls;
    for (int i = 0; i < n; ++i)
      calls += "abs(";
    check("x = " + calls + "1" + std::string(static_cast<std::size_t>(n), ')'), 5 + 4 * ScriptMaxNesting, "calls");
    // each head and the column of the '{' that opens level ScriptMaxNesting + 1
    const std::pair<std::string, int> heads[] = { { "if 1 {", 6 * (ScriptMaxNesting + 1) },
      { "for i in 0 .. 1 {", 17 * (ScriptMaxNesting + 1) }, { "while 0 {", 9 * (ScriptMaxNesting + 1) },
      { "if 0 {} else {", 14 * ScriptMaxNesting + 6 } }; // (the if's '{' of the next level comes first)
    for (const auto& [head, column] : heads)
    {
      // blocks count on their own (an if's condition is no block level): the
      // (ScriptMaxNesting + 1)-th '{' is refused naming blocks and the limit; it
      // said "expressions nested too deeply" at the 200th if
      std::string blocks;
      for (int i = 0; i < n; ++i)
        blocks += head;
      const Where w = errorOf(blocks);
      EXPECT_EQ(w.code, ErrorCode::ParseError) << head;
      EXPECT_EQ(w.line, 1) << head;
      EXPECT_EQ(w.column, column) << head;
      EXPECT_EQ(w.detail, "blocks nested too deeply: this '{' opens level " + std::to_string(ScriptMaxNesting + 1) +
          ", more than the limit of " + std::to_string(ScriptMaxNesting) + " nested if, else, for and while blocks")
        << head;
    }
  }
  // just inside the limits still runs: expressions, blocks, and both at once
  // (the deepest recursion a script can reach)
  const int ok = ScriptMaxNesting - 1;
  EXPECT_EQ(valueOf("x = " + std::string(ok, '(') + "5" + std::string(ok, ')')), 5.0);
  std::string deepest;
  for (int i = 0; i < ScriptMaxNesting; ++i)
    deepest += "if 1 {\n";
  deepest += "x = " + std::string(ok, '(') + "7" + std::string(ok, ')') + "\n" + std::string(ScriptMaxNesting, '}');
  EXPECT_EQ(valueOf(deepest), 7.0);
}

// Dabs count as steps and a runaway line is refused before its dabs exist:
// generated spacings and lengths, each either runs within the step limit or
// stops at its own line and column with nothing of it applied.
TEST(Script, DabsCountAsStepsAndRunawayLinesAreRefusedFirst)
{
  std::mt19937 rng(18);
  std::uniform_real_distribution<double> spacing(0.001, 0.01), length(50, 1e6);
  for (int i = 0; i < 20; ++i)
  {
    ScriptOptions o;
    o.maxSteps = 100000;
    const double s = spacing(rng), l = length(rng);
    std::ostringstream src;
    src << "canvas 32\nspacing " << s << "\nline 2 2 2 " << 2 + l << " 2 2\n";
    ScriptRunner r(o);
    const auto t0 = std::chrono::steady_clock::now();
    const double dabs = std::floor(l / s) + 2;
    try
    {
      r.run(src.str());
      EXPECT_LE(dabs, double(o.maxSteps)) << src.str();
      EXPECT_GE(double(r.steps()), std::floor(l / s)); // the dabs were counted
    }
    catch (const ScriptError& e)
    {
      EXPECT_GT(dabs, double(o.maxSteps) - 10) << src.str();
      EXPECT_EQ(e.line(), 3);
      EXPECT_EQ(e.column(), 1);
      EXPECT_NE(e.detail().find("more than the limit"), std::string::npos) << e.detail();
      EXPECT_EQ(r.edits(), 0u);
    }
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 10.0);
  }
  // out-of-range numbers are named at the number (they named the command's position)
  for (const std::string cmd : { "blend 1e300", "round 1e300", "spacing 1e-9", "radius 1e300" })
  {
    const Where w = errorOf("canvas 16\n" + cmd + "\n");
    EXPECT_EQ(w.line, 2) << cmd;
    EXPECT_EQ(w.column, int(cmd.find(' ')) + 2) << cmd;
    EXPECT_NE(w.detail.find("must be a finite number in"), std::string::npos) << w.detail;
  }
}

TEST(Script, ReadScriptFileRefusesFoldersAndFifosWithoutBlocking)
{
  const std::string dir = ::testing::TempDir();
  auto errorOf = [](const std::string& path) {
    return errortest::errorMessageOf([&] { lvdif::readScriptFile(path); }, ErrorCode::IoFailure);
  };
  EXPECT_NE(errorOf(dir).find("not a regular file"), std::string::npos) << errorOf(dir);
  const std::string fifo = dir + "/lvdif_script_fifo.lvs";
  std::remove(fifo.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(errorOf(fifo).find("not a regular file"), std::string::npos) << errorOf(fifo); // no writer: open would block
  std::remove(fifo.c_str());
  const std::string path = dir + "/lvdif_script_text.lvs";
  FILE* f = std::fopen(path.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  std::fputs("x = 1\r\ny = 2\n", f);
  std::fclose(f);
  EXPECT_EQ(lvdif::readScriptFile(path), "x = 1\r\ny = 2\n"); // bytes as they are (the lexer takes CRLF)
  f = std::fopen(path.c_str(), "wb");
  std::fclose(f);
  EXPECT_EQ(lvdif::readScriptFile(path), "");
  // lone CRs end lines too: the error is on line 3 (it was line 1, the file read as one line)
  try
  {
    lvdif::checkScript("canvas 32\r# note\rsphere 16, 16, 16, 8\rfrobnicate 1\r");
    ADD_FAILURE() << "no error";
  }
  catch (const lvdif::ScriptError& e)
  {
    EXPECT_EQ(e.line(), 4);
    EXPECT_EQ(e.column(), 1);
    EXPECT_EQ(e.detail(), "unknown command 'frobnicate'");
  }
  lvdif::checkScript("canvas 32\r\nsphere 16, 16, 16, 8\r\n"); // CRLF as before
  std::remove(path.c_str());
}

// A caller that fixed the start canvas's size (lvdif script --size) gets the
// script's `canvas N` refused before anything runs, wherever it stands (it
// silently replaced that canvas); `canvas fill|clear` keeps the canvas and runs.
TEST(Script, CanvasSizeGivenByTheCallerRefusesTheScriptsCanvas)
{
  ScriptOptions o;
  o.canvasSizeGivenBy = "--size 64";
  const std::string head = "x = 1\nif x > 5 {\n  radius 2\n} else {\n  ";
  for (const std::string& canvas : { std::string("canvas 32"), std::string("canvas 8 16 24") })
  {
    const Where w = errorOf(head + canvas + "\n}\nx = 2\n", o);
    EXPECT_EQ(w.code, ErrorCode::InvalidArgument);
    EXPECT_EQ(w.line, 5);
    EXPECT_EQ(w.column, 3);
    EXPECT_EQ(w.detail, "'canvas' makes its own canvas, but the start canvas's size was given (--size 64): remove one of them");
  }
  // nothing ran: the assignment before it did not happen either
  {
    ScriptRunner r(o);
    DictionaryVolume v(VolumeOptions{});
    r.attach(v);
    EXPECT_THROW(r.run("y = 7\ncanvas 16\n"), ScriptError);
    EXPECT_THROW(r.variable("y"), Error);
  }
  // without the option the same script runs and makes its canvas; fill and clear are no new canvas
  ScriptRunner plain;
  plain.run("canvas 16\ncanvas fill\n");
  ASSERT_NE(plain.volume(), nullptr);
  EXPECT_EQ(plain.volume()->dims()[0], 16);
  ScriptRunner fixed(o);
  DictionaryVolume v(VolumeOptions{});
  fixed.attach(v);
  EXPECT_NO_THROW(fixed.run("canvas clear\nx = 3\n"));
  EXPECT_EQ(fixed.variable("x"), 3.0);
}

// A caller's rule on the volume the script leaves (lvdif script --out x.bv: a
// cube) stops the script before its edits: at a `canvas N` that breaks it
// (before the canvas is made), or before anything runs for an attached volume
// the script keeps. It failed only when saving, after the whole script.
TEST(Script, ResultRuleIsCheckedBeforeTheEdits)
{
  ScriptOptions o;
  std::vector<Index3> asked;
  o.resultRule = [&asked](const Index3& d, const std::array<double, 3>& h) {
    asked.push_back(d);
    if (h[0] != h[1] || h[1] != h[2])
      return std::string("not one spacing");
    return d[0] == d[1] && d[1] == d[2] ? std::string() : std::string("not a cube");
  };
  {
    ScriptRunner r(o);
    try
    {
      r.run("x = 1\ncanvas 8 16 24\nsphere 4 4 4 3\ny = 2\n");
      ADD_FAILURE() << "a non-cubic canvas ran";
    }
    catch (const ScriptError& e)
    {
      EXPECT_EQ(e.line(), 2);
      EXPECT_EQ(e.detail(), "not a cube");
    }
    EXPECT_EQ(r.volume(), nullptr); // no canvas was made
    EXPECT_EQ(r.edits(), 0u);
    EXPECT_THROW(r.variable("y"), Error);
  }
  ASSERT_EQ(asked.size(), 1u);
  EXPECT_EQ(asked[0], (Index3{ 8, 16, 24 }));
  // an attached non-cubic volume that the script keeps: refused before anything runs
  VolumeOptions thin;
  thin.dims = { 32, 32, 16 };
  DictionaryVolume v(thin);
  {
    ScriptRunner r(o);
    r.attach(v);
    // no statement is blamed (a ScriptError's message starts with its line)
    EXPECT_EQ(errortest::errorMessageOf([&] { r.run("x = 1\nsphere 4 4 4 3\n"); }, ErrorCode::InvalidArgument),
      "not a cube");
    EXPECT_THROW(r.variable("x"), Error);
    EXPECT_EQ(r.edits(), 0u);
  }
  // ... but a script that makes its own cubic canvas runs; so does a cubic one
  {
    ScriptRunner r(o);
    r.attach(v);
    EXPECT_NO_THROW(r.run("canvas 16\nsphere 8 8 8 3\n"));
    EXPECT_EQ(r.edits(), 1u);
  }
  ScriptRunner cube(o);
  EXPECT_NO_THROW(cube.run("canvas 16\nsphere 8 8 8 3\n"));
  EXPECT_EQ(cube.edits(), 1u);
  // the rule is given the volume's spacing too (lvdif script --in x.lvdv --out x.vdb of unequal
  // spacing ran the whole script, then the save refused it)
  VolumeOptions stretched;
  stretched.dims = { 16, 16, 16 };
  stretched.spacing = { 1, 2, 1 };
  DictionaryVolume w(stretched);
  {
    ScriptRunner r(o);
    r.attach(w);
    EXPECT_EQ(errortest::errorMessageOf([&] { r.run("sphere 4 4 4 3\n"); }, ErrorCode::InvalidArgument),
      "not one spacing");
    EXPECT_EQ(r.edits(), 0u);
  }
  {
    ScriptRunner r(o); // its own canvas has the canvas options' spacing
    r.attach(w);
    EXPECT_NO_THROW(r.run("canvas 16\nsphere 8 8 8 3\n"));
  }
}
