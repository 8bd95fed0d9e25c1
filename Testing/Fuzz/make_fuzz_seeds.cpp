// Writes the seed corpus of the fuzz targets (run by scripts/fuzz.sh): small
// valid volume files (random chunks, an analytic sphere with paint, metadata)
// and small .bv files, so the fuzzers start from inputs that reach deep code.
// and small meshes in every format the mesh readers take.
// Usage: make_fuzz_seeds <volume corpus dir> <bv corpus dir> [mesh corpus dir]
#include "lvdif/AnalyticFill.h"
#include "lvdif/LegacyBv.h"
#include "lvdif/TriangleMesh.h"
#include "lvdif/VolumeFile.h"

#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

using namespace lvdif;

static void writeFile(const std::string& path, const std::vector<std::uint8_t>& bytes, std::uint8_t prefix = 0,
  bool withPrefix = false)
{
  std::ofstream f(path, std::ios::binary);
  if (withPrefix)
    f.put(static_cast<char>(prefix));
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

/// Small mesh files of a coarse sphere; the first byte selects the reader (fuzz_mesh.cpp).
static void writeMeshSeeds(const std::string& dir)
{
  const TriangleMesh m = makeSphereMesh(0, 0, 0, 1, 3, 4);
  std::ostringstream obj, off, ply, stl;
  for (const auto& p : m.points)
    obj << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
  for (const auto& t : m.triangles)
    obj << "f " << t[0] + 1 << " " << t[1] + 1 << "/1 " << t[2] + 1 << "//2\n";
  off << "OFF\n" << m.points.size() << " " << m.triangles.size() << " 0\n";
  for (const auto& p : m.points)
    off << p[0] << " " << p[1] << " " << p[2] << "\n";
  for (const auto& t : m.triangles)
    off << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  ply << "ply\nformat ascii 1.0\nelement vertex " << m.points.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << m.triangles.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : m.points)
    ply << p[0] << " " << p[1] << " " << p[2] << "\n";
  for (const auto& t : m.triangles)
    ply << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  stl << "solid s\n";
  for (const auto& t : m.triangles)
  {
    stl << "facet normal 0 0 1\nouter loop\n";
    for (int c = 0; c < 3; ++c)
      stl << "vertex " << m.points[t[c]][0] << " " << m.points[t[c]][1] << " " << m.points[t[c]][2] << "\n";
    stl << "endloop\nendfacet\n";
  }
  stl << "endsolid s\n";
  // binary little-endian PLY of the same mesh
  std::string bin = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(m.points.size()) +
    "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(m.triangles.size()) +
    "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : m.points)
    bin.append(reinterpret_cast<const char*>(p.data()), 12);
  for (const auto& t : m.triangles)
  {
    bin.push_back(3);
    for (int c = 0; c < 3; ++c)
    {
      const std::int32_t i = static_cast<std::int32_t>(t[c]);
      bin.append(reinterpret_cast<const char*>(&i), 4);
    }
  }
  auto save = [&](const std::string& name, char selector, const std::string& text) {
    std::vector<std::uint8_t> bytes(text.begin(), text.end());
    writeFile(dir + "/" + name, bytes, static_cast<std::uint8_t>(selector), true);
  };
  save("sphere.obj", 0, obj.str());
  save("sphere.off", 1, off.str());
  save("sphere.stl", 2, stl.str());
  save("sphere.ply", 3, ply.str());
  save("sphere-bin.ply", 3, bin);
}

int main(int argc, char** argv)
{
  if (argc != 3 && argc != 4)
  {
    std::cerr << "usage: make_fuzz_seeds <volume corpus dir> <bv corpus dir> [mesh corpus dir]\n";
    return 2;
  }
  if (argc == 4)
    writeMeshSeeds(argv[3]);
  const std::string vdir = argv[1], bdir = argv[2];
  std::mt19937 rng(7);
  int index = 0;
  for (Index3 dims : { Index3{ 9, 7, 5 }, Index3{ 20, 12, 8 }, Index3{ 16, 16, 16 } })
  {
    for (int edge : { 4, 8 })
    {
      VolumeOptions o;
      o.dims = dims;
      o.chunkEdge = edge;
      DictionaryVolume v(o);
      fillFromFunction(v, sphereSdf(dims[0] / 2.0, dims[1] / 2.0, dims[2] / 2.0, dims[2] / 3.0));
      const ColorKey red = v.colors().add(Rgba{ 255, 0, 0, 255 });
      for (int i = 0; i < 20; ++i)
        v.set(rng() % dims[0], rng() % dims[1], rng() % dims[2], Voxel{ SdfKey(rng()), red });
      VolumeFileWriteOptions wo;
      wo.metadata["name"] = "seed " + std::to_string(index);
      wo.metadata["source mesh"] = "analytic sphere";
      MemorySink sink;
      writeVolume(v, sink, wo);
      writeFile(vdir + "/seed" + std::to_string(index) + ".lvdv", sink.buffer());
      if (dims[0] == dims[1] && dims[1] == dims[2])
      {
        MemorySink bv;
        writeLegacyBv(v, bv);
        writeFile(bdir + "/seed" + std::to_string(index) + ".bv", bv.buffer(), std::uint8_t(1 | (16 << 1)), true);
        writeFile(bdir + "/seed" + std::to_string(index) + "-noname.bv", bv.buffer(), 2, true);
      }
      ++index;
    }
  }
  for (int n : { 1, 2, 3, 5 })
  {
    std::vector<std::uint8_t> raw(static_cast<size_t>(4 * n * n * n));
    for (auto& b : raw)
      b = std::uint8_t(rng() % 4 ? rng() : 0);
    writeFile(bdir + "/raw" + std::to_string(n) + ".bv", raw, std::uint8_t(1 | (n << 1)), true);
  }
  std::cout << "wrote " << index << " volume seeds to " << vdir << " and .bv seeds to " << bdir << "\n";
  return 0;
}
