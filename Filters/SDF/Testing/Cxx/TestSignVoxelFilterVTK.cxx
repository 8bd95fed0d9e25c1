// vtkSignVoxelFilter: repairs injected wrong signs of an analytic sphere SDF
// (oracle: the analytic sign), reports flips that match an independent count
// of changed voxels, leaves the input and other arrays alone, honours the
// chosen array and the filter mask, refuses non-float arrays, and aborts.
#include "vtkSignVoxelFilter.h"

#include "AlgorithmErrorsTestUtil.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkFlyingEdges3D.h"
#include "vtkPolyData.h"
#include "vtkPolyDataConnectivityFilter.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace
{
constexpr int N = 40;

float sphere(int i, int j, int k)
{
  const double c = 0.5 * (N - 1);
  return static_cast<float>(std::sqrt((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c)) - 12.0);
}

/// Image with `sdf` (sphere with wrong signs: a streak along x inside and
/// outside, isolated voxels) and an untouched `other` array.
vtkSmartPointer<vtkImageData> makeImage()
{
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->SetDimensions(N, N, N);
  img->SetSpacing(0.5, 0.5, 0.5);
  vtkNew<vtkFloatArray> sdf;
  sdf->SetName("sdf");
  sdf->SetNumberOfTuples(N * N * N);
  vtkNew<vtkFloatArray> other;
  other->SetName("other");
  other->SetNumberOfTuples(N * N * N);
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
      {
        const vtkIdType id = i + N * (j + N * k);
        float v = sphere(i, j, k);
        const bool streak = (j == 20 && k == 20 && i > 22 && i < 30) || (j == 5 && k == 30 && i > 10 && i < 25);
        const bool isolated = (i == 7 && j == 9 && k == 11) || (i == 20 && j == 18 && k == 21);
        if ((streak || isolated) && std::fabs(v) > 2.0f)
          v = -v;
        sdf->SetValue(id, v);
        other->SetValue(id, 7.0f);
      }
  img->GetPointData()->SetScalars(sdf);
  img->GetPointData()->AddArray(other);
  return img;
}

int wrongSigns(vtkDataArray* a)
{
  int wrong = 0;
  for (int k = 0; k < N; ++k)
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i)
        wrong += (a->GetTuple1(i + N * (j + N * k)) < 0) != (sphere(i, j, k) < 0) ? 1 : 0;
  return wrong;
}
} // namespace

TEST(vtkSignVoxelFilter, RepairsInjectedWrongSigns)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  vtkDataArray* in = img->GetPointData()->GetArray("sdf");
  const int before = wrongSigns(in);
  ASSERT_GT(before, 10);
  std::vector<float> original(static_cast<size_t>(N * N * N));
  for (vtkIdType i = 0; i < N * N * N; ++i)
    original[static_cast<size_t>(i)] = static_cast<float>(in->GetTuple1(i));

  vtkNew<vtkSignVoxelFilter> f;
  f->SetInputData(img);
  f->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
  f->Update();
  vtkImageData* out = vtkImageData::SafeDownCast(f->GetOutput());
  vtkDataArray* res = out->GetPointData()->GetArray("sdf");
  ASSERT_NE(res, nullptr);
  EXPECT_EQ(out->GetPointData()->GetScalars(), res); // keeps the scalars role
  EXPECT_EQ(wrongSigns(res), 0);
  EXPECT_EQ(wrongSigns(in), before); // input untouched
  EXPECT_EQ(out->GetPointData()->GetArray("other")->GetTuple1(5), 7.0);

  int changed = 0;
  for (vtkIdType i = 0; i < N * N * N; ++i)
    changed += res->GetTuple1(i) != original[static_cast<size_t>(i)] ? 1 : 0;
  auto* flips = vtkIdTypeArray::SafeDownCast(out->GetFieldData()->GetArray("svf_flips"));
  ASSERT_NE(flips, nullptr);
  ASSERT_EQ(flips->GetNumberOfValues(), 4);
  vtkIdType total = 0;
  for (int q = 0; q < 4; ++q)
    total += flips->GetValue(q);
  EXPECT_EQ(total, changed);
  EXPECT_GT(flips->GetValue(0), 0);
  ASSERT_NE(out->GetFieldData()->GetArray("svf_iterations"), nullptr);
}

