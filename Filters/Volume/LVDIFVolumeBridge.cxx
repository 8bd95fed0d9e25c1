// LVDIFVolumeBridge: the bridge between Core and VTK: the filters' option
// checks and error reporting (CallCore, the quiet executive), the mesh and
// image <-> volume conversions, and the pipeline information the filters
// share. The arrays' cached ranges (StoreRange) are in LVDIFVolumeBridgeRanges.cxx.
#include "LVDIFVolumeBridge.h"

#include "lvdif/Error.h"
#include "lvdif/Memory.h"

#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkInformationExecutivePortKey.h"
#include "vtkOutputWindow.h"
#include "vtkCellArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"
#include "vtkExtentTranslator.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkMatrix3x3.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleVectorKey.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkInformationIntegerKey.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkSparseDictionaryVolume.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <new>
#include <cstring>
#include <numeric>
#include <sstream>
#include <vector>

namespace LVDIFVolumeBridge
{
std::string MessageText(const char* vtkMessage)
{
  std::string text = vtkMessage ? vtkMessage : "";
  const auto colon = text.find("): ");
  if (colon != std::string::npos) text = text.substr(colon + 3);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}


lvdif::Device ToDevice(int device)
{
  return device == 1 ? lvdif::Device::Cpu : (device == 2 ? lvdif::Device::Cuda : lvdif::Device::Auto);
}

int EnumOption(int value, const std::string& name, std::initializer_list<const char*> names)
{
  const int n = static_cast<int>(names.size());
  if (value < 0 || value >= n)
  {
    std::ostringstream msg;
    msg << name << " must be ";
    int i = 0;
    for (const char* what : names)
    {
      msg << (i == 0 ? "" : i == n - 1 ? " or " : ", ") << i << " (" << what << ")";
      ++i;
    }
    msg << ", not " << value;
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, msg.str());
  }
  return value;
}

int DeviceOption(int device)
{
  return EnumOption(device, "Device", { "auto", "CPU", "CUDA" });
}

std::string WithContext(const std::string& context, const std::string& what)
{
  const auto open = context.find('\'');
  const auto close = open == std::string::npos ? std::string::npos : context.find('\'', open + 1);
  if (close != std::string::npos && what.find(context.substr(open, close - open + 1)) != std::string::npos) return what;
  return context + what;
}

float BandOption(double bandWidth, const std::string& name)
{
  // one rule for every band setting (docs/USER_GUIDE.md, "Band width, chunk edge, padding, compression level")
  if (std::isnan(bandWidth) || bandWidth < 0)
  {
    std::ostringstream msg;
    msg << name << " must be a number of voxels >= 0 (0: no band), not " << bandWidth;
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, msg.str());
  }
  // 0 and every value beyond float's range (the writers' VTK_FLOAT_MAX) mean no band
  return bandWidth == 0 || bandWidth >= std::numeric_limits<float>::max() ? std::numeric_limits<float>::infinity()
                                                                          : static_cast<float>(bandWidth);
}

double PaddingOption(double padding, const std::string& name)
{
  if (!std::isfinite(padding) || padding < 0)
  {
    std::ostringstream msg;
    msg << name << " must be a finite number of voxels >= 0, not " << padding;
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, msg.str());
  }
  return padding;
}

float CheckVolumeSettings(int chunkEdge, double bandWidth, const std::string& bandName)
{
  lvdif::VolumeOptions o;
  o.chunkEdge = chunkEdge;
  o.bandWidth = BandOption(bandWidth, bandName);
  lvdif::DictionaryVolume::tableBytes(o); // Core's own check of the options; allocates nothing
  return o.bandWidth;
}

std::string FileError(const std::string& verb, const std::string& path, const std::string& what)
{
  return WithContext("cannot " + verb + " '" + path + "': ", what);
}

bool CallCore(vtkAlgorithm* algorithm, const std::function<void()>& work, const std::string& context, bool* cancelled)
{
  if (cancelled) *cancelled = false;
  try
  {
    work();
    return true;
  }
  catch (const lvdif::Error& e)
  {
    if (e.code() == lvdif::ErrorCode::Cancelled)
    {
      if (cancelled) *cancelled = true;
      return false;
    }
    vtkErrorWithObjectMacro(algorithm, << WithContext(context, e.what()));
    return false;
  }
  catch (const std::bad_alloc&)
  {
    // an allocation no estimate refused first: still one error, not an
    // exception through the pipeline (which would leave MPI peers waiting)
    vtkErrorWithObjectMacro(algorithm, << WithContext(context, "out of memory"));
    return false;
  }
}

