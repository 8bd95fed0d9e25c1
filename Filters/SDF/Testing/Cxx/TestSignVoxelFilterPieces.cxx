// vtkSignVoxelFilter under pieces: UpdatePiece(i, n, 0) must equal the same
// region of the serial (one-piece) result, for n = 2 and 3, with wrong-sign
// regions that cross the piece cuts. The upstream honours sub-extents
// (vtkImageClip with ClipData), so a filter that asked only for its piece
// would filter the piece alone; the negative control shows that filtering a
// piece alone does give a different answer here (the test can fail).
// The serial result itself is checked against the analytic sign.
#include "vtkSignVoxelFilter.h"

#include "vtkExtentTranslator.h"
#include "vtkFloatArray.h"
#include "vtkImageClip.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
constexpr int N = 36;
constexpr double C = 0.5 * (N - 1), RADIUS = 13.0;

double sphere(int i, int j, int k)
{
  return std::sqrt((i - C) * (i - C) + (j - C) * (j - C) + (k - C) * (k - C)) - RADIUS;
}

/// Sphere SDF with wrong signs: a positive slab inside the sphere and a
/// negative streak outside it, both spanning z = 10..26 (every cut of 2 and 3
/// pieces along z lies there), plus streaks along y and x.
vtkSmartPointer<vtkImageData> makeImage()
{
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->SetDimensions(N, N, N);
  vtkNew<vtkFloatArray> sdf;
  sdf->SetName("sdf");
  sdf->SetNumberOfTuples(N * N * N);
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
      {
        float v = static_cast<float>(sphere(i, j, k));
        const bool slab = i >= 15 && i <= 19 && j >= 16 && j <= 18 && k >= 10 && k <= 26;
        const bool outsideStreak = i == 2 && j == 3 && k >= 10 && k <= 26;
        const bool yStreak = i == 17 && k == 17 && j >= 8 && j <= 12;
        if ((slab || outsideStreak || yStreak) && std::fabs(v) > 2.0f)
          v = -v;
        sdf->SetValue(i + N * (j + N * k), v);
      }
  img->GetPointData()->SetScalars(sdf);
  return img;
}

vtkSmartPointer<vtkImageData> runSerial(vtkImageData* img, int axis)
{
  vtkNew<vtkSignVoxelFilter> f;
  f->SetInputData(img);
  f->SetAxis(axis);
  f->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
  f->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(f->GetOutput());
  return out;
}

/// Number of points of `piece` whose `sdf` differs from `serial` at the same (i, j, k).
int differences(vtkImageData* piece, vtkImageData* serial)
{
  int e[6];
  piece->GetExtent(e);
  vtkDataArray* a = piece->GetPointData()->GetArray("sdf");
  vtkDataArray* b = serial->GetPointData()->GetArray("sdf");
  int diff = 0;
  for (int k = e[4]; k <= e[5]; ++k)
    for (int j = e[2]; j <= e[3]; ++j)
      for (int i = e[0]; i <= e[1]; ++i)
      {
        const int ijk[3] = { i, j, k };
        diff += a->GetTuple1(piece->ComputePointId(const_cast<int*>(ijk))) !=
            b->GetTuple1(serial->ComputePointId(const_cast<int*>(ijk)))
          ? 1
          : 0;
      }
  return diff;
}
} // namespace

class SvfPieces : public ::testing::TestWithParam<int>
{
};

TEST_P(SvfPieces, EveryPieceEqualsTheSerialResult)
{
  const int axis = GetParam();
  vtkSmartPointer<vtkImageData> img = makeImage();
  vtkSmartPointer<vtkImageData> serial = runSerial(img, axis);
  // the serial result is right (oracle: the analytic sign)
  vtkDataArray* s = serial->GetPointData()->GetArray("sdf");
  int wrong = 0;
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
        wrong += (s->GetTuple1(i + N * (j + N * k)) < 0) != (sphere(i, j, k) < 0) ? 1 : 0;
  EXPECT_EQ(wrong, 0);

  int pieceAloneDiffers = 0;
  for (int n : { 2, 3 })
  {
    long long covered = 0;
    for (int p = 0; p < n; ++p)
    {
      // an upstream that produces exactly the requested sub-extent
      vtkNew<vtkImageClip> clip;
      clip->SetInputData(img);
      clip->ClipDataOn();
      vtkNew<vtkSignVoxelFilter> f;
      f->SetInputConnection(clip->GetOutputPort());
      f->SetAxis(axis);
      f->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
      ASSERT_TRUE(f->UpdatePiece(p, n, 0));
      vtkImageData* out = f->GetOutput();
      int e[6], req[6];
      out->GetExtent(e);
      int whole[6] = { 0, N - 1, 0, N - 1, 0, N - 1 };
      vtkNew<vtkExtentTranslator> t; // the executive's piece -> extent rule (block mode, split by cells)
      ASSERT_TRUE(t->PieceToExtentThreadSafe(p, n, 0, whole, req, vtkExtentTranslator::BLOCK_MODE, 0));
      for (int q = 0; q < 6; ++q)
        EXPECT_EQ(e[q], req[q]) << "piece " << p << " of " << n << ": output is not the piece's extent";
      EXPECT_LT(e[5] - e[4], N - 1) << "the piece is the whole volume: pieces were not cut";
      EXPECT_EQ(differences(out, serial), 0) << "piece " << p << " of " << n << ", axis " << axis;
      // owned points (upper plane belongs to the next piece) tile the volume
      covered += static_cast<long long>(e[1] - e[0] + 1) * (e[3] - e[2] + 1) * (e[5] - e[4] + (e[5] == N - 1 ? 1 : 0));

      // negative control: the same piece filtered alone
      vtkNew<vtkImageClip> alone;
      alone->SetInputData(img);
      alone->SetOutputWholeExtent(e);
      alone->ClipDataOn();
      alone->Update();
      auto pieceImg = vtkSmartPointer<vtkImageData>::New();
      pieceImg->DeepCopy(alone->GetOutput());
      vtkNew<vtkSignVoxelFilter> g;
      g->SetInputData(pieceImg);
      g->SetAxis(axis);
      g->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
      g->Update();
      pieceAloneDiffers += differences(g->GetOutput(), serial);
    }
    EXPECT_EQ(covered, static_cast<long long>(N) * N * N) << n << " pieces";
  }
  // pieces are cut along z: with axis z, SVF1's rows are cut, and a piece
  // filtered alone misses the slab's repair
  if (axis == 2)
  {
    EXPECT_GT(pieceAloneDiffers, 0) << "the injected regions do not exercise the cuts";
  }
}

INSTANTIATE_TEST_SUITE_P(Axes, SvfPieces, ::testing::Values(0, 1, 2));
