// Tree-walking interpreter of the scripting language: evaluates expressions in
// double precision with one global variable scope, and turns commands into
// lvdif::Editor calls.
#include "ScriptAst.h"

#include "lvdif/Script.h"

#include "lvdif/ByteStream.h"
#include "lvdif/Memory.h"
#include "lvdif/QuotedText.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <sstream>

namespace lvdif
{

ScriptError::ScriptError(ErrorCode code, int line, int column, const std::string& what)
  : Error(code, "line " + std::to_string(line) + ", column " + std::to_string(column) + ": " + what)
  , Line(line)
  , Column(column)
  , Detail(what)
{
}

void checkScript(const std::string& source)
{
  detail::script::parse(detail::script::lex(source));
}

std::string readScriptFile(const std::string& path)
{
  FileSource src(path); // refuses FIFOs, directories and devices without blocking
  requireMemory(src.size(), "reading the script " + path);
  std::string text(static_cast<std::size_t>(src.size()), '\0');
  if (!text.empty())
    src.read(0, &text[0], text.size());
  return text;
}

using detail::script::Expr;
using detail::script::Stmt;

struct ScriptRunner::Impl
{
  ScriptOptions Options;
  ScriptRunner* Owner = nullptr;
  std::unique_ptr<DictionaryVolume> Owned;
  DictionaryVolume* Volume = nullptr;
  std::unique_ptr<Editor> OwnedEd; // the editor of an owned or attached volume
  Editor* Ed = nullptr;            // the editor in use (OwnedEd or one attached by the caller)
  std::map<std::string, double> Vars;
  BrushShape Shape = BrushShape::Sphere;
  double Radius = 3;
  int StrokeLine = 0, StrokeColumn = 0;
  std::size_t StrokeUndoCount = 0; // the editor's undo count at the open stroke's 'begin'
  bool StrokeOpen = false; // a stroke this script began is open (the editor may be the caller's)
  std::size_t TopDone = 0, TopTotal = 1;
  // The script's own history: every edit command is one step (docs/SCRIPTING.md),
  // also one that changed no voxel (a dab beside the canvas, `op paint` away from
  // the surface), which the editor's history does not hold (its steps are the
  // chunks written), so `undo` after it undid the edit before it. Done/Undone:
  // the steps of this run since its start or its last `canvas`, true where the
  // editor holds the step. RedoDropped: an edit since then, so the editor's redo
  // steps from before the run (an attached editor's) are not the script's to redo.
  std::vector<bool> Done, Undone;
  bool RedoDropped = false;

  [[noreturn]] static void fail(int line, int col, const std::string& what)
  {
    throw ScriptError(ErrorCode::InvalidArgument, line, col, what);
  }

  void step(int line, int col)
  {
    if (++this->Owner->Steps > this->Options.maxSteps)
      fail(line, col, "step limit of " + std::to_string(this->Options.maxSteps) + " exceeded (an endless loop?" +
          (this->Options.maxStepsRaisedBy.empty() ? std::string() : " If not, raise the limit with " + this->Options.maxStepsRaisedBy) +
          ")");
    if ((this->Owner->Steps & 1023) == 0 && this->Options.interrupter)
      this->Options.interrupter->checkInterrupt();
  }

  void resetHistory()
  {
    this->Done.clear();
    this->Undone.clear();
    this->RedoDropped = false;
  }

  /// An edit command made one script step; `before`: the editor's undo count before it.
  void edited(const Editor& ed, const EditResult& r, std::size_t before)
  {
    // the editor keeps a step for every edit that changed a voxel (a device's history may keep one more)
    this->Done.push_back(r.changedVoxels > 0 || !r.changedChunks.empty() || ed.undoCount() > before);
    this->Undone.clear();
    this->RedoDropped = true;
  }

  void setVolume(DictionaryVolume* v)
  {
    this->Volume = v;
    this->resetHistory();
    this->OwnedEd = std::make_unique<Editor>(*v);
    this->Ed = this->OwnedEd.get();
    this->Ed->stroke.radius = this->Radius;
    this->Ed->stroke.shape = this->Shape;
    this->Vars["nx"] = static_cast<double>(v->dims()[0]);
    this->Vars["ny"] = static_cast<double>(v->dims()[1]);
    this->Vars["nz"] = static_cast<double>(v->dims()[2]);
  }