lvdif::TriangleMesh ToTriangleMesh(vtkPolyData* pd, bool withNormals)
{
  lvdif::TriangleMesh m;
  const vtkIdType np = pd->GetNumberOfPoints();
  if (np > static_cast<vtkIdType>(std::numeric_limits<std::uint32_t>::max()))
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument,
      "the mesh has " + std::to_string(np) + " points, more than 32-bit indices reach (4294967295)");
  m.points.resize(static_cast<std::size_t>(np));
  for (vtkIdType i = 0; i < np; ++i)
  {
    double p[3];
    pd->GetPoint(i, p);
    m.points[i] = { static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]) };
  }
  vtkDataArray* normals = pd->GetPointData()->GetNormals();
  if (withNormals && normals && normals->GetNumberOfComponents() == 3 && normals->GetNumberOfTuples() == np)
  {
    m.normals.resize(static_cast<std::size_t>(np));
    for (vtkIdType i = 0; i < np; ++i)
    {
      double n[3];
      normals->GetTuple(i, n);
      m.normals[i] = { static_cast<float>(n[0]), static_cast<float>(n[1]), static_cast<float>(n[2]) };
    }
  }
  // VTK's ids are 64-bit and no reader checks a cell's against the points: an id of 2^32 + 2 was cast
  // to point 2 (a wrong triangle, without a word), and a negative one said "refers to point 4294967295"
  vtkIdType cell = 0;
  const char* kind = "polygon";
  auto id = [&](vtkIdType v) {
    if (v < 0 || v >= np)
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, std::string(kind) + " " + std::to_string(cell) +
          " of the mesh refers to point " + std::to_string(v) + ", but the mesh has " + std::to_string(np) + " points");
    return static_cast<std::uint32_t>(v);
  };
  vtkIdType n;
  const vtkIdType* ids;
  vtkCellArray* polys = pd->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(n, ids); ++cell)
  {
    for (vtkIdType k = 1; k + 1 < n; ++k)
    {
      m.triangles.push_back({ id(ids[0]), id(ids[k]), id(ids[k + 1]) });
    }
  }
  vtkCellArray* strips = pd->GetStrips();
  kind = "triangle strip";
  cell = 0;
  for (strips->InitTraversal(); strips->GetNextCell(n, ids); ++cell)
  {
    for (vtkIdType k = 0; k + 2 < n; ++k)
    {
      if (k % 2 == 0)
        m.triangles.push_back({ id(ids[k]), id(ids[k + 1]), id(ids[k + 2]) });
      else
        m.triangles.push_back({ id(ids[k + 1]), id(ids[k]), id(ids[k + 2]) });
    }
  }
  return m;
}

vtkSmartPointer<vtkPolyData> ToPolyData(const lvdif::TriangleMesh& mesh)
{
  auto output = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(static_cast<vtkIdType>(mesh.points.size()));
  std::memcpy(vtkFloatArray::SafeDownCast(points->GetData())->GetPointer(0), mesh.points.data(),
    mesh.points.size() * sizeof(lvdif::Vec3f));
  const vtkIdType n = static_cast<vtkIdType>(mesh.triangles.size());
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(3 * n);
  for (vtkIdType t = 0; t < n; ++t)
  {
    offsets->SetValue(t, 3 * t);
    for (int c = 0; c < 3; ++c)
    {
      connectivity->SetValue(3 * t + c, mesh.triangles[t][c]);
    }
  }
  offsets->SetValue(n, 3 * n);
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, connectivity);
  output->SetPoints(points);
  output->SetPolys(polys);
  if (!mesh.normals.empty())
  {
    vtkNew<vtkFloatArray> normals;
    normals->SetName("Normals");
    normals->SetNumberOfComponents(3);
    normals->SetNumberOfTuples(static_cast<vtkIdType>(mesh.normals.size()));
    std::memcpy(normals->GetPointer(0), mesh.normals.data(), mesh.normals.size() * sizeof(lvdif::Vec3f));
    output->GetPointData()->SetNormals(normals);
  }
  return output;
}

void EnsureSparseOutput(vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (!vtkSparseDictionaryVolume::GetData(outInfo))
  {
    vtkNew<vtkSparseDictionaryVolume> out;
    outInfo->Set(vtkDataObject::DATA_OBJECT(), out);
  }
}

