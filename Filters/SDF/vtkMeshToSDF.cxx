#include "vtkMeshToSDF.h"

#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/DictionaryVolume.h"

#include "lvdif/Error.h"
#include "lvdif/Memory.h"
#include "lvdif/MeshToSdf.h"
#include "lvdif/SignVoxelFilter.h"
#include "lvdif/TriangleMesh.h"

#include "vtkAlgorithmOutput.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

vtkStandardNewMacro(vtkMeshToSDF);

vtkMeshToSDF::vtkMeshToSDF()
{
  this->SetNumberOfInputPorts(1);
}

vtkMeshToSDF::~vtkMeshToSDF() = default;

int vtkMeshToSDF::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkMeshToSDF::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkSparseDictionaryVolume");
  return 1;
}

int vtkMeshToSDF::RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  LVDIFVolumeBridge::EnsureSparseOutput(out);
  return 1;
}

namespace
{
/// The grid of the filter's settings for this input; throws lvdif::Error.
lvdif::GridGeometry gridFor(vtkPolyData* pd, bool explicitGrid, const int dims[3], const double origin[3],
  const double spacing[3], int maxDim, double sampleSpacing, double padding)
{
  lvdif::GridGeometry g;
  if (explicitGrid)
  {
    for (int a = 0; a < 3; ++a)
    {
      g.dims[a] = dims[a];
      g.origin[a] = origin[a];
      g.spacing[a] = spacing[a];
    }
    return g;
  }
  // (Padding was checked with the other settings: LVDIFVolumeBridge::PaddingOption)
  lvdif::require(pd && pd->GetNumberOfPoints() > 0, "the input mesh has no points");
  double b[6];
  pd->GetBounds(b);
  for (double v : b)
  {
    if (std::isfinite(v) && lvdif::isWorldCoordinate(static_cast<float>(v))) continue;
    // Core's words for the mesh's points (the first NaN or infinite point, or the
    // mesh's span), as the data pass and an explicit grid report them: an infinite
    // point read "the input has NaN or infinite points" here and a NaN one "mesh
    // point 3 has a NaN or infinite coordinate" (VTK's bounds skip NaN)
    lvdif::TriangleMesh points;
    points.points.resize(static_cast<std::size_t>(pd->GetNumberOfPoints()));
    for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
    {
      double x[3];
      pd->GetPoint(i, x);
      points.points[static_cast<std::size_t>(i)] = { static_cast<float>(x[0]), static_cast<float>(x[1]),
        static_cast<float>(x[2]) };
    }
    points.triangles.push_back({ 0, 0, 0 });
    points.validate();
    lvdif::require(false, "the input has NaN or infinite points"); // (validate found it in float)
  }
  if (sampleSpacing > 0)
  {
    double longest = 0;
    for (int a = 0; a < 3; ++a) longest = std::max(longest, b[2 * a + 1] - b[2 * a]);
    lvdif::require(longest > 0, "the mesh bounds have zero size");
    for (int a = 0; a < 3; ++a)
    {
      // at least one cell per axis, as fitGridToMesh
      const double n = std::max(std::ceil((b[2 * a + 1] - b[2 * a]) / sampleSpacing + 2 * padding - 1e-9) + 1,
        static_cast<double>(lvdif::DictionaryVolume::MinCanvasDimension));
      if (n > static_cast<double>(lvdif::DictionaryVolume::MaxDimension))
      {
        std::ostringstream msg;
        msg << "Sample Spacing " << sampleSpacing << " gives more than " << lvdif::DictionaryVolume::MaxDimension
            << " points along an axis";
        throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, msg.str());
      }
      g.dims[a] = static_cast<std::int64_t>(n);
      g.spacing[a] = sampleSpacing;
      g.origin[a] = 0.5 * (b[2 * a] + b[2 * a + 1]) - 0.5 * static_cast<double>(g.dims[a] - 1) * sampleSpacing;
    }
    return g;
  }
  lvdif::TriangleMesh box; // fitGridToMesh needs only the bounds: the 8 corners stand in
  for (int c = 0; c < 8; ++c)
  {
    box.points.push_back({ static_cast<float>(b[(c & 1) ? 1 : 0]), static_cast<float>(b[(c & 2) ? 3 : 2]),
      static_cast<float>(b[(c & 4) ? 5 : 4]) });
  }
  box.triangles.push_back({ 0, 1, 2 });
  // fitGridToMesh's own check would name its parameters (maxDim, padding):
  // the properties the user sees are named here
  if (static_cast<double>(maxDim) - 1 - 2 * padding < 1)
  {
    std::ostringstream msg;
    msg << "Max Dimension " << maxDim << " leaves no voxel for the mesh inside " << padding
        << " voxels of Padding on each side: use a Max Dimension of at least 2 x Padding + 2 ("
        << static_cast<long long>(std::ceil(2 * padding + 2)) << "), or less Padding";
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, msg.str());
  }
  return lvdif::fitGridToMesh(box, maxDim, padding);
}
} // namespace

