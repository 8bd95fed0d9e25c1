// Shared helpers for the vtkChunkedMarchingCubes tests: analytic SDF images
// and independent measures (area, enclosed volume, triangle-set matching up to
// float rounding, boundary edges) computed in double precision with VTK's own classes.
#pragma once

#include "vtkAlgorithm.h"
#include "vtkAppendPolyData.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkCellArray.h"
#include "vtkCleanPolyData.h"
#include "vtkFeatureEdges.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkMath.h"
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
#include <map>
#include <random>
#include <set>
#include <vector>

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

/// A sphere plus per-point uniform noise of amplitude `amp` (fixed seed, one
/// value per grid point, so the field is defined on the grid only: use with
/// sampledNoisy). Many cells with ambiguous faces near the surface.
inline vtkSmartPointer<vtkImageData> sampledNoisy(const int dims[3], const double origin[3], const double spacing[3],
  const Sdf& f, double amp, unsigned seed)
{
  auto img = sampled(dims, origin, spacing, f);
  auto* sdf = vtkFloatArray::SafeDownCast(img->GetPointData()->GetArray("sdf"));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amp, amp);
  for (vtkIdType i = 0; i < sdf->GetNumberOfTuples(); ++i) sdf->SetValue(i, static_cast<float>(sdf->GetValue(i) + u(rng)));
  return img;
}

/// Cells of the image with at least one ambiguous face (two diagonal corners
/// above iso, the other two below).
inline vtkIdType ambiguousCells(vtkImageData* img, const char* array, double iso)
{
  int d[3];
  img->GetDimensions(d);
  vtkDataArray* a = img->GetPointData()->GetArray(array);
  auto above = [&](int i, int j, int k) { return a->GetComponent(i + d[0] * (j + static_cast<vtkIdType>(d[1]) * k), 0) >= iso; };
  vtkIdType n = 0;
  for (int k = 0; k + 1 < d[2]; ++k)
    for (int j = 0; j + 1 < d[1]; ++j)
      for (int i = 0; i + 1 < d[0]; ++i)
      {
        bool amb = false;
        for (int axis = 0; axis < 3 && !amb; ++axis)
          for (int side = 0; side < 2 && !amb; ++side)
          {
            int c[4][3];
            for (int q = 0; q < 4; ++q)
            {
              int o[3];
              o[axis] = side;
              o[(axis + 1) % 3] = q & 1;
              o[(axis + 2) % 3] = q >> 1;
              c[q][0] = i + o[0];
              c[q][1] = j + o[1];
              c[q][2] = k + o[2];
            }
            const bool s0 = above(c[0][0], c[0][1], c[0][2]), s1 = above(c[1][0], c[1][1], c[1][2]),
                       s2 = above(c[2][0], c[2][1], c[2][2]), s3 = above(c[3][0], c[3][1], c[3][2]);
            amb = s0 == s3 && s1 == s2 && s0 != s1; // corners 0,3 and 1,2 are the diagonals
          }
        n += amb;
      }
  return n;
}

/// The triangles of a and b as sets of 3 vertex positions, compared up to
/// `tol` per vertex: every point of a is matched to the nearest point of b
/// (and the reverse); the matching must be one-to-one; then every triangle of
/// a, as an unordered triple of matched points, must be a triangle of b, and
/// vice versa (as multisets). When identical(), every triangle of a coincides
/// with one of b up to tol per vertex: the Hausdorff distance between the two
/// surfaces is at most tol. (Points with a second candidate within tol, e.g.
/// several vertices within rounding of one grid point, are counted in
/// ambiguousPoints; they do not weaken that conclusion, since any candidate is
/// within tol.)
struct TriangleMatch
{
  vtkIdType unmatchedPoints = 0; // no point within tol, or the matching is not one-to-one
  vtkIdType ambiguousPoints = 0; // two candidates within tol
  vtkIdType onlyInA = 0, onlyInB = 0; // triangles without a counterpart
  vtkIdType sameOrientation = 0, reversedOrientation = 0; // of the matched triangles
  double maxPointDistance = 0;
  bool identical() const { return !unmatchedPoints && !onlyInA && !onlyInB; }
};

