/**
 * @class   vtkLegacyBvReader
 * @brief   reads the original LVDIF's `.bv` volume file as a vtkSparseDictionaryVolume
 *
 * A thin wrapper over lvdif::loadLegacyBv (Core/Formats/include/lvdif/LegacyBv.h,
 * original-code-spec.md section 3): N^3 records {uint16 SDF key, uint16
 * colour index}, no header. The edge N comes from the file size (4 N^3 bytes)
 * and must agree with an `SDF_<N>_` token in the file name when there is one.
 * Their inside-positive distances become the project's convention (negative
 * inside), the palette index a colour key (default the Mouse scene's
 * palette); the output is the sparse dictionary volume (vtkSparseVolumeToImage
 * makes the dense `sdf`/`rgba` image). Spacing 1, origin 0. The options mirror lvdif::LegacyBvOptions (SwapXZ,
 * DistanceScale, BandWidth). A bad size or name gives one error naming the
 * problem and an empty output. Reports progress and honours AbortExecute.
 */
#ifndef vtkLegacyBvReader_h
#define vtkLegacyBvReader_h

#include "lvdifIOVolumeModule.h"
#include "vtkDataObjectAlgorithm.h"

#include <string>

class LVDIFIOVOLUME_EXPORT vtkLegacyBvReader : public vtkDataObjectAlgorithm
{
public:
  static vtkLegacyBvReader* New();
  vtkTypeMacro(vtkLegacyBvReader, vtkDataObjectAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// Exchange X and Z (default on: the original stores mesh-derived volumes
  /// with X and Z exchanged, see LegacyBv.h).
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
  /// Distances saturate to +-BandWidth voxels on import (default 8; 0: no band;
  /// negative or NaN is an error: LVDIFVolumeBridge::BandOption).
  vtkSetMacro(BandWidth, double);
  vtkGetMacro(BandWidth, double);
  ///@}

  /// The edge N after UpdateInformation (0 if the file was refused).
  vtkGetMacro(Edge, int);

  /// True if the file's size is 4 N^3 bytes (N >= 1) and agrees with any SDF_<N>_ name token.
  static bool CanReadFile(const char* fileName);

protected:
  vtkLegacyBvReader();
  ~vtkLegacyBvReader() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  bool SwapXZ = true;
  double DistanceScale = 1.0;
  double BandWidth = 8.0;
  int Edge = 0;

private:
  vtkLegacyBvReader(const vtkLegacyBvReader&) = delete;
  void operator=(const vtkLegacyBvReader&) = delete;
};

#endif
