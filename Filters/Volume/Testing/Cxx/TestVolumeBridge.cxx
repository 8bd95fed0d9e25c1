// The dictionary volume <-> vtkImageData bridge: decoded values, colours,
// sub-extents, and the error paths.
#include "vtkDictionaryVolumeToImage.h"
#include "vtkLVDIFVolumeBridge.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/Error.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkRTAnalyticSource.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <cmath>

static std::shared_ptr<lvdif::DictionaryVolume> sphereVolume()
{
  lvdif::VolumeOptions o;
  o.dims = { 40, 33, 50 };
  o.chunkEdge = 16;
  o.origin = { -1.0, 2.0, 0.5 };
  o.spacing = { 0.5, 0.5, 0.5 };
  auto v = std::make_shared<lvdif::DictionaryVolume>(o);
  lvdif::fillFromFunction(*v, lvdif::sphereSdf(20, 16, 25, 10));
  const lvdif::ColorKey red = v->colors().add(lvdif::Rgba{ 255, 0, 0, 255 });
  v->set(3, 4, 5, lvdif::Voxel{ v->get(3, 4, 5).sdf, red });
  return v;
}

TEST(VolumeBridge, SourceProducesDecodedValuesAndColours)
{
  auto v = sphereVolume();
  vtkNew<vtkDictionaryVolumeToImage> src;
  src->SetVolume(v);
  src->Update();
  vtkImageData* img = src->GetOutput();
  int dims[3];
  img->GetDimensions(dims);
  EXPECT_EQ(dims[0], 40);
  EXPECT_EQ(dims[2], 50);
  auto* sdf = vtkFloatArray::SafeDownCast(img->GetPointData()->GetArray("sdf"));
  ASSERT_NE(sdf, nullptr);
  double p[3];
  int at[3] = { 30, 16, 25 };
  const vtkIdType id = img->ComputePointId(at);
  img->GetPoint(id, p);
  EXPECT_DOUBLE_EQ(p[0], -1.0 + 30 * 0.5);
  // oracle: the analytic distance, within the dictionary's Group A bound
  EXPECT_NEAR(sdf->GetValue(id), 0.0, 5e-4);
  auto* rgba = vtkUnsignedCharArray::SafeDownCast(img->GetPointData()->GetArray("rgba"));
  ASSERT_NE(rgba, nullptr);
  int atRed[3] = { 3, 4, 5 };
  const vtkIdType red = img->ComputePointId(atRed);
  EXPECT_EQ(rgba->GetComponent(red, 0), 255);
  EXPECT_EQ(rgba->GetComponent(red, 1), 0);
  EXPECT_EQ(rgba->GetComponent(0, 0), 200); // default colour
}

TEST(VolumeBridge, SubExtentMatchesWhole)
{
  auto v = sphereVolume();
  vtkNew<vtkDictionaryVolumeToImage> src;
  src->SetVolume(v);
  int piece[6] = { 5, 20, 0, 10, 30, 49 };
  src->UpdateExtent(piece);
  vtkImageData* img = src->GetOutput();
  int ext[6];
  img->GetExtent(ext);
  EXPECT_EQ(ext[0], 5);
  EXPECT_EQ(ext[5], 49);
  auto* sdf = vtkFloatArray::SafeDownCast(img->GetPointData()->GetArray("sdf"));
  ASSERT_EQ(sdf->GetNumberOfTuples(), 16 * 11 * 20);
  int ijk[3] = { 12, 7, 40 };
  EXPECT_FLOAT_EQ(sdf->GetValue(img->ComputePointId(ijk)), v->sdf(12, 7, 40));
}

TEST(VolumeBridge, ImageToVolumeRoundTrip)
{
  vtkNew<vtkRTAnalyticSource> wavelet; // an independent field: values 37..277, shifted to span 0
  wavelet->SetWholeExtent(0, 20, 0, 17, 0, 9);
  wavelet->Update();
  vtkImageData* img = wavelet->GetOutput();
  vtkDataArray* field = img->GetPointData()->GetScalars();
  vtkNew<vtkFloatArray> sdf;
  sdf->SetName("sdf");
  sdf->SetNumberOfTuples(field->GetNumberOfTuples());
  for (vtkIdType i = 0; i < field->GetNumberOfTuples(); ++i)
  {
    sdf->SetValue(i, static_cast<float>((field->GetComponent(i, 0) - 150.0) / 40.0));
  }
  lvdif::VolumeOptions o;
  o.chunkEdge = 8;
  auto v = vtkLVDIFVolumeBridge::VolumeFromImage(img, sdf, nullptr, o);
  EXPECT_EQ(v->dims()[0], 21);
  for (vtkIdType i = 0; i < sdf->GetNumberOfTuples(); i += 7)
  {
    double p[3];
    img->GetPoint(i, p);
    const float expect = std::max(-8.0f, std::min(8.0f, sdf->GetValue(i)));
    const float got = v->sdf(std::lround(p[0]), std::lround(p[1]), std::lround(p[2]));
    // documented bounds: 0.0005 in Group A (|d| <= 4.001), 0.05 beyond
    ASSERT_NEAR(got, expect, (std::fabs(expect) <= 4.001f ? 5e-4 : 0.05) + 1e-5) << i;
  }
}

TEST(VolumeBridge, BadInputIsAClearError)
{
  vtkNew<vtkImageData> img;
  img->SetDimensions(4, 4, 4);
  vtkNew<vtkFloatArray> wrong;
  wrong->SetNumberOfTuples(10);
  EXPECT_THROW(vtkLVDIFVolumeBridge::VolumeFromImage(img, wrong, nullptr, lvdif::VolumeOptions()), lvdif::Error);
  vtkNew<vtkFloatArray> nan;
  nan->SetNumberOfTuples(64);
  nan->FillValue(1.0f);
  nan->SetValue(5, std::nanf(""));
  EXPECT_THROW(vtkLVDIFVolumeBridge::VolumeFromImage(img, nan, nullptr, lvdif::VolumeOptions()), lvdif::Error);
}
