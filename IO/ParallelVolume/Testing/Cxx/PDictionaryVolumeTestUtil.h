// Shared helpers of the vtkPDictionaryVolumeWriter / vtkPDictionaryVolumeReader
// tests (TestPDictionaryVolumeIO.cxx, TestPDictionaryVolumeSafeWrites.cxx).
#ifndef PDictionaryVolumeTestUtil_h
#define PDictionaryVolumeTestUtil_h

#include "vtkDictionaryVolumeReader.h"
#include "vtkImageToSparseVolume.h"
#include "vtkSparseVolumeToImage.h"
#include "vtkDictionaryVolumeWriter.h"
#include "vtkPDictionaryVolumeReader.h"
#include "vtkPDictionaryVolumeWriter.h"
#include "vtkSparseDictionaryVolume.h"
#include "SdfImageTestUtil.h"

#include "lvdif/DictionaryVolume.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkFloatArray.h"
#include "vtkImageClip.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <fcntl.h>
#include <functional>
#include <future>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>
#include <dirent.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>


namespace pvio
{
const int NX = 41, NY = 34, NZ = 37;

inline double analytic(int i, int j, int k)
{
  const double dx = i - 20.3, dy = j - 16.8, dz = k - 18.1;
  return std::sqrt(dx * dx + dy * dy + dz * dz) - 12.0;
}

inline vtkSmartPointer<vtkImageData> makeImage()
{
  // not 0-based: the index keeps it
  return makeSdfImage({ 3, 3 + NX - 1, -2, -2 + NY - 1, 5, 5 + NZ - 1 }, { -2.0, 0.5, 3.0 }, { 0.25, 0.5, 0.75 },
    analytic, [](int i, int j, int k) {
      return std::array<unsigned char, 4>{ static_cast<unsigned char>(i < 20 ? 255 : 10),
        static_cast<unsigned char>(j % 3 * 60), static_cast<unsigned char>(k < 10 ? 0 : 200), 255 };
    });
}

/// The reader's sparse volume decoded (the whole extent, or `extent` when given).
inline vtkSmartPointer<vtkImageData> decoded(vtkPDictionaryVolumeReader* r, const int* extent = nullptr)
{
  vtkNew<vtkSparseVolumeToImage> dense;
  dense->SetInputConnection(r->GetOutputPort());
  if (extent)
  {
    dense->UpdateInformation();
    dense->UpdateExtent(extent);
  }
  else
  {
    dense->Update();
  }
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(dense->GetOutput());
  return out;
}

/// Voxels of the reader's sparse volume (0 when it holds none: an error).
inline std::int64_t voxels(vtkPDictionaryVolumeReader* r)
{
  auto* v = vtkSparseDictionaryVolume::SafeDownCast(r->GetOutputDataObject(0));
  return v && v->HasVolume() ? v->GetVolume()->voxelCount() : 0;
}

inline std::string tmpName(const std::string& stem)
{
  return std::string(::testing::TempDir()) + "lvdif_p_" + std::to_string(getpid()) + "_" + stem;
}

/// The serial round trip: the oracle for the distributed one.
inline vtkSmartPointer<vtkImageData> serialRoundTrip(vtkImageData* img)
{
  const std::string f = tmpName("serial.lvdv");
  vtkNew<vtkDictionaryVolumeWriter> w;
  w->SetInputData(img);
  w->SetFileName(f.c_str());
  w->Write();
  vtkNew<vtkDictionaryVolumeReader> r;
  r->SetFileName(f.c_str());
  vtkNew<vtkSparseVolumeToImage> dense;
  dense->SetInputConnection(r->GetOutputPort());
  dense->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(dense->GetOutput());
  std::remove(f.c_str());
  return out;
}

inline void writePieces(vtkImageData* img, const std::string& index, int n)
{
  // one Write() of a serial run writes every piece and the index
  vtkNew<vtkImageClip> clip; // passes the whole image: the writer must crop its pieces
  clip->SetInputData(img);
  clip->ClipDataOn();
  vtkNew<vtkPDictionaryVolumeWriter> w;
  w->SetController(nullptr);
  w->SetInputConnection(clip->GetOutputPort());
  w->SetFileName(index.c_str());
  w->SetNumberOfPieces(n);
  ASSERT_TRUE(w->Write());
}
/// The "sdf" and "rgba" arrays of out equal the oracle's, component for component.
inline void expectSameArrays(vtkImageData* out, vtkImageData* oracle)
{
  for (const char* name : { "sdf", "rgba" })
  {
    vtkDataArray* a = out->GetPointData()->GetArray(name);
    vtkDataArray* b = oracle->GetPointData()->GetArray(name);
    ASSERT_TRUE(a && b) << name;
    long diff = 0;
    for (vtkIdType id = 0; id < a->GetNumberOfTuples(); ++id)
      for (int c = 0; c < a->GetNumberOfComponents(); ++c)
        diff += a->GetComponent(id, c) != b->GetComponent(id, c) ? 1 : 0;
    EXPECT_EQ(diff, 0) << name;
  }
}

} // namespace pvio

#endif
