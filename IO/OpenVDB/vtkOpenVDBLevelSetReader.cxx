#include "vtkOpenVDBLevelSetReader.h"

#include "LVDIFOpenVDB.h"
#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <sys/stat.h>

vtkStandardNewMacro(vtkOpenVDBLevelSetReader);

struct vtkOpenVDBLevelSetReader::Internals
{
  std::shared_ptr<lvdif::DictionaryVolume> Volume;
  vtkMTimeType ReadTime = 0; // this->GetMTime() when Volume was read
  std::string ReadFile;
  long long FileStamp = -1;
};

namespace
{
long long fileStamp(const std::string& path)
{
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 ? static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec + st.st_size
                                        : -1;
}
}

vtkOpenVDBLevelSetReader::vtkOpenVDBLevelSetReader()
  : Internal(new Internals)
{
  this->SetNumberOfInputPorts(0);
}

vtkOpenVDBLevelSetReader::~vtkOpenVDBLevelSetReader()
{
  delete this->Internal;
}

bool vtkOpenVDBLevelSetReader::CanReadFile(const char* fileName)
{
  try
  {
    lvdif::vdb::listGrids(fileName ? fileName : "");
    return true;
  }
  catch (const lvdif::Error&)
  {
    return false;
  }
}

std::string vtkOpenVDBLevelSetReader::GetGridList()
{
  std::string out;
  try
  {
    for (const auto& g : lvdif::vdb::listGrids(this->FileName))
    {
      out += g.name + " (" + g.type + ", " + g.gridClass + ")\n";
    }
  }
  catch (const lvdif::Error& e)
  {
    vtkErrorMacro(<< e.what());
  }
  return out;
}

int vtkOpenVDBLevelSetReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  LVDIFVolumeBridge::BeginInformation(outputVector->GetInformationObject(0));
  if (this->FileName.empty())
  {
    vtkErrorMacro("no file name: call SetFileName() first");
    return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
  }
  // the settings before the file: one error naming the property, no clamp
  if (!LVDIFVolumeBridge::CallCore(this, [&] {
        LVDIFVolumeBridge::PaddingOption(this->Padding); // the project's padding rule (>= 0)
        lvdif::vdb::checkImportPadding(this->Padding, "Padding");
      }))
    return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
  Internals& in = *this->Internal;
  const long long stamp = fileStamp(this->FileName);
  if (!in.Volume || in.ReadTime != this->GetMTime() || in.ReadFile != this->FileName || in.FileStamp != stamp)
  {
    in.Volume.reset();
    lvdif::vdb::ImportOptions options;
    options.gridName = this->GridName;
    options.colorName = this->WithColor ? this->ColorGridName : std::string();
    options.padding = this->Padding;
    LVDIFInterrupter interrupter(this);
    try
    {
      in.Volume = lvdif::vdb::importLevelSet(this->FileName, options, interrupter);
    }
    catch (const lvdif::Error& e)
    {
      if (e.code() != lvdif::ErrorCode::Cancelled)
      {
        vtkErrorMacro(<< LVDIFVolumeBridge::FileError("read", this->FileName, e.what()));
      }
      return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
    }
    in.ReadTime = this->GetMTime();
    in.ReadFile = this->FileName;
    in.FileStamp = stamp;
  }
  const lvdif::VolumeOptions& o = in.Volume->options();
  LVDIFVolumeBridge::SetSparseInformation(outputVector->GetInformationObject(0), o);
  return 1;
}

int vtkOpenVDBLevelSetReader::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkSparseDictionaryVolume");
  return 1;
}

int vtkOpenVDBLevelSetReader::RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  LVDIFVolumeBridge::EnsureSparseOutput(out);
  return 1;
}

int vtkOpenVDBLevelSetReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (LVDIFVolumeBridge::InformationFailed(outputVector->GetInformationObject(0)))
    return 0; // RequestInformation reported why (ParaView runs RequestData anyway)
  vtkSparseDictionaryVolume* output = vtkSparseDictionaryVolume::GetData(outputVector);
  if (!this->Internal->Volume)
  {
    output->Initialize();
    return 0;
  }
  // a piece (UpdatePiece, a pvbatch rank) owns only its block of chunks, by
  // the .lvdv reader's rule: every piece's partitions were the whole volume
  int owned[6] = { 0, -1, 0, -1, 0, -1 };
  lvdif::VoxelBox region;
  const int kind = LVDIFVolumeBridge::RequestedVoxels(
    outputVector->GetInformationObject(0), this->Internal->Volume->options(), owned, region);
  if (kind < 0)
  {
    output->Initialize(); // a piece without chunks: empty
    return 1;
  }
  output->SetPartitionColors(this->WithColor);
  output->SetVolume(this->Internal->Volume);
  if (kind == 1)
    output->SetOwnedChunks(owned);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkOpenVDBLevelSetReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "GridName: " << this->GridName << "\n";
  os << indent << "ColorGridName: " << this->ColorGridName << "\n";
  os << indent << "WithColor: " << this->WithColor << "\n";
  os << indent << "Padding: " << this->Padding << "\n";
}
