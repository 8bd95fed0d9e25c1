/**
 * @class   vtkImageToSparseVolume
 * @brief   dense -> sparse: encodes an SDF image into a vtkSparseDictionaryVolume
 *
 * Input: vtkImageData with a scalar point array (default `sdf`, negative
 * inside, voxel units; SetInputArrayToProcess chooses another) and an optional
 * colour array (default `rgba`, 1 to 4 unsigned char components). Output: the
 * sparse dictionary volume with the given ChunkEdge and BandWidth (distances
 * saturate to +-BandWidth; chunks that become uniform collapse). The same
 * encoding as vtkDictionaryVolumeWriter uses for image input.
 *
 * Pieces (pvbatch rank r of n, UpdatePiece): a block of the whole grid's
 * storage chunks, by the .lvdv reader's rule (LVDIFVolumeBridge::RequestedVoxels):
 * the filter asks its input for those chunks' points and the next chunks',
 * the output is a volume of the whole grid holding them (the other chunks
 * uniform outside) with SetOwnedChunks, so the pieces' partitions together
 * are exactly the serial run's.
 */
#ifndef vtkImageToSparseVolume_h
#define vtkImageToSparseVolume_h

#include "lvdifFiltersVolumeModule.h"
#include "vtkDataObjectAlgorithm.h"

class LVDIFFILTERSVOLUME_EXPORT vtkImageToSparseVolume : public vtkDataObjectAlgorithm
{
public:
  static vtkImageToSparseVolume* New();
  vtkTypeMacro(vtkImageToSparseVolume, vtkDataObjectAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Voxels per chunk edge, a power of two in 4..256 (default 32).
  vtkSetMacro(ChunkEdge, int); // out of range: an error at update (no clamp)
  vtkGetMacro(ChunkEdge, int);
  ///@}

  ///@{
  /// Distances saturate at +-BandWidth voxels (default 8, as lvdif's volumes); 0 = no band;
  /// negative or NaN is an error at update (LVDIFVolumeBridge::BandOption).
  vtkSetMacro(BandWidth, double);
  vtkGetMacro(BandWidth, double);
  ///@}

  ///@{
  /// Name of the colour point array (default `rgba`; empty: no colours).
  vtkSetStringMacro(ColorArrayName);
  vtkGetStringMacro(ColorArrayName);
  ///@}

protected:
  vtkImageToSparseVolume();
  ~vtkImageToSparseVolume() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// RequestData: Produce, and a failure (always after its one error, or a
  /// cancel) marked reported (LVDIFVolumeBridge::FailReported: no executive
  /// "returned failure for request" dump after it).
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int Produce(vtkInformationVector** inputVector, vtkInformationVector* outputVector);

  int ChunkEdge = 32;
  double BandWidth = 8.0;
  char* ColorArrayName = nullptr;

private:
  vtkImageToSparseVolume(const vtkImageToSparseVolume&) = delete;
  void operator=(const vtkImageToSparseVolume&) = delete;
};

#endif
