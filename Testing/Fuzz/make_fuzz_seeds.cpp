// Writes the seed corpus of the fuzz targets (run by scripts/fuzz.sh): small
// valid volume files (random chunks, an analytic sphere with paint, metadata)
// and small .bv files, so the fuzzers start from inputs that reach deep code.
// Usage: make_fuzz_seeds <volume corpus dir> <bv corpus dir>
#include "lvdif/AnalyticFill.h"
#include "lvdif/LegacyBv.h"
#include "lvdif/VolumeFile.h"

#include <fstream>
#include <iostream>
#include <random>

using namespace lvdif;

static void writeFile(const std::string& path, const std::vector<std::uint8_t>& bytes, std::uint8_t prefix = 0,
  bool withPrefix = false)
{
  std::ofstream f(path, std::ios::binary);
  if (withPrefix)
    f.put(static_cast<char>(prefix));
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

int main(int argc, char** argv)
{
  if (argc != 3)
  {
    std::cerr << "usage: make_fuzz_seeds <volume corpus dir> <bv corpus dir>\n";
    return 2;
  }
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
