#include "lvdif/Recording.h"
#include "lvdif/CNumbers.h"

#include "lvdif/ByteStream.h"
#include "lvdif/EditLimits.h"
#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

namespace lvdif
{

namespace
{
std::string num(double v)
{
  char buf[40];
  formatDoubleC(buf, sizeof(buf), "%.17g", v);
  return buf;
}

std::string colorText(const Rgba& c)
{
  return std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b) + "," + std::to_string(c.a);
}

// Errors read "<name>:<line>:<column>: what" (1-based), like the scripts'.
struct Where
{
  const std::string& Name;
  std::size_t Line = 0;
  [[noreturn]] void bad(std::size_t column, const std::string& what) const
  {
    throw Error(ErrorCode::ParseError,
      this->Name + ":" + std::to_string(this->Line) + ":" + std::to_string(column) + ": " + what);
  }
};

struct Word
{
  std::string text;
  std::size_t column = 1;
};

// getline with a bound: a recording's lines are short, so a huge line (a
// garbage or hostile file) is refused after MaxLine bytes, not read whole.
constexpr std::size_t MaxLine = 4096;
bool readLine(std::istream& in, std::string& line, const Where& at)
{
  line.clear();
  std::streambuf* b = in.rdbuf();
  for (;;)
  {
    const int c = b->sbumpc();
    if (c == std::char_traits<char>::eof())
    {
      in.setstate(std::ios::eofbit);
      return !line.empty();
    }
    if (c == '\n')
      return true;
    if (line.size() == MaxLine)
    {
      Where next{ at.Name, at.Line + 1 };
      next.bad(MaxLine + 1, "line longer than " + std::to_string(MaxLine) + " bytes");
    }
    line.push_back(static_cast<char>(c));
  }
}

std::vector<Word> splitWords(const std::string& line)
{
  std::vector<Word> out;
  std::size_t i = 0;
  while (i < line.size())
  {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t'))
      ++i;
    if (i == line.size())
      break;
    const std::size_t b = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t')
      ++i;
    out.push_back(Word{ line.substr(b, i - b), b + 1 });
  }
  return out;
}

double toNumber(const std::string& s, const Where& at, std::size_t column, const std::string& what)
{
  char* end = nullptr;
  const double v = strtodC(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(v))
    at.bad(column, what + " is not a finite number: '" + s + "'");
  return v;
}

template <typename E>
E lookup(const std::string& word, const std::map<std::string, E>& table, const Where& at, std::size_t column,
  const char* what)
{
  auto it = table.find(word);
  if (it == table.end())
    at.bad(column, std::string("unknown ") + what + " '" + word + "'");
  return it->second;
}

const std::map<std::string, BrushOp> Ops{ { "add", BrushOp::Add }, { "subtract", BrushOp::Subtract },
  { "paint", BrushOp::Paint }, { "smooth", BrushOp::Smooth }, { "inflate", BrushOp::Inflate }, { "grab", BrushOp::Grab },
  { "flatten", BrushOp::Flatten }, { "crease", BrushOp::Crease }, { "pinch", BrushOp::Pinch } };
const std::map<std::string, Falloff> Falloffs{ { "constant", Falloff::Constant }, { "linear", Falloff::Linear },
  { "smooth", Falloff::Smooth }, { "sharp", Falloff::Sharp } };
const std::map<std::string, BrushShape> Shapes{ { "sphere", BrushShape::Sphere }, { "cube", BrushShape::Cube },
  { "capsule", BrushShape::Capsule } };
// the keys of an edit record (docs/RECORDING.md)
const std::set<std::string> EditKeys{ "time", "op", "shape", "kind", "spacing", "blend", "coloroffset", "rounding",
  "color", "dabs", "strength", "falloff", "invert", "mirrorx", "mirrory", "mirrorz" };
// the keys of a fill record
const std::set<std::string> FillKeys{ "time", "sdf", "color" };
const std::map<std::string, BrushKind> Kinds{ { "single", BrushKind::Single }, { "basic", BrushKind::Basic },
  { "dynamic", BrushKind::Dynamic }, { "drill", BrushKind::Drill } };
} // namespace

