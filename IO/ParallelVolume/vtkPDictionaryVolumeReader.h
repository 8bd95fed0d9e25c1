/**
 * @class   vtkPDictionaryVolumeReader
 * @brief   reads a distributed dictionary volume (.lvdvp index + one .lvdv per piece)
 *
 * Reads the index written by vtkPDictionaryVolumeWriter (docs/FORMAT.md,
 * "Distributed volumes") and produces the sparse dictionary volume
 * (vtkSparseDictionaryVolume), never a dense image: the piece files' chunks
 * are copied key by key (colours mapped to the output's colour dictionary,
 * distances re-encoded only when a piece's SDF dictionary differs) into one
 * Core volume with the pieces' chunk edge and band. Which voxels a request
 * needs is decided as by vtkDictionaryVolumeReader:
 * - piece p of n > 1 (pvbatch): the block of storage chunks the ownership rule
 *   gives it (LVDIFVolumeBridge::PieceChunks: chunk boundaries split like a point
 *   extent by vtkExtentTranslator) plus the layer of points their partitions
 *   share; the partitions are its own chunks only (SetOwnedChunks);
 * - an update extent smaller than the whole (a consumer's sub-extent): those voxels;
 * - otherwise the whole volume.
 * Only the piece files overlapping those voxels are opened, and each decodes
 * only its chunks overlapping them, so a rank reads only its part whatever
 * the number of ranks that wrote the files. Points on a plane shared by two
 * pieces are taken from the first piece listed (both hold the same values).
 */
#ifndef vtkPDictionaryVolumeReader_h
#define vtkPDictionaryVolumeReader_h

#include "lvdifIOParallelVolumeModule.h"
#include "vtkDataObjectAlgorithm.h"

#include <string>

class LVDIFIOPARALLELVOLUME_EXPORT vtkPDictionaryVolumeReader : public vtkDataObjectAlgorithm
{
public:
  static vtkPDictionaryVolumeReader* New();
  vtkTypeMacro(vtkPDictionaryVolumeReader, vtkDataObjectAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);

  ///@{
  /// Also produce `rgba` (default on).
  vtkSetMacro(WithColor, bool);
  vtkGetMacro(WithColor, bool);
  vtkBooleanMacro(WithColor, bool);
  ///@}

  /// True if the file starts with the index's magic line.
  static bool CanReadFile(const char* fileName);

  /// Pieces opened by the last update (for tests and diagnostics).
  vtkGetMacro(PiecesRead, int);

protected:
  vtkPDictionaryVolumeReader();
  ~vtkPDictionaryVolumeReader() override;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  bool WithColor = true;
  int PiecesRead = 0;

private:
  vtkPDictionaryVolumeReader(const vtkPDictionaryVolumeReader&) = delete;
  void operator=(const vtkPDictionaryVolumeReader&) = delete;
};

#endif
