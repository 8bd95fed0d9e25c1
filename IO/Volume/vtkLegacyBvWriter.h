/**
 * @class   vtkLegacyBvWriter
 * @brief   writes vtkImageData as the original LVDIF's `.bv` volume file
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
#include "vtkWriter.h"

#include <string>

class vtkImageData;

class LVDIFIOVOLUME_EXPORT vtkLegacyBvWriter : public vtkWriter
{
public:
  static vtkLegacyBvWriter* New();
  vtkTypeMacro(vtkLegacyBvWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);

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
  /// Distances saturate to +-BandWidth voxels before encoding (default 8).
  vtkSetMacro(BandWidth, double);
  vtkGetMacro(BandWidth, double);
  ///@}

  vtkImageData* GetInput();

protected:
  vtkLegacyBvWriter();
  ~vtkLegacyBvWriter() override;

  void WriteData() override;
  int FillInputPortInformation(int port, vtkInformation* info) override;

  std::string FileName;
  bool SwapXZ = true;
  double DistanceScale = 1.0;
  double BandWidth = 8.0;

private:
  vtkLegacyBvWriter(const vtkLegacyBvWriter&) = delete;
  void operator=(const vtkLegacyBvWriter&) = delete;
};

#endif