TEST(vtkSignVoxelFilter, ChosenArrayAndMask)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  vtkNew<vtkSignVoxelFilter> f;
  f->SetInputData(img);
  f->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "other");
  f->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
  f->Update();
  // `other` is uniform: nothing flips; `sdf` passes through unchanged
  EXPECT_EQ(wrongSigns(vtkImageData::SafeDownCast(f->GetOutput())->GetPointData()->GetArray("sdf")),
    wrongSigns(img->GetPointData()->GetArray("sdf")));

  f->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "sdf");
  f->SetFilters(0);
  f->Update();
  auto* flips = vtkIdTypeArray::SafeDownCast(vtkImageData::SafeDownCast(f->GetOutput())->GetFieldData()->GetArray("svf_flips"));
  ASSERT_NE(flips, nullptr);
  for (int q = 0; q < 4; ++q)
    EXPECT_EQ(flips->GetValue(q), 0);
}

TEST(vtkSignVoxelFilter, RefusesNonFloatArrays)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  vtkNew<vtkDoubleArray> d;
  d->SetName("sdf");
  d->SetNumberOfTuples(N * N * N);
  d->Fill(1.0);
  img->GetPointData()->RemoveArray("sdf");
  img->GetPointData()->SetScalars(d);
  vtkNew<vtkSignVoxelFilter> f;
  f->SetInputData(img);
  f->GlobalWarningDisplayOff();
  f->Update();
  EXPECT_EQ(vtkImageData::SafeDownCast(f->GetOutput())->GetNumberOfPoints(), 0);
}

namespace
{
class AbortOnProgress : public vtkCommand
{
public:
  static AbortOnProgress* New() { return new AbortOnProgress; }
  void Execute(vtkObject* caller, unsigned long, void*) override
  {
    static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    ++this->Calls;
  }
  int Calls = 0;
};
} // namespace

TEST(vtkSignVoxelFilter, AbortStops)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  vtkNew<vtkSignVoxelFilter> f;
  f->SetInputData(img);
  f->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
  vtkNew<AbortOnProgress> cb;
  f->AddObserver(vtkCommand::ProgressEvent, cb);
  f->Update();
  EXPECT_GT(cb->Calls, 0);
  EXPECT_EQ(vtkImageData::SafeDownCast(f->GetOutput())->GetFieldData()->GetArray("svf_flips"), nullptr);
}

// The repaired surface, checked geometrically: marching cubes of a torus SDF
// with injected wrong signs has spurious pieces; after the filters it is one
// connected surface whose vertices all lie within a voxel of the analytic torus.
namespace
{
constexpr int M = 48;
constexpr double R = 13.0, Rt = 5.0, C = 0.5 * (M - 1);
double torus(double x, double y, double z)
{
  const double q = std::sqrt((x - C) * (x - C) + (z - C) * (z - C)) - R;
  return std::sqrt(q * q + (y - C) * (y - C)) - Rt;
}

struct Surface
{
  int regions;
  double maxError;
};

Surface surfaceOf(vtkImageData* img)
{
  vtkNew<vtkFlyingEdges3D> mc;
  mc->SetInputData(img);
  mc->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "sdf");
  mc->SetValue(0, 0.0);
  mc->ComputeNormalsOff();
  vtkNew<vtkPolyDataConnectivityFilter> conn;
  conn->SetInputConnection(mc->GetOutputPort());
  conn->SetExtractionModeToAllRegions();
  conn->Update();
  Surface s{ conn->GetNumberOfExtractedRegions(), 0.0 };
  vtkPolyData* pd = mc->GetOutput();
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
  {
    double p[3];
    pd->GetPoint(i, p);
    s.maxError = std::max(s.maxError, std::fabs(torus(p[0], p[1], p[2])));
  }
  return s;
}
} // namespace

