#include "vtkLegacyBvReader.h"

#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/CNumbers.h"
#include "lvdif/DictionaryVolume.h"
#include "lvdif/Error.h"
#include "lvdif/LegacyBv.h"

#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>

vtkStandardNewMacro(vtkLegacyBvReader);

namespace
{
/// N from the file's size and name (Core's one rule and words, as the import
/// and the CLI), or a message saying why there is none. Checking here lets
/// RequestInformation announce the extent without reading the file.
std::int64_t edgeOf(const std::string& path, std::string& why)
{
  try
  {
    const std::int64_t n = lvdif::legacy_bv::edgeOfFile(path);
    if (n > VTK_INT_MAX)
    {
      why = "edge " + std::to_string(n) + " exceeds VTK's extent range";
      return -1;
    }
    return n;
  }
  catch (const lvdif::Error& e)
  {
    why = e.what();
    return -1;
  }
}
} // namespace

vtkLegacyBvReader::vtkLegacyBvReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkLegacyBvReader::~vtkLegacyBvReader() = default;

bool vtkLegacyBvReader::CanReadFile(const char* fileName)
{
  std::string why;
  return fileName && edgeOf(fileName, why) > 0;
}

int vtkLegacyBvReader::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkSparseDictionaryVolume");
  return 1;
}

int vtkLegacyBvReader::RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  LVDIFVolumeBridge::EnsureSparseOutput(out);
  return 1;
}

int vtkLegacyBvReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  LVDIFVolumeBridge::BeginInformation(outputVector->GetInformationObject(0));
  this->Edge = 0;
  if (this->FileName.empty())
  {
    vtkErrorMacro("no file name: call SetFileName() first");
    return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
  }
  // the settings by name before the file: their errors read as the file's
  // ("cannot read 'x.bv': distance scale must be finite and > 0", after reading it)
  if (!LVDIFVolumeBridge::CallCore(this, [&] {
        LVDIFVolumeBridge::BandOption(this->BandWidth);
        if (!(std::isfinite(this->DistanceScale) && this->DistanceScale > 0))
        {
          char text[40];
          lvdif::formatDoubleC(text, sizeof text, "%g", this->DistanceScale);
          throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
            std::string("DistanceScale must be a finite number > 0 (our voxel units per the file's unit), not ") + text);
        }
      }))
    return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
  std::string why;
  const std::int64_t n = edgeOf(this->FileName, why);
  if (n <= 0)
  {
    vtkErrorMacro(<< LVDIFVolumeBridge::FileError("read", this->FileName, why));
    return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
  }
  this->Edge = static_cast<int>(n);
  lvdif::VolumeOptions o; // origin 0, spacing 1
  o.dims = { n, n, n };
  LVDIFVolumeBridge::SetSparseInformation(outputVector->GetInformationObject(0), o);
  return 1;
}

int vtkLegacyBvReader::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (LVDIFVolumeBridge::InformationFailed(outputVector->GetInformationObject(0)))
    return 0; // RequestInformation reported why (ParaView runs RequestData anyway)
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkSparseDictionaryVolume* output = vtkSparseDictionaryVolume::GetData(outInfo);
  lvdif::LegacyBvOptions options;
  options.swapXZ = this->SwapXZ;
  options.distanceScale = this->DistanceScale;
  LVDIFInterrupter interrupter(this);
  try
  {
    options.bandWidth = LVDIFVolumeBridge::BandOption(this->BandWidth);
    // The file has no index: it is read whole (no sub-extents). A piece of a
    // distributed read (pvbatch rank r of n) still owns only its block of
    // chunks, by the .lvdv reader's rule (LVDIFVolumeBridge::RequestedVoxels):
    // every rank's partitions were the whole volume, and ParaView's filters
    // over them (Contour, Integrate Variables) counted it once a rank.
    std::shared_ptr<lvdif::DictionaryVolume> volume = lvdif::loadLegacyBv(this->FileName, options, interrupter);
    int owned[6] = { 0, -1, 0, -1, 0, -1 };
    lvdif::VoxelBox region;
    const int kind = LVDIFVolumeBridge::RequestedVoxels(outInfo, volume->options(), owned, region);
    if (kind < 0)
    {
      output->Initialize(); // a piece without chunks: empty
      return 1;
    }
    output->SetVolume(std::move(volume));
    if (kind == 1)
      output->SetOwnedChunks(owned);
  }
  catch (const lvdif::Error& e)
  {
    output->Initialize();
    if (e.code() != lvdif::ErrorCode::Cancelled)
    {
      vtkErrorMacro(<< LVDIFVolumeBridge::FileError("read", this->FileName, e.what()));
    }
    return LVDIFVolumeBridge::FailReported(outInfo);
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkLegacyBvReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "SwapXZ: " << this->SwapXZ << "\n";
  os << indent << "DistanceScale: " << this->DistanceScale << "\n";
  os << indent << "BandWidth: " << this->BandWidth << "\n";
  os << indent << "Edge (after UpdateInformation): " << this->Edge << "\n";
}