void vtkMeshToSDF::CheckFittedGridSettings() const
{
  LVDIFVolumeBridge::PaddingOption(this->Padding);
  if (!std::isfinite(this->SampleSpacing) || this->SampleSpacing < 0)
  {
    std::ostringstream msg;
    msg << "Sample Spacing must be a finite length >= 0 (0: use Max Dimension), not " << this->SampleSpacing;
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, msg.str());
  }
  if (this->SampleSpacing == 0 &&
    (this->MaxDimension < lvdif::DictionaryVolume::MinCanvasDimension ||
      this->MaxDimension > lvdif::DictionaryVolume::MaxDimension))
  {
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
      "Max Dimension must be in [" + std::to_string(lvdif::DictionaryVolume::MinCanvasDimension) + ", " +
        std::to_string(lvdif::DictionaryVolume::MaxDimension) +
        "] (points on the longest axis), not " + std::to_string(this->MaxDimension));
  }
}

void vtkMeshToSDF::CheckEnumerations() const
{
  LVDIFVolumeBridge::EnumOption(
    this->SignMode, "SignMode", { "normal", "pseudo-normal", "winding number", "unsigned" });
  LVDIFVolumeBridge::EnumOption(this->Accelerator, "Accelerator", { "BVH", "faithful", "brute force" });
  lvdif::SignVoxelFilterParams svf; // the mask by Core's rule, the sign filters' own
  svf.filters = static_cast<unsigned>(this->SignVoxelFilters);
  lvdif::checkSignVoxelFilterParams(svf);
  LVDIFVolumeBridge::DeviceOption(this->Device);
}