void SetSparseInformation(vtkInformation* outInfo, const lvdif::VolumeOptions& o)
{
  int whole[6] = { 0, static_cast<int>(o.dims[0] - 1), 0, static_cast<int>(o.dims[1] - 1), 0,
    static_cast<int>(o.dims[2] - 1) };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), o.origin.data(), 3);
  outInfo->Set(vtkDataObject::SPACING(), o.spacing.data(), 3);
  outInfo->Set(CHUNK_EDGE(), o.chunkEdge);
}

bool PieceChunks(int piece, int pieces, const lvdif::VolumeOptions& o, int owned[6], lvdif::VoxelBox& region)
{
  int bounds[6], block[6];
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = 0; // chunk boundaries 0..count: a split by cells gives disjoint chunk ranges
    bounds[2 * a + 1] = static_cast<int>((o.dims[a] + o.chunkEdge - 1) / o.chunkEdge);
  }
  vtkNew<vtkExtentTranslator> t;
  if (!t->PieceToExtentThreadSafe(piece, pieces, 0, bounds, block, vtkExtentTranslator::BLOCK_MODE, 0) ||
    block[0] >= block[1] || block[2] >= block[3] || block[4] >= block[5])
  {
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    owned[2 * a] = block[2 * a];
    owned[2 * a + 1] = block[2 * a + 1] - 1;
    region.lo[a] = static_cast<std::int64_t>(block[2 * a]) * o.chunkEdge;
    region.hi[a] = std::min<std::int64_t>(static_cast<std::int64_t>(block[2 * a + 1]) * o.chunkEdge, o.dims[a] - 1);
  }
  return true;
}

void GrowToWholeChunks(lvdif::VoxelBox& region, const lvdif::VolumeOptions& o)
{
  for (int a = 0; a < 3; ++a)
  {
    region.hi[a] = std::min<std::int64_t>((region.hi[a] / o.chunkEdge + 1) * o.chunkEdge - 1, o.dims[a] - 1);
  }
}

int RequestedVoxels(vtkInformation* outInfo, const lvdif::VolumeOptions& o, int owned[6], lvdif::VoxelBox& region)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  const int pieces = outInfo->Has(SDDP::UPDATE_NUMBER_OF_PIECES()) ? outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES()) : 1;
  const int piece = outInfo->Has(SDDP::UPDATE_PIECE_NUMBER()) ? outInfo->Get(SDDP::UPDATE_PIECE_NUMBER()) : 0;
  region.lo = { 0, 0, 0 };
  region.hi = { o.dims[0] - 1, o.dims[1] - 1, o.dims[2] - 1 };
  if (pieces > 1)
  {
    return PieceChunks(piece, pieces, o, owned, region) ? 1 : -1;
  }
  if (outInfo->Has(SDDP::UPDATE_EXTENT()))
  {
    int ext[6];
    outInfo->Get(SDDP::UPDATE_EXTENT(), ext);
    const lvdif::VoxelBox all = region;
    for (int a = 0; a < 3; ++a)
    {
      region.lo[a] = std::max<std::int64_t>(ext[2 * a], 0);
      region.hi[a] = std::min<std::int64_t>(ext[2 * a + 1], o.dims[a] - 1);
    }
    return region.lo == all.lo && region.hi == all.hi ? 0 : 2;
  }
  return 0;
}

namespace
{
/// Meta data that flows downstream with the information pass through any
/// filter (ParaView puts a post filter after every source), as
/// vtkInformationDataObjectMetaDataKey does for data objects.
class ChunkEdgeKey : public vtkInformationIntegerKey
{
public:
  ChunkEdgeKey() : vtkInformationIntegerKey("LVDIF_CHUNK_EDGE", "LVDIFVolumeBridge") {}
  void CopyDefaultInformation(vtkInformation* request, vtkInformation* fromInfo, vtkInformation* toInfo) override
  {
    if (request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()))
    {
      this->ShallowCopy(fromInfo, toInfo);
    }
  }
};
} // namespace

vtkInformationIntegerKey* CHUNK_EDGE()
{
  // never deleted: VTK's key managers delete their keys at exit, after a
  // plugin's library (and so this class's code) may have been unloaded
  static vtkInformationIntegerKey* key = new ChunkEdgeKey;
  return key;
}

