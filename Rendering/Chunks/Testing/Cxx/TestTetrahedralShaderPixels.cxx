// The tetrahedral colour shader against an independent oracle: an unlit
// quad at z = 0.37 crossing one marching cubes cell is rendered with a
// parallel camera so that pixel (i, j) shows the cell point
// ((i+0.5)/N, (j+0.5)/N, 0.37); every pixel must equal the tetrahedral
// interpolation of the 8 corner colours computed on the CPU by solving for
// barycentric coordinates (double precision) in whichever of the 6
// tetrahedra around the main diagonal contains the point. The plane z = 0.37
// crosses all 6 tetrahedra. The per-vertex fallback must differ from it.
#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkChunkActorManager.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTetrahedralColorMapper.h"
#include "vtkUnsignedCharArray.h"
#include "RenderTestHarness.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace
{
const int N = 160;
const double Z = 0.37;
// Corner c at offset (c&1, (c>>1)&1, (c>>2)&1); distinct, saturated colours.
const unsigned char Corner[8][4] = { { 255, 0, 0, 255 }, { 0, 255, 0, 255 }, { 0, 0, 255, 255 },
  { 255, 255, 0, 255 }, { 255, 0, 255, 255 }, { 0, 255, 255, 255 }, { 40, 40, 40, 255 },
  { 250, 250, 250, 255 } };

// Oracle: barycentric coordinates in each tetrahedron (0, e_a, e_a+e_b, 1).
void oracle(const double u[3], double rgb[3])
{
  const int perms[6][3] = { { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 }, { 2, 0, 1 }, { 2, 1, 0 } };
  for (const auto& p : perms)
  {
    double v[4][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 }, { 1, 1, 1 } };
    v[1][p[0]] = 1;
    v[2][p[0]] = 1;
    v[2][p[1]] = 1;
    // Solve u - v0 = sum_{i=1..3} w_i (v_i - v0) with v0 = 0.
    double m[3][3], b[3];
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
        m[r][c] = v[c + 1][r];
      b[r] = u[r];
    }
    double* rows[3] = { m[0], m[1], m[2] };
    int index[3];
    double tmp[3];
    if (!vtkMath::LUFactorLinearSystem(rows, index, 3, tmp))
      continue;
    vtkMath::LUSolveLinearSystem(rows, index, b, 3);
    const double w[4] = { 1 - b[0] - b[1] - b[2], b[0], b[1], b[2] };
    if (*std::min_element(w, w + 4) < -1e-9)
      continue;
    for (int q = 0; q < 3; ++q)
    {
      rgb[q] = 0;
      for (int i = 0; i < 4; ++i)
      {
        const int corner = static_cast<int>(v[i][0]) + 2 * static_cast<int>(v[i][1]) + 4 * static_cast<int>(v[i][2]);
        rgb[q] += w[i] * Corner[corner][q];
      }
    }
    return;
  }
  rgb[0] = rgb[1] = rgb[2] = -1000; // not in any tetrahedron: cannot happen inside the cube
}

