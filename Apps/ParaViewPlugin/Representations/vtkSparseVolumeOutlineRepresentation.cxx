#include "vtkSparseVolumeOutlineRepresentation.h"

#include "vtkCellArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSparseDictionaryVolume.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "lvdif/DictionaryVolume.h"

vtkStandardNewMacro(vtkSparseVolumeOutlineRepresentation);

int vtkSparseVolumeOutlineRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkSparseDictionaryVolume* sparse = inputVector[0]->GetNumberOfInformationObjects() == 1
    ? vtkSparseDictionaryVolume::GetData(inputVector[0], 0)
    : nullptr;
  // Every rank of a sparse volume takes this path, also one whose piece has no
  // chunks (no volume: more ranks than chunk blocks): the superclass's geometry
  // filter communicates between ranks, and one rank in it while the others are
  // not aborted pvbatch (MPI_ERR_TRUNCATE: a one-chunk volume shown on 2 ranks).
  if (!sparse)
  {
    // the superclass's pipeline: its geometry filter feeds the mapper's input
    this->MultiBlockMaker->SetInputConnection(this->GeometryFilter->GetOutputPort());
    return this->Superclass::RequestData(request, inputVector, outputVector);
  }

  vtkNew<vtkPolyData> box;
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  const int piece = inInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    ? inInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    : 0;
  if (piece == 0 && sparse->HasVolume())
  {
    const lvdif::DictionaryVolume& volume = *sparse->GetVolume();
    const auto& o = volume.options();
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = o.origin[a];
      hi[a] = o.origin[a] + o.spacing[a] * static_cast<double>(volume.dims()[a] - 1);
    }
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    for (int k = 0; k < 8; ++k) // corner k: bit 0 -> x, bit 1 -> y, bit 2 -> z
    {
      points->InsertNextPoint(k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]);
    }
    vtkNew<vtkCellArray> lines;
    for (int k = 0; k < 8; ++k)
    {
      for (int bit = 1; bit < 8; bit <<= 1)
      {
        if (!(k & bit)) // the edge from corner k along axis `bit`
        {
          const vtkIdType edge[2] = { k, k | bit };
          lines->InsertNextCell(2, edge);
        }
      }
    }
    box->SetPoints(points);
    box->SetLines(lines);
  }
  // The box goes to the mapper's input directly: the geometry filter would
  // walk the composite input's leaves; it keeps an input so that
  // GetRenderedDataObject answers, but is not executed (on any rank).
  this->GeometryFilter->SetInputDataObject(0, box);
  this->MultiBlockMaker->SetInputDataObject(0, box);
  this->MultiBlockMaker->Update();
  // what vtkGeometryRepresentation::RequestData does after updating its pipeline
  return this->vtkPVDataRepresentation::RequestData(request, inputVector, outputVector);
}

void vtkSparseVolumeOutlineRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