namespace
{
vtkInformationIntegerKey* INFORMATION_FAILED()
{
  // never deleted, as CHUNK_EDGE; a plain key: it stays on the algorithm's own output information
  static vtkInformationIntegerKey* key = new vtkInformationIntegerKey("LVDIF_INFORMATION_FAILED", "LVDIFVolumeBridge");
  return key;
}

vtkInformationIntegerKey* QUIET_EXECUTIVE()
{
  static vtkInformationIntegerKey* key = new vtkInformationIntegerKey("LVDIF_QUIET_EXECUTIVE", "LVDIFVolumeBridge");
  return key;
}

vtkInformationIntegerKey* FAILURE_REPORTED()
{
  static vtkInformationIntegerKey* key = new vtkInformationIntegerKey("LVDIF_FAILURE_REPORTED", "LVDIFVolumeBridge");
  return key;
}

/// On the executive of an algorithm whose request failed with its own error
/// (FAILURE_REPORTED): drops the executive's errors that only repeat it while the
/// failure stands: "Algorithm X returned failure for request: <the request
/// dumped>" (the information pass and each later update added one) and "No ...
/// has been set in the information for output port 0" (a later update of the
/// failed pass); every other error of the executive goes where it went without
/// this filter: to the caller's own ErrorEvent observers of the executive when
/// there are any (VTK's rule: an observed object's errors go to its observers
/// only), else to the output window. (It went to the output window always, so
/// a caller whose observer handled or silenced the executive's errors saw them
/// printed too, once a failure had installed this filter.)
class ReportedFailureFilter : public vtkCommand
{
public:
  static ReportedFailureFilter* New() { return new ReportedFailureFilter; }
  vtkExecutive* Executive = nullptr; // owns this command: no reference
  void Execute(vtkObject*, unsigned long, void* callData) override
  {
    const char* text = static_cast<const char*>(callData);
    // the dump of the failed request, and what a later update asks of the
    // information the failed pass never set ("No update piece number has been
    // set in the information for output port 0 on algorithm X")
    if (text && (std::strstr(text, "returned failure for request") || std::strstr(text, "has been set in the information")) &&
      this->Failed())
    {
      this->AbortFlagOn(); // nor to other observers: the algorithm's error said it
      return;
    }
    if (text && !this->OthersObserve()) vtkOutputWindow::GetInstance()->DisplayErrorText(text);
  }

private:
  /// Whether an ErrorEvent observer of the executive other than this one exists.
  /// vtkObject cannot list its observers: this one is taken off, the question
  /// asked, and it is put back. Safe inside the executive's InvokeEvent: the
  /// changed list restarts its walk, this command's old tag counts as visited
  /// and its new tag is newer than the event (so it is not called again); the
  /// observers not yet called are then called.
  bool OthersObserve()
  {
    this->Register(this); // alive while off the list
    this->Executive->RemoveObservers(vtkCommand::ErrorEvent, this);
    const bool others = this->Executive->HasObserver(vtkCommand::ErrorEvent) != 0;
    this->Executive->AddObserver(vtkCommand::ErrorEvent, this, 1.0f);
    this->UnRegister(this);
    return others;
  }

  bool Failed() const
  {
    for (int port = 0; port < this->Executive->GetNumberOfOutputPorts(); ++port)
    {
      vtkInformation* info = this->Executive->GetOutputInformation(port);
      if (info && info->Has(FAILURE_REPORTED())) return true;
    }
    return false;
  }
};
} // namespace

bool IsEmptyInput(vtkDataObject* input)
{
  if (auto* sparse = vtkSparseDictionaryVolume::SafeDownCast(input)) return !sparse->HasVolume();
  if (auto* dataSet = vtkDataSet::SafeDownCast(input)) return dataSet->GetNumberOfPoints() == 0;
  return false;
}

void BeginInformation(vtkInformation* outInfo)
{
  if (!outInfo) return;
  outInfo->Remove(INFORMATION_FAILED());
  outInfo->Remove(FAILURE_REPORTED());
}

int FailInformation(vtkInformation* outInfo)
{
  if (outInfo) outInfo->Set(INFORMATION_FAILED(), 1);
  return FailReported(outInfo);
}

int FailReported(vtkInformation* outInfo)
{
  if (!outInfo) return 0;
  outInfo->Set(FAILURE_REPORTED(), 1);
  vtkExecutive* executive = vtkExecutive::PRODUCER()->GetExecutive(outInfo);
  if (executive && !outInfo->Has(QUIET_EXECUTIVE()))
  {
    vtkNew<ReportedFailureFilter> filter;
    filter->Executive = executive;
    executive->AddObserver(vtkCommand::ErrorEvent, filter, 1.0f); // before a caller's own observers
    outInfo->Set(QUIET_EXECUTIVE(), 1);
  }
  return 0;
}