void writeRecording(std::ostream& out, const Recording& r)
{
  // version 3 only where a fill record needs it, 4 where the canvas is not a cube (its
  // starter shape in the editors is the rounded box): the others stay readable by older builds
  const bool fills = std::any_of(
    r.records.begin(), r.records.end(), [](const EditRecord& e) { return e.type == EditRecord::Type::Fill; });
  const bool cubic = r.canvas[0] == r.canvas[1] && r.canvas[1] == r.canvas[2];
  out << "LVDIF-RECORDING " << (!cubic ? 4 : fills ? 3 : 2) << "\n";
  if (r.canvas[0] > 0)
    out << "canvas " << r.canvas[0] << " " << r.canvas[1] << " " << r.canvas[2] << "\n";
  for (const EditRecord& e : r.records)
  {
    if (e.type == EditRecord::Type::Undo || e.type == EditRecord::Type::Redo)
    {
      out << (e.type == EditRecord::Type::Undo ? "undo" : "redo") << " time=" << num(e.time) << "\n";
      continue;
    }
    if (e.type == EditRecord::Type::Fill)
    {
      out << "fill time=" << num(e.time) << " sdf=" << num(e.sdf) << " color=" << colorText(e.brush.color) << "\n";
      continue;
    }
    // the shape of the first dab names the edit; each dab line carries its own when capsules mix in
    const BrushShape shape = e.dabs.empty() ? BrushShape::Sphere : e.dabs.front().shape;
    out << "edit time=" << num(e.time) << " op=" << toString(e.brush.op) << " shape=" << toString(shape)
        << " kind=" << toString(e.kind) << " spacing=" << num(e.spacing) << " blend=" << num(e.brush.blend)
        << " coloroffset=" << num(e.brush.colorOffset) << " rounding=" << num(e.brush.rounding)
        << " color=" << colorText(e.brush.color) << " dabs=" << e.dabs.size();
    // the sculpting settings only where they differ from the defaults (older files stay as they were)
    if (e.brush.strength != 1)
      out << " strength=" << num(e.brush.strength);
    if (e.brush.falloff != Falloff::Constant)
      out << " falloff=" << toString(e.brush.falloff);
    if (e.brush.invert)
      out << " invert=1";
    for (int a = 0; a < 3; ++a)
      if (e.brush.symmetry.mirror[a])
        out << " mirror" << "xyz"[a] << "=" << num(e.brush.symmetry.plane[a]);
    out << "\n";
    for (const Dab& d : e.dabs)
    {
      out << (d.shape == shape ? "d" : (std::string("d:") + toString(d.shape))) << " " << num(d.center[0]) << " "
          << num(d.center[1]) << " " << num(d.center[2]) << " " << num(d.radius);
      if (d.shape == BrushShape::Capsule)
        out << " " << num(d.end[0]) << " " << num(d.end[1]) << " " << num(d.end[2]);
      if (e.brush.op == BrushOp::Grab || e.brush.op == BrushOp::Pinch) // grab's drag, pinch's stroke direction
        out << " " << num(d.vec[0]) << " " << num(d.vec[1]) << " " << num(d.vec[2]);
      out << "\n";
    }
  }
  // the end: a file cut short (at a line, or inside a number) has none or another count
  out << "end records=" << r.records.size() << "\n";
}

