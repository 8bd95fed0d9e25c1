#include "vtkSparseVolumeToImage.h"

#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/DictionaryVolume.h"
#include "lvdif/Memory.h"

#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <sstream>
#include <string>

vtkStandardNewMacro(vtkSparseVolumeToImage);

namespace
{
/// What a user can change when the dense image of `points` is refused: without
/// colours (4 bytes a point) when that fits, else a smaller extent or the
/// sparse volume's own filters, which need no dense image.
std::string RefusalFix(std::uint64_t points, bool withColor, std::uint64_t limit)
{
  if (withColor && points <= limit / 4)
    return "; without colours (WithColor off, ParaView's With Color) it needs " + lvdif::formatBytes(points * 4) +
      ", within the limit";
  return "; ask for a smaller extent (an update extent: a vtkExtractVOI after it asks for its box only), or use the "
         "sparse volume's own filters (Chunked Marching Cubes, the writers), which need no dense image";
}
}

vtkSparseVolumeToImage::vtkSparseVolumeToImage() = default;
vtkSparseVolumeToImage::~vtkSparseVolumeToImage() = default;

int vtkSparseVolumeToImage::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkSparseDictionaryVolume");
  return 1;
}

int vtkSparseVolumeToImage::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  LVDIFVolumeBridge::BeginInformation(outputVector->GetInformationObject(0));
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int whole[6];
  if (inInfo->Has(SDDP::WHOLE_EXTENT()))
  {
    inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
    if (inInfo->Has(vtkDataObject::ORIGIN())) outInfo->CopyEntry(inInfo, vtkDataObject::ORIGIN());
    if (inInfo->Has(vtkDataObject::SPACING())) outInfo->CopyEntry(inInfo, vtkDataObject::SPACING());
  }
  else if (vtkSparseDictionaryVolume* given = vtkSparseDictionaryVolume::GetData(inInfo))
  {
    if (LVDIFVolumeBridge::IsEmptyInput(given))
    {
      // an empty input (a failed upstream said why): an empty image, no error
      const int empty[6] = { 0, -1, 0, -1, 0, -1 };
      outInfo->Set(SDDP::WHOLE_EXTENT(), empty, 6);
      this->RequiredBytes = 0;
      return 1;
    }
    // a volume given as data (vtkTrivialProducer) announces nothing: read it off the volume
    const lvdif::VolumeOptions& o = given->GetVolume()->options();
    for (int a = 0; a < 3; ++a)
    {
      whole[2 * a] = 0;
      whole[2 * a + 1] = static_cast<int>(o.dims[a] - 1);
    }
    outInfo->Set(vtkDataObject::ORIGIN(), o.origin.data(), 3);
    outInfo->Set(vtkDataObject::SPACING(), o.spacing.data(), 3);
  }
  else
  {
    vtkErrorMacro("the input does not announce the volume's extent (not a sparse volume producer?)");
    return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
  }
  outInfo->Set(SDDP::WHOLE_EXTENT(), whole, 6);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  double points = 1;
  for (int a = 0; a < 3; ++a) points *= whole[2 * a + 1] - whole[2 * a] + 1;
  this->RequiredBytes = points * (this->WithColor ? 8.0 : 4.0);
  return 1;
}

int vtkSparseVolumeToImage::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // the sparse producer reads only the chunks of this extent
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (outInfo->Has(SDDP::UPDATE_EXTENT()))
  {
    int ext[6];
    outInfo->Get(SDDP::UPDATE_EXTENT(), ext);
    inInfo->Set(SDDP::UPDATE_EXTENT(), ext, 6);
  }
  inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), 1);
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  return 1;
}

int vtkSparseVolumeToImage::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return this->Produce(inputVector, outputVector) ? 1
                                                  : LVDIFVolumeBridge::FailReported(outputVector->GetInformationObject(0));
}

int vtkSparseVolumeToImage::Produce(vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (LVDIFVolumeBridge::InformationFailed(outputVector->GetInformationObject(0)))
    return 0; // RequestInformation reported why (ParaView runs RequestData anyway)
  vtkSparseDictionaryVolume* input = vtkSparseDictionaryVolume::GetData(inputVector[0]);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  if (!input)
  {
    vtkErrorMacro("the input is not a sparse dictionary volume");
    return 0;
  }
  if (LVDIFVolumeBridge::IsEmptyInput(input))
  {
    output->Initialize(); // VTK's rule for an empty input: empty output, no error
    return 1;
  }
  int ext[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext);
  const lvdif::DictionaryVolume& volume = *input->GetVolume();
  LVDIFInterrupter interrupter(this);
  const bool ok = LVDIFVolumeBridge::CallCore(this, [&] {
    std::uint64_t points = 1;
    std::ostringstream what;
    what << "a dense image of "; // (the error names the class already)
    for (int a = 0; a < 3; ++a)
    {
      const std::int64_t n = std::max(0, ext[2 * a + 1] - ext[2 * a] + 1);
      points = lvdif::checkedMultiply(points, static_cast<std::uint64_t>(n), "dense image");
      what << n << (a < 2 ? " x " : " points");
    }
    what << (this->WithColor ? " (float sdf + rgba, 8 bytes a point)" : " (float sdf, 4 bytes a point)");
    const std::uint64_t bytes = lvdif::checkedMultiply(points, this->WithColor ? 8 : 4, "dense image");
    const std::uint64_t limit = lvdif::memoryLimitBytes();
    if (bytes <= limit)
    {
      // said before the allocation, so a user sees why memory fills up
      const std::string warning =
        LVDIFVolumeBridge::DenseImageWarning(bytes, ext, limit, "the sparse volume's own filters need no dense image");
      if (!warning.empty()) vtkWarningMacro(<< warning);
    }
    try
    {
      lvdif::requireMemory(bytes, what.str(), limit);
    }
    catch (const lvdif::Error& e)
    {
      // the refusal named only LVDIF_MEMORY_LIMIT: name what fits within the limit as well
      throw lvdif::Error(e.code(), std::string(e.what()) + RefusalFix(points, this->WithColor, limit));
    }
    LVDIFVolumeBridge::FillImage(volume, ext, output, this->WithColor, &interrupter);
  });
  if (!ok)
  {
    output->Initialize(); // a cancel (no error: VTK's rule) or an error: no image, not a part of one
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkSparseVolumeToImage::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "WithColor: " << this->WithColor << "\n";
  os << indent << "RequiredBytes: " << this->RequiredBytes << "\n";
}
