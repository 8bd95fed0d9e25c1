// Shared helpers for the vtkChunkedMarchingCubes tests: analytic SDF images
// and independent measures (area, enclosed volume, nearest-point distances,
// boundary edges) computed in double precision with VTK's own classes.
#pragma once

#include "vtkAppendPolyData.h"
#include "vtkCellArray.h"
#include "vtkCleanPolyData.h"
#include "vtkFeatureEdges.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStaticPointLocator.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <set>

namespace meshtest
{
using Sdf = std::function<double(double, double, double)>;

inline Sdf sphere(double cx, double cy, double cz, double r)
{
  return [=](double x, double y, double z) { return std::sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz)) - r; };
}

inline Sdf torus(double cx, double cy, double cz, double R, double r)
{
  return [=](double x, double y, double z) {
    const double q = std::sqrt((x - cx) * (x - cx) + (y - cy) * (y - cy)) - R;
    return std::sqrt(q * q + (z - cz) * (z - cz)) - r;
  };
}

/// An image with a float `sdf` sampled from f at world positions, and an
/// `rgba` array that is a linear function of x (r) and z (b).
inline vtkSmartPointer<vtkImageData> sampled(const int dims[3], const double origin[3], const double spacing[3], const Sdf& f)
{
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->SetDimensions(dims[0], dims[1], dims[2]);
  img->SetOrigin(origin[0], origin[1], origin[2]);
  img->SetSpacing(spacing[0], spacing[1], spacing[2]);
  vtkNew<vtkFloatArray> sdf;
  sdf->SetName("sdf");
  sdf->SetNumberOfTuples(img->GetNumberOfPoints());
  vtkNew<vtkUnsignedCharArray> rgba;
  rgba->SetName("rgba");
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(img->GetNumberOfPoints());
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        const vtkIdType id = i + dims[0] * (j + static_cast<vtkIdType>(dims[1]) * k);
        const double x = origin[0] + spacing[0] * i, y = origin[1] + spacing[1] * j, z = origin[2] + spacing[2] * k;
        sdf->SetValue(id, static_cast<float>(f(x, y, z)));
        const unsigned char c[4] = { static_cast<unsigned char>(2 * i), static_cast<unsigned char>(j),
          static_cast<unsigned char>(3 * k), 200 };
        rgba->SetTypedTuple(id, c);
      }
  img->GetPointData()->AddArray(sdf);
  img->GetPointData()->AddArray(rgba);
  return img;
}

struct Measures
{
  double area = 0, volume = 0;
  vtkIdType triangles = 0;
};

inline Measures measure(vtkPolyData* pd)
{
  Measures m;
  vtkCellArray* polys = pd->GetPolys();
  vtkNew<vtkIdList> ids;
  for (polys->InitTraversal(); polys->GetNextCell(ids);)
  {
    if (ids->GetNumberOfIds() != 3) continue;
    double p[3][3];
    for (int k = 0; k < 3; ++k) pd->GetPoint(ids->GetId(k), p[k]);
    const double u[3] = { p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2] };
    const double v[3] = { p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2] };
    const double c[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] };
    m.area += 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    m.volume += (p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) - p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
                  p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0])) / 6.0;
    ++m.triangles;
  }
  return m;
}

/// max over points of a of the distance to the nearest point of b.
inline double oneSidedDistance(vtkPolyData* a, vtkPolyData* b)
{
  vtkNew<vtkStaticPointLocator> loc;
  loc->SetDataSet(b);
  loc->BuildLocator();
  double worst = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    a->GetPoint(i, p);
    b->GetPoint(loc->FindClosestPoint(p), q);
    worst = std::max(worst, std::sqrt(vtkMath::Distance2BetweenPoints(p, q)));
  }
  return worst;
}

inline double hausdorff(vtkPolyData* a, vtkPolyData* b)
{
  return std::max(oneSidedDistance(a, b), oneSidedDistance(b, a));
}

/// Merges points with equal coordinates (tolerance 0) and keeps degenerate triangles.
inline vtkSmartPointer<vtkPolyData> mergeByPosition(vtkPolyData* pd)
{
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputData(pd);
  clean->SetTolerance(0.0);
  clean->ConvertPolysToLinesOff();
  clean->ConvertLinesToPointsOff();
  clean->ConvertStripsToPolysOff();
  clean->PointMergingOn();
  clean->Update();
  return clean->GetOutput();
}

/// Boundary + non-manifold edges (0 for a closed, manifold surface).
inline vtkIdType openEdges(vtkPolyData* pd)
{
  vtkNew<vtkFeatureEdges> fe;
  fe->SetInputData(pd);
  fe->BoundaryEdgesOn();
  fe->NonManifoldEdgesOn();
  fe->FeatureEdgesOff();
  fe->ManifoldEdgesOff();
  fe->Update();
  return fe->GetOutput()->GetNumberOfCells();
}

/// Number of triangles whose sorted point-id triple occurs more than once.
inline vtkIdType duplicatedTriangles(vtkPolyData* pd)
{
  std::set<std::array<vtkIdType, 3>> seen;
  vtkIdType dups = 0;
  vtkNew<vtkIdList> ids;
  vtkCellArray* polys = pd->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(ids);)
  {
    std::array<vtkIdType, 3> t{ ids->GetId(0), ids->GetId(1), ids->GetId(2) };
    std::sort(t.begin(), t.end());
    if (!seen.insert(t).second) ++dups;
  }
  return dups;
}
} // namespace meshtest