Recording readRecording(std::istream& in, const std::string& name)
{
  Recording r;
  std::string line;
  Where at{ name };
  bool header = false, ended = false;
  long version = 0;
  std::size_t expectDabs = 0;
  BrushShape editShape = BrushShape::Sphere;
  const EditLimits limits;
  std::uint64_t totalDabs = 0;
  // The same rules as every other edit (lvdif/EditLimits.h), reported at the value.
  auto rule = [&](const std::function<void()>& check, std::size_t column) {
    try
    {
      check();
    }
    catch (const Error& e)
    {
      at.bad(column, e.what());
    }
  };
  while (in.rdbuf() && readLine(in, line, at))
  {
    ++at.Line;
    if (at.Line == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0)
      line.erase(0, 3); // a UTF-8 byte order mark (editors add one), as scripts skip it
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    if (line.empty() || line[0] == '#')
      continue;
    const std::vector<Word> words = splitWords(line);
    if (words.empty())
      continue;
    const Word& head = words[0];
    if (!header)
    {
      if (head.text != "LVDIF-RECORDING" || words.size() != 2)
        at.bad(head.column, "expected the version line 'LVDIF-RECORDING 2'");
      char* end = nullptr;
      version = std::strtol(words[1].text.c_str(), &end, 10);
      if (*end != '\0' || version < 1 || version > Recording::Version)
        at.bad(words[1].column, "unsupported recording version '" + words[1].text + "'");
      header = true;
      continue;
    }
    if (ended)
      at.bad(head.column, "'" + head.text.substr(0, 40) + "' after the end record (the end record is the last line)");
    if (expectDabs > 0)
    {
      Dab d;
      d.shape = editShape;
      if (head.text.rfind("d:", 0) == 0)
        d.shape = lookup(head.text.substr(2), Shapes, at, head.column + 2, "shape");
      else if (head.text != "d")
        at.bad(head.column, "expected a dab line 'd x y z r', " + std::to_string(expectDabs) + " more due");
      const bool withVec = r.records.back().brush.op == BrushOp::Grab || r.records.back().brush.op == BrushOp::Pinch;
      const std::size_t want = (d.shape == BrushShape::Capsule ? 7 : 4) + (withVec ? 3 : 0);
      if (words.size() - 1 != want)
        at.bad(words.size() - 1 > want ? words[want + 1].column : line.size() + 1,
          "a dab needs " + std::to_string(want) + " numbers, got " + std::to_string(words.size() - 1));
      if (withVec)
        for (int a = 0; a < 3; ++a)
          d.vec[a] =
            toNumber(words[want - 2 + a].text, at, words[want - 2 + a].column, "grab displacement or pinch direction");
      for (int a = 0; a < 3; ++a)
        d.center[a] = toNumber(words[1 + a].text, at, words[1 + a].column, "dab position");
      d.radius = toNumber(words[4].text, at, words[4].column, "dab radius");
      if (!(d.radius >= 0))
        at.bad(words[4].column, "dab radius must be >= 0 (got " + words[4].text + ")");
      if (d.shape == BrushShape::Capsule)
        for (int a = 0; a < 3; ++a)
          d.end[a] = toNumber(words[5 + a].text, at, words[5 + a].column, "capsule end");
      {
        // the one rule of a dab (validate), reported at the value it refuses: each
        // group of values alone, in the line's order (a huge radius was named at x)
        const std::size_t n = r.records.back().dabs.size();
        const std::size_t end = d.shape == BrushShape::Capsule ? 5 : 0, vec = withVec ? want - 2 : 0;
        for (std::size_t at : { std::size_t(1), std::size_t(4), end, vec })
        {
          Dab probe;
          probe.shape = d.shape;
          if (at == 1)
            probe.center = d.center;
          if (at == 4)
            probe.radius = d.radius;
          if (at == end && end)
            probe.end = d.end;
          if (at == vec && vec)
            probe.vec = d.vec;
          if (at)
            rule([&] { validate(probe, n); }, words[at].column);
        }
      }
      r.records.back().dabs.push_back(d);
      --expectDabs;
      continue;
    }
    if (head.text == "canvas")
    {
      // the recorded volume's dimensions: once, before the first record
      if (!r.records.empty() || r.canvas[0] > 0)
        at.bad(head.column, "the canvas line must come once, right after the version line");
      if (words.size() != 4)
        at.bad(head.column, "expected 'canvas NX NY NZ'");
      for (int a = 0; a < 3; ++a)
      {
        const Word& w = words[static_cast<std::size_t>(1 + a)];
        char* end = nullptr;
        const long long n = std::strtoll(w.text.c_str(), &end, 10);
        if (w.text.empty() || *end != '\0' || n < 1 || n > DictionaryVolume::MaxDimension)
          at.bad(w.column, "canvas dimensions must be whole numbers 1.." + std::to_string(DictionaryVolume::MaxDimension) +
              ", got '" + w.text + "'");
        r.canvas[static_cast<std::size_t>(a)] = n;
      }
      continue;
    }
    if (head.text == "end")
    {
      // `end records=N`: the last line of a version 2 recording
      if (version < 2)
        at.bad(head.column, "an end record needs version 2 ('LVDIF-RECORDING 2'), this file says version 1");
      if (words.size() != 2 || words[1].text.rfind("records=", 0) != 0)
        at.bad(head.column, "expected 'end records=N'");
      const std::string count = words[1].text.substr(8);
      char* end = nullptr;
      const unsigned long long n = std::strtoull(count.c_str(), &end, 10);
      if (count.empty() || *end != '\0' || count[0] < '0' || count[0] > '9' || n != r.records.size())
        at.bad(words[1].column + 8, "the end record counts '" + count + "' records, the recording has " +
            std::to_string(r.records.size()) + " (the file was cut or edited)");
      ended = true;
      continue;
    }
    // the record word first: a stray dab line is named as one, not as a bad key=value
    const bool undoRedo = head.text == "undo" || head.text == "redo";
    const bool fill = head.text == "fill";
    if (head.text == "d" || head.text.rfind("d:", 0) == 0)
      at.bad(head.column, "dab line outside an edit (the edit's dabs= count is already read)");
    if (!undoRedo && !fill && head.text != "edit")
      at.bad(head.column, "unknown record '" + head.text + "'");
    if (fill && version < 3)
      at.bad(head.column, "a fill record needs version 3 ('LVDIF-RECORDING 3'), this file says version " +
          std::to_string(version));
    // every key once and known: a misspelt optional key (strenght=) would otherwise be ignored
    std::map<std::string, std::pair<std::string, std::size_t>> kv;
    for (std::size_t w = 1; w < words.size(); ++w)
    {
      const auto eq = words[w].text.find('=');
      if (eq == std::string::npos)
        at.bad(words[w].column, "expected key=value, got '" + words[w].text + "'");
      const std::string key = words[w].text.substr(0, eq);
      if (!(undoRedo ? key == "time" : fill ? FillKeys.count(key) > 0 : EditKeys.count(key) > 0))
        at.bad(words[w].column, "unknown key '" + key + "' in a '" + head.text + "' record");
      if (!kv.emplace(key, std::make_pair(words[w].text.substr(eq + 1), words[w].column + eq + 1)).second)
        at.bad(words[w].column, "key '" + key + "' given twice");
    }
    auto get = [&](const char* key) -> const std::pair<std::string, std::size_t>& {
      auto it = kv.find(key);
      if (it == kv.end())
        at.bad(line.size() + 1, std::string("missing ") + key + "=");
      return it->second;
    };
    auto number = [&](const char* key) {
      const auto& v = get(key);
      return toNumber(v.first, at, v.second, key);
    };
    // exactly four whole numbers 0..255 and three commas ("1.5,2,3,4" read as 1,5,2,3 before)
    auto color = [&] {
      const std::string& text = get("color").first;
      int rgba[4] = { 0, 0, 0, 0 };
      int n = 0;
      std::size_t i = 0;
      bool ok = true;
      for (; ok && n < 4; ++n)
      {
        const std::size_t from = i;
        int v = 0;
        while (i < text.size() && text[i] >= '0' && text[i] <= '9' && i - from < 3)
          v = 10 * v + (text[i++] - '0');
        ok = i > from && (n == 3 ? i == text.size() : i < text.size() && text[i++] == ',');
        rgba[n] = v;
      }
      if (!ok)
        at.bad(get("color").second, "color must be r,g,b,a (four whole numbers 0..255), got '" + text + "'");
      for (int v : rgba)
        if (v > 255)
          at.bad(get("color").second, "color components must be 0..255, got '" + text + "'");
      return Rgba{ std::uint8_t(rgba[0]), std::uint8_t(rgba[1]), std::uint8_t(rgba[2]), std::uint8_t(rgba[3]) };
    };
    EditRecord e;
    e.time = number("time");
    if (undoRedo)
    {
      e.type = head.text == "undo" ? EditRecord::Type::Undo : EditRecord::Type::Redo;
      r.records.push_back(e);
      continue;
    }
    if (fill)
    {
      e.type = EditRecord::Type::Fill;
      e.sdf = number("sdf");
      e.brush.color = color();
      r.records.push_back(e);
      continue;
    }
    e.brush.op = lookup(get("op").first, Ops, at, get("op").second, "op");
    editShape = lookup(get("shape").first, Shapes, at, get("shape").second, "shape");
    e.kind = lookup(get("kind").first, Kinds, at, get("kind").second, "kind");
    e.spacing = number("spacing");
    e.brush.blend = number("blend");
    e.brush.colorOffset = number("coloroffset");
    if (kv.count("rounding"))
      e.brush.rounding = number("rounding");
    if (kv.count("strength"))
      e.brush.strength = number("strength");
    if (kv.count("falloff"))
      e.brush.falloff = lookup(get("falloff").first, Falloffs, at, get("falloff").second, "falloff");
    if (kv.count("invert"))
    {
      const double inv = number("invert");
      if (inv != 0 && inv != 1)
        at.bad(get("invert").second, "invert must be 0 or 1 (got " + get("invert").first + ")");
      e.brush.invert = inv != 0;
    }
    for (int a = 0; a < 3; ++a)
    {
      const std::string key = std::string("mirror") + "xyz"[a];
      if (kv.count(key))
      {
        e.brush.symmetry.mirror[a] = true;
        e.brush.symmetry.plane[a] = number(key.c_str());
      }
    }
    // each value by the one brush rule, named at its column (a blend of -1 or strength=2 was named
    // at the record's first column, where the dab values and the spacing are named at theirs)
    for (const char* key : { "blend", "coloroffset", "rounding", "strength", "mirrorx", "mirrory", "mirrorz" })
      if (kv.count(key))
      {
        BrushSettings one;
        const std::string k = key;
        if (k == "blend") one.blend = e.brush.blend;
        else if (k == "coloroffset") one.colorOffset = e.brush.colorOffset;
        else if (k == "rounding") one.rounding = e.brush.rounding;
        else if (k == "strength") one.strength = e.brush.strength;
        else
        {
          const int a = k.back() - 'x';
          one.symmetry.mirror[a] = true;
          one.symmetry.plane[a] = e.brush.symmetry.plane[a];
        }
        rule([&] { validate(one); }, get(key).second);
      }
    rule([&] { validate(e.brush); }, head.column);
    rule([&] { checkedNumber(e.spacing, EditLimits::MinSpacing, EditLimits::MaxSize, "spacing"); }, get("spacing").second);
    e.brush.color = color();
    const double n = number("dabs");
    if (n < 0 || n != std::floor(n) || n > double(limits.maxDabsPerEdit))
      at.bad(get("dabs").second, "dabs must be a count of at most " + std::to_string(limits.maxDabsPerEdit));
    totalDabs += static_cast<std::uint64_t>(n);
    if (totalDabs > limits.maxTotalDabs)
      at.bad(get("dabs").second, "the recording has more than " + std::to_string(limits.maxTotalDabs) + " dabs in all");
    expectDabs = static_cast<std::size_t>(n);
    r.records.push_back(e);
  }
  if (!header)
  {
    at.Line = std::max<std::size_t>(at.Line, 1); // an empty file's error is on line 1 (it said line 0)
    at.bad(1, "empty recording (no version line)");
  }
  if (expectDabs > 0)
    at.bad(1, "recording ends " + std::to_string(expectDabs) + " dab lines early");
  if (!ended && version >= 2)
  {
    ++at.Line; // where the end record was due
    at.bad(1, "the recording is cut short: no 'end records=N' line (a version 2 recording ends with one)");
  }
  r.version = static_cast<int>(version);
  if (version < 2)
    r.warning = name + ": a version 1 recording has no end record, so a cut file cannot be told from a whole one; its " +
      std::to_string(r.records.size()) + " records are played as they are";
  return r;
}