TEST(vtkSignVoxelFilter, RepairedTorusSurface)
{
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->SetDimensions(M, M, M);
  vtkNew<vtkFloatArray> sdf;
  sdf->SetName("sdf");
  sdf->SetNumberOfTuples(M * M * M);
  unsigned state = 12345u;
  auto rnd = [&]() {
    state = state * 1664525u + 1013904223u;
    return state >> 8;
  };
  for (int k = 0; k < M; ++k)
    for (int j = 0; j < M; ++j)
      for (int i = 0; i < M; ++i)
        sdf->SetValue(i + M * (j + M * k), static_cast<float>(torus(i, j, k)));
  // 60 streaks along x and 100 isolated far voxels with the wrong sign
  for (int s = 0; s < 60; ++s)
  {
    const int j = static_cast<int>(rnd() % M), k = static_cast<int>(rnd() % M), i0 = static_cast<int>(rnd() % M);
    for (int i = i0; i < std::min(M, i0 + 10); ++i)
    {
      const vtkIdType id = i + M * (j + M * k);
      if (std::fabs(sdf->GetValue(id)) > 2.0f)
        sdf->SetValue(id, -sdf->GetValue(id));
    }
  }
  for (int s = 0; s < 100; ++s)
  {
    const vtkIdType id = static_cast<vtkIdType>(rnd() % (M * M * M));
    if (std::fabs(sdf->GetValue(id)) > 2.0f)
      sdf->SetValue(id, -sdf->GetValue(id));
  }
  img->GetPointData()->SetScalars(sdf);

  const Surface broken = surfaceOf(img);
  EXPECT_GT(broken.regions, 10);
  EXPECT_GT(broken.maxError, 3.0);

  vtkNew<vtkSignVoxelFilter> f;
  f->SetInputData(img);
  f->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
  f->Update();
  const Surface fixed = surfaceOf(vtkImageData::SafeDownCast(f->GetOutput()));
  EXPECT_EQ(fixed.regions, 1);
  EXPECT_LT(fixed.maxError, 1.0);
}

// The checkboxes (SetUseSVF1..4) are the bits of Filters: with only one on,
// only that filter's counter moves, and the output equals SetFilters(bit).
// The output's range (stored by the filter) is that of its values.
TEST(vtkSignVoxelFilter, CheckboxesAreTheMaskBits)
{
  vtkSmartPointer<vtkImageData> img = makeImage();
  const int bits[4] = { vtkSignVoxelFilter::SVF1, vtkSignVoxelFilter::SVF2, vtkSignVoxelFilter::SVF3,
    vtkSignVoxelFilter::SVF4 };
  for (int q = 0; q < 4; ++q)
  {
    vtkNew<vtkSignVoxelFilter> boxes, mask;
    boxes->SetUseSVF1(q == 0);
    boxes->SetUseSVF2(q == 1);
    boxes->SetUseSVF3(q == 2);
    boxes->SetUseSVF4(q == 3);
    EXPECT_EQ(boxes->GetFilters(), bits[q]);
    EXPECT_TRUE(q != 0 || boxes->GetUseSVF1());
    EXPECT_TRUE(q != 3 || (boxes->GetUseSVF4() && !boxes->GetUseSVF1()));
    mask->SetFilters(bits[q]);
    for (vtkSignVoxelFilter* f : { boxes.Get(), mask.Get() })
    {
      f->SetInputData(img);
      f->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
      f->Update();
    }
    auto* flips = vtkIdTypeArray::SafeDownCast(boxes->GetOutput()->GetFieldData()->GetArray("svf_flips"));
    ASSERT_NE(flips, nullptr);
    for (int r = 0; r < 4; ++r)
      if (r != q) EXPECT_EQ(flips->GetValue(r), 0) << "filter " << q + 1 << " alone, counter " << r + 1;
    vtkDataArray* a = vtkImageData::SafeDownCast(boxes->GetOutput())->GetPointData()->GetArray("sdf");
    vtkDataArray* b = vtkImageData::SafeDownCast(mask->GetOutput())->GetPointData()->GetArray("sdf");
    double lo = a->GetTuple1(0), hi = lo;
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      ASSERT_EQ(a->GetTuple1(i), b->GetTuple1(i));
      lo = std::min(lo, a->GetTuple1(i));
      hi = std::max(hi, a->GetTuple1(i));
    }
    double range[2];
    a->GetRange(range, 0);
    EXPECT_EQ(range[0], lo);
    EXPECT_EQ(range[1], hi);
  }
}

// Default properties and no input: one error that says what is missing (it
// was only the executive's "returned failure for request: REQUEST_DATA_OBJECT"
// with a dump of the request, not naming the input).
TEST(vtkSignVoxelFilter, NoInputIsOneClearError)
{
  vtkNew<vtkSignVoxelFilter> f;
  const AlgorithmErrors errors(f);
  f->Update();
  ASSERT_EQ(errors.messages().size(), 1u) << errors.summary();
  EXPECT_NE(errors.messages()[0].find("Input port 0"), std::string::npos) << errors.summary();
}