bool InformationFailed(vtkInformation* outInfo)
{
  if (!outInfo || !outInfo->Has(INFORMATION_FAILED())) return false;
  // no stale data from an earlier run (a reader pointed at a missing file)
  if (vtkDataObject* output = outInfo->Get(vtkDataObject::DATA_OBJECT())) output->Initialize();
  return true;
}

void FillImage(const lvdif::DictionaryVolume& volume, const int extentIn[6], vtkImageData* image, bool withColor,
  lvdif::Interrupter* interrupter)
{
  const auto& dims = volume.dims();
  int ext[6];
  for (int a = 0; a < 3; ++a)
  {
    ext[2 * a] = std::max<int>(extentIn[2 * a], 0);
    ext[2 * a + 1] = static_cast<int>(std::min<std::int64_t>(extentIn[2 * a + 1], dims[a] - 1));
  }
  const std::int64_t nx = std::max(0, ext[1] - ext[0] + 1), ny = std::max(0, ext[3] - ext[2] + 1),
                     nz = std::max(0, ext[5] - ext[4] + 1);
  const std::uint64_t n = static_cast<std::uint64_t>(nx * ny * nz);
  lvdif::requireMemory(n * (withColor ? 8u : 4u), "image of the requested extent");
  const auto& o = volume.options();
  image->SetExtent(ext);
  image->SetOrigin(o.origin[0], o.origin[1], o.origin[2]);
  image->SetSpacing(o.spacing[0], o.spacing[1], o.spacing[2]);

  vtkNew<vtkFloatArray> sdf;
  sdf->SetName(SdfArrayName);
  sdf->SetNumberOfTuples(static_cast<vtkIdType>(n));
  float* s = sdf->GetPointer(0);
  vtkNew<vtkUnsignedCharArray> rgba;
  unsigned char* c = nullptr;
  if (withColor)
  {
    rgba->SetName(ColorArrayName);
    rgba->SetNumberOfComponents(4);
    rgba->SetNumberOfTuples(static_cast<vtkIdType>(n));
    c = rgba->GetPointer(0);
  }
  const lvdif::ColorDictionary& colors = volume.colors();
  // threads only for large images: with a parallel region for each partition (one
  // chunk, ~36k points), ParaView's data information on the 1024^3 dice took
  // 128 s instead of 7 s on the shared 2-core VM
  const bool parallel = n >= (std::uint64_t(1) << 20);
  const float* table = volume.sdfDictionary().table();
  const std::int64_t edgeMask = volume.chunkEdge() - 1;
  const std::size_t colorCount = colors.size();
  // progress and cancel by planes, as VolumeFromImage's by chunks (Sparse Volume
  // To Image of a large extent ran with no progress and ignored ParaView's cancel);
  // static: the calling thread, whose reports LVDIFInterrupter forwards, has its share
  std::atomic<std::int64_t> done{ 0 };
  std::atomic<bool> cancelled{ false };
  if (interrupter) interrupter->start("sparse volume to image");
#pragma omp parallel for schedule(static) if (parallel)
  for (std::int64_t k = 0; k < nz; ++k)
  {
    if (cancelled.load(std::memory_order_relaxed)) continue;
    if (interrupter)
    {
      if (interrupter->wasInterrupted())
      {
        cancelled = true;
        continue;
      }
      interrupter->progress(static_cast<double>(done.fetch_add(1) + 1) / static_cast<double>(nz));
    }
    const std::int64_t z = ext[4] + k;
    for (std::int64_t j = 0; j < ny; ++j)
    {
      const std::int64_t y = ext[2] + j;
      std::int64_t idx = nx * (j + ny * k);
      // the row in runs of one chunk: a chunk's x is its fastest index
      for (std::int64_t x0 = ext[0]; x0 <= ext[1];)
      {
        const std::int64_t x1 = std::min<std::int64_t>(ext[1], x0 | edgeMask);
        const std::int64_t chunk = volume.chunkOf(x0, y, z);
        const lvdif::Voxel* data = volume.chunkData(chunk);
        const lvdif::Voxel uniform = volume.uniformValue(chunk);
        const lvdif::Voxel* run = data ? data + volume.localIndex(x0, y, z) : nullptr;
        for (std::int64_t n = 0; n <= x1 - x0; ++n, ++idx)
        {
          const lvdif::Voxel v = run ? run[n] : uniform;
          s[idx] = table[v.sdf];
          if (c)
          {
            const lvdif::Rgba col = colors[v.color < colorCount ? v.color : 0];
            c[4 * idx + 0] = col.r;
            c[4 * idx + 1] = col.g;
            c[4 * idx + 2] = col.b;
            c[4 * idx + 3] = col.a;
          }
        }
        x0 = x1 + 1;
      }
    }
  }
  if (cancelled)
  {
    throw lvdif::Error(lvdif::ErrorCode::Cancelled, "operation cancelled");
  }
  // ParaView's data information then needs no range pass of its own
  StoreRange(sdf);
  image->GetPointData()->AddArray(sdf);
  image->GetPointData()->SetActiveScalars(SdfArrayName);
  if (withColor)
  {
    StoreRange(rgba);
    image->GetPointData()->AddArray(rgba);
  }
}

