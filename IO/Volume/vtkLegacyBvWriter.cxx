#include "vtkLegacyBvWriter.h"

#include "LVDIFVolumeBridge.h"

#include "lvdif/Error.h"
#include "lvdif/LegacyBv.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
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

lvdif::VolumeOptions vtkLegacyBvWriter::ImageVolumeOptions()
{
  lvdif::VolumeOptions options;
  options.bandWidth = LVDIFVolumeBridge::BandOption(this->BandWidth);
  return options;
}

std::unique_ptr<lvdif::DictionaryVolume> vtkLegacyBvWriter::ImageToVolume(
  vtkImageData* image, vtkDataArray* sdf, vtkDataArray* rgba)
{
  // colours become palette indices, not colour-dictionary entries
  auto volume = LVDIFVolumeBridge::VolumeFromImage(image, sdf, nullptr, this->ImageVolumeOptions());
  if (rgba)
  {
    assignPaletteIndices(*volume, image, rgba);
  }
  return volume;
}

void vtkLegacyBvWriter::Save(const lvdif::DictionaryVolume& volume, const SaveSource&, lvdif::Interrupter& interrupter)
{
  // the volume's keys as they are (a sparse input is written as `lvdif convert` writes it)
  lvdif::LegacyBvOptions options;
  options.swapXZ = this->SwapXZ;
  options.distanceScale = this->DistanceScale;
  lvdif::saveLegacyBv(volume, this->FileName, options, interrupter);
}

void vtkLegacyBvWriter::CheckGrid(const std::int64_t dims[3], const double*)
{
  const std::string problem = lvdif::checkLegacyBvDims({ dims[0], dims[1], dims[2] }, this->FileName);
  if (!problem.empty())
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, problem);
}

void vtkLegacyBvWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SwapXZ: " << this->SwapXZ << "\n";
  os << indent << "DistanceScale: " << this->DistanceScale << "\n";
  os << indent << "BandWidth: " << this->BandWidth << "\n";
}