int vtkMeshToSDF::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  LVDIFVolumeBridge::BeginInformation(outputVector->GetInformationObject(0));
  // the settings first: their error before any work upstream
  if (!LVDIFVolumeBridge::CallCore(this, [&] {
        LVDIFVolumeBridge::CheckVolumeSettings(this->ChunkEdge, this->BandWidth);
        this->CheckEnumerations();
        if (!this->UseExplicitGrid) // the fitted grid's settings, by the names the user sees
          this->CheckFittedGridSettings();
      }))
    return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  if (!this->UseExplicitGrid && (!input || input->GetNumberOfPoints() == 0))
  {
    // a fitted grid needs the mesh bounds before RequestData: bring the input up to date
    vtkAlgorithmOutput* conn = this->GetInputConnection(0, 0);
    if (conn && conn->GetProducer())
    {
      conn->GetProducer()->Update(conn->GetIndex());
      input = vtkPolyData::GetData(inputVector[0]);
    }
  }
  if (!this->UseExplicitGrid && LVDIFVolumeBridge::IsEmptyInput(input))
  {
    // no bounds to fit: an empty volume, as VTK's filters treat an empty input
    // (a failed reader above said why; this filter added "no points")
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    outputVector->GetInformationObject(0)->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
    return 1;
  }
  lvdif::GridGeometry g;
  try
  {
    g = gridFor(input, this->UseExplicitGrid, this->Dimensions, this->Origin, this->Spacing, this->MaxDimension,
      this->SampleSpacing, this->Padding);
    // an explicit grid by the names the user sees (a fitted one has >= 2 points an
    // axis); an axis of 1 point is kept: a 2-D slice of the field (VTK's Contour
    // gives the mesh's cross-section on it; marching cubes needs 2 points an axis)
    const bool dimsOk = g.dims[0] >= 1 && g.dims[1] >= 1 && g.dims[2] >= 1 && g.dims[0] <= VTK_INT_MAX &&
      g.dims[1] <= VTK_INT_MAX && g.dims[2] <= VTK_INT_MAX;
    if (!dimsOk || !(g.spacing[0] > 0 && g.spacing[1] > 0 && g.spacing[2] > 0))
    {
      std::ostringstream msg;
      if (!dimsOk)
        msg << "Dimensions must be at least 1 point on each axis, not " << g.dims[0] << " x " << g.dims[1] << " x "
            << g.dims[2];
      else
        msg << "Spacing must be > 0 on each axis, not " << g.spacing[0] << ", " << g.spacing[1] << ", " << g.spacing[2];
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, msg.str());
    }
  }
  catch (const lvdif::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
  }
  lvdif::VolumeOptions vo = lvdif::volumeOptionsOn(g);
  vo.chunkEdge = this->ChunkEdge;
  LVDIFVolumeBridge::SetSparseInformation(outputVector->GetInformationObject(0), vo);
  return 1;
}

int vtkMeshToSDF::RequestUpdateExtent(vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // every piece of the image needs the whole mesh
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  return 1;
}

int vtkMeshToSDF::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return this->Produce(inputVector, outputVector) ? 1
                                                  : LVDIFVolumeBridge::FailReported(outputVector->GetInformationObject(0));
}