  double eval(const Expr& e)
  {
    switch (e.kind)
    {
      case Expr::Kind::Number:
        return e.number;
      case Expr::Kind::Variable:
      {
        auto it = this->Vars.find(e.name);
        if (it == this->Vars.end())
          fail(e.line, e.column, "undefined variable " + quotedText(e.name));
        return it->second;
      }
      case Expr::Kind::Unary:
      {
        const double a = this->eval(*e.args[0]);
        return e.op == "-" ? -a : (a == 0 ? 1.0 : 0.0);
      }
      case Expr::Kind::Binary:
        return this->binary(e);
      case Expr::Kind::Call:
        return this->call(e);
    }
    return 0;
  }

  // A chain evaluates left to right in a loop; 'and' and 'or' stop at the
  // first operand that decides the result.
  double binary(const Expr& e)
  {
    double a = this->eval(*e.args[0]);
    for (std::size_t i = 0; i < e.ops.size(); ++i)
    {
      const Expr::Op& o = e.ops[i];
      const Expr& rhs = *e.args[i + 1];
      if (o.op == "&")
      {
        a = a != 0 && this->eval(rhs) != 0 ? 1.0 : 0.0;
        continue;
      }
      if (o.op == "|")
      {
        a = a != 0 || this->eval(rhs) != 0 ? 1.0 : 0.0;
        continue;
      }
      a = this->apply(o, a, this->eval(rhs));
    }
    return a;
  }

  static double apply(const Expr::Op& o, double a, double b)
  {
    const std::string& op = o.op;
    double r = 0;
    if (op == "+")
      r = a + b;
    else if (op == "-")
      r = a - b;
    else if (op == "*")
      r = a * b;
    else if (op == "/" || op == "%")
    {
      if (b == 0)
        fail(o.line, o.column, op == "/" ? "division by zero" : "remainder by zero");
      r = op == "/" ? a / b : a - b * std::floor(a / b); // % takes the sign of the divisor
    }
    else if (op == "<")
      r = a < b;
    else if (op == "<=")
      r = a <= b;
    else if (op == ">")
      r = a > b;
    else if (op == ">=")
      r = a >= b;
    else if (op == "==")
      r = a == b;
    else if (op == "!=")
      r = a != b;
    if (!std::isfinite(r))
      fail(o.line, o.column, "'" + op + "' gives a non-finite result");
    return r;
  }

  double call(const Expr& e)
  {
    static const std::map<std::string, int> arity{ { "sin", 1 }, { "cos", 1 }, { "tan", 1 }, { "asin", 1 },
      { "acos", 1 }, { "atan", 1 }, { "atan2", 2 }, { "sqrt", 1 }, { "abs", 1 }, { "floor", 1 }, { "ceil", 1 },
      { "round", 1 }, { "exp", 1 }, { "log", 1 }, { "pow", 2 }, { "min", -2 }, { "max", -2 }, { "clamp", 3 } };
    auto it = arity.find(e.name);
    if (it == arity.end())
      fail(e.line, e.column, "unknown function " + quotedText(e.name));
    const int n = static_cast<int>(e.args.size());
    if ((it->second > 0 && n != it->second) || (it->second < 0 && n < -it->second))
      fail(e.line, e.column,
        quotedText(e.name) + " takes " + (it->second > 0 ? std::to_string(it->second) : "at least 2") + " argument" +
          (it->second == 1 ? "" : "s") + ", got " + std::to_string(n));
    std::vector<double> a;
    for (const auto& x : e.args)
      a.push_back(this->eval(*x));
    const std::string& f = e.name;
    double r = 0;
    if (f == "sin") r = std::sin(a[0]);
    else if (f == "cos") r = std::cos(a[0]);
    else if (f == "tan") r = std::tan(a[0]);
    else if (f == "asin") r = std::asin(a[0]);
    else if (f == "acos") r = std::acos(a[0]);
    else if (f == "atan") r = std::atan(a[0]);
    else if (f == "atan2") r = std::atan2(a[0], a[1]);
    else if (f == "sqrt") r = std::sqrt(a[0]);
    else if (f == "abs") r = std::fabs(a[0]);
    else if (f == "floor") r = std::floor(a[0]);
    else if (f == "ceil") r = std::ceil(a[0]);
    else if (f == "round") r = std::round(a[0]);
    else if (f == "exp") r = std::exp(a[0]);
    else if (f == "log") r = std::log(a[0]);
    else if (f == "pow") r = std::pow(a[0], a[1]);
    else if (f == "clamp")
    {
      // reversed bounds are a mistake, not a constant (clamp(x, 10, 0) gave 10 for every x)
      if (a[1] > a[2])
      {
        std::ostringstream o;
        o << "'clamp' takes (x, lo, hi) with lo <= hi, got lo " << a[1] << " above hi " << a[2];
        fail(e.args[1]->line, e.args[1]->column, o.str());
      }
      r = std::max(a[1], std::min(a[2], a[0]));
    }
    else if (f == "min" || f == "max")
    {
      r = a[0];
      for (double v : a)
        r = f == "min" ? std::min(r, v) : std::max(r, v);
    }
    if (!std::isfinite(r))
      fail(e.line, e.column, "'" + f + "' gives a non-finite result (argument out of its domain?)");
    return r;
  }

