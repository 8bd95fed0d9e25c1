#include "vtkImageToSparseVolume.h"

#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/DictionaryVolume.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <limits>

vtkStandardNewMacro(vtkImageToSparseVolume);

vtkImageToSparseVolume::vtkImageToSparseVolume()
{
  this->SetColorArrayName(LVDIFVolumeBridge::ColorArrayName);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, LVDIFVolumeBridge::SdfArrayName);
}

vtkImageToSparseVolume::~vtkImageToSparseVolume()
{
  this->SetColorArrayName(nullptr);
}

int vtkImageToSparseVolume::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkImageToSparseVolume::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkSparseDictionaryVolume");
  return 1;
}

int vtkImageToSparseVolume::RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  LVDIFVolumeBridge::EnsureSparseOutput(out);
  return 1;
}

int vtkImageToSparseVolume::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  LVDIFVolumeBridge::BeginInformation(outputVector->GetInformationObject(0));
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (!LVDIFVolumeBridge::CallCore(this, [&] { LVDIFVolumeBridge::CheckVolumeSettings(this->ChunkEdge, this->BandWidth); }))
    return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
  if (!inInfo->Has(SDDP::WHOLE_EXTENT())) return 1;
  // the volume's indices start at 0: its origin is the whole extent's first point
  int whole[6];
  inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
  double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  if (inInfo->Has(vtkDataObject::ORIGIN())) inInfo->Get(vtkDataObject::ORIGIN(), origin);
  if (inInfo->Has(vtkDataObject::SPACING())) inInfo->Get(vtkDataObject::SPACING(), spacing);
  lvdif::VolumeOptions o;
  o.chunkEdge = this->ChunkEdge;
  for (int a = 0; a < 3; ++a)
  {
    o.dims[a] = whole[2 * a + 1] - whole[2 * a] + 1;
    o.origin[a] = origin[a] + whole[2 * a] * spacing[a];
    o.spacing[a] = spacing[a];
  }
  LVDIFVolumeBridge::SetSparseInformation(outInfo, o);
  return 1;
}

namespace
{
/// The whole grid of the input (its whole extent's points; spacing and origin
/// of the information), the chunk edge of the filter; false without a whole extent.
bool WholeGrid(vtkInformation* inInfo, int chunkEdge, lvdif::VolumeOptions& o, int wholeLo[3])
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  if (!inInfo->Has(SDDP::WHOLE_EXTENT())) return false;
  int whole[6];
  inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
  double origin[3] = { 0, 0, 0 }, spacing[3] = { 1, 1, 1 };
  if (inInfo->Has(vtkDataObject::ORIGIN())) inInfo->Get(vtkDataObject::ORIGIN(), origin);
  if (inInfo->Has(vtkDataObject::SPACING())) inInfo->Get(vtkDataObject::SPACING(), spacing);
  o.chunkEdge = chunkEdge;
  for (int a = 0; a < 3; ++a)
  {
    wholeLo[a] = whole[2 * a];
    o.dims[a] = std::max(0, whole[2 * a + 1] - whole[2 * a] + 1);
    o.origin[a] = origin[a] + whole[2 * a] * spacing[a];
    o.spacing[a] = spacing[a];
  }
  return true;
}

int Pieces(vtkInformation* outInfo)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  return outInfo->Has(SDDP::UPDATE_NUMBER_OF_PIECES()) ? outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES()) : 1;
}
} // namespace

int vtkImageToSparseVolume::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (inInfo->Has(SDDP::WHOLE_EXTENT()))
  {
    int whole[6];
    inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
    lvdif::VolumeOptions o;
    int lo[3];
    int owned[6];
    lvdif::VoxelBox region;
    if (Pieces(outInfo) > 1 && WholeGrid(inInfo, this->ChunkEdge, o, lo) && o.chunkEdge > 0 &&
      o.dims[0] > 0 && o.dims[1] > 0 && o.dims[2] > 0)
    {
      // a piece (pvbatch rank r of n) is a block of the whole grid's chunks, by
      // the .lvdv reader's rule: the image points of those chunks and of the
      // next chunks, as the reader loads them (a piece without chunks: one point, unused)
      const int kind = LVDIFVolumeBridge::RequestedVoxels(outInfo, o, owned, region);
      LVDIFVolumeBridge::GrowToWholeChunks(region, o);
      for (int a = 0; a < 3; ++a)
      {
        whole[2 * a] = lo[a] + (kind < 0 ? 0 : static_cast<int>(region.lo[a]));
        whole[2 * a + 1] = lo[a] + (kind < 0 ? 0 : static_cast<int>(region.hi[a]));
      }
    }
    inInfo->Set(SDDP::UPDATE_EXTENT(), whole, 6);
    // one piece of one, without ghosts: the extent is the request
    inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), 0);
    inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), 1);
    inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  }
  return 1;
}

