#include "vtkDictionaryVolumeToImage.h"

#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"

#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"

vtkStandardNewMacro(vtkDictionaryVolumeToImage);

vtkDictionaryVolumeToImage::vtkDictionaryVolumeToImage()
{
  this->SetNumberOfInputPorts(0);
}

vtkDictionaryVolumeToImage::~vtkDictionaryVolumeToImage() = default;

void vtkDictionaryVolumeToImage::SetVolume(std::shared_ptr<lvdif::DictionaryVolume> volume)
{
  this->Volume = std::move(volume);
  this->Modified();
}

int vtkDictionaryVolumeToImage::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  // the project's one failure path: one error, not the executive's request dump after it
  LVDIFVolumeBridge::BeginInformation(outInfo);
  if (!this->Volume)
  {
    vtkErrorMacro("no volume: call SetVolume() first");
    return LVDIFVolumeBridge::FailInformation(outInfo);
  }
  LVDIFVolumeBridge::SetImageInformation(outInfo, this->Volume->options());
  return 1;
}

int vtkDictionaryVolumeToImage::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (LVDIFVolumeBridge::InformationFailed(outInfo))
    return 0; // RequestInformation reported why
  vtkImageData* output = vtkImageData::GetData(outInfo);
  int ext[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext);
  // progress and cancel as vtkSparseVolumeToImage's (it had neither)
  LVDIFInterrupter interrupter(this);
  if (!LVDIFVolumeBridge::CallCore(this, [&] { LVDIFVolumeBridge::FillImage(*this->Volume, ext, output, this->WithColor, &interrupter); }))
  {
    output->Initialize(); // a cancel (no error) or an error: no image, not a part of one
    return LVDIFVolumeBridge::FailReported(outInfo);
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkDictionaryVolumeToImage::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Volume: ";
  if (this->Volume)
  {
    const auto& d = this->Volume->dims();
    os << d[0] << " x " << d[1] << " x " << d[2] << ", chunk edge " << this->Volume->chunkEdge() << ", band "
       << this->Volume->bandWidth() << "\n";
  }
  else
  {
    os << "(none)\n";
  }
  os << indent << "WithColor: " << this->WithColor << "\n";
}