void saveRecording(const std::string& path, const Recording& recording)
{
  std::ostringstream out;
  writeRecording(out, recording);
  const std::string text = out.str();
  saveAtomically(path, [&](ByteSink& sink) { sink.write(text.data(), text.size()); });
}

Recording loadRecording(const std::string& path)
{
  FileSource src(path); // refuses FIFOs, directories and devices without blocking
  // the version line first: a garbage file is refused without reading it whole
  const std::string magic = "LVDIF-RECORDING";
  std::string head(static_cast<std::size_t>(std::min<std::uint64_t>(src.size(), 4096)), '\0');
  src.read(0, &head[0], head.size());
  std::size_t b = head.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0; // a UTF-8 byte order mark
  while (b < head.size() && head[b] == '#') // comment lines before the version line
  {
    const std::size_t nl = head.find('\n', b);
    b = nl == std::string::npos ? head.size() : nl + 1;
  }
  if (head.compare(b, magic.size(), magic) != 0 && b < head.size())
  {
    std::istringstream first(head.substr(b, head.find('\n', b) - b) + "\n");
    readRecording(first, path); // throws the usual error for the first line
  }
  requireMemory(checkedMultiply(src.size(), 8, "recording"), "reading the recording " + path);
  std::string text(static_cast<std::size_t>(src.size()), '\0');
  src.read(0, &text[0], text.size());
  std::istringstream in(text);
  return readRecording(in, path);
}

} // namespace lvdif
