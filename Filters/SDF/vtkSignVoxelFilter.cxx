#include "vtkSignVoxelFilter.h"

#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/DictionaryVolume.h"

#include "lvdif/Error.h"
#include "lvdif/SignVoxelFilter.h"

#include "vtkDataObject.h"
#include "vtkExtentTranslator.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>

vtkStandardNewMacro(vtkSignVoxelFilter);

vtkSignVoxelFilter::vtkSignVoxelFilter()
{
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "sdf");
}

vtkSignVoxelFilter::~vtkSignVoxelFilter() = default;

namespace
{
using SDDP = vtkStreamingDemandDrivenPipeline;
/// A consumer's request arrives as UPDATE_EXTENT (the executive translates a
/// downstream piece request into it). UpdatePiece() called on this filter
/// itself leaves UPDATE_EXTENT at the whole extent and sets only the piece
/// keys: then the piece is translated here, as the executive would (block
/// mode, split by cells: pieces share one point plane).
void RequestedPiece(vtkInformation* outInfo, int ext[6])
{
  const int pieces = outInfo->Has(SDDP::UPDATE_NUMBER_OF_PIECES()) ? outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES()) : 1;
  if (pieces <= 1 || !outInfo->Has(SDDP::WHOLE_EXTENT()))
  {
    return;
  }
  int whole[6];
  outInfo->Get(SDDP::WHOLE_EXTENT(), whole);
  if (!std::equal(whole, whole + 6, ext))
  {
    return;
  }
  const int piece = outInfo->Has(SDDP::UPDATE_PIECE_NUMBER()) ? outInfo->Get(SDDP::UPDATE_PIECE_NUMBER()) : 0;
  const int ghosts =
    outInfo->Has(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS()) ? outInfo->Get(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS()) : 0;
  vtkNew<vtkExtentTranslator> t;
  if (!t->PieceToExtentThreadSafe(piece, pieces, ghosts, whole, ext, vtkExtentTranslator::BLOCK_MODE, 0))
  {
    ext[0] = ext[2] = ext[4] = 0; // an empty piece
    ext[1] = ext[3] = ext[5] = -1;
  }
}

void AddStats(vtkDataObject* output, const lvdif::SignVoxelFilterStats& st)
{
  vtkNew<vtkIdTypeArray> flips;
  flips->SetName("svf_flips");
  vtkNew<vtkIntArray> iterations;
  iterations->SetName("svf_iterations");
  for (int f = 0; f < 4; ++f)
  {
    flips->InsertNextValue(static_cast<vtkIdType>(st.flips[f]));
    iterations->InsertNextValue(st.iterations[f]);
  }
  output->GetFieldData()->AddArray(flips);
  output->GetFieldData()->AddArray(iterations);
}
} // namespace

int vtkSignVoxelFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkSparseDictionaryVolume");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkSignVoxelFilter::RequestDataObject(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // the output is of the input's kind: sparse in, sparse out; image in, image out
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0]);
  if (!input) return 0;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkDataObject* current = outInfo->Get(vtkDataObject::DATA_OBJECT());
  if (vtkSparseDictionaryVolume::SafeDownCast(input))
  {
    LVDIFVolumeBridge::EnsureSparseOutput(outputVector);
  }
  else if (!vtkImageData::SafeDownCast(current))
  {
    vtkNew<vtkImageData> image;
    outInfo->Set(vtkDataObject::DATA_OBJECT(), image);
  }
  return 1;
}

// The scans need whole rows and planes: always filter the whole input (see the header).
int vtkSignVoxelFilter::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    int whole[6];
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), whole, 6);
  }
  // a request for the whole extent is one piece of one, without ghosts
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::EXACT_EXTENT(), 1);
  return 1;
}

int vtkSignVoxelFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (auto* sparse = vtkSparseDictionaryVolume::GetData(inputVector[0]))
  {
    return this->FilterSparse(sparse, vtkSparseDictionaryVolume::GetData(outputVector));
  }
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("input and output must be vtkImageData");
    return 0;
  }
  vtkDataArray* in = LVDIFVolumeBridge::SdfArray(
    this->GetInputArrayInformation(0), input, this->GetInputArrayToProcess(0, inputVector));
  if (!in)
  {
    vtkErrorMacro("no point array to process (default: `sdf`; see SetInputArrayToProcess)");
    return 0;
  }
  vtkFloatArray* inFloat = vtkFloatArray::SafeDownCast(in);
  if (!inFloat || in->GetNumberOfComponents() != 1)
  {
    vtkErrorMacro("array `" << (in->GetName() ? in->GetName() : "") << "` must be a 1-component vtkFloatArray, is "
                            << in->GetClassName() << " with " << in->GetNumberOfComponents() << " components");
    return 0;
  }
  int dims[3];
  input->GetDimensions(dims);
  if (in->GetNumberOfTuples() != static_cast<vtkIdType>(dims[0]) * dims[1] * dims[2])
  {
    vtkErrorMacro("array `" << in->GetName() << "` is not a point array of the image (" << in->GetNumberOfTuples()
                            << " values for " << dims[0] << " x " << dims[1] << " x " << dims[2] << " points)");
    return 0;
  }

  vtkNew<vtkFloatArray> filtered;
  filtered->DeepCopy(inFloat);
  filtered->SetName(in->GetName());

  lvdif::FloatGridView grid;
  grid.data = filtered->GetPointer(0);
  grid.geometry.dims = { dims[0], dims[1], dims[2] };
  const lvdif::SignVoxelFilterParams p = this->CoreParams();
  lvdif::SignVoxelFilterStats st;
  LVDIFInterrupter interrupter(this);
  try
  {
    st = lvdif::signVoxelFilter(grid, p, interrupter);
  }
  catch (const lvdif::Error& e)
  {
    if (e.code() != lvdif::ErrorCode::Cancelled)
    {
      vtkErrorMacro(<< e.what());
    }
    return 0;
  }

  // signs changed through the pointer: the range of the new values, stored for ParaView's data information
  LVDIFVolumeBridge::StoreRange(filtered);
  output->ShallowCopy(input);
  // replace the processed array, keeping its attribute role (e.g. active scalars)
  vtkPointData* pd = output->GetPointData();
  const bool wasScalars = pd->GetScalars() == in;
  if (in->GetName())
  {
    pd->RemoveArray(in->GetName());
  }
  if (wasScalars)
  {
    pd->SetScalars(filtered);
  }
  else
  {
    pd->AddArray(filtered);
  }

  AddStats(output, st);
  // only the requested piece leaves the filter (every piece is a crop of the serial result)
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    int uExt[6];
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), uExt);
    RequestedPiece(outInfo, uExt);
    if (uExt[0] > uExt[1] || uExt[2] > uExt[3] || uExt[4] > uExt[5])
    {
      output->Initialize(); // an empty piece (more pieces than cells)
    }
    else
    {
      output->Crop(uExt);
    }
  }
  this->UpdateProgress(1.0);
  return 1;
}

lvdif::SignVoxelFilterParams vtkSignVoxelFilter::CoreParams() const
{
  lvdif::SignVoxelFilterParams p;
  p.threshold = static_cast<float>(this->Threshold);
  p.axis = this->Axis;
  p.filters = static_cast<unsigned>(this->Filters);
  p.maxIterations = this->MaxIterations;
  p.boundary = this->Boundary == BOUNDARY_FREE ? lvdif::SvfBoundary::Free : lvdif::SvfBoundary::Outside;
  p.device = LVDIFVolumeBridge::ToDevice(this->Device);
  return p;
}

int vtkSignVoxelFilter::FilterSparse(vtkSparseDictionaryVolume* input, vtkSparseDictionaryVolume* output)
{
  if (!input->HasVolume())
  {
    vtkErrorMacro("the input sparse volume holds no dictionary volume");
    return 0;
  }
  lvdif::SignVoxelFilterStats st;
  LVDIFInterrupter interrupter(this);
  const bool ok = LVDIFVolumeBridge::CallCore(this, [&] {
    // a copy: VTK filters leave their input alone (the copy is as sparse as the input)
    std::shared_ptr<lvdif::DictionaryVolume> volume(input->GetVolume()->clone());
    st = lvdif::signVoxelFilter(*volume, this->CoreParams(), interrupter);
    output->SetVolume(std::move(volume));
    output->SetPartitionColors(input->GetPartitionColors());
  });
  if (!ok)
  {
    output->Initialize();
    return 0;
  }
  AddStats(output, st);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkSignVoxelFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Threshold: " << this->Threshold << "\n";
  os << indent << "Axis: " << this->Axis << "\n";
  os << indent << "Filters: " << this->Filters << "\n";
  os << indent << "MaxIterations: " << this->MaxIterations << "\n";
  os << indent << "Boundary: " << (this->Boundary == BOUNDARY_FREE ? "free" : "outside") << "\n";
  os << indent << "Device: " << this->Device << "\n";
}
