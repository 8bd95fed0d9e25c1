/**
 * @class   vtkOpenVDBLevelSetWriter
 * @brief   writes a vtkSparseDictionaryVolume, or vtkImageData's `sdf` (and `rgba`), as an OpenVDB level set (.vdb)
 *
 * A sparse volume is exported as it is: its band, unless HalfWidth asks for a
 * narrower one (a warning names the band asked and the band written when they
 * differ otherwise: an unlimited band is written 3 voxels wide, a HalfWidth
 * wider than the band is written as the band). An image input needs a point array `sdf` (negative inside, voxel units) and
 * isotropic spacing; an unsigned char `rgba` array (1 to 4 components) is
 * written too when WithColor is on. The file holds a FloatGrid `sdf` of class
 * level set whose values are WORLD-unit distances (voxel distance x spacing),
 * active where |d| < HalfWidth voxels, background HalfWidth x spacing, the
 * transform mapping index (i,j,k) to origin + spacing (i,j,k); plus an
 * Int32Grid `rgba` of packed colours (r | g<<8 | b<<16 | a<<24) on the same
 * active voxels. Distances pass through the SDF dictionary (quantization of
 * docs/FORMAT.md). See docs/FORMAT.md, "OpenVDB interop". Check with
 * `vdb_print -l file.vdb`.
 */
#ifndef vtkOpenVDBLevelSetWriter_h
#define vtkOpenVDBLevelSetWriter_h

#include "lvdifIOOpenVDBModule.h"
#include "vtkLVDIFVolumeWriter.h"

#include <string>

class LVDIFIOOPENVDB_EXPORT vtkOpenVDBLevelSetWriter : public vtkLVDIFVolumeWriter
{
public:
  static vtkOpenVDBLevelSetWriter* New();
  vtkTypeMacro(vtkOpenVDBLevelSetWriter, vtkLVDIFVolumeWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Narrow-band half width in voxels; 0 (default) = the sparse volume's band
  /// (3, OpenVDB's default, for an image or an unlimited band). It was 3 by
  /// default, so `lvdif convert` narrowed a band of 8 to 3 without a word.
  /// Else 1 to 10000; anything else (NaN too) is an error at write, nothing
  /// written and an older file kept (lvdif::vdb::checkHalfWidth; never clamped).
  vtkSetMacro(HalfWidth, double);
  vtkGetMacro(HalfWidth, double);
  ///@}

  ///@{
  /// Write the `rgba` grid when the input has an `rgba` array (default on).
  vtkSetMacro(WithColor, bool);
  vtkGetMacro(WithColor, bool);
  vtkBooleanMacro(WithColor, bool);
  ///@}

  ///@{
  /// Name of the level-set grid (default `sdf`).
  vtkSetStdStringFromCharMacro(GridName);
  vtkGetCharFromStdStringMacro(GridName);
  ///@}

protected:
  vtkOpenVDBLevelSetWriter();
  ~vtkOpenVDBLevelSetWriter() override;

  void Save(const lvdif::DictionaryVolume& volume, const SaveSource& source, lvdif::Interrupter& interrupter) override;
  void CheckSettings() override;
  /// One spacing on every axis (lvdif::vdb::checkExportSpacing).
  void CheckGrid(const std::int64_t dims[3], const double* spacing) override;
  bool ReadsImageColors() override { return this->WithColor; }
  lvdif::VolumeOptions ImageVolumeOptions() override;

  std::string GridName = "sdf";
  double HalfWidth = 0.0;
  bool WithColor = true;

private:
  vtkOpenVDBLevelSetWriter(const vtkOpenVDBLevelSetWriter&) = delete;
  void operator=(const vtkOpenVDBLevelSetWriter&) = delete;
};

#endif
