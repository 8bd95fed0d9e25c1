// Test meshes that follow the marching cubes filter's output contract
// (cell data corner_rgba + cell_ijk, point data rgba + Normals), built
// independently of the project's marching cubes: vtkFlyingEdges3D on an
// analytic SDF image, then the arrays computed from the triangle geometry.
#pragma once

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkFlyingEdges3D.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <array>
#include <cmath>
#include <functional>
#include <map>

namespace lvdiftest
{
using Rgba = std::array<unsigned char, 4>;
using SdfFn = std::function<double(double, double, double)>; // voxel coordinates
using ColorFn = std::function<Rgba(int, int, int)>;          // voxel index

inline vtkSmartPointer<vtkImageData> sdfImage(int n, const SdfFn& f, double spacing = 1.0)
{
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->SetDimensions(n, n, n);
  img->SetSpacing(spacing, spacing, spacing);
  img->SetOrigin(0, 0, 0);
  vtkNew<vtkFloatArray> sdf;
  sdf->SetName("sdf");
  sdf->SetNumberOfTuples(static_cast<vtkIdType>(n) * n * n);
  vtkIdType id = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        sdf->SetValue(id++, static_cast<float>(f(i, j, k)));
  img->GetPointData()->SetScalars(sdf);
  return img;
}

/// A mesh with the contract arrays; colours from voxel indices.
inline vtkSmartPointer<vtkPolyData> contractMesh(vtkImageData* img, const ColorFn& color)
{
  vtkNew<vtkFlyingEdges3D> fe;
  fe->SetInputData(img);
  fe->SetValue(0, 0.0);
  fe->ComputeNormalsOn();
  fe->ComputeScalarsOff();
  fe->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(fe->GetOutput());
  double o[3], h[3];
  int dims[3];
  img->GetOrigin(o);
  img->GetSpacing(h);
  img->GetDimensions(dims);
  if (auto* n = mesh->GetPointData()->GetNormals())
  {
    n->SetName("Normals");
  }
  const vtkIdType nt = mesh->GetNumberOfPolys();
  vtkNew<vtkUnsignedCharArray> corners;
  corners->SetName("corner_rgba");
  corners->SetNumberOfComponents(32);
  corners->SetNumberOfTuples(nt);
  vtkNew<vtkIntArray> ijk;
  ijk->SetName("cell_ijk");
  ijk->SetNumberOfComponents(3);
  ijk->SetNumberOfTuples(nt);
  vtkNew<vtkUnsignedCharArray> rgba;
  rgba->SetName("rgba");
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(mesh->GetNumberOfPoints());
  vtkIdType npts;
  const vtkIdType* pts;
  vtkCellArray* polys = mesh->GetPolys();
  polys->InitTraversal();
  for (vtkIdType t = 0; polys->GetNextCell(npts, pts); ++t)
  {
    double c[3] = { 0, 0, 0 };
    for (int v = 0; v < 3; ++v)
    {
      double p[3];
      mesh->GetPoint(pts[v], p);
      for (int a = 0; a < 3; ++a)
        c[a] += p[a] / 3.0;
    }
    int cell[3];
    for (int a = 0; a < 3; ++a)
    {
      cell[a] = static_cast<int>(std::floor((c[a] - o[a]) / h[a]));
      cell[a] = std::max(0, std::min(dims[a] - 2, cell[a]));
      ijk->SetTypedComponent(t, a, cell[a]);
    }
    Rgba cc[8];
    for (int k = 0; k < 8; ++k)
    {
      cc[k] = color(cell[0] + (k & 1), cell[1] + ((k >> 1) & 1), cell[2] + ((k >> 2) & 1));
      for (int q = 0; q < 4; ++q)
        corners->SetTypedComponent(t, 4 * k + q, cc[k][q]);
    }
    // Per-vertex colour: trilinear in the cell (= linear along the cut edge, as MC).
    for (int v = 0; v < 3; ++v)
    {
      double p[3];
      mesh->GetPoint(pts[v], p);
      double u[3];
      for (int a = 0; a < 3; ++a)
        u[a] = std::max(0.0, std::min(1.0, (p[a] - o[a]) / h[a] - cell[a]));
      for (int q = 0; q < 4; ++q)
      {
        double s = 0;
        for (int k = 0; k < 8; ++k)
        {
          const double w = ((k & 1) ? u[0] : 1 - u[0]) * (((k >> 1) & 1) ? u[1] : 1 - u[1]) *
            (((k >> 2) & 1) ? u[2] : 1 - u[2]);
          s += w * cc[k][q];
        }
        rgba->SetTypedComponent(pts[v], q, static_cast<unsigned char>(std::lround(s)));
      }
    }
  }
  mesh->GetCellData()->AddArray(corners);
  mesh->GetCellData()->AddArray(ijk);
  mesh->GetPointData()->AddArray(rgba);
  return mesh;
}

/// Splits a contract mesh into chunks of `edge` cells (by cell_ijk); chunk id x-fastest.
inline std::map<vtkIdType, vtkSmartPointer<vtkPolyData>> splitChunks(vtkPolyData* mesh, int edge, int cellsPerAxis)
{
  const int nc = (cellsPerAxis + edge - 1) / edge;
  std::map<vtkIdType, std::vector<vtkIdType>> cellsOf;
  vtkDataArray* ijk = mesh->GetCellData()->GetArray("cell_ijk");
  for (vtkIdType t = 0; t < mesh->GetNumberOfCells(); ++t)
  {
    const int cx = static_cast<int>(ijk->GetComponent(t, 0)) / edge;
    const int cy = static_cast<int>(ijk->GetComponent(t, 1)) / edge;
    const int cz = static_cast<int>(ijk->GetComponent(t, 2)) / edge;
    cellsOf[cx + nc * (cy + static_cast<vtkIdType>(nc) * cz)].push_back(t);
  }
  std::map<vtkIdType, vtkSmartPointer<vtkPolyData>> out;
  for (auto& kv : cellsOf)
  {
    auto pd = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkPoints> pts;
    vtkNew<vtkCellArray> polys;
    pd->GetPointData()->CopyAllocate(mesh->GetPointData());
    pd->GetCellData()->CopyAllocate(mesh->GetCellData());
    std::map<vtkIdType, vtkIdType> remap;
    vtkIdType t2 = 0;
    for (vtkIdType t : kv.second)
    {
      vtkIdType npts;
      const vtkIdType* ids;
      mesh->GetCellPoints(t, npts, ids);
      vtkIdType nid[3];
      for (int v = 0; v < 3; ++v)
      {
        auto it = remap.find(ids[v]);
        if (it == remap.end())
        {
          const vtkIdType id = pts->InsertNextPoint(mesh->GetPoint(ids[v]));
          pd->GetPointData()->CopyData(mesh->GetPointData(), ids[v], id);
          it = remap.emplace(ids[v], id).first;
        }
        nid[v] = it->second;
      }
      polys->InsertNextCell(3, nid);
      pd->GetCellData()->CopyData(mesh->GetCellData(), t, t2++);
    }
    pd->SetPoints(pts);
    pd->SetPolys(polys);
    out[kv.first] = pd;
  }
  return out;
}

/// Colourful voxels: a smooth hue field with a 4-voxel checker overlay.
inline Rgba checkerColor(int i, int j, int k)
{
  const bool odd = ((i / 4) + (j / 4) + (k / 4)) % 2;
  return odd ? Rgba{ 230, 60, 40, 255 } : Rgba{ 40, 90, 220, 255 };
}

/// A sphere of radius 0.33 n about the image's centre, as a contract mesh in
/// checker colours.
inline vtkSmartPointer<vtkPolyData> sphereMesh(int n = 24, double spacing = 1.0)
{
  auto img = sdfImage(n, [n](double x, double y, double z) {
    const double c = 0.5 * (n - 1);
    return std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c)) - 0.33 * n;
  }, spacing);
  return contractMesh(img, checkerColor);
}
} // namespace lvdiftest
