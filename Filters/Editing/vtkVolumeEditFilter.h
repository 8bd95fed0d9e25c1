/**
 * @class   vtkVolumeEditFilter
 * @brief   applies an edit script or a recording to a sparse volume or SDF image ("the editing filter")
 *
 * Input, one of: a vtkSparseDictionaryVolume, edited in a copy of its Core
 * volume (sparse, no dense image; the output is a vtkSparseDictionaryVolume
 * whose dirty flags mark the edited chunks; ChunkEdge and BandWidth are the
 * volume's own then); or vtkImageData with a point array `sdf` (negative inside, voxel units;
 * any real type) and optionally `rgba` (unsigned char, 1 to 4 components).
 * Output: the same grid with the edited `sdf` (float) and `rgba` (4 unsigned
 * char components). The image becomes an lvdif::DictionaryVolume (chunk edge
 * ChunkEdge, distances saturated to +-BandWidth and quantized by the SDF
 * dictionary, docs/FORMAT.md), the edits run through lvdif::Editor exactly as
 * in the editor and the CLI, and the volume is decoded back. Coordinates in
 * scripts and recordings are voxel indices of the input grid (index 0 at the
 * extent's first point).
 *
 * Set ScriptText (docs/SCRIPTING.md) or RecordingFileName
 * (docs/RECORDING.md); with both, the recording plays first. A script that
 * uses `canvas` replaces the input by its new volume. Errors (with the
 * script's line and column) are reported through vtkErrorMacro and
 * GetLastError(); the output is then empty.
 */
#ifndef vtkVolumeEditFilter_h
#define vtkVolumeEditFilter_h

#include "lvdifFiltersEditingModule.h"
#include "vtkDataObjectAlgorithm.h"

#include <string>

class LVDIFFILTERSEDITING_EXPORT vtkVolumeEditFilter : public vtkDataObjectAlgorithm
{
public:
  static vtkVolumeEditFilter* New();
  vtkTypeMacro(vtkVolumeEditFilter, vtkDataObjectAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The script to run (empty: none).
  vtkSetStdStringFromCharMacro(ScriptText);
  vtkGetCharFromStdStringMacro(ScriptText);
  ///@}

  ///@{
  /// A recording file to play (empty: none).
  vtkSetStdStringFromCharMacro(RecordingFileName);
  vtkGetCharFromStdStringMacro(RecordingFileName);
  ///@}

  ///@{
  /// Distances saturate to +-BandWidth voxels (default 8; large values keep
  /// more of the input field, brushes only need the band near the surface; 0:
  /// no band; negative or NaN is an error: LVDIFVolumeBridge::BandOption).
  vtkSetMacro(BandWidth, double);
  vtkGetMacro(BandWidth, double);
  ///@}

  ///@{
  /// Chunk edge of the working volume (power of two, 4..256; default 32).
  vtkSetMacro(ChunkEdge, int); // out of range: an error at update (no clamp)
  vtkGetMacro(ChunkEdge, int);
  ///@}

  ///@{
  /// Produce `rgba` (default on).
  vtkSetMacro(WithColor, bool);
  vtkGetMacro(WithColor, bool);
  vtkBooleanMacro(WithColor, bool);
  ///@}

  /// The last error ("" after a successful update), and a script error's line/column (0 otherwise).
  const char* GetLastError() { return this->LastError.c_str(); }
  int GetLastErrorLine() { return this->LastErrorLine; }
  int GetLastErrorColumn() { return this->LastErrorColumn; }

protected:
  vtkVolumeEditFilter();
  ~vtkVolumeEditFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string ScriptText;
  std::string RecordingFileName;
  double BandWidth = 8.0;
  int ChunkEdge = 32;
  bool WithColor = true;
  std::string LastError;
  int LastErrorLine = 0;
  int LastErrorColumn = 0;

private:
  vtkVolumeEditFilter(const vtkVolumeEditFilter&) = delete;
  void operator=(const vtkVolumeEditFilter&) = delete;
};

#endif