  void run(const detail::script::Block& b, bool top)
  {
    for (const auto& s : b)
    {
      this->exec(*s);
      if (top && this->Options.interrupter)
        this->Options.interrupter->progress(double(++this->TopDone) / double(this->TopTotal));
    }
  }

  void exec(const Stmt& s)
  {
    this->step(s.line, s.column);
    switch (s.kind)
    {
      case Stmt::Kind::Assign:
        this->Vars[s.name] = this->eval(*s.cond);
        return;
      case Stmt::Kind::If:
      {
        if (this->eval(*s.cond) != 0)
          return this->run(s.body, false);
        for (const Stmt::Clause& c : s.elifs)
          if (this->eval(*c.cond) != 0)
            return this->run(c.body, false);
        this->run(s.orelse, false);
        return;
      }
      case Stmt::Kind::While:
        while (this->eval(*s.cond) != 0)
        {
          this->step(s.line, s.column);
          this->run(s.body, false);
        }
        return;
      case Stmt::Kind::For:
      {
        const double from = this->eval(*s.from), to = this->eval(*s.to);
        for (double i = from; i < to; i += 1.0)
        {
          // past 2^53 a double's neighbours are 2 or more apart: i + 1 rounds back to i, and
          // 'for i in 1e16..1e16+4' ran the same i until the step limit (25 million prints)
          if (i + 1.0 == i)
          {
            std::ostringstream o;
            o.precision(17);
            o << "the loop cannot count past " << i << ": adding 1 gives the same number (doubles are whole "
              << "steps apart only below 2^53 = 9007199254740992)";
            fail(s.line, s.column, o.str());
          }
          this->step(s.line, s.column);
          this->Vars[s.name] = i;
          this->run(s.body, false);
        }
        return;
      }
      case Stmt::Kind::Command:
        try
        {
          this->command(s);
        }
        catch (const ScriptError&)
        {
          throw;
        }
        catch (const Error& e)
        {
          if (e.code() == ErrorCode::Cancelled)
            throw;
          throw ScriptError(e.code(), s.line, s.column, e.what());
        }
        return;
    }
  }

  Editor& editor(const Stmt& s)
  {
    if (!this->Ed)
      fail(s.line, s.column, "no canvas: start with 'canvas N' (or attach a volume)");
    return *this->Ed;
  }

  /// A rule on the value of argument i, reported at that value (`color 300 0 0`
  /// named the statement's column).
  template <typename Check>
  double argument(const Stmt& s, std::size_t i, double v, Check check)
  {
    try
    {
      return check(v);
    }
    catch (const Error& e)
    {
      const Expr& at = *s.args[i];
      fail(at.line, at.column, e.what());
    }
  }

  // one rule and one message for sizes ('radius -1' said "must be > 0", 'radius 2e7' "in [0, 1e+07]")
  double positive(const Stmt& s, std::size_t i, double v, const char* what)
  {
    return this->argument(s, i, v, [&](double x) { return checkedPositive(x, EditLimits::MaxSize, what); });
  }

  double ranged(const Stmt& s, std::size_t i, double v, double lo, double hi, const char* what)
  {
    return this->argument(s, i, v, [&](double x) { return checkedNumber(x, lo, hi, what); });
  }

