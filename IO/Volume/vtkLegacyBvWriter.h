/**
 * @class   vtkLegacyBvWriter
 * @brief   writes a vtkSparseDictionaryVolume (or vtkImageData) as the original LVDIF's `.bv` volume file
 *
 * A thin wrapper over lvdif::saveLegacyBv (Core/Formats/include/lvdif/LegacyBv.h).
 * The input must be a cube of N^3 points with a point array `sdf` (negative
 * inside, voxel units) and may have an unsigned char array `rgba`. Distances
 * are encoded with the project's dictionary (saturated to +-BandWidth), then
 * with the original's inside-positive key formula. Colours become palette
 * indices: a colour of Palette (default: the Mouse scene's palette, the one
 * vtkLegacyBvReader uses) gets its index; any other colour gets the next free
 * index in order of first appearance (the original does not store the
 * palette). A file name with an `SDF_<N>_` token must agree with N. Written
 * crash-safely; reports progress and honours AbortExecute.
 */
#ifndef vtkLegacyBvWriter_h
#define vtkLegacyBvWriter_h

#include "lvdifIOVolumeModule.h"
#include "vtkLVDIFVolumeWriter.h"

#include <string>

class LVDIFIOVOLUME_EXPORT vtkLegacyBvWriter : public vtkLVDIFVolumeWriter
{
public:
  static vtkLegacyBvWriter* New();
  vtkTypeMacro(vtkLegacyBvWriter, vtkLVDIFVolumeWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Exchange X and Z (default on, as vtkLegacyBvReader).
  vtkSetMacro(SwapXZ, bool);
  vtkGetMacro(SwapXZ, bool);
  vtkBooleanMacro(SwapXZ, bool);
  ///@}

  ///@{
  /// Our voxel units per their grid unit (default 1; must be finite and > 0).
  vtkSetMacro(DistanceScale, double);
  vtkGetMacro(DistanceScale, double);
  ///@}

  ///@{
  /// Distances saturate to +-BandWidth voxels before encoding (default 8; 0: no
  /// band; negative or NaN is an error: LVDIFVolumeBridge::BandOption).
  vtkSetMacro(BandWidth, double);
  vtkGetMacro(BandWidth, double);
  ///@}

protected:
  vtkLegacyBvWriter();
  ~vtkLegacyBvWriter() override;

  void Save(const lvdif::DictionaryVolume& volume, const SaveSource& source, lvdif::Interrupter& interrupter) override;
  /// A cube, of the edge the file name's SDF_<N>_ names (lvdif::checkLegacyBvDims).
  void CheckGrid(const std::int64_t dims[3], const double* spacing) override;
  std::unique_ptr<lvdif::DictionaryVolume> ImageToVolume(
    vtkImageData* image, vtkDataArray* sdf, vtkDataArray* rgba) override;
  lvdif::VolumeOptions ImageVolumeOptions() override;

  bool SwapXZ = true;
  double DistanceScale = 1.0;
  double BandWidth = 8.0;

private:
  vtkLegacyBvWriter(const vtkLegacyBvWriter&) = delete;
  void operator=(const vtkLegacyBvWriter&) = delete;
};

#endif
