#include "vtkDictionaryVolumeToImage.h"

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
  try
  {
    LVDIFVolumeBridge::FillImage(*this->Volume, ext, output, this->WithColor);
  }
  catch (const lvdif::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return LVDIFVolumeBridge::FailReported(outInfo);
  }
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