  // Dabs count as steps: an edit may make at most the steps left (checked
  // before the dabs are generated), and the dabs it made are added after.
  void command(const Stmt& s)
  {
    if (!this->Ed)
      return this->commandOn(s);
    Editor& ed = *this->Ed;
    const EditLimits saved = ed.limits;
    Interrupter* savedIn = ed.interrupter;
    const std::uint64_t left = this->Options.maxSteps - std::min(this->Options.maxSteps, this->Owner->Steps);
    ed.limits.maxDabsPerEdit = std::min<std::uint64_t>(ed.limits.maxDabsPerEdit, left);
    ed.limits.maxTotalDabs = std::min<std::uint64_t>(ed.limits.maxTotalDabs, ed.dabsApplied() + left);
    if (this->Options.interrupter)
      ed.interrupter = this->Options.interrupter;
    const std::uint64_t before = ed.dabsApplied();
    Editor* used = &ed;
    try
    {
      this->commandOn(s);
    }
    catch (...)
    {
      if (this->Ed == used) // 'canvas' replaces the editor
      {
        used->limits = saved;
        used->interrupter = savedIn;
      }
      throw;
    }
    if (this->Ed == used)
    {
      this->Owner->Steps += used->dabsApplied() - before;
      used->limits = saved;
      used->interrupter = savedIn;
    }
  }

  void commandOn(const Stmt& s)
  {
    const std::string& c = s.name;
    std::vector<double> a;
    for (const auto& e : s.args)
      a.push_back(this->eval(*e));
    if (c == "print")
    {
      std::ostringstream o;
      for (size_t i = 0; i < a.size(); ++i)
        o << (i ? " " : "") << a[i];
      if (this->Options.print)
        this->Options.print(o.str());
      else
        std::cout << o.str() << "\n";
      return;
    }
    if (c == "canvas")
      return this->canvas(s, a);
    if (c == "radius")
    {
      this->Radius = this->positive(s, 0, a[0], "radius");
      if (this->Ed)
        this->Ed->stroke.radius = this->Radius;
      return;
    }
    if (c == "brush")
    {
      this->Shape = s.word == "cube" ? BrushShape::Cube : BrushShape::Sphere;
      if (this->Ed)
        this->Ed->stroke.shape = this->Shape;
      return;
    }
    Editor& ed = this->editor(s);
    if (c == "color")
    {
      std::uint8_t v[4] = { 0, 0, 0, 255 };
      for (size_t i = 0; i < a.size(); ++i)
      {
        v[i] = static_cast<std::uint8_t>(std::lround(this->argument(s, i, a[i], [](double x) {
          if (!(x >= 0 && x <= 255))
          {
            std::ostringstream o;
            o << "colour components must be in 0..255, got " << x;
            throw Error(ErrorCode::InvalidArgument, o.str());
          }
          return x;
        })));
      }
      ed.brush.color = Rgba{ v[0], v[1], v[2], v[3] };
    }
    else if (c == "op")
      ed.brush.op = s.word == "add" ? BrushOp::Add : s.word == "subtract" ? BrushOp::Subtract : BrushOp::Paint;
    else if (c == "kind")
      ed.stroke.kind = s.word == "single" ? BrushKind::Single
        : s.word == "basic"               ? BrushKind::Basic
        : s.word == "dynamic"             ? BrushKind::Dynamic
                                          : BrushKind::Drill;
    else if (c == "blend")
    {
      ed.brush.blend = this->ranged(s, 0, a[0], 0, EditLimits::MaxSize, "blend");
    }
    else if (c == "round")
    {
      ed.brush.rounding = this->ranged(s, 0, a[0], 0, EditLimits::MaxSize, "round");
    }
    else if (c == "spacing")
      ed.stroke.spacing = this->ranged(s, 0, a[0], EditLimits::MinSpacing, EditLimits::MaxSize, "spacing");
    else if (c == "dab" || c == "sphere" || c == "cube")
    {
      Dab d;
      d.shape = c == "dab" ? this->Shape : c == "cube" ? BrushShape::Cube : BrushShape::Sphere;
      d.center = { a[0], a[1], a[2] };
      d.radius = c == "dab" ? this->Radius : this->positive(s, 3, a[3], c == "cube" ? "half edge" : "radius");
      const std::size_t before = ed.undoCount();
      this->edited(ed, ed.dab(d), before);
      ++this->Owner->Edits;
    }
    else if (c == "line")
    {
      BrushSample p0, p1;
      p0.position = { a[0], a[1], a[2] };
      p1.position = { a[3], a[4], a[5] };
      const std::size_t before = ed.undoCount();
      this->edited(ed, ed.strokeThrough({ p0, p1 }), before);
      ++this->Owner->Edits;
    }
    else if (c == "begin")
    {
      this->StrokeUndoCount = ed.undoCount();
      ed.beginStroke();
      this->StrokeOpen = true;
      this->StrokeLine = s.line;
      this->StrokeColumn = s.column;
    }
    else if (c == "point")
    {
      if (!ed.strokeOpen())
        fail(s.line, s.column, "'point' outside a stroke: use 'begin' first");
      BrushSample p;
      p.position = { a[0], a[1], a[2] };
      if (a.size() == 4)
        p.pressure = a[3];
      ed.addSample(p);
    }
    else if (c == "end")
    {
      if (!ed.strokeOpen())
        fail(s.line, s.column, "'end' without 'begin'");
      this->StrokeOpen = false; // endStroke closes it even when it fails
      this->edited(ed, ed.endStroke(), this->StrokeUndoCount);
      ++this->Owner->Edits;
    }
    // nothing to undo or redo is the script's mistake, named as the player names it
    // (both did nothing without a word: an `undo` after `canvas fill`, which clears
    // the history, or one `undo` too many ran on and saved the edits it meant to drop)
    // (a step of the script's that changed nothing is undone and redone without the editor)
    else if (c == "undo")
    {
      const bool held = this->Done.empty() || this->Done.back();
      if (held && !ed.undo())
        fail(s.line, s.column, "'undo' has nothing to undo: no edit since the start or the last 'canvas'");
      if (!this->Done.empty())
        this->Done.pop_back();
      this->Undone.push_back(held);
    }
    else if (c == "redo")
    {
      const bool held = this->Undone.empty() || this->Undone.back();
      if (held && ((this->Undone.empty() && this->RedoDropped) || !ed.redo()))
        fail(s.line, s.column, "'redo' has nothing to redo: no edit was undone since the last edit");
      if (!this->Undone.empty())
        this->Undone.pop_back();
      this->Done.push_back(held);
    }
  }

