#include "vtkImageToSparseVolume.h"

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

int vtkImageToSparseVolume::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (inInfo->Has(SDDP::WHOLE_EXTENT()))
  {
    int whole[6];
    inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
    inInfo->Set(SDDP::UPDATE_EXTENT(), whole, 6);
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
  return LVDIFVolumeBridge::CallCore(this, [&] {
    options.bandWidth = LVDIFVolumeBridge::BandOption(this->BandWidth);
    output->SetVolume(LVDIFVolumeBridge::VolumeFromImage(image, sdf, rgba, options));
  }) ? 1 : 0;
}

void vtkImageToSparseVolume::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ChunkEdge: " << this->ChunkEdge << "\n";
  os << indent << "BandWidth: " << this->BandWidth << "\n";
  os << indent << "ColorArrayName: " << (this->ColorArrayName ? this->ColorArrayName : "(none)") << "\n";
}
