// A small SDF image for the IO modules' tests: "sdf" (float) and "rgba"
// (4 x uint8) point arrays made from functions of the voxel index (i, j, k
// counted from the extent's first point), the input their writers take.
#ifndef LVDIF_IO_SDF_IMAGE_TEST_UTIL_H
#define LVDIF_IO_SDF_IMAGE_TEST_UTIL_H

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <array>

/// sdfOf(i, j, k) -> double, rgbaOf(i, j, k) -> std::array<unsigned char, 4>.
template <class SdfOf, class RgbaOf>
vtkSmartPointer<vtkImageData> makeSdfImage(const int (&extent)[6], const double (&origin)[3],
  const double (&spacing)[3], SdfOf sdfOf, RgbaOf rgbaOf)
{
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->SetExtent(extent[0], extent[1], extent[2], extent[3], extent[4], extent[5]);
  img->SetOrigin(origin[0], origin[1], origin[2]);
  img->SetSpacing(spacing[0], spacing[1], spacing[2]);
  const int nx = extent[1] - extent[0] + 1, ny = extent[3] - extent[2] + 1, nz = extent[5] - extent[4] + 1;
  vtkNew<vtkFloatArray> sdf;
  sdf->SetName("sdf");
  sdf->SetNumberOfTuples(static_cast<vtkIdType>(nx) * ny * nz);
  vtkNew<vtkUnsignedCharArray> rgba;
  rgba->SetName("rgba");
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(sdf->GetNumberOfTuples());
  vtkIdType id = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i, ++id)
      {
        sdf->SetValue(id, static_cast<float>(sdfOf(i, j, k)));
        const std::array<unsigned char, 4> c = rgbaOf(i, j, k);
        rgba->SetTypedTuple(id, c.data());
      }
  img->GetPointData()->AddArray(sdf);
  img->GetPointData()->AddArray(rgba);
  return img;
}

#endif
