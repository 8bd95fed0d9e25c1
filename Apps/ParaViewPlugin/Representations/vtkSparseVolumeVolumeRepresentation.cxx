#include "vtkSparseVolumeVolumeRepresentation.h"

#include "LVDIFVolumeBridge.h"
#include "vtkAlgorithm.h"
#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/ByteStream.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Memory.h"

#include <algorithm>
#include <cstdint>
#include <sstream>

vtkStandardNewMacro(vtkSparseVolumeVolumeRepresentation);

int vtkSparseVolumeVolumeRepresentation::FillInputPortInformation(int port, vtkInformation* info)
{
  this->Superclass::FillInputPortInformation(port, info);
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkSparseDictionaryVolume");
  return 1;
}

int vtkSparseVolumeVolumeRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkSparseDictionaryVolume* sparse = inputVector[0]->GetNumberOfInformationObjects() == 1
    ? vtkSparseDictionaryVolume::GetData(inputVector[0], 0)
    : nullptr;
  if (!sparse)
  {
    return this->Superclass::RequestData(request, inputVector, outputVector);
  }
  vtkNew<vtkImageData> dense;
  if (sparse->HasVolume())
  {
    const lvdif::DictionaryVolume& volume = *sparse->GetVolume();
    const int edge = volume.chunkEdge();
    // the points this rank holds: its chunks' voxels plus the layer shared with the next chunks
    int owned[6], ext[6];
    sparse->GetOwnedChunks(owned);
    bool any = true;
    for (int a = 0; a < 3; ++a)
    {
      const int last = static_cast<int>(volume.dims()[a] - 1);
      any = any && owned[2 * a] <= owned[2 * a + 1];
      ext[2 * a] = std::min(owned[2 * a] * edge, last);
      ext[2 * a + 1] = std::min((owned[2 * a + 1] + 1) * edge, last);
    }
    const bool withColor = sparse->GetPartitionColors();
    if (any &&
      !LVDIFVolumeBridge::CallCore(this, [&] {
        std::uint64_t points = 1;
        std::ostringstream what;
        what << "the Volume representation's dense image of ";
        for (int a = 0; a < 3; ++a)
        {
          const std::int64_t n = ext[2 * a + 1] - ext[2 * a] + 1;
          points = lvdif::checkedMultiply(points, static_cast<std::uint64_t>(n), "dense image");
          what << n << (a < 2 ? " x " : " points");
        }
        const std::uint64_t bytes = lvdif::checkedMultiply(points, withColor ? 8 : 4, "dense image");
        const std::uint64_t limit = lvdif::memoryLimitBytes();
        if (bytes <= limit)
        {
          const std::string warning = LVDIFVolumeBridge::DenseImageWarning(
            bytes, ext, limit, "the Volume representation renders every voxel; Slice and Outline need no dense image");
          if (!warning.empty()) vtkWarningMacro(<< warning);
        }
        lvdif::requireMemory(bytes, what.str(), limit);
        LVDIFVolumeBridge::FillImage(volume, ext, dense, withColor);
      }))
    {
      dense->Initialize(); // refused (one error): nothing drawn
    }
  }
  // the superclass on the dense image, as for an image input
  vtkNew<vtkInformation> info;
  info->Copy(inputVector[0]->GetInformationObject(0));
  info->Set(vtkDataObject::DATA_OBJECT(), dense);
  vtkNew<vtkInformationVector> denseVector;
  denseVector->Append(info);
  vtkInformationVector* inputs[1] = { denseVector };
  return this->Superclass::RequestData(request, inputs, outputVector);
}

void vtkSparseVolumeVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