int vtkMeshToSDF::Produce(vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (LVDIFVolumeBridge::InformationFailed(outputVector->GetInformationObject(0)))
    return 0; // RequestInformation reported why (ParaView runs RequestData anyway)
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkSparseDictionaryVolume* output = vtkSparseDictionaryVolume::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("input must be vtkPolyData");
    return 0;
  }
  if (LVDIFVolumeBridge::IsEmptyInput(input))
  {
    output->Initialize(); // VTK's rule for an empty input: empty output, no error
    return 1;
  }
  if (input->GetNumberOfPolys() + input->GetNumberOfStrips() == 0)
  {
    vtkErrorMacro("the input mesh has no polygons or triangle strips (lines and vertices are ignored)");
    return 0;
  }
  lvdif::MeshToSdfStats st;
  vtkIdType chunksComputed = 0;
  LVDIFInterrupter interrupter(this);
  const bool ok = LVDIFVolumeBridge::CallCore(this, [&] {
    const lvdif::GridGeometry g = gridFor(input, this->UseExplicitGrid, this->Dimensions, this->Origin,
      this->Spacing, this->MaxDimension, this->SampleSpacing, this->Padding);
    lvdif::VolumeOptions vo = lvdif::volumeOptionsOn(g);
    vo.chunkEdge = this->ChunkEdge;
    vo.bandWidth = LVDIFVolumeBridge::BandOption(this->BandWidth);
    auto volume = std::make_shared<lvdif::DictionaryVolume>(vo); // validates and checks the memory limit
    const lvdif::TriangleMesh mesh = LVDIFVolumeBridge::ToTriangleMesh(input, this->UseVertexNormals);
    lvdif::MeshToSdfOptions o;
    o.sign = this->SignMode == NORMAL ? lvdif::SignMode::Normal
      : this->SignMode == PSEUDO_NORMAL ? lvdif::SignMode::PseudoNormal
      : this->SignMode == UNSIGNED      ? lvdif::SignMode::Unsigned
                                        : lvdif::SignMode::WindingNumber;
    o.accel = this->Accelerator == FAITHFUL ? lvdif::MeshToSdfAccel::Faithful
      : this->Accelerator == BRUTE_FORCE    ? lvdif::MeshToSdfAccel::BruteForce
                                            : lvdif::MeshToSdfAccel::Bvh;
    o.useVertexNormals = this->UseVertexNormals;
    o.reorientFaces = this->ReorientFaces;
    o.svfFilters = static_cast<unsigned>(this->SignVoxelFilters);
    o.device = LVDIFVolumeBridge::ToDevice(this->Device);
    o.svf.device = o.device;
    // a piece (pvbatch) or a smaller extent: only the storage chunks holding
    // its voxels, by the .lvdv reader's rule (the sign filters need them all)
    int owned[6];
    lvdif::VoxelBox voxels;
    const int kind = o.svfFilters != 0 ? 0
                                       : LVDIFVolumeBridge::RequestedVoxels(
                                           outputVector->GetInformationObject(0), vo, owned, voxels);
    if (kind < 0)
    {
      output->Initialize(); // a piece without chunks
      return;
    }
    if (kind > 0)
    {
      for (int a = 0; a < 3; ++a)
      {
        o.chunkRegion.lo[a] = voxels.lo[a] / vo.chunkEdge;
        o.chunkRegion.hi[a] = voxels.hi[a] / vo.chunkEdge;
      }
    }
    st = lvdif::meshToSdf(mesh, *volume, o, interrupter);
    volume->takeDirtyChunks(); // a new volume: nothing to re-mesh incrementally
    output->SetVolume(std::move(volume));
    if (kind == 1)
    {
      output->SetOwnedChunks(owned);
    }
    chunksComputed = kind > 0 ? o.chunkRegion.voxelCount() : output->GetNumberOfChunks();
  });
  if (!ok)
  {
    output->Initialize();
    return 0;
  }
  // The warnings are about the mesh (or the whole grid, which only a whole
  // run judges), the same on every piece: a pvbatch run of N ranks prints them
  // once, from piece 0.
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const bool firstPiece = !outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) ||
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) == 0;
  for (std::size_t i = 0; firstPiece && i < st.warnings.size(); ++i)
  {
    vtkWarningMacro(<< st.warnings[i]);
  }
  vtkNew<vtkIdTypeArray> degenerate;
  degenerate->SetName("degenerate_triangles");
  degenerate->InsertNextValue(static_cast<vtkIdType>(st.degenerateSkipped));
  output->GetFieldData()->AddArray(degenerate);
  vtkNew<vtkIdTypeArray> computed; // this process's share of the work (pvbatch ranks)
  computed->SetName("mesh_to_sdf_chunks");
  computed->InsertNextValue(chunksComputed);
  output->GetFieldData()->AddArray(computed);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkMeshToSDF::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SignMode: " << this->SignMode << "\n";
  os << indent << "Accelerator: " << this->Accelerator << "\n";
  os << indent << "MaxDimension: " << this->MaxDimension << "\n";
  os << indent << "SampleSpacing: " << this->SampleSpacing << "\n";
  os << indent << "Padding: " << this->Padding << "\n";
  os << indent << "UseExplicitGrid: " << this->UseExplicitGrid << "\n";
  os << indent << "Dimensions: " << this->Dimensions[0] << " " << this->Dimensions[1] << " " << this->Dimensions[2]
     << "\n";
  os << indent << "Origin: " << this->Origin[0] << " " << this->Origin[1] << " " << this->Origin[2] << "\n";
  os << indent << "Spacing: " << this->Spacing[0] << " " << this->Spacing[1] << " " << this->Spacing[2] << "\n";
  os << indent << "BandWidth: " << this->BandWidth << "\n";
  os << indent << "ChunkEdge: " << this->ChunkEdge << "\n";
  os << indent << "UseVertexNormals: " << this->UseVertexNormals << "\n";
  os << indent << "ReorientFaces: " << this->ReorientFaces << "\n";
  os << indent << "SignVoxelFilters: " << this->SignVoxelFilters << "\n";
  os << indent << "Device: " << this->Device << "\n";
}
