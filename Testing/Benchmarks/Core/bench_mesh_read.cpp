// Mesh reader benchmark: writes a generated mesh of about N triangles (a
// closed wavy torus, exact float positions) as binary little-endian PLY,
// binary STL, ASCII PLY and OFF, then times loadMesh on each (best of 3) and
// the raw read of the same bytes, so the figure to compare across machines is
// the ratio to the raw read of the file (from the page cache after the first).
// usage: bench_mesh_read [N=10000000] [DIR=/tmp] [formats=ply,stl,asciiply,off,obj]
#include "BenchCommon.h"

#include "lvdif/MeshFile.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace lvdif;

namespace
{
TriangleMesh torus(std::int64_t triangles)
{
  const auto n = static_cast<std::int64_t>(std::sqrt(static_cast<double>(triangles) / 2.0));
  TriangleMesh m;
  for (std::int64_t i = 0; i < n; ++i)
    for (std::int64_t j = 0; j < n; ++j)
    {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / n, r = 0.3 + 0.02 * std::sin(7 * u) * std::cos(5 * v);
      m.points.push_back({ static_cast<float>((1 + r * std::cos(v)) * std::cos(u)),
        static_cast<float>((1 + r * std::cos(v)) * std::sin(u)), static_cast<float>(r * std::sin(v)) });
    }
  auto id = [n](std::int64_t i, std::int64_t j) { return static_cast<std::uint32_t>((i % n) * n + (j % n)); };
  for (std::int64_t i = 0; i < n; ++i)
    for (std::int64_t j = 0; j < n; ++j)
    {
      m.triangles.push_back({ id(i, j), id(i + 1, j), id(i + 1, j + 1) });
      m.triangles.push_back({ id(i, j), id(i + 1, j + 1), id(i, j + 1) });
    }
  return m;
}

void writeFile(const std::string& path, const std::string& bytes)
{
  std::ofstream f(path, std::ios::binary);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string plyBinary(const TriangleMesh& m)
{
  std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(m.points.size()) +
    "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(m.triangles.size()) +
    "\nproperty list uchar int vertex_indices\nend_header\n";
  s.append(reinterpret_cast<const char*>(m.points.data()), m.points.size() * 12);
  for (const auto& t : m.triangles)
  {
    s.push_back(3);
    s.append(reinterpret_cast<const char*>(t.data()), 12);
  }
  return s;
}

std::string stlBinary(const TriangleMesh& m)
{
  std::string s(80, ' ');
  const auto n = static_cast<std::uint32_t>(m.triangles.size());
  s.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : m.triangles)
  {
    const float normal[3] = { 0, 0, 0 };
    s.append(reinterpret_cast<const char*>(normal), 12);
    for (int k = 0; k < 3; ++k) s.append(reinterpret_cast<const char*>(m.points[t[k]].data()), 12);
    s.append(2, '\0');
  }
  return s;
}

std::string text(const TriangleMesh& m, bool ply)
{
  std::string s = ply ? "ply\nformat ascii 1.0\nelement vertex " + std::to_string(m.points.size()) +
      "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(m.triangles.size()) +
      "\nproperty list uchar int vertex_indices\nend_header\n"
                      : "OFF\n" + std::to_string(m.points.size()) + " " + std::to_string(m.triangles.size()) + " 0\n";
  char buf[96];
  for (const auto& p : m.points)
    s.append(buf, static_cast<std::size_t>(std::snprintf(buf, sizeof buf, "%.9g %.9g %.9g\n", p[0], p[1], p[2])));
  for (const auto& t : m.triangles)
    s.append(buf, static_cast<std::size_t>(std::snprintf(buf, sizeof buf, "3 %u %u %u\n", t[0], t[1], t[2])));
  return s;
}
std::string obj(const TriangleMesh& m)
{
  std::string s;
  char buf[96];
  for (const auto& p : m.points)
    s.append(buf, static_cast<std::size_t>(std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g\n", p[0], p[1], p[2])));
  for (const auto& t : m.triangles)
    s.append(buf, static_cast<std::size_t>(std::snprintf(buf, sizeof buf, "f %u %u %u\n", t[0] + 1, t[1] + 1, t[2] + 1)));
  return s;
}
} // namespace

static int benchMain(int argc, char** argv)
{
  const std::int64_t n = argc > 1 ? std::atoll(argv[1]) : 10000000;
  const std::string dir = argc > 2 ? argv[2] : "/tmp";
  const std::string formats = argc > 3 ? argv[3] : "ply,stl,asciiply,off,obj";
  const TriangleMesh m = torus(n);
  std::printf("machine: %s\n", bench::machineDescription().c_str());
  std::printf("mesh: %zu points, %zu triangles\n", m.points.size(), m.triangles.size());
  std::vector<std::vector<std::string>> rows;
  struct F
  {
    std::string name, ext;
    std::string (*make)(const TriangleMesh&);
  };
  const F all[] = { { "ply", "ply", plyBinary }, { "stl", "stl", stlBinary },
    { "asciiply", "ply", [](const TriangleMesh& x) { return text(x, true); } },
    { "off", "off", [](const TriangleMesh& x) { return text(x, false); } }, { "obj", "obj", obj } };
  for (const F& f : all)
  {
    if (formats.find(f.name) == std::string::npos) continue;
    const std::string path = dir + "/lvdif-bench-read-" + f.name + "." + f.ext;
    writeFile(path, f.make(m));
    double best = 1e300, raw = 1e300;
    std::size_t tris = 0, points = 0;
    for (int rep = 0; rep < 3; ++rep)
    {
      bench::Stopwatch w;
      {
        // the reference: the whole file in one fread
        std::FILE* in = std::fopen(path.c_str(), "rb");
        std::fseek(in, 0, SEEK_END);
        std::vector<char> bytes(static_cast<std::size_t>(std::ftell(in)));
        std::fseek(in, 0, SEEK_SET);
        const std::size_t got = std::fread(bytes.data(), 1, bytes.size(), in);
        std::fclose(in);
        if (got != bytes.size()) std::fprintf(stderr, "short read of %s\n", path.c_str());
      }
      raw = std::min(raw, w.ms());
      w.reset();
      const TriangleMesh r = loadMesh(path);
      best = std::min(best, w.ms());
      tris = r.triangles.size();
      points = r.points.size();
    }
    std::remove(path.c_str());
    rows.push_back({ f.name, std::to_string(points), std::to_string(tris), bench::fmt(raw, 1), bench::fmt(best, 1),
      bench::fmt(best / raw, 1) });
  }
  bench::printTable({ "format", "points", "triangles", "raw read ms", "loadMesh ms", "ratio" }, rows);
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
