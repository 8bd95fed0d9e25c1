/**
 * @class   vtkDictionaryVolumeReader
 * @brief   reads an LVDIF dictionary volume file (.lvdv) as a vtkSparseDictionaryVolume
 *
 * The output is the sparse dictionary volume itself (no dense image): the
 * file's chunks as stored, uniform chunks collapsed. Generic VTK filters see
 * its partitions (vtkImageData with `sdf` and, when WithColor is on, `rgba`;
 * see vtkSparseDictionaryVolume); a dense image is vtkSparseVolumeToImage's
 * job. The header and chunk table are read in RequestInformation, which
 * announces WHOLE_EXTENT, ORIGIN and SPACING; RequestData reads and
 * decompresses only the chunks that overlap the UPDATE_EXTENT when a
 * consumer asked for less than the whole extent (vtkChunkedMarchingCubes
 * pieces, vtkSparseVolumeToImage sub-extents). Reports progress and honours
 * AbortExecute. A corrupt file gives one error naming the problem and an
 * empty output.
 *
 * Pieces (pvbatch; a request of piece p of n > 1 pieces, as ParaView makes for
 * generic filters): a piece is a block of storage chunks. Ownership rule: the
 * chunk grid's boundaries 0..C (C chunks along an axis) are split like a point
 * extent by vtkExtentTranslator (block mode, by cells), and piece p owns the
 * chunks [b0, b1 - 1] of its boundary range [b0, b1] on every axis: pieces own
 * disjoint chunk blocks that cover the volume. The piece reads its chunks plus
 * the first layer of points of the next ones (their partitions share it) and
 * its partitions are its own chunks only (SetOwnedChunks), so Contour/Slice
 * over all ranks gives every cell once.
 */
#ifndef vtkDictionaryVolumeReader_h
#define vtkDictionaryVolumeReader_h

#include "lvdifIOVolumeModule.h"
#include "vtkDataObjectAlgorithm.h"

#include <string>

class LVDIFIOVOLUME_EXPORT vtkDictionaryVolumeReader : public vtkDataObjectAlgorithm
{
public:
  static vtkDictionaryVolumeReader* New();
  vtkTypeMacro(vtkDictionaryVolumeReader, vtkDataObjectAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// Give the output's partitions an `rgba` array as well (default on).
  vtkSetMacro(WithColor, bool);
  vtkGetMacro(WithColor, bool);
  vtkBooleanMacro(WithColor, bool);
  ///@}

  /// The metadata value of `key` after UpdateInformation ("" if absent), e.g. "name".
  std::string GetMetadata(const std::string& key) const;

  /// True if the file starts with the format's magic number.
  static bool CanReadFile(const char* fileName);

protected:
  vtkDictionaryVolumeReader();
  ~vtkDictionaryVolumeReader() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  bool WithColor = true;

private:
  struct Internals;
  Internals* Internal;
  vtkDictionaryVolumeReader(const vtkDictionaryVolumeReader&) = delete;
  void operator=(const vtkDictionaryVolumeReader&) = delete;
};

#endif
