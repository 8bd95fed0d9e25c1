/**
 * @class   vtkSparseVolumeSliceRepresentation
 * @brief   ParaView's Slice representation for the sparse dictionary volume too
 *
 * ParaView picks its image representation (UniformGridRepresentation) for any
 * dataset whose leaves are images, so a vtkSparseDictionaryVolume gets the
 * Slice entry; but vtkImageSliceRepresentation accepts only a vtkImageData and,
 * being a sink, cannot be looped over the partitions by the composite
 * executive ("Can not execute simple algorithm ... without output ports").
 *
 * This subclass accepts the sparse volume as well and builds the slice plane
 * straight from the Core volume (LVDIFVolumeBridge::FillImage on a one-point
 * thick extent): one plane of `sdf` (and `rgba`), uniform chunks included,
 * no partition decoded and no dense volume. Under pieces a rank slices the
 * points of its own chunks (GetOwnedChunks plus the shared layer of points).
 * A plain vtkImageData is handled exactly as by the superclass.
 */
#ifndef vtkSparseVolumeSliceRepresentation_h
#define vtkSparseVolumeSliceRepresentation_h

#include "lvdifParaViewRepresentationsModule.h"
#include "vtkImageSliceRepresentation.h"

class LVDIFPARAVIEWREPRESENTATIONS_EXPORT vtkSparseVolumeSliceRepresentation : public vtkImageSliceRepresentation
{
public:
  static vtkSparseVolumeSliceRepresentation* New();
  vtkTypeMacro(vtkSparseVolumeSliceRepresentation, vtkImageSliceRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSparseVolumeSliceRepresentation() = default;
  ~vtkSparseVolumeSliceRepresentation() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkSparseVolumeSliceRepresentation(const vtkSparseVolumeSliceRepresentation&) = delete;
  void operator=(const vtkSparseVolumeSliceRepresentation&) = delete;
};

#endif