std::unique_ptr<lvdif::DictionaryVolume> CropVolume(const lvdif::DictionaryVolume& v, const int ext[6])
{
  lvdif::VolumeOptions o = v.options();
  o.memoryLimit = 0;
  for (int a = 0; a < 3; ++a)
  {
    lvdif::require(ext[2 * a] >= 0 && ext[2 * a + 1] < v.dims()[a] && ext[2 * a] <= ext[2 * a + 1],
      "the extent to crop is empty or outside the volume");
    o.dims[a] = ext[2 * a + 1] - ext[2 * a] + 1;
    o.origin[a] += ext[2 * a] * o.spacing[a];
  }
  auto out = std::make_unique<lvdif::DictionaryVolume>(o);
  out->colors() = v.colors(); // the same keys
  const std::int64_t n = out->chunkCount();
#pragma omp parallel for schedule(dynamic, 4)
  for (std::int64_t id = 0; id < n; ++id)
  {
    const lvdif::VoxelBox b = out->chunkBox(id);
    lvdif::Voxel* d = out->expandChunk(id);
    for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
      for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
        for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
          d[out->localIndex(x, y, z)] = v.get(x + ext[0], y + ext[2], z + ext[4]);
    out->tryCollapseChunk(id);
  }
  out->takeDirtyChunks();
  return out;
}

void SetImageInformation(vtkInformation* outInfo, const lvdif::VolumeOptions& o)
{
  int whole[6] = { 0, static_cast<int>(o.dims[0] - 1), 0, static_cast<int>(o.dims[1] - 1), 0,
    static_cast<int>(o.dims[2] - 1) };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), o.origin.data(), 3);
  outInfo->Set(vtkDataObject::SPACING(), o.spacing.data(), 3);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
}

lvdif::GridGeometry Geometry(vtkImageData* image)
{
  lvdif::GridGeometry g;
  int ext[6];
  image->GetExtent(ext);
  double origin[3], spacing[3];
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  for (int a = 0; a < 3; ++a)
  {
    g.dims[a] = std::max(0, ext[2 * a + 1] - ext[2 * a] + 1);
    g.spacing[a] = spacing[a];
    g.origin[a] = origin[a] + ext[2 * a] * spacing[a];
  }
  return g;
}

lvdif::FloatGridView FloatView(vtkImageData* image, vtkDataArray* array)
{
  lvdif::FloatGridView view;
  view.geometry = Geometry(image);
  auto* f = vtkFloatArray::SafeDownCast(array);
  if (f && f->GetNumberOfComponents() == 1 && f->GetNumberOfTuples() == view.geometry.count())
  {
    view.data = f->GetPointer(0);
  }
  return view;
}

vtkDataArray* SdfArray(vtkInformation* selection, vtkDataSet* input, vtkDataArray* selected)
{
  if (selected || !input)
  {
    return selected;
  }
  const char* name =
    selection && selection->Has(vtkDataObject::FIELD_NAME()) ? selection->Get(vtkDataObject::FIELD_NAME()) : nullptr;
  if (name && *name)
  {
    return nullptr; // a named array that is not there: the caller's error names it
  }
  vtkDataArray* sdf = input->GetPointData()->GetArray("sdf");
  return sdf ? sdf : input->GetPointData()->GetScalars();
}

std::string DenseImageWarning(std::uint64_t bytes, const int extent[6], std::uint64_t limit, const char* advice)
{
  constexpr std::uint64_t Large = std::uint64_t(1) << 30;
  if (bytes < std::min(Large, limit / 2))
  {
    return std::string();
  }
  std::ostringstream msg;
  msg << "the dense image of " << (extent[1] - extent[0] + 1) << " x " << (extent[3] - extent[2] + 1) << " x "
      << (extent[5] - extent[4] + 1) << " points needs " << lvdif::formatBytes(bytes) << " (memory limit "
      << lvdif::formatBytes(limit) << ", LVDIF_MEMORY_LIMIT)";
  if (advice && *advice)
  {
    msg << "; " << advice;
  }
  return msg.str();
}

