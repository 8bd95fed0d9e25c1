#include "vtkChunkedMarchingCubes.h"

#include "LVDIFChunkedMarchingCubesOutput.h"
#include "LVDIFChunkedMarchingCubesVtkTable.h"
#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdif/Error.h"

#include "vtkDataArray.h"
#include "vtkExtentTranslator.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <map>
#include <vector>

vtkStandardNewMacro(vtkChunkedMarchingCubes);

namespace
{
/// The ghost-free extent of a piece: block split by cells, so neighbouring
/// pieces share one plane of points. Empty (hi < lo) when there are more
/// pieces than cells.
void pieceExtent(int piece, int pieces, const int whole[6], int ext[6])
{
  vtkNew<vtkExtentTranslator> t;
  int w[6];
  std::copy(whole, whole + 6, w);
  if (!t->PieceToExtentThreadSafe(piece, pieces, 0, w, ext, vtkExtentTranslator::BLOCK_MODE, 0))
  {
    for (int a = 0; a < 3; ++a)
    {
      ext[2 * a] = whole[2 * a];
      ext[2 * a + 1] = whole[2 * a] - 1;
    }
  }
}

/// A volume one point thick on some axis (16 x 12 x 1: a 2-D slice, which
/// vtkMeshToSDF's explicit grid and vtkImageToSparseVolume make on purpose)
/// has no cells, so marching cubes has nothing to mesh: the filter said
/// nothing and gave no triangles (VTK's vtkMarchingCubes: "Cannot contour data
/// of dimension != 3"). One error naming the dimensions and what gives the
/// slice's iso-lines; false, output emptied. An empty volume (an axis of 0
/// points) is not flat: empty output, no error (VTK's rule for empty input).
bool flatVolumeCheck(vtkChunkedMarchingCubes* self, const std::int64_t dims[3], vtkDataObject* output)
{
  if (dims[0] < 1 || dims[1] < 1 || dims[2] < 1 || (dims[0] >= 2 && dims[1] >= 2 && dims[2] >= 2)) return true;
  output->Initialize();
  vtkErrorWithObjectMacro(self, "cannot mesh a volume of " << dims[0] << " x " << dims[1] << " x " << dims[2]
    << " points: marching cubes needs at least 2 points along every axis (a volume one point thick has no "
       "cells); VTK's Contour filter gives the iso-lines of such a slice");
  return false;
}

void pieceRequest(vtkInformation* info, int& piece, int& pieces)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  piece = info->Has(SDDP::UPDATE_PIECE_NUMBER()) ? info->Get(SDDP::UPDATE_PIECE_NUMBER()) : 0;
  pieces = info->Has(SDDP::UPDATE_NUMBER_OF_PIECES()) ? info->Get(SDDP::UPDATE_NUMBER_OF_PIECES()) : 1;
  pieces = std::max(pieces, 1);
}
}

vtkChunkedMarchingCubes::vtkChunkedMarchingCubes()
{
  this->SetColorArrayName("rgba");
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "sdf");
}

vtkChunkedMarchingCubes::~vtkChunkedMarchingCubes()
{
  this->SetColorArrayName(nullptr);
}

void vtkChunkedMarchingCubes::SetVolume(std::shared_ptr<lvdif::DictionaryVolume> volume)
{
  this->Volume = std::move(volume);
  this->Modified();
}

int vtkChunkedMarchingCubes::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkSparseDictionaryVolume");
  // optional: a dictionary volume (SetVolume) replaces the input
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkChunkedMarchingCubes::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkDataObject");
  return 1;
}

int vtkChunkedMarchingCubes::RequestDataObject(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkDataObject* current = outInfo->Get(vtkDataObject::DATA_OBJECT());
  const bool merged = this->OutputMode == MERGED;
  if (merged && vtkPolyData::SafeDownCast(current)) return 1;
  if (!merged && vtkPartitionedDataSet::SafeDownCast(current)) return 1;
  vtkSmartPointer<vtkDataObject> out;
  if (merged)
    out = vtkSmartPointer<vtkPolyData>::New();
  else
    out = vtkSmartPointer<vtkPartitionedDataSet>::New();
  outInfo->Set(vtkDataObject::DATA_OBJECT(), out);
  return 1;
}

