#include "vtkSparseVolumeSliceRepresentation.h"

#include "LVDIFVolumeBridge.h"
#include "vtkAlgorithm.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"

#include <algorithm>

vtkStandardNewMacro(vtkSparseVolumeSliceRepresentation);

int vtkSparseVolumeSliceRepresentation::FillInputPortInformation(int port, vtkInformation* info)
{
  this->Superclass::FillInputPortInformation(port, info);
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkSparseDictionaryVolume");
  return 1;
}

int vtkSparseVolumeSliceRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkSparseDictionaryVolume* sparse = inputVector[0]->GetNumberOfInformationObjects() == 1
    ? vtkSparseDictionaryVolume::GetData(inputVector[0], 0)
    : nullptr;
  if (!sparse)
  {
    return this->Superclass::RequestData(request, inputVector, outputVector);
  }

  vtkMath::UninitializeBounds(this->WholeBounds);
  this->SliceData->Initialize();
  if (sparse->HasVolume())
  {
    const lvdif::DictionaryVolume& volume = *sparse->GetVolume();
    const auto& o = volume.options();
    const int edge = volume.chunkEdge();
    // the points this rank holds: its chunks' voxels plus the layer shared with the next chunks
    int owned[6], ext[6];
    sparse->GetOwnedChunks(owned);
    for (int a = 0; a < 3; ++a)
    {
      const int last = static_cast<int>(volume.dims()[a] - 1);
      ext[2 * a] = std::min(owned[2 * a] * edge, last);
      ext[2 * a + 1] = std::min((owned[2 * a + 1] + 1) * edge, last);
      this->WholeBounds[2 * a] = o.origin[a] + o.spacing[a] * ext[2 * a];
      this->WholeBounds[2 * a + 1] = o.origin[a] + o.spacing[a] * ext[2 * a + 1];
    }
    // the superclass's choice of plane: Slice along the SliceMode axis, clamped to the volume
    const int axis = this->SliceMode == YZ_PLANE ? 0 : (this->SliceMode == XZ_PLANE ? 1 : 2);
    const int plane = static_cast<int>(std::min<std::int64_t>(this->Slice, volume.dims()[axis] - 1));
    if (owned[2 * axis] <= owned[2 * axis + 1] && plane >= ext[2 * axis] && plane <= ext[2 * axis + 1])
    {
      ext[2 * axis] = ext[2 * axis + 1] = plane;
      try
      {
        LVDIFVolumeBridge::FillImage(volume, ext, this->SliceData, sparse->GetPartitionColors());
      }
      catch (const lvdif::Error& e)
      {
        vtkErrorMacro(<< "cannot slice the sparse volume: " << e.what());
        this->SliceData->Initialize();
      }
    }
  }
  // what vtkImageSliceRepresentation::RequestData does after extracting its slice
  return this->vtkPVDataRepresentation::RequestData(request, inputVector, outputVector);
}

void vtkSparseVolumeSliceRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