void RequireAxisAligned(vtkImageData* image)
{
  // a rotated or flipped image (VTK's direction matrix, e.g. a .vti's
  // Direction) would silently lose its orientation
  vtkMatrix3x3* d = image ? image->GetDirectionMatrix() : nullptr;
  if (d && !d->IsIdentity())
  {
    std::ostringstream msg;
    msg << "the image's direction matrix is not the identity (";
    for (int i = 0; i < 9; ++i)
      msg << (i ? " " : "") << d->GetElement(i / 3, i % 3);
    msg << "): a dictionary volume and its meshes are axis-aligned, resample the image onto an axis-aligned grid "
           "first";
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, msg.str());
  }
}

namespace
{
/// VolumeFromImage and VolumeFromImageRegion: `options` holds the volume's
/// grid; its voxel (x, y, z) is the image's point (x, y, z) + `shift` (image
/// indices from the image's first point); only the chunks of `region` are written.
std::unique_ptr<lvdif::DictionaryVolume> FillFromImage(vtkImageData* image, vtkDataArray* sdf, vtkDataArray* rgba,
  const lvdif::VolumeOptions& options, const std::array<std::int64_t, 3>& shift, const lvdif::VoxelBox* region,
  lvdif::Interrupter* interrupter)
{
  const lvdif::GridGeometry g = Geometry(image);
  if (sdf->GetNumberOfTuples() != g.count() || sdf->GetNumberOfComponents() != 1)
  {
    std::ostringstream msg;
    msg << "SDF array '" << (sdf->GetName() ? sdf->GetName() : "") << "' has " << sdf->GetNumberOfTuples()
        << " tuples of " << sdf->GetNumberOfComponents() << " components; expected " << g.count() << " scalars";
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, msg.str());
  }
  if (rgba && (rgba->GetNumberOfTuples() != g.count() || rgba->GetNumberOfComponents() < 1 ||
                rgba->GetNumberOfComponents() > 4))
  {
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "RGBA array does not match the image's points");
  }
  auto volume = std::make_unique<lvdif::DictionaryVolume>(options);
  const int nc = rgba ? rgba->GetNumberOfComponents() : 0;
  auto* f = vtkFloatArray::SafeDownCast(sdf);
  std::vector<std::int64_t> ids;
  if (region)
  {
    ids = volume->chunksInBox(*region);
  }
  else
  {
    ids.resize(static_cast<std::size_t>(volume->chunkCount()));
    std::iota(ids.begin(), ids.end(), std::int64_t(0));
  }
  const std::int64_t chunks = static_cast<std::int64_t>(ids.size());
  // Colours are added serially first so keys are deterministic.
  std::vector<lvdif::ColorKey> keyOfPoint;
  if (rgba)
  {
    keyOfPoint.resize(static_cast<size_t>(g.count()));
    for (std::int64_t p = 0; p < g.count(); ++p)
    {
      double t[4] = { 0, 0, 0, 255 };
      for (int cidx = 0; cidx < nc; ++cidx)
      {
        // whole numbers 0..255 (a float array of colours in [0, 1], as many VTK sources make, was
        // cast to black, and a value past 255 or below 0 cast to whatever the conversion gave)
        t[cidx] = rgba->GetComponent(p, cidx);
        if (!(t[cidx] >= 0 && t[cidx] <= 255 && t[cidx] == std::floor(t[cidx])))
        {
          std::ostringstream msg;
          msg << "RGBA array '" << (rgba->GetName() ? rgba->GetName() : "") << "' holds " << t[cidx] << " at point " << p
              << ", component " << cidx << ": colours are whole numbers 0..255 (an unsigned char array)";
          if (rgba->GetDataType() == VTK_FLOAT || rgba->GetDataType() == VTK_DOUBLE)
            msg << "; colours in [0, 1] are to be scaled by 255 first";
          throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, msg.str());
        }
      }
      if (nc == 1) t[1] = t[2] = t[0];
      if (nc == 2) // luminance and alpha, as VTK reads two components
      {
        t[3] = t[1];
        t[1] = t[2] = t[0];
      }
      lvdif::Rgba col{ static_cast<std::uint8_t>(t[0]), static_cast<std::uint8_t>(t[1]),
        static_cast<std::uint8_t>(t[2]), static_cast<std::uint8_t>(t[3]) };
      keyOfPoint[static_cast<size_t>(p)] = volume->colors().add(col);
    }
  }
  bool sawNaN = false;
  // progress and cancel: Image To Sparse Volume of a 1024^3 image ran for many
  // seconds with no progress between 0 and 1 and ignored ParaView's cancel
  std::atomic<std::int64_t> done{ 0 };
  std::atomic<bool> cancelled{ false };
  if (interrupter) interrupter->start("image to sparse volume");
  // static: the calling thread (the only one whose reports LVDIFInterrupter
  // forwards) gets its fixed share of chunks from the start, so progress and an
  // observer's cancel come however the threads are scheduled (with dynamic
  // grabs a descheduled calling thread reported nothing on a loaded machine)
