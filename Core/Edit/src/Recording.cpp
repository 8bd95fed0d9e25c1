#include "lvdif/Recording.h"

#include "lvdif/Error.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

namespace lvdif
{

namespace
{
std::string num(double v)
{
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

[[noreturn]] void bad(std::size_t line, const std::string& what)
{
  throw Error(ErrorCode::ParseError, "recording line " + std::to_string(line) + ": " + what);
}

double toNumber(const std::string& s, std::size_t line, const std::string& what)
{
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(v))
    bad(line, what + " is not a finite number: '" + s + "'");
  return v;
}

template <typename E>
E lookup(const std::string& word, const std::map<std::string, E>& table, std::size_t line, const char* what)
{
  auto it = table.find(word);
  if (it == table.end())
    bad(line, std::string("unknown ") + what + " '" + word + "'");
  return it->second;
}

const std::map<std::string, BrushOp> Ops{ { "add", BrushOp::Add }, { "subtract", BrushOp::Subtract },
  { "paint", BrushOp::Paint } };
const std::map<std::string, BrushShape> Shapes{ { "sphere", BrushShape::Sphere }, { "cube", BrushShape::Cube },
  { "capsule", BrushShape::Capsule } };
const std::map<std::string, BrushKind> Kinds{ { "single", BrushKind::Single }, { "basic", BrushKind::Basic },
  { "dynamic", BrushKind::Dynamic }, { "drill", BrushKind::Drill } };
} // namespace

void writeRecording(std::ostream& out, const Recording& r)
{
  out << "LVDIF-RECORDING " << Recording::Version << "\n";
  for (const EditRecord& e : r.records)
  {
    if (e.type == EditRecord::Type::Undo || e.type == EditRecord::Type::Redo)
    {
      out << (e.type == EditRecord::Type::Undo ? "undo" : "redo") << " time=" << num(e.time) << "\n";
      continue;
    }
    // the shape of the first dab names the edit; each dab line carries its own when capsules mix in
    const BrushShape shape = e.dabs.empty() ? BrushShape::Sphere : e.dabs.front().shape;
    out << "edit time=" << num(e.time) << " op=" << toString(e.brush.op) << " shape=" << toString(shape)
        << " kind=" << toString(e.kind) << " spacing=" << num(e.spacing) << " blend=" << num(e.brush.blend)
        << " coloroffset=" << num(e.brush.colorOffset) << " rounding=" << num(e.brush.rounding) << " color=" << int(e.brush.color.r) << ","
        << int(e.brush.color.g) << "," << int(e.brush.color.b) << "," << int(e.brush.color.a)
        << " dabs=" << e.dabs.size() << "\n";
    for (const Dab& d : e.dabs)
    {
      out << (d.shape == shape ? "d" : (std::string("d:") + toString(d.shape))) << " " << num(d.center[0]) << " "
          << num(d.center[1]) << " " << num(d.center[2]) << " " << num(d.radius);
      if (d.shape == BrushShape::Capsule)
        out << " " << num(d.end[0]) << " " << num(d.end[1]) << " " << num(d.end[2]);
      out << "\n";
    }
  }
}

Recording readRecording(std::istream& in)
{
  Recording r;
  std::string line;
  std::size_t no = 0;
  bool header = false;
  std::size_t expectDabs = 0;
  BrushShape editShape = BrushShape::Sphere;
  while (std::getline(in, line))
  {
    ++no;
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    if (line.empty() || line[0] == '#')
      continue;
    std::istringstream words(line);
    std::string head;
    words >> head;
    if (!header)
    {
      int version = 0;
      if (head != "LVDIF-RECORDING" || !(words >> version))
        bad(no, "expected the version line 'LVDIF-RECORDING 1'");
      if (version != Recording::Version)
        bad(no, "unsupported recording version " + std::to_string(version));
      header = true;
      continue;
    }
    if (expectDabs > 0)
    {
      Dab d;
      d.shape = editShape;
      if (head.rfind("d:", 0) == 0)
        d.shape = lookup(head.substr(2), Shapes, no, "shape");
      else if (head != "d")
        bad(no, "expected a dab line 'd x y z r', " + std::to_string(expectDabs) + " more due");
      std::vector<std::string> f;
      for (std::string w; words >> w;)
        f.push_back(w);
      const std::size_t want = d.shape == BrushShape::Capsule ? 7 : 4;
      if (f.size() != want)
        bad(no, "a dab needs " + std::to_string(want) + " numbers");
      for (int a = 0; a < 3; ++a)
        d.center[a] = toNumber(f[a], no, "dab position");
      d.radius = toNumber(f[3], no, "dab radius");
      if (want == 7)
        for (int a = 0; a < 3; ++a)
          d.end[a] = toNumber(f[4 + a], no, "capsule end");
      r.records.back().dabs.push_back(d);
      --expectDabs;
      continue;
    }
    std::map<std::string, std::string> kv;
    for (std::string w; words >> w;)
    {
      const auto eq = w.find('=');
      if (eq == std::string::npos)
        bad(no, "expected key=value, got '" + w + "'");
      kv[w.substr(0, eq)] = w.substr(eq + 1);
    }
    auto get = [&](const char* key) -> std::string {
      auto it = kv.find(key);
      if (it == kv.end())
        bad(no, std::string("missing ") + key + "=");
      return it->second;
    };
    EditRecord e;
    e.time = toNumber(get("time"), no, "time");
    if (head == "undo" || head == "redo")
    {
      e.type = head == "undo" ? EditRecord::Type::Undo : EditRecord::Type::Redo;
      r.records.push_back(e);
      continue;
    }
    if (head != "edit")
      bad(no, "unknown record '" + head + "'");
    e.brush.op = lookup(get("op"), Ops, no, "op");
    editShape = lookup(get("shape"), Shapes, no, "shape");
    e.kind = lookup(get("kind"), Kinds, no, "kind");
    e.spacing = toNumber(get("spacing"), no, "spacing");
    e.brush.blend = toNumber(get("blend"), no, "blend");
    e.brush.colorOffset = toNumber(get("coloroffset"), no, "coloroffset");
    if (kv.count("rounding"))
      e.brush.rounding = toNumber(kv["rounding"], no, "rounding");
    {
      std::istringstream c(get("color"));
      int rgba[4];
      char sep;
      if (!(c >> rgba[0] >> sep >> rgba[1] >> sep >> rgba[2] >> sep >> rgba[3]))
        bad(no, "color must be r,g,b,a");
      for (int v : rgba)
        if (v < 0 || v > 255)
          bad(no, "color components must be 0..255");
      e.brush.color = Rgba{ std::uint8_t(rgba[0]), std::uint8_t(rgba[1]), std::uint8_t(rgba[2]), std::uint8_t(rgba[3]) };
    }
    const double n = toNumber(get("dabs"), no, "dabs");
    if (n < 0 || n > 1e8 || n != std::floor(n))
      bad(no, "dabs must be a count");
    expectDabs = static_cast<std::size_t>(n);
    r.records.push_back(e);
  }
  if (!header)
    bad(no, "empty recording (no version line)");
  if (expectDabs > 0)
    bad(no, "recording ends " + std::to_string(expectDabs) + " dab lines early");
  return r;
}

void saveRecording(const std::string& path, const Recording& recording)
{
  std::ofstream out(path);
  if (!out)
    throw Error(ErrorCode::IoFailure, "cannot write recording '" + path + "'");
  writeRecording(out, recording);
  if (!out)
    throw Error(ErrorCode::IoFailure, "writing recording '" + path + "' failed");
}

Recording loadRecording(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
    throw Error(ErrorCode::IoFailure, "cannot read recording '" + path + "'");
  return readRecording(in);
}

} // namespace lvdif