vtkSmartPointer<vtkPolyData> quad()
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  const double xy[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkUnsignedCharArray> rgba;
  rgba->SetName("rgba");
  rgba->SetNumberOfComponents(4);
  for (auto& p : xy)
  {
    pts->InsertNextPoint(p[0], p[1], Z);
    normals->InsertNextTuple3(0, 0, 1);
    // per-vertex colour: the trilinear value at the vertex (what MC gives)
    double c[4] = { 0, 0, 0, 0 };
    for (int k = 0; k < 8; ++k)
    {
      const double w = ((k & 1) ? p[0] : 1 - p[0]) * (((k >> 1) & 1) ? p[1] : 1 - p[1]) * ((k >> 2) ? Z : 1 - Z);
      for (int q = 0; q < 4; ++q)
        c[q] += w * Corner[k][q];
    }
    rgba->InsertNextTuple4(std::round(c[0]), std::round(c[1]), std::round(c[2]), 255);
  }
  vtkNew<vtkCellArray> polys;
  const vtkIdType t0[3] = { 0, 1, 2 }, t1[3] = { 0, 2, 3 };
  polys->InsertNextCell(3, t0);
  polys->InsertNextCell(3, t1);
  vtkNew<vtkUnsignedCharArray> corners;
  corners->SetName("corner_rgba");
  corners->SetNumberOfComponents(32);
  corners->SetNumberOfTuples(2);
  vtkNew<vtkIntArray> ijk;
  ijk->SetName("cell_ijk");
  ijk->SetNumberOfComponents(3);
  ijk->SetNumberOfTuples(2);
  for (int t = 0; t < 2; ++t)
  {
    for (int k = 0; k < 32; ++k)
      corners->SetTypedComponent(t, k, Corner[k / 4][k % 4]);
    for (int a = 0; a < 3; ++a)
      ijk->SetTypedComponent(t, a, 0);
  }
  pd->SetPoints(pts);
  pd->SetPolys(polys);
  pd->GetPointData()->SetNormals(normals);
  pd->GetPointData()->AddArray(rgba);
  pd->GetCellData()->AddArray(corners);
  pd->GetCellData()->AddArray(ijk);
  return pd;
}

} // namespace

using namespace lvdiftest;

int TestTetrahedralShaderPixels(int, char*[])
{
  vtkNew<vtkRenderer> ren;
  auto rw = makeTestWindow(N, N);
  rw->AddRenderer(ren);
  vtkNew<vtkChunkActorManager> mgr;
  mgr->SetRenderer(ren);
  mgr->GetProperty()->SetAmbient(1.0);
  mgr->GetProperty()->SetDiffuse(0.0);
  mgr->GetProperty()->SetSpecular(0.0);
  mgr->SetChunk(0, quad());
  vtkCamera* cam = ren->GetActiveCamera();
  cam->ParallelProjectionOn();
  cam->SetFocalPoint(0.5, 0.5, Z);
  cam->SetPosition(0.5, 0.5, Z + 5);
  cam->SetViewUp(0, 1, 0);
  cam->SetParallelScale(0.5);
  ren->ResetCameraClippingRange();

  auto tetra = grabWindow(rw);
  auto* mapper = vtkTetrahedralColorMapper::SafeDownCast(mgr->GetChunkActor(0)->GetMapper());
  if (!mapper->GetUsedTetrahedral())
  {
    std::printf("ERROR: the tetrahedral shader was not used\n");
    return 1;
  }
  double maxErr = 0;
  int checked = 0;
  for (int j = 2; j < N - 2; ++j)
  {
    for (int i = 2; i < N - 2; ++i)
    {
      const double u[3] = { (i + 0.5) / N, (j + 0.5) / N, Z };
      double expect[3];
      oracle(u, expect);
      const auto* px = static_cast<unsigned char*>(tetra->GetScalarPointer(i, j, 0));
      for (int q = 0; q < 3; ++q)
        maxErr = std::max(maxErr, std::fabs(px[q] - expect[q]));
      ++checked;
    }
  }
  std::printf("tetrahedral shader: %d pixels, max |error| %.2f (8-bit levels)\n", checked, maxErr);

  mgr->SetInterpolationMode(vtkTetrahedralColorMapper::PerVertex);
  auto vertex = grabWindow(rw);
  double maxDiff = 0;
  for (int j = 2; j < N - 2; ++j)
    for (int i = 2; i < N - 2; ++i)
    {
      const auto* a = static_cast<unsigned char*>(tetra->GetScalarPointer(i, j, 0));
      const auto* b = static_cast<unsigned char*>(vertex->GetScalarPointer(i, j, 0));
      for (int q = 0; q < 3; ++q)
        maxDiff = std::max(maxDiff, std::fabs(double(a[q]) - double(b[q])));
    }
  std::printf("per-vertex fallback differs from tetrahedral by up to %.1f levels; used tetrahedral: %d\n", maxDiff,
    int(mapper->GetUsedTetrahedral()));
  const bool ok = maxErr <= 3.0 && maxDiff > 30.0 && !mapper->GetUsedTetrahedral();
  return ok ? 0 : 1;
}
