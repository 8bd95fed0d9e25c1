// libFuzzer target: the mesh readers (OBJ, OFF, STL, PLY) on arbitrary
// bytes. The first byte chooses the format; the rest is the file.
#include "lvdif/MeshFile.h"

#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0)
  {
    return 0;
  }
  const lvdif::MeshFormat formats[4] = { lvdif::MeshFormat::Obj, lvdif::MeshFormat::Off, lvdif::MeshFormat::Stl,
    lvdif::MeshFormat::Ply };
  try
  {
    lvdif::MemorySource src(data + 1, size - 1);
    const lvdif::TriangleMesh mesh = lvdif::readMesh(src, formats[data[0] & 3], "fuzz");
    // a mesh that was accepted must be safe to index
    volatile float sum = 0;
    for (const auto& t : mesh.triangles)
      sum = sum + mesh.points[t[0]][0] + mesh.points[t[1]][1] + mesh.points[t[2]][2];
  }
  catch (const lvdif::Error&)
  {
  }
  return 0;
}