  /// Ends a stroke this script began and left open; true if there was one.
  /// Under the script's interrupter: after a cancel the stroke's pending dabs
  /// (all of a Basic stroke's) are not applied, and a long rest stays cancellable.
  /// Its own failure (that cancel, a budget) is dropped: the script's error is the one reported.
  bool endScriptStroke()
  {
    if (!this->StrokeOpen || !this->Ed || !this->Ed->strokeOpen())
      return false;
    this->StrokeOpen = false;
    Interrupter* saved = this->Ed->interrupter;
    if (this->Options.interrupter)
      this->Ed->interrupter = this->Options.interrupter;
    try
    {
      this->Ed->endStroke();
    }
    catch (const Error&)
    {
      // endStroke closes the stroke and its undo step even when it throws
    }
    this->Ed->interrupter = saved;
    return true;
  }

  void canvas(const Stmt& s, const std::vector<double>& a)
  {
    if (!s.word.empty())
    {
      Editor& ed = this->editor(s);
      if (ed.strokeOpen())
        fail(s.line, s.column, "finish the stroke before 'canvas " + s.word + "'");
      DictionaryVolume& v = *this->Volume;
      const Voxel fill = s.word == "fill" ? Voxel{ v.insideVoxel().sdf, v.colors().add(ed.brush.color) } : v.outsideVoxel();
      ed.fillVolume(fill); // not undoable: clears the history
      this->resetHistory();
      return;
    }
    Index3 dims;
    for (int i = 0; i < 3; ++i)
    {
      const double d = a.size() == 1 ? a[0] : a[static_cast<size_t>(i)];
      if (d != std::floor(d)) // also NaN and infinities
        fail(s.line, s.column, "canvas dimensions must be whole numbers");
      // clamped only to convert (to +-1e18, exact in 64 bits, so the message of the
      // editors' one rule below shows the number asked for: 'canvas -5' said -1)
      dims[i] = static_cast<std::int64_t>(std::max(-1e18, std::min(d, 1e18)));
    }
    const std::string tooThin = DictionaryVolume::checkCanvasDimensions(dims);
    if (!tooThin.empty())
      fail(s.line, s.column, tooThin);
    if (double(dims[0]) * double(dims[1]) * double(dims[2]) > double(this->Options.maxCanvasVoxels))
      fail(s.line, s.column, "canvas of " + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " +
          std::to_string(dims[2]) + " voxels exceeds the limit of " + std::to_string(this->Options.maxCanvasVoxels) +
          " voxels (ScriptOptions::maxCanvasVoxels)");
    if (this->Options.resultRule)
    {
      const std::string refused = this->Options.resultRule(dims, this->Options.canvas.spacing);
      if (!refused.empty())
        fail(s.line, s.column, refused);
    }
    if (this->Ed && this->Ed->strokeOpen())
      fail(s.line, s.column, "finish the stroke before 'canvas'");
    VolumeOptions o = this->Options.canvas;
    o.dims = dims;
    this->Ed = nullptr;
    this->OwnedEd.reset();
    this->StrokeOpen = false;
    this->Owned = std::make_unique<DictionaryVolume>(o);
    this->setVolume(this->Owned.get());
  }
};

ScriptRunner::ScriptRunner(const ScriptOptions& options)
  : P(std::make_unique<Impl>())
{
  this->P->Options = options;
  this->P->Owner = this;
  this->P->Vars["pi"] = 3.14159265358979323846;
}

ScriptRunner::~ScriptRunner() = default;

void ScriptRunner::attach(DictionaryVolume& volume)
{
  this->P->Owned.reset();
  this->P->setVolume(&volume);
}

void ScriptRunner::attach(Editor& editor)
{
  this->P->Owned.reset();
  this->P->OwnedEd.reset();
  this->P->Volume = &editor.volume();
  this->P->Ed = &editor;
  // the script continues from the editor's brush, not from the script defaults
  this->P->Radius = editor.stroke.radius;
  this->P->Shape = editor.stroke.shape;
  this->P->Vars["nx"] = static_cast<double>(editor.volume().dims()[0]);
  this->P->Vars["ny"] = static_cast<double>(editor.volume().dims()[1]);
  this->P->Vars["nz"] = static_cast<double>(editor.volume().dims()[2]);
}

namespace
{
/// The first `canvas N` (a new canvas, not `canvas fill|clear`) in b and its
/// blocks, or nullptr. Recurses once per block level (ScriptMaxNesting at most).
const detail::script::Stmt* firstNewCanvas(const detail::script::Block& b)
{
  for (const auto& s : b)
  {
    if (s->kind == detail::script::Stmt::Kind::Command && s->name == "canvas" && s->word.empty())
      return s.get();
    const detail::script::Stmt* inner = firstNewCanvas(s->body);
    for (std::size_t c = 0; !inner && c < s->elifs.size(); ++c) inner = firstNewCanvas(s->elifs[c].body);
    if (!inner) inner = firstNewCanvas(s->orelse);
    if (inner) return inner;
  }
  return nullptr;
}
}

void ScriptRunner::run(const std::string& source)
{
  const detail::script::Program prog = detail::script::parse(detail::script::lex(source));
  if (!this->P->Options.canvasSizeGivenBy.empty())
    if (const detail::script::Stmt* c = firstNewCanvas(prog.statements))
      throw ScriptError(ErrorCode::InvalidArgument, c->line, c->column,
        "'canvas' makes its own canvas, but the start canvas's size was given (" + this->P->Options.canvasSizeGivenBy +
          "): remove one of them");
  // the attached volume is the result unless a `canvas N` replaces it (checked there)
  if (this->P->Options.resultRule && this->P->Volume && !firstNewCanvas(prog.statements))
  {
    const std::string refused =
      this->P->Options.resultRule(this->P->Volume->dims(), this->P->Volume->options().spacing);
    if (!refused.empty())
      throw Error(ErrorCode::InvalidArgument, refused);
  }
  Interrupter* in = this->P->Options.interrupter;
  if (in)
    in->start("script");
  this->P->TopDone = 0;
  this->P->TopTotal = std::max<std::size_t>(1, prog.statements.size());
  this->P->StrokeOpen = false;
  this->P->resetHistory(); // the caller's editor may have undone or redone since the last run
  try
  {
    this->P->run(prog.statements, true);
  }
  catch (...)
  {
    // A stroke the script began is ended as the end of the script ends it
    // (its points so far kept, one undo step): left open, it would lock the
    // caller's editor (no undo, no new stroke) after the error.
    this->P->endScriptStroke();
    throw;
  }
  if (this->P->endScriptStroke())
    throw ScriptError(ErrorCode::InvalidArgument, this->P->StrokeLine, this->P->StrokeColumn,
      "'begin' without 'end' (the stroke was ended at the end of the script)");
  if (in)
    in->end();
}

DictionaryVolume* ScriptRunner::volume()
{
  return this->P->Volume;
}

std::unique_ptr<DictionaryVolume> ScriptRunner::takeVolume()
{
  this->P->Ed = nullptr;
  this->P->OwnedEd.reset();
  this->P->Volume = nullptr;
  return std::move(this->P->Owned);
}

Editor* ScriptRunner::editor()
{
  return this->P->Ed;
}

double ScriptRunner::variable(const std::string& name) const
{
  auto it = this->P->Vars.find(name);
  require(it != this->P->Vars.end(), "no variable '" + name + "'");
  return it->second;
}

} // namespace lvdif