int vtkImageToSparseVolume::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return this->Produce(inputVector, outputVector) ? 1
                                                  : LVDIFVolumeBridge::FailReported(outputVector->GetInformationObject(0));
}

int vtkImageToSparseVolume::Produce(vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (LVDIFVolumeBridge::InformationFailed(outputVector->GetInformationObject(0)))
    return 0; // RequestInformation reported why (ParaView runs RequestData anyway)
  vtkImageData* image = vtkImageData::GetData(inputVector[0]);
  vtkSparseDictionaryVolume* output = vtkSparseDictionaryVolume::GetData(outputVector);
  if (LVDIFVolumeBridge::IsEmptyInput(image))
  {
    output->Initialize(); // VTK's rule for an empty input (a failed upstream said why): no error
    return 1;
  }
  // an empty selection (a filter made on an input never updated) means the documented default
  vtkDataArray* sdf = image ? LVDIFVolumeBridge::SdfArray(this->GetInputArrayInformation(0), image,
                                this->GetInputArrayToProcess(0, inputVector))
                            : nullptr;
  if (!image || !sdf)
  {
    vtkErrorMacro("no input image with an SDF point array (default name 'sdf')");
    return 0;
  }
  vtkDataArray* rgba = this->ColorArrayName && *this->ColorArrayName
    ? image->GetPointData()->GetArray(this->ColorArrayName)
    : nullptr;
  lvdif::VolumeOptions options;
  options.chunkEdge = this->ChunkEdge;
  // a piece (pvbatch): the whole grid's chunks of this piece, so that the
  // pieces together are the serial volume (each piece's own chunk grid, from
  // its image's first point, gave other chunks and other partitions: ParaView's
  // Integrate Variables over 2 ranks differed from the serial run)
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int wholeLo[3];
  int owned[6] = { 0, -1, 0, -1, 0, -1 };
  lvdif::VoxelBox region;
  int kind = 0;
  if (Pieces(outInfo) > 1 && WholeGrid(inputVector[0]->GetInformationObject(0), this->ChunkEdge, options, wholeLo))
  {
    double origin[3], spacing[3];
    image->GetOrigin(origin);
    image->GetSpacing(spacing);
    for (int a = 0; a < 3; ++a)
    {
      options.origin[a] = origin[a] + wholeLo[a] * spacing[a];
      options.spacing[a] = spacing[a];
    }
    kind = LVDIFVolumeBridge::RequestedVoxels(outInfo, options, owned, region);
    if (kind < 0)
    {
      output->Initialize(); // a piece without chunks: empty
      return 1;
    }
    LVDIFVolumeBridge::GrowToWholeChunks(region, options);
  }
  LVDIFInterrupter interrupter(this);
  const bool ok = LVDIFVolumeBridge::CallCore(this, [&] {
    options.bandWidth = LVDIFVolumeBridge::BandOption(this->BandWidth);
    if (kind == 1)
    {
      output->SetVolume(
        LVDIFVolumeBridge::VolumeFromImageRegion(image, sdf, rgba, options, wholeLo, region, &interrupter));
      output->SetOwnedChunks(owned);
    }
    else
    {
      output->SetVolume(LVDIFVolumeBridge::VolumeFromImage(image, sdf, rgba, options, &interrupter));
    }
  });
  if (!ok)
  {
    output->Initialize(); // a cancel or an error: no volume
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkImageToSparseVolume::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ChunkEdge: " << this->ChunkEdge << "\n";
  os << indent << "BandWidth: " << this->BandWidth << "\n";
  os << indent << "ColorArrayName: " << (this->ColorArrayName ? this->ColorArrayName : "(none)") << "\n";
}