inline std::vector<vtkIdType> nearestMap(vtkPolyData* a, vtkPolyData* b, double tol, TriangleMatch& r)
{
  vtkNew<vtkStaticPointLocator> loc;
  loc->SetDataSet(b);
  loc->BuildLocator();
  std::vector<vtkIdType> map(static_cast<std::size_t>(a->GetNumberOfPoints()), -1);
  vtkNew<vtkIdList> near;
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    a->GetPoint(i, p);
    loc->FindClosestNPoints(2, p, near);
    if (near->GetNumberOfIds() < 1) continue;
    b->GetPoint(near->GetId(0), q);
    const double d = std::sqrt(vtkMath::Distance2BetweenPoints(p, q));
    r.maxPointDistance = std::max(r.maxPointDistance, d);
    if (d > tol) continue;
    if (near->GetNumberOfIds() > 1)
    {
      b->GetPoint(near->GetId(1), q);
      if (std::sqrt(vtkMath::Distance2BetweenPoints(p, q)) <= tol) ++r.ambiguousPoints;
    }
    map[static_cast<std::size_t>(i)] = near->GetId(0);
  }
  return map;
}

inline std::vector<std::array<vtkIdType, 3>> triangleIds(vtkPolyData* pd)
{
  std::vector<std::array<vtkIdType, 3>> t;
  vtkNew<vtkIdList> ids;
  vtkCellArray* polys = pd->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(ids);)
    if (ids->GetNumberOfIds() == 3) t.push_back({ ids->GetId(0), ids->GetId(1), ids->GetId(2) });
  return t;
}

inline TriangleMatch matchTriangles(vtkPolyData* a, vtkPolyData* b, double tol)
{
  TriangleMatch r;
  const std::vector<vtkIdType> ab = nearestMap(a, b, tol, r), ba = nearestMap(b, a, tol, r);
  for (std::size_t i = 0; i < ab.size(); ++i)
    if (ab[i] < 0 || ba[static_cast<std::size_t>(ab[i])] != static_cast<vtkIdType>(i)) ++r.unmatchedPoints;
  for (std::size_t i = 0; i < ba.size(); ++i)
    if (ba[i] < 0) ++r.unmatchedPoints;
  // b's triangles: sorted triple -> oriented (rotated) triples
  std::multimap<std::array<vtkIdType, 3>, std::array<vtkIdType, 3>> inB;
  auto rotate = [](std::array<vtkIdType, 3> t) {
    while (t[0] > t[1] || t[0] > t[2]) t = { t[1], t[2], t[0] };
    return t;
  };
  for (auto t : triangleIds(b))
  {
    std::array<vtkIdType, 3> s = t;
    std::sort(s.begin(), s.end());
    inB.emplace(s, rotate(t));
  }
  for (auto t : triangleIds(a))
  {
    std::array<vtkIdType, 3> m;
    bool ok = true;
    for (int k = 0; k < 3; ++k)
    {
      m[k] = ab[static_cast<std::size_t>(t[k])];
      ok = ok && m[k] >= 0;
    }
    std::array<vtkIdType, 3> s = m;
    std::sort(s.begin(), s.end());
    const auto it = ok ? inB.find(s) : inB.end();
    if (it == inB.end())
    {
      ++r.onlyInA;
      continue;
    }
    if (it->second == rotate(m))
      ++r.sameOrientation;
    else
      ++r.reversedOrientation;
    inB.erase(it);
  }
  r.onlyInB = static_cast<vtkIdType>(inB.size());
  return r;
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
/// Updates alg and returns how many ErrorEvents it (or its executive) raised.
inline int countErrors(vtkAlgorithm* mc)
{
  int errors = 0;
  vtkNew<vtkCallbackCommand> cb;
  cb->SetClientData(&errors);
  cb->SetCallback([](vtkObject*, unsigned long, void* data, void*) { ++*static_cast<int*>(data); });
  mc->AddObserver(vtkCommand::ErrorEvent, cb);
  mc->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, cb);
  mc->Update();
  return errors;
}

} // namespace meshtest
