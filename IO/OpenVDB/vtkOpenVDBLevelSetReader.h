/**
 * @class   vtkOpenVDBLevelSetReader
 * @brief   reads a level set from an OpenVDB file (.vdb) as a vtkSparseDictionaryVolume
 *
 * Reads one FloatGrid (GridName; default: the file's first grid of class
 * level set) with an axis-aligned, uniformly scaled transform. The output
 * covers the grid's active bounding box grown by Padding voxels: point (0,0,0)
 * is the world position of the box's first voxel, spacing the voxel size.
 * Array `sdf` holds distances in VOXEL units (OpenVDB's world distances
 * divided by the voxel size), negative inside, saturated at the grid's
 * background; inactive voxels take their tile/background value (inside
 * regions keep their negative sign). If an Int32Grid named ColorGridName
 * (default `rgba`, packed r | g<<8 | b<<16 | a<<24) with the same transform
 * exists and WithColor is on, its active voxels colour the `rgba` array; others
 * get the default colour. Values pass through the SDF dictionary (see
 * docs/FORMAT.md). The grid is read once in RequestInformation into a sparse
 * dictionary volume, the output (shared with the reader's cache: filters that
 * change it work on a copy); vtkSparseVolumeToImage gives the dense image.
 */
#ifndef vtkOpenVDBLevelSetReader_h
#define vtkOpenVDBLevelSetReader_h

#include "lvdifIOOpenVDBModule.h"
#include "vtkDataObjectAlgorithm.h"

#include <string>

class LVDIFIOOPENVDB_EXPORT vtkOpenVDBLevelSetReader : public vtkDataObjectAlgorithm
{
public:
  static vtkOpenVDBLevelSetReader* New();
  vtkTypeMacro(vtkOpenVDBLevelSetReader, vtkDataObjectAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);

  ///@{
  /// The grid to read; empty (default) = the first level-set FloatGrid.
  vtkSetStdStringFromCharMacro(GridName);
  vtkGetCharFromStdStringMacro(GridName);
  ///@}

  ///@{
  /// The packed colour grid (default `rgba`); empty = none.
  vtkSetStdStringFromCharMacro(ColorGridName);
  vtkGetCharFromStdStringMacro(ColorGridName);
  ///@}

  ///@{
  /// Produce the `rgba` array (default on).
  vtkSetMacro(WithColor, bool);
  vtkGetMacro(WithColor, bool);
  vtkBooleanMacro(WithColor, bool);
  ///@}

  ///@{
  /// Voxels added around the active bounding box (default 1, so marching
  /// cubes closes surfaces that touch the band's edge), 0 to 65536; anything
  /// else is an error at update, no output (never clamped).
  vtkSetMacro(Padding, int);
  vtkGetMacro(Padding, int);
  ///@}

  /// The names of the file's grids with type and class ("sdf (float, level set)"), one per line.
  std::string GetGridList();

  /// True if OpenVDB can open the file.
  static bool CanReadFile(const char* fileName);

protected:
  vtkOpenVDBLevelSetReader();
  ~vtkOpenVDBLevelSetReader() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  std::string GridName;
  std::string ColorGridName = "rgba";
  bool WithColor = true;
  int Padding = 1;

private:
  struct Internals;
  Internals* Internal;
  vtkOpenVDBLevelSetReader(const vtkOpenVDBLevelSetReader&) = delete;
  void operator=(const vtkOpenVDBLevelSetReader&) = delete;
};

#endif
