#include "LVDIFChunkedMarchingCubesVtkTable.h"

#include "vtkMarchingCubesTriangleCases.h"

namespace LVDIFChunkedMarchingCubesVtkTable
{
namespace
{
std::shared_ptr<const lvdif::MarchingCubesTriangleTable> convert()
{
  // VTK vertex -> (x, y, z); see the header
  static const int vertex[8][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 },
    { 1, 1, 1 }, { 0, 1, 1 } };
  static const int vtkEdge[12][2] = { { 0, 1 }, { 1, 2 }, { 3, 2 }, { 0, 3 }, { 4, 5 }, { 5, 6 }, { 7, 6 }, { 4, 7 },
    { 0, 4 }, { 1, 5 }, { 3, 7 }, { 2, 6 } };
  int corner[8];
  for (int v = 0; v < 8; ++v) corner[v] = vertex[v][0] + 2 * vertex[v][1] + 4 * vertex[v][2];
  // lvdif edge of VTK edge k: axis = the coordinate that differs; (bu, bv) = the
  // lower vertex's coordinates along axis+1, axis+2
  int edge[12];
  for (int k = 0; k < 12; ++k)
  {
    const int* a = vertex[vtkEdge[k][0]];
    const int* b = vertex[vtkEdge[k][1]];
    int axis = 0;
    while (a[axis] == b[axis]) ++axis;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    edge[k] = 4 * axis + 2 * a[u] + a[v];
  }
  auto table = std::make_shared<lvdif::MarchingCubesTriangleTable>();
  for (auto& row : *table) row.fill(-1);
  const vtkMarchingCubesTriangleCases* cases = vtkMarchingCubesTriangleCases::GetCases();
  for (int vc = 0; vc < 256; ++vc)
  {
    int ours = 0;
    for (int v = 0; v < 8; ++v)
      if ((vc >> v) & 1) ours |= 1 << corner[v];
    const auto* e = cases[vc].edges; // int (EDGE_LIST in VTK 9.1; a plain int in ParaView 5.11's VTK)
    auto& row = (*table)[static_cast<std::size_t>(ours)];
    for (int k = 0; k < 15 && e[k] >= 0; k += 3)
    {
      // reversed: (a, b, c) -> (c, b, a)
      row[static_cast<std::size_t>(k)] = static_cast<std::int8_t>(edge[e[k + 2]]);
      row[static_cast<std::size_t>(k + 1)] = static_cast<std::int8_t>(edge[e[k + 1]]);
      row[static_cast<std::size_t>(k + 2)] = static_cast<std::int8_t>(edge[e[k]]);
    }
  }
  return table;
}
}

std::shared_ptr<const lvdif::MarchingCubesTriangleTable> Get()
{
  static const std::shared_ptr<const lvdif::MarchingCubesTriangleTable> table = convert();
  return table;
}
}
