#include "vtkDictionaryVolumeReader.h"

#include "vtkLVDIFInterrupter.h"
#include "vtkLVDIFVolumeBridge.h"

#include "lvdif/Memory.h"
#include "lvdif/VolumeFile.h"

#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

vtkStandardNewMacro(vtkDictionaryVolumeReader);

struct vtkDictionaryVolumeReader::Internals
{
  lvdif::VolumeFileInfo Info;
};

vtkDictionaryVolumeReader::vtkDictionaryVolumeReader()
  : Internal(new Internals)
{
  this->SetNumberOfInputPorts(0);
}

vtkDictionaryVolumeReader::~vtkDictionaryVolumeReader()
{
  delete this->Internal;
}

bool vtkDictionaryVolumeReader::CanReadFile(const char* fileName)
{
  std::ifstream f(fileName ? fileName : "", std::ios::binary);
  char magic[8] = {};
  return f.read(magic, 8) && std::memcmp(magic, "LVDIFVOL", 8) == 0;
}

std::string vtkDictionaryVolumeReader::GetMetadata(const std::string& key) const
{
  auto it = this->Internal->Info.metadata.find(key);
  return it == this->Internal->Info.metadata.end() ? std::string() : it->second;
}

int vtkDictionaryVolumeReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (this->FileName.empty())
  {
    vtkErrorMacro("no file name: call SetFileName() first");
    return 0;
  }
  try
  {
    this->Internal->Info = lvdif::readVolumeInfo(this->FileName);
  }
  catch (const lvdif::Error& e)
  {
    this->Internal->Info = lvdif::VolumeFileInfo();
    vtkErrorMacro(<< "cannot read '" << this->FileName << "': " << e.what());
    return 0;
  }
  const lvdif::VolumeOptions& o = this->Internal->Info.options;
  for (int a = 0; a < 3; ++a)
  {
    if (o.dims[a] > VTK_INT_MAX)
    {
      vtkErrorMacro("volume dimension " << o.dims[a] << " exceeds VTK's extent range");
      return 0;
    }
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkLVDIFVolumeBridge::SetImageInformation(outInfo, o);
  return 1;
}

int vtkDictionaryVolumeReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  int ext[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext);
  lvdif::VolumeFileReadOptions options;
  options.wholeVolume = false;
  options.region.lo = { ext[0], ext[2], ext[4] };
  options.region.hi = { ext[1], ext[3], ext[5] };
  vtkLVDIFInterrupter interrupter(this, 0.0, 0.9);
  std::uint64_t points = 1;
  for (int a = 0; a < 3; ++a)
  {
    points *= static_cast<std::uint64_t>(std::max(0, ext[2 * a + 1] - ext[2 * a] + 1));
  }
  const std::string warning = vtkLVDIFVolumeBridge::DenseImageWarning(points * (this->WithColor ? 8 : 4), ext,
    lvdif::memoryLimitBytes(), this->WithColor ? "without colours (With Color off) it needs half" : "");
  if (!warning.empty())
  {
    vtkWarningMacro(<< warning);
  }
  try
  {
    auto volume = lvdif::loadVolume(this->FileName, options, interrupter);
    this->UpdateProgress(0.9);
    vtkLVDIFVolumeBridge::FillImage(*volume, ext, output, this->WithColor);
  }
  catch (const lvdif::Error& e)
  {
    output->Initialize();
    if (e.code() != lvdif::ErrorCode::Cancelled)
    {
      vtkErrorMacro(<< "cannot read '" << this->FileName << "': " << e.what());
    }
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkDictionaryVolumeReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "WithColor: " << this->WithColor << "\n";
  const auto& d = this->Internal->Info.options.dims;
  os << indent << "Dimensions (after UpdateInformation): " << d[0] << " x " << d[1] << " x " << d[2] << "\n";
}