#pragma omp parallel for schedule(static) reduction(|| : sawNaN)
  for (std::int64_t i = 0; i < chunks; ++i)
  {
    if (cancelled.load(std::memory_order_relaxed)) continue;
    if (interrupter)
    {
      if (interrupter->wasInterrupted())
      {
        cancelled = true;
        continue;
      }
      // (LVDIFInterrupter forwards only its own thread's reports)
      interrupter->progress(static_cast<double>(done.fetch_add(1) + 1) / static_cast<double>(chunks));
    }
    const std::int64_t id = ids[static_cast<std::size_t>(i)];
    const lvdif::VoxelBox b = region ? volume->chunkBox(id).intersect(*region) : volume->chunkBox(id);
    lvdif::Voxel* d = volume->expandChunk(id);
    for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
      for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
        for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
        {
          const std::int64_t p = g.index(x + shift[0], y + shift[1], z + shift[2]);
          const float v = f ? f->GetValue(p) : static_cast<float>(sdf->GetComponent(p, 0));
          sawNaN = sawNaN || std::isnan(v);
          d[volume->localIndex(x, y, z)] =
            lvdif::Voxel{ volume->encode(v), rgba ? keyOfPoint[static_cast<size_t>(p)] : lvdif::ColorKey(0) };
        }
    volume->tryCollapseChunk(id);
  }
  if (cancelled)
  {
    throw lvdif::Error(lvdif::ErrorCode::Cancelled, "operation cancelled");
  }
  if (sawNaN)
  {
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "the SDF array contains NaN values");
  }
  volume->takeDirtyChunks();
  return volume;
}
} // namespace

std::unique_ptr<lvdif::DictionaryVolume> VolumeFromImage(vtkImageData* image, vtkDataArray* sdf, vtkDataArray* rgba,
  lvdif::VolumeOptions options, lvdif::Interrupter* interrupter)
{
  if (!image || !sdf)
  {
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "no image or no SDF array");
  }
  RequireAxisAligned(image);
  const lvdif::GridGeometry g = Geometry(image);
  options.dims = g.dims;
  options.origin = g.origin;
  options.spacing = g.spacing;
  return FillFromImage(image, sdf, rgba, options, { 0, 0, 0 }, nullptr, interrupter);
}

std::unique_ptr<lvdif::DictionaryVolume> VolumeFromImageRegion(vtkImageData* image, vtkDataArray* sdf,
  vtkDataArray* rgba, lvdif::VolumeOptions options, const int wholeLo[3], const lvdif::VoxelBox& region,
  lvdif::Interrupter* interrupter)
{
  if (!image || !sdf)
  {
    throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, "no image or no SDF array");
  }
  RequireAxisAligned(image);
  int ext[6];
  image->GetExtent(ext);
  std::array<std::int64_t, 3> shift{};
  for (int a = 0; a < 3; ++a)
  {
    shift[a] = static_cast<std::int64_t>(wholeLo[a]) - ext[2 * a];
    if (region.lo[a] + shift[a] < 0 || region.hi[a] + wholeLo[a] > ext[2 * a + 1])
    {
      std::ostringstream msg;
      msg << "the input image's extent (" << ext[0] << " " << ext[1] << " " << ext[2] << " " << ext[3] << " " << ext[4]
          << " " << ext[5] << ") does not cover the piece's points " << region.lo[0] + wholeLo[0] << ".."
          << region.hi[0] + wholeLo[0] << ", " << region.lo[1] + wholeLo[1] << ".." << region.hi[1] + wholeLo[1]
          << ", " << region.lo[2] + wholeLo[2] << ".." << region.hi[2] + wholeLo[2];
      throw lvdif::Error(lvdif::ErrorCode::InvalidArgument, msg.str());
    }
  }
  return FillFromImage(image, sdf, rgba, options, shift, &region, interrupter);
}

} // namespace LVDIFVolumeBridge
