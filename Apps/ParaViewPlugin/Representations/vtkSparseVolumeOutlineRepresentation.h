/**
 * @class   vtkSparseVolumeOutlineRepresentation
 * @brief   ParaView's Outline representation for the sparse dictionary volume, nothing decoded
 *
 * ParaView outlines a composite dataset with vtkPVGeometryFilter over every
 * leaf: for a vtkSparseDictionaryVolume that decodes every partition (one
 * chunk image each) to draw one box per partition, minutes for a 1024^3
 * volume. This subclass draws the one box of the whole volume from the Core
 * volume's geometry (dims, origin, spacing) and hands it straight to the
 * mapper's input; no partition is built or decoded.
 *
 * Under pieces it follows ParaView's outline of a distributed image
 * (vtkPVGeometryFilter::ImageDataExecute): the whole volume's box, drawn by
 * piece 0 only, every other piece empty. Any other input is outlined exactly
 * as by the superclass.
 */
#ifndef vtkSparseVolumeOutlineRepresentation_h
#define vtkSparseVolumeOutlineRepresentation_h

#include "lvdifParaViewRepresentationsModule.h"
#include "vtkOutlineRepresentation.h"

class LVDIFPARAVIEWREPRESENTATIONS_EXPORT vtkSparseVolumeOutlineRepresentation : public vtkOutlineRepresentation
{
public:
  static vtkSparseVolumeOutlineRepresentation* New();
  vtkTypeMacro(vtkSparseVolumeOutlineRepresentation, vtkOutlineRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSparseVolumeOutlineRepresentation() = default;
  ~vtkSparseVolumeOutlineRepresentation() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkSparseVolumeOutlineRepresentation(const vtkSparseVolumeOutlineRepresentation&) = delete;
  void operator=(const vtkSparseVolumeOutlineRepresentation&) = delete;
};

#endif
