/**
 * @class   vtkSparseVolumeVolumeRepresentation
 * @brief   ParaView's Volume representation for the sparse dictionary volume too
 *
 * ParaView offers its image representation's *Volume* for the sparse volume
 * (a vtkPartitionedDataSet of images), but vtkImageVolumeRepresentation drew
 * nothing of it, without a message: only the partitions' images could be
 * volume-rendered, and they are decoded on demand (and the uniform chunks have
 * none). Volume rendering needs the voxels on the GPU in any case; this subclass
 * gives the superclass the dense image of the points this rank holds (its own
 * chunks plus the layer of points shared with the next ones; the whole volume
 * in one process), decoded straight from the Core volume with
 * LVDIFVolumeBridge::FillImage, uniform chunks included. Its size is said
 * before it is allocated and refused above the memory limit (the rule of
 * vtkSparseVolumeToImage: LVDIFVolumeBridge::DenseImageWarning, lvdif::requireMemory),
 * then nothing is drawn. A plain vtkImageData is handled exactly as by the superclass.
 */
#ifndef vtkSparseVolumeVolumeRepresentation_h
#define vtkSparseVolumeVolumeRepresentation_h

#include "lvdifParaViewRepresentationsModule.h"
#include "vtkImageVolumeRepresentation.h"

class LVDIFPARAVIEWREPRESENTATIONS_EXPORT vtkSparseVolumeVolumeRepresentation : public vtkImageVolumeRepresentation
{
public:
  static vtkSparseVolumeVolumeRepresentation* New();
  vtkTypeMacro(vtkSparseVolumeVolumeRepresentation, vtkImageVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSparseVolumeVolumeRepresentation() = default;
  ~vtkSparseVolumeVolumeRepresentation() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkSparseVolumeVolumeRepresentation(const vtkSparseVolumeVolumeRepresentation&) = delete;
  void operator=(const vtkSparseVolumeVolumeRepresentation&) = delete;
};

#endif