int vtkChunkedMarchingCubes::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  LVDIFVolumeBridge::BeginInformation(outInfo);
  // the enumerations first, by the one rule (refused by name, never clamped)
  if (!LVDIFVolumeBridge::CallCore(this, [&] {
        LVDIFVolumeBridge::EnumOption(this->OutputMode, "OutputMode", { "partitioned", "merged" });
        LVDIFVolumeBridge::DeviceOption(this->Device);
      }))
    return LVDIFVolumeBridge::FailInformation(outInfo);
  // the output is split by pieces (not extents): every piece request is served
  outInfo->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkChunkedMarchingCubes::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (!inInfo || LVDIFVolumeBridge::InformationFailed(outInfo))
    return 1; // no input: a dictionary volume (SetVolume) is meshed; or RequestInformation failed
  int piece, pieces;
  pieceRequest(outInfo, piece, pieces);
  int whole[6];
  inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
  int ext[6];
  pieceExtent(piece, pieces, whole, ext);
  // one ghost layer: central-difference gradients at the piece's border
  for (int a = 0; a < 3; ++a)
  {
    if (ext[2 * a + 1] < ext[2 * a]) continue;
    ext[2 * a] = std::max(ext[2 * a] - 1, whole[2 * a]);
    ext[2 * a + 1] = std::min(ext[2 * a + 1] + 1, whole[2 * a + 1]);
  }
  // The request is the extent alone: with the piece keys left in place the
  // executive would split the input again with its own piece layout and
  // intersect that with this extent.
  inInfo->Set(SDDP::UPDATE_EXTENT(), ext, 6);
  inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), 1);
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  // (no EXACT_EXTENT: a trivial producer would crop the caller's image in
  // place; a larger input extent is fine, only the owned cells are meshed)
  return 1;
}

lvdif::MarchingCubesOptions vtkChunkedMarchingCubes::CoreOptions() const
{
  lvdif::MarchingCubesOptions o;
  o.isoValue = static_cast<float>(this->IsoValue);
  o.chunkEdge = this->ChunkEdge;
  o.computeNormals = this->ComputeNormals != 0;
  o.computeColors = this->ComputeColors != 0;
  o.cornerColors = this->ComputeCornerColors != 0;
  o.device = this->Device == DEVICE_CPU ? lvdif::Device::Cpu
                                        : (this->Device == DEVICE_CUDA ? lvdif::Device::Cuda : lvdif::Device::Auto);
  if (this->UseVTKCaseTable) o.triangleTable = LVDIFChunkedMarchingCubesVtkTable::Get();
  return o;
}

int vtkChunkedMarchingCubes::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // every failure below reported its error (a cancel returns 1): no executive
  // "returned failure for request" dump after it
  return this->Extract(inputVector, outputVector) ? 1
                                                  : LVDIFVolumeBridge::FailReported(outputVector->GetInformationObject(0));
}

