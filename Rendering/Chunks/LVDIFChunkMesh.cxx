#include "LVDIFChunkMesh.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstring>
#include <iterator>

vtkSmartPointer<vtkPolyData> LVDIFChunkMesh::ToPolyData(
  const lvdif::ChunkMesh& mesh, const lvdif::ColorDictionary& colors, const lvdif::Index3& pointDims)
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  const vtkIdType np = static_cast<vtkIdType>(mesh.points.size());
  const vtkIdType nt = static_cast<vtkIdType>(mesh.triangles.size());
  vtkNew<vtkFloatArray> xyz;
  xyz->SetNumberOfComponents(3);
  xyz->SetNumberOfTuples(np);
  std::memcpy(xyz->GetPointer(0), mesh.points.data(), sizeof(float) * 3 * np);
  vtkNew<vtkPoints> pts;
  pts->SetData(xyz);
  pd->SetPoints(pts);

  vtkNew<vtkIdTypeArray> offsets, conn;
  offsets->SetNumberOfTuples(nt + 1);
  conn->SetNumberOfTuples(3 * nt);
  for (vtkIdType t = 0; t < nt; ++t)
  {
    offsets->SetValue(t, 3 * t);
    for (int v = 0; v < 3; ++v)
    {
      conn->SetValue(3 * t + v, mesh.triangles[t][v]);
    }
  }
  offsets->SetValue(nt, 3 * nt);
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, conn);
  pd->SetPolys(polys);

  if (mesh.normals.size() == mesh.points.size())
  {
    vtkNew<vtkFloatArray> n;
    n->SetName("Normals");
    n->SetNumberOfComponents(3);
    n->SetNumberOfTuples(np);
    std::memcpy(n->GetPointer(0), mesh.normals.data(), sizeof(float) * 3 * np);
    pd->GetPointData()->SetNormals(n);
  }
  if (mesh.colors.size() == mesh.points.size())
  {
    vtkNew<vtkUnsignedCharArray> c;
    c->SetName("rgba");
    c->SetNumberOfComponents(4);
    c->SetNumberOfTuples(np);
    static_assert(sizeof(lvdif::Rgba) == 4, "Rgba is r, g, b, a bytes");
    std::memcpy(c->GetPointer(0), mesh.colors.data(), 4 * static_cast<size_t>(np));
    pd->GetPointData()->AddArray(c);
  }
  if (mesh.cornerColors.size() == mesh.triangles.size() && mesh.triangleCells.size() == mesh.triangles.size())
  {
    vtkNew<vtkUnsignedCharArray> corners;
    corners->SetName("corner_rgba");
    corners->SetNumberOfComponents(32);
    corners->SetNumberOfTuples(nt);
    vtkNew<vtkIntArray> ijk;
    ijk->SetName("cell_ijk");
    ijk->SetNumberOfComponents(3);
    ijk->SetNumberOfTuples(nt);
    const std::int64_t nx = pointDims[0], nxy = pointDims[0] * pointDims[1];
    for (vtkIdType t = 0; t < nt; ++t)
    {
      unsigned char* out = corners->GetPointer(32 * t);
      for (int k = 0; k < 8; ++k)
      {
        const lvdif::Rgba& col = colors[mesh.cornerColors[t][k]];
        out[4 * k + 0] = col.r;
        out[4 * k + 1] = col.g;
        out[4 * k + 2] = col.b;
        out[4 * k + 3] = col.a;
      }
      const std::int64_t lin = mesh.triangleCells[t];
      ijk->SetTypedComponent(t, 0, static_cast<int>(lin % nx));
      ijk->SetTypedComponent(t, 1, static_cast<int>((lin / nx) % pointDims[1]));
      ijk->SetTypedComponent(t, 2, static_cast<int>(lin / nxy));
    }
    pd->GetCellData()->AddArray(corners);
    pd->GetCellData()->AddArray(ijk);
  }
  return pd;
}
