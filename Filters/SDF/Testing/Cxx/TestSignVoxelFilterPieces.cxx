// vtkSignVoxelFilter under pieces: UpdatePiece(i, n, 0) must equal the same
// region of the serial (one-piece) result, for n = 2 and 3, with wrong-sign
// regions that cross the piece cuts. The upstream honours sub-extents
// (a source producing exactly its update extent), so a filter that asked only for its piece
// would filter the piece alone; the negative control shows that filtering a
// piece alone does give a different answer here (the test can fail).
// The serial result itself is checked against the analytic sign.
#include "vtkSignVoxelFilter.h"

#include "vtkContourFilter.h"
#include "vtkExtentTranslator.h"
#include "vtkFloatArray.h"
#include "vtkImageClip.h"
#include "vtkImageAlgorithm.h"
#include "vtkImageData.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
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
/// pieces lies there), plus a streak along y.
float value(int i, int j, int k)
{
  float v = static_cast<float>(sphere(i, j, k));
  const bool slab = i >= 15 && i <= 19 && j >= 16 && j <= 18 && k >= 10 && k <= 26;
  const bool outsideStreak = i == 2 && j == 3 && k >= 10 && k <= 26;
  const bool yStreak = i == 17 && k == 17 && j >= 8 && j <= 12;
  return (slab || outsideStreak || yStreak) && std::fabs(v) > 2.0f ? -v : v;
}

void fill(vtkImageData* img, const int ext[6])
{
  img->SetExtent(const_cast<int*>(ext));
  vtkNew<vtkFloatArray> sdf;
  sdf->SetName("sdf");
  sdf->SetNumberOfTuples(img->GetNumberOfPoints());
  vtkIdType id = 0;
  for (int k = ext[4]; k <= ext[5]; ++k)
    for (int j = ext[2]; j <= ext[3]; ++j)
      for (int i = ext[0]; i <= ext[1]; ++i)
        sdf->SetValue(id++, value(i, j, k));
  img->GetPointData()->SetScalars(sdf);
}

vtkSmartPointer<vtkImageData> makeImage()
{
  auto img = vtkSmartPointer<vtkImageData>::New();
  const int whole[6] = { 0, N - 1, 0, N - 1, 0, N - 1 };
  fill(img, whole);
  return img;
}

/// A source that produces exactly the requested extent (as streaming image
/// sources do), so a filter that asked only for its piece gets only it.
class SubExtentSource : public vtkImageAlgorithm
{
public:
  static SubExtentSource* New();
  vtkTypeMacro(SubExtentSource, vtkImageAlgorithm);
  SubExtentSource() { this->SetNumberOfInputPorts(0); }
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector* ov) override
  {
    const int whole[6] = { 0, N - 1, 0, N - 1, 0, N - 1 };
    vtkInformation* info = ov->GetInformationObject(0);
    info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
    info->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
    vtkDataObject::SetPointDataActiveScalarInfo(info, VTK_FLOAT, 1);
    return 1;
  }
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* ov) override
  {
    vtkInformation* info = ov->GetInformationObject(0);
    int ext[6];
    info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext);
    fill(vtkImageData::GetData(info), ext);
    this->LastPoints = vtkImageData::GetData(info)->GetNumberOfPoints();
    return 1;
  }
  vtkIdType LastPoints = 0;
};
vtkStandardNewMacro(SubExtentSource);

vtkSmartPointer<vtkImageData> runSerial(vtkImageData* img, int axis)
{
  vtkNew<vtkSignVoxelFilter> f;
  f->SetInputData(img);
  f->SetAxis(axis);
  f->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
  f->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(vtkImageData::SafeDownCast(f->GetOutput()));
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
      vtkNew<SubExtentSource> src; // produces exactly the requested extent
      vtkNew<vtkSignVoxelFilter> f;
      f->SetInputConnection(src->GetOutputPort());
      f->SetAxis(axis);
      f->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
      ASSERT_TRUE(f->UpdatePiece(p, n, 0));
      vtkImageData* out = vtkImageData::SafeDownCast(f->GetOutput());
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
      long long owned = 1;
      for (int a = 0; a < 3; ++a)
        owned *= e[2 * a + 1] - e[2 * a] + (e[2 * a + 1] == N - 1 ? 1 : 0);
      covered += owned;

      // the same piece asked for by a downstream consumer (as in ParaView: the
      // executive turns the consumer's piece into the filter's update extent)
      {
        vtkNew<SubExtentSource> src2;
        vtkNew<vtkSignVoxelFilter> f2;
        f2->SetInputConnection(src2->GetOutputPort());
        f2->SetAxis(axis);
        f2->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
        vtkNew<vtkContourFilter> contour;
        contour->SetInputConnection(f2->GetOutputPort());
        contour->SetValue(0, 0.0);
        ASSERT_TRUE(contour->UpdatePiece(p, n, 0));
        int e2[6];
        vtkImageData::SafeDownCast(f2->GetOutput())->GetExtent(e2);
        EXPECT_LT(e2[5] - e2[4], N - 1) << "consumer's piece " << p << " of " << n << " was not cut";
        for (int a = 0; a < 3; ++a)
          EXPECT_TRUE(e2[2 * a] <= e[2 * a] && e2[2 * a + 1] >= e[2 * a + 1]) << "consumer's piece misses the piece";
        EXPECT_EQ(differences(vtkImageData::SafeDownCast(f2->GetOutput()), serial), 0) << "consumer's piece " << p << " of " << n;
      }

      // negative control: the same piece filtered alone
      vtkNew<vtkImageClip> alone;
      alone->SetInputData(img);
      alone->SetOutputWholeExtent(e);
      alone->ClipDataOn();
      alone->Update();
      auto pieceImg = vtkSmartPointer<vtkImageData>::New();
      pieceImg->DeepCopy(vtkImageData::SafeDownCast(alone->GetOutput()));
      vtkNew<vtkSignVoxelFilter> g;
      g->SetInputData(pieceImg);
      g->SetAxis(axis);
      g->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
      g->Update();
      pieceAloneDiffers += differences(vtkImageData::SafeDownCast(g->GetOutput()), serial);
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
