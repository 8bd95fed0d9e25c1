#include "vtkLegacyBvWriter.h"

#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/LegacyBv.h"

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"

#include <unordered_map>
#include <vector>

vtkStandardNewMacro(vtkLegacyBvWriter);

namespace
{
lvdif::Rgba colorAt(vtkDataArray* rgba, vtkIdType p)
{
  const int nc = rgba->GetNumberOfComponents();
  double t[4] = { 0, 0, 0, 255 };
  for (int c = 0; c < nc && c < 4; ++c)
    t[c] = rgba->GetComponent(p, c);
  if (nc == 1)
    t[1] = t[2] = t[0];
  return lvdif::Rgba{ static_cast<std::uint8_t>(t[0]), static_cast<std::uint8_t>(t[1]),
    static_cast<std::uint8_t>(t[2]), static_cast<std::uint8_t>(t[3]) };
}

/// Gives every voxel the palette index of its colour (see the class comment).
void assignPaletteIndices(lvdif::DictionaryVolume& volume, vtkImageData* image, vtkDataArray* rgba)
{
  if (rgba->GetNumberOfTuples() != image->GetNumberOfPoints() || rgba->GetNumberOfComponents() < 1 ||
    rgba->GetNumberOfComponents() > 4)
  {
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "RGBA array does not match the image's points");
  }
  std::vector<lvdif::Rgba> palette = lvdif::legacy_bv::defaultPalette();
  std::unordered_map<std::uint32_t, lvdif::ColorKey> index;
  for (std::size_t i = 0; i < palette.size(); ++i)
    index.emplace(palette[i].packed(), static_cast<lvdif::ColorKey>(i));
  const lvdif::GridGeometry g = LVDIFVolumeBridge::Geometry(image);
  std::vector<lvdif::ColorKey> keys(static_cast<std::size_t>(g.count()));
  for (std::int64_t p = 0; p < g.count(); ++p)
  {
    const lvdif::Rgba c = colorAt(rgba, p);
    auto it = index.find(c.packed());
    if (it == index.end())
    {
      if (palette.size() >= lvdif::ColorDictionary::Capacity)
        throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "more colours than a .bv palette index holds");
      it = index.emplace(c.packed(), static_cast<lvdif::ColorKey>(palette.size())).first;
      palette.push_back(c);
    }
    keys[static_cast<std::size_t>(p)] = it->second;
  }
  volume.colors().assign(palette);
  for (std::int64_t z = 0; z < g.dims[2]; ++z)
    for (std::int64_t y = 0; y < g.dims[1]; ++y)
      for (std::int64_t x = 0; x < g.dims[0]; ++x)
      {
        const lvdif::ColorKey k = keys[static_cast<std::size_t>(g.index(x, y, z))];
        if (k != 0)
        {
          lvdif::Voxel v = volume.get(x, y, z);
          v.color = k;
          volume.set(x, y, z, v);
        }
      }
}
} // namespace

vtkLegacyBvWriter::vtkLegacyBvWriter() = default;
vtkLegacyBvWriter::~vtkLegacyBvWriter() = default;

vtkImageData* vtkLegacyBvWriter::GetInput()
{
  return vtkImageData::SafeDownCast(this->Superclass::GetInput());
}

int vtkLegacyBvWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkSparseDictionaryVolume");
  return 1;
}

void vtkLegacyBvWriter::WriteData()
{
  if (auto* sparse = vtkSparseDictionaryVolume::SafeDownCast(this->Superclass::GetInput()))
  {
    // the volume's keys as they are, as `lvdif convert` writes them
    if (this->FileName.empty() || !sparse->HasVolume())
    {
      vtkErrorMacro(<< (this->FileName.empty() ? "no file name: call SetFileName() first" : "the input holds no volume"));
      this->SetErrorCode(this->FileName.empty() ? vtkErrorCode::NoFileNameError : vtkErrorCode::UnknownError);
      return;
    }
    lvdif::LegacyBvOptions options;
    options.swapXZ = this->SwapXZ;
    options.distanceScale = this->DistanceScale;
    LVDIFInterrupter interrupter(this);
    if (!LVDIFVolumeBridge::CallCore(
          this, [&] { lvdif::saveLegacyBv(*sparse->GetVolume(), this->FileName, options, interrupter); },
          "cannot write '" + this->FileName + "': "))
    {
      this->SetErrorCode(vtkErrorCode::UnknownError);
    }
    return;
  }
  vtkImageData* image = this->GetInput();
  vtkDataArray *sdf, *rgba;
  bool missingFileName;
  const std::string problem =
    LVDIFVolumeBridge::WriterInput(image, this->FileName, true, sdf, rgba, missingFileName);
  if (!problem.empty())
  {
    vtkErrorMacro(<< problem);
    this->SetErrorCode(missingFileName ? vtkErrorCode::NoFileNameError : vtkErrorCode::UnknownError);
    return;
  }
  lvdif::VolumeOptions volumeOptions;
  volumeOptions.bandWidth = static_cast<float>(this->BandWidth);
  lvdif::LegacyBvOptions options;
  options.swapXZ = this->SwapXZ;
  options.distanceScale = this->DistanceScale;
  LVDIFInterrupter interrupter(this, 0.0, 1.0);
  try
  {
    interrupter.setStage(0.0, 0.3);
    auto volume = LVDIFVolumeBridge::VolumeFromImage(image, sdf, nullptr, volumeOptions);
    if (rgba)
    {
      assignPaletteIndices(*volume, image, rgba);
    }
    interrupter.setStage(0.3, 0.7);
    lvdif::saveLegacyBv(*volume, this->FileName, options, interrupter);
  }
  catch (const lvdif::Error& e)
  {
    if (e.code() != lvdif::ErrorCode::Cancelled)
    {
      vtkErrorMacro(<< "cannot write '" << this->FileName << "': " << e.what());
    }
    this->SetErrorCode(e.code() == lvdif::ErrorCode::IoFailure ? vtkErrorCode::CannotOpenFileError
                                                               : vtkErrorCode::UnknownError);
  }
}

void vtkLegacyBvWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "SwapXZ: " << this->SwapXZ << "\n";
  os << indent << "DistanceScale: " << this->DistanceScale << "\n";
  os << indent << "BandWidth: " << this->BandWidth << "\n";
}