int vtkChunkedMarchingCubes::Extract(vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (LVDIFVolumeBridge::InformationFailed(outInfo))
    return 0; // RequestInformation reported why (ParaView runs RequestData anyway)
  vtkDataObject* output = outInfo->Get(vtkDataObject::DATA_OBJECT());
  if (!vtkPolyData::SafeDownCast(output) && !vtkPartitionedDataSet::SafeDownCast(output))
  {
    vtkErrorMacro("no output of the expected type");
    return 0;
  }
  int piece, pieces;
  pieceRequest(outInfo, piece, pieces);
  if (this->Volume)
  {
    if (inInfo)
    {
      vtkErrorMacro("both an input image and a dictionary volume (SetVolume): disconnect the input or SetVolume(nullptr)");
      return 0;
    }
    if (!flatVolumeCheck(this, this->Volume->dims().data(), output)) return 0;
    return this->MeshVolume(*this->Volume, piece, pieces, output);
  }
  if (auto* sparse = vtkSparseDictionaryVolume::GetData(inInfo))
  {
    if (!sparse->HasVolume()) return 1; // an empty or failed upstream: empty output
    if (!flatVolumeCheck(this, sparse->GetVolume()->dims().data(), output)) return 0;
    auto* partitioned = vtkPartitionedDataSet::SafeDownCast(output);
    if (partitioned && pieces == 1)
    {
      return this->MeshVolumeIncrementally(sparse->GetVolume(), partitioned);
    }
    this->Cache = nullptr;
    return this->MeshVolume(*sparse->GetVolume(), piece, pieces, output);
  }
  this->Cache = nullptr;
  vtkImageData* input = inInfo ? vtkImageData::GetData(inInfo) : nullptr;
  if (!input)
  {
    vtkErrorMacro("no input: connect a sparse dictionary volume or an image with an SDF point array, or call SetVolume()");
    return 0;
  }
  try
  {
    // the surface of a rotated image came out unrotated, without a word
    LVDIFVolumeBridge::RequireAxisAligned(input);
  }
  catch (const lvdif::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  int inExt[6];
  input->GetExtent(inExt);
  int whole[6];
  if (inInfo->Has(SDDP::WHOLE_EXTENT()))
    inInfo->Get(SDDP::WHOLE_EXTENT(), whole);
  else
    std::copy(inExt, inExt + 6, whole);
  if (input->GetNumberOfPoints() > 0)
  {
    const std::int64_t wholeDims[3] = { whole[1] - whole[0] + 1, whole[3] - whole[2] + 1, whole[5] - whole[4] + 1 };
    if (!flatVolumeCheck(this, wholeDims, output)) return 0;
  }
  int own[6];
  pieceExtent(piece, pieces, whole, own);

  // the cells this piece owns, in the input grid's local indices (see the class comment)
  lvdif::VoxelBox region;
  for (int a = 0; a < 3; ++a)
  {
    region.lo[a] = std::max(own[2 * a], inExt[2 * a]) - inExt[2 * a];
    region.hi[a] = std::min(own[2 * a + 1], inExt[2 * a + 1]) - 1 - inExt[2 * a];
  }
  if (region.empty() || input->GetNumberOfPoints() == 0) return 1; // nothing owned: empty output

  vtkDataArray* sdf = LVDIFVolumeBridge::SdfArray(
    this->GetInputArrayInformation(0), input, this->GetInputArrayToProcess(0, inputVector));
  if (!sdf)
  {
    vtkErrorMacro("no SDF point array (default name 'sdf'; see SetInputArrayToProcess)");
    return 0;
  }
  if (sdf->GetNumberOfComponents() != 1 || sdf->GetNumberOfTuples() != input->GetNumberOfPoints())
  {
    vtkErrorMacro("SDF array '" << (sdf->GetName() ? sdf->GetName() : "") << "' must have one component per point");
    return 0;
  }
  lvdif::FloatGridView grid = LVDIFVolumeBridge::FloatView(input, sdf);
  std::vector<float> converted;
  if (!grid.data)
  {
    converted.resize(static_cast<std::size_t>(sdf->GetNumberOfTuples()));
    for (vtkIdType i = 0; i < sdf->GetNumberOfTuples(); ++i) converted[i] = static_cast<float>(sdf->GetComponent(i, 0));
    grid.data = converted.data();
  }
  // positions from global indices: origin of the whole extent's point 0 + spacing * global index
  double origin[3], spacing[3];
  input->GetOrigin(origin);
  input->GetSpacing(spacing);
  lvdif::MarchingCubesOptions o = this->CoreOptions();
  for (int a = 0; a < 3; ++a)
  {
    grid.geometry.origin[a] = origin[a] + spacing[a] * whole[2 * a];
    o.gridOffset[a] = inExt[2 * a] - whole[2 * a];
  }

  // colours: the array as it is when it is 4-component unsigned char, else converted
  vtkDataArray* colorArray =
    this->ColorArrayName ? input->GetPointData()->GetArray(this->ColorArrayName) : nullptr;
  const lvdif::Rgba* colors = nullptr;
  std::vector<lvdif::Rgba> colorCopy;
  if (colorArray && colorArray->GetNumberOfTuples() == input->GetNumberOfPoints() &&
    (this->ComputeColors || this->ComputeCornerColors))
  {
    auto* uc = vtkUnsignedCharArray::SafeDownCast(colorArray);
    if (uc && uc->GetNumberOfComponents() == 4)
    {
      colors = reinterpret_cast<const lvdif::Rgba*>(uc->GetPointer(0));
    }
    else
    {
      const int nc = colorArray->GetNumberOfComponents();
      colorCopy.resize(static_cast<std::size_t>(colorArray->GetNumberOfTuples()));
      for (vtkIdType i = 0; i < colorArray->GetNumberOfTuples(); ++i)
      {
        unsigned char c[4] = { 0, 0, 0, 255 };
        for (int k = 0; k < std::min(nc, 4); ++k)
          c[k] = static_cast<unsigned char>(std::min(255.0, std::max(0.0, colorArray->GetComponent(i, k))));
        if (nc == 1) c[1] = c[2] = c[0];
        colorCopy[i] = lvdif::Rgba{ c[0], c[1], c[2], c[3] };
      }
      colors = colorCopy.data();
    }
  }
  o.computeColors = o.computeColors && colors != nullptr;
  o.cellRegion = region;
  std::vector<lvdif::ChunkMesh> meshes;
  try
  {
    lvdif::ChunkedMarchingCubes mc(grid, o.computeColors ? colors : nullptr, o);
    LVDIFInterrupter interrupter(this, 0.0, 0.8);
    meshes = mc.extractAll(interrupter);
  }
  catch (const lvdif::Error& e)
  {
    if (e.code() == lvdif::ErrorCode::Cancelled) return 1; // aborted: empty output
    vtkErrorMacro(<< e.what());
    return 0;
  }

  LVDIFChunkedMarchingCubesOutput::Context ctx;
  ctx.gridDims = grid.geometry.dims;
  for (int a = 0; a < 3; ++a) ctx.extentLo[a] = inExt[2 * a];
  ctx.colors = colors;
  ctx.normals = o.computeNormals;
  ctx.pointColors = o.computeColors;
  ctx.cellData = o.cornerColors;
  return this->Emit(meshes, ctx, whole, output);
}

int vtkChunkedMarchingCubes::MeshVolume(
  const lvdif::DictionaryVolume& volume, int piece, int pieces, vtkDataObject* output)
{
  const lvdif::Index3& dims = volume.dims();
  int whole[6];
  for (int a = 0; a < 3; ++a)
  {
    whole[2 * a] = 0;
    whole[2 * a + 1] = static_cast<int>(dims[a] - 1);
  }
  int own[6];
  pieceExtent(piece, pieces, whole, own);
  // the cells this piece owns (same rule as for images; grid indices are global here)
  lvdif::MarchingCubesOptions o = this->CoreOptions();
  for (int a = 0; a < 3; ++a)
  {
    o.cellRegion.lo[a] = own[2 * a];
    o.cellRegion.hi[a] = own[2 * a + 1] - 1;
  }
  if (o.cellRegion.empty()) return 1; // nothing owned: empty output
  LVDIFChunkedMarchingCubesOutput::Context ctx;
  ctx.gridDims = dims;
  ctx.palette = volume.colors().colors().data(); // corner colours come as keys
  ctx.normals = o.computeNormals;
  ctx.pointColors = o.computeColors;
  ctx.cellData = o.cornerColors;
  // A volume can be far larger than its surface: chunks are meshed in batches
  // and only one batch of chunk meshes is held at a time.
  constexpr std::size_t Batch = 64;
  try
  {
    lvdif::ChunkedMarchingCubes mc(volume, o);
    std::vector<std::int64_t> ids;
    for (std::int64_t id = 0; id < mc.chunkCount(); ++id)
      if (!mc.chunkIsEmpty(id)) ids.push_back(id);
    const std::size_t batches = (ids.size() + Batch - 1) / Batch;
    const bool merged = vtkPolyData::SafeDownCast(output) != nullptr;
    LVDIFInterrupter interrupter(this);
    auto batch = [&](std::size_t b, int pass) {
      // progress: merged runs two passes (count, fill), partitioned one
      const double share = merged ? 0.5 : 1.0;
      interrupter.setStage(share * (pass + static_cast<double>(b) / batches), share / batches);
      const std::size_t lo = b * Batch, hi = std::min(ids.size(), lo + Batch);
      std::vector<lvdif::ChunkMesh> meshes =
        mc.extractChunks(std::vector<std::int64_t>(ids.begin() + lo, ids.begin() + hi), interrupter);
      meshes.erase(std::remove_if(meshes.begin(), meshes.end(), [](const lvdif::ChunkMesh& m) { return m.empty(); }),
        meshes.end());
      return meshes;
    };
    if (auto* pd = vtkPolyData::SafeDownCast(output))
    {
      pd->ShallowCopy(LVDIFChunkedMarchingCubesOutput::MergeBatches(batch, batches, ctx));
    }
    else
    {
      auto* partitioned = vtkPartitionedDataSet::SafeDownCast(output);
      partitioned->SetNumberOfPartitions(0);
      for (std::size_t b = 0; b < batches; ++b)
        this->AddPartitions(batch(b, 0), ctx, whole, partitioned);
    }
  }
  catch (const lvdif::Error& e)
  {
    output->Initialize();
    if (e.code() == lvdif::ErrorCode::Cancelled) return 1; // aborted: empty output
    vtkErrorMacro(<< e.what());
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

int vtkChunkedMarchingCubes::MeshVolumeIncrementally(
  const std::shared_ptr<lvdif::DictionaryVolume>& volume, vtkPartitionedDataSet* output)
{
  // The cache holds the last run's chunk meshes (the same vtkPolyData objects
  // the output shares, so no extra memory). It is valid for the same Core
  // volume and unchanged settings; then only the chunks that the volume's
  // dirty storage chunks reach are meshed again.
  const bool reuse = this->Cache && this->CachedVolume.lock() == volume && this->CacheTime > this->GetMTime();
  lvdif::MarchingCubesOptions o = this->CoreOptions();
  const lvdif::Index3& dims = volume->dims();
  int whole[6];
  for (int a = 0; a < 3; ++a)
  {
    whole[2 * a] = 0;
    whole[2 * a + 1] = static_cast<int>(dims[a] - 1);
    o.cellRegion.lo[a] = 0;
    o.cellRegion.hi[a] = dims[a] - 2;
  }
  if (!reuse)
  {
    this->Cache = nullptr;
    volume->takeDirtyChunks(); // everything is meshed now
    const int ok = o.cellRegion.empty() ? 1 : this->MeshVolume(*volume, 0, 1, output);
    this->LastChunksMeshed = -1;
    if (ok && !this->GetAbortExecute())
    {
      this->Cache = vtkSmartPointer<vtkPartitionedDataSet>::New();
      this->Cache->ShallowCopy(output);
      this->CachedVolume = volume;
      this->CacheTime.Modified();
    }
    return ok;
  }
  LVDIFChunkedMarchingCubesOutput::Context ctx;
  ctx.gridDims = dims;
  ctx.palette = volume->colors().colors().data();
  ctx.normals = o.computeNormals;
  ctx.pointColors = o.computeColors;
  ctx.cellData = o.cornerColors;
  std::map<vtkIdType, vtkSmartPointer<vtkDataObject>> byChunk;
  for (unsigned int i = 0; i < this->Cache->GetNumberOfPartitions(); ++i)
  {
    vtkDataObject* pd = this->Cache->GetPartitionAsDataObject(i);
    auto* id = pd ? vtkIdTypeArray::SafeDownCast(pd->GetFieldData()->GetArray("chunk_id")) : nullptr;
    if (id) byChunk[id->GetValue(0)] = pd;
  }
  try
  {
    lvdif::ChunkedMarchingCubes mc(*volume, o);
    const std::vector<std::int64_t> redo = mc.chunksAffectedByStorageChunks(volume->takeDirtyChunks());
    std::vector<std::int64_t> ids;
    for (std::int64_t id : redo)
    {
      byChunk.erase(static_cast<vtkIdType>(id));
      if (!mc.chunkIsEmpty(id)) ids.push_back(id);
    }
    LVDIFInterrupter interrupter(this, 0.0, 0.9);
    std::vector<lvdif::ChunkMesh> meshes = mc.extractChunks(ids, interrupter);
    meshes.erase(std::remove_if(meshes.begin(), meshes.end(), [](const lvdif::ChunkMesh& m) { return m.empty(); }),
      meshes.end());
    vtkNew<vtkPartitionedDataSet> fresh;
    this->AddPartitions(meshes, ctx, whole, fresh);
    for (unsigned int i = 0; i < fresh->GetNumberOfPartitions(); ++i)
    {
      vtkDataObject* pd = fresh->GetPartitionAsDataObject(i);
      byChunk[vtkIdTypeArray::SafeDownCast(pd->GetFieldData()->GetArray("chunk_id"))->GetValue(0)] = pd;
    }
    this->LastChunksMeshed = static_cast<vtkIdType>(ids.size());
  }
  catch (const lvdif::Error& e)
  {
    this->Cache = nullptr;
    output->Initialize();
    if (e.code() == lvdif::ErrorCode::Cancelled) return 1; // aborted: empty output
    vtkErrorMacro(<< e.what());
    return 0;
  }
  // partitions in chunk id order, as a full run gives them
  this->Cache = vtkSmartPointer<vtkPartitionedDataSet>::New();
  this->Cache->SetNumberOfPartitions(static_cast<unsigned int>(byChunk.size()));
  unsigned int i = 0;
  for (auto& kv : byChunk) this->Cache->SetPartition(i++, kv.second);
  this->CacheTime.Modified();
  output->ShallowCopy(this->Cache);
  this->UpdateProgress(1.0);
  return 1;
}

int vtkChunkedMarchingCubes::Emit(const std::vector<lvdif::ChunkMesh>& meshes,
  const LVDIFChunkedMarchingCubesOutput::Context& ctx, const int whole[6], vtkDataObject* output)
{
  if (auto* merged = vtkPolyData::SafeDownCast(output))
  {
    merged->ShallowCopy(LVDIFChunkedMarchingCubesOutput::MergeChunks(meshes, ctx));
    this->UpdateProgress(1.0);
    return 1;
  }
  auto* partitioned = vtkPartitionedDataSet::SafeDownCast(output);
  partitioned->SetNumberOfPartitions(0);
  this->AddPartitions(meshes, ctx, whole, partitioned);
  this->UpdateProgress(1.0);
  return 1;
}

void vtkChunkedMarchingCubes::AddPartitions(const std::vector<lvdif::ChunkMesh>& meshes,
  const LVDIFChunkedMarchingCubesOutput::Context& ctx, const int whole[6], vtkPartitionedDataSet* partitioned)
{
  // chunk counts of the whole extent, for a chunk id every piece agrees on
  vtkIdType counts[3];
  for (int a = 0; a < 3; ++a)
    counts[a] = std::max<vtkIdType>(1, (whole[2 * a + 1] - whole[2 * a] + this->ChunkEdge - 1) / this->ChunkEdge);
  const unsigned int first = partitioned->GetNumberOfPartitions();
  partitioned->SetNumberOfPartitions(first + static_cast<unsigned int>(meshes.size()));
  for (std::size_t i = 0; i < meshes.size(); ++i)
  {
    if (i % 64 == 0 && this->GetAbortExecute()) break;
    vtkSmartPointer<vtkPolyData> pd = LVDIFChunkedMarchingCubesOutput::ChunkToPolyData(meshes[i], ctx);
    const lvdif::Index3& c = meshes[i].chunkCoord;
    vtkNew<vtkIdTypeArray> id;
    id->SetName("chunk_id");
    id->InsertNextValue(c[0] + counts[0] * (c[1] + counts[1] * c[2]));
    vtkNew<vtkIntArray> ijk;
    ijk->SetName("chunk_ijk");
    ijk->SetNumberOfComponents(3);
    ijk->InsertNextTuple3(c[0], c[1], c[2]);
    pd->GetFieldData()->AddArray(id);
    pd->GetFieldData()->AddArray(ijk);
    partitioned->SetPartition(first + static_cast<unsigned int>(i), pd);
  }
}

void vtkChunkedMarchingCubes::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OutputMode: " << (this->OutputMode == MERGED ? "Merged" : "Partitioned") << "\n";
  os << indent << "IsoValue: " << this->IsoValue << "\n";
  os << indent << "ChunkEdge: " << this->ChunkEdge << "\n";
  os << indent << "ComputeNormals: " << this->ComputeNormals << "\n";
  os << indent << "ComputeColors: " << this->ComputeColors << "\n";
  os << indent << "ComputeCornerColors: " << this->ComputeCornerColors << "\n";
  os << indent << "ColorArrayName: " << (this->ColorArrayName ? this->ColorArrayName : "(none)") << "\n";
  os << indent << "Device: "
     << (this->Device == DEVICE_CPU ? "Cpu" : (this->Device == DEVICE_CUDA ? "Cuda" : "Auto")) << "\n";
  os << indent << "UseVTKCaseTable: " << this->UseVTKCaseTable << "\n";
  os << indent << "Volume: ";
  if (this->Volume)
  {
    const auto& d = this->Volume->dims();
    os << d[0] << " x " << d[1] << " x " << d[2] << "\n";
  }
  else
  {
    os << "(none)\n";
  }
}
