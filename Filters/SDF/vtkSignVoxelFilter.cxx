#include "vtkSignVoxelFilter.h"

#include "LVDIFInterrupter.h"
#include "LVDIFVolumeBridge.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/DictionaryVolume.h"

#include "lvdif/Error.h"
#include "lvdif/SignVoxelFilter.h"

#include "vtkCompositeDataPipeline.h"
#include "vtkDataObject.h"
#include "vtkExtentTranslator.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSignVoxelFilter);
vtkCxxSetObjectMacro(vtkSignVoxelFilter, Controller, vtkMultiProcessController);

vtkSignVoxelFilter::vtkSignVoxelFilter()
{
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "sdf");
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkSignVoxelFilter::~vtkSignVoxelFilter()
{
  this->SetController(nullptr);
}

bool vtkSignVoxelFilter::Distributed() const
{
  return this->Controller && this->Controller->GetNumberOfProcesses() > 1;
}

// The ranks of a distributed sparse run meet in collectives (an all-reduce of
// success, all-gathers, pair exchanges). A rank whose input fails upstream
// never reaches RequestInformation/RequestData (the executive stops before the
// algorithm), so the others would wait in the first collective forever. This
// executive notes a failed pass of that rank and joins the pass's agreement
// for it, as failed: every rank then fails the pass and reports why. (In
// ParaView it stands in for vtkPVCompositeDataPipeline, whose one addition
// passes array-component requests on to a post filter: this filter reads one
// 1-component array.)
class vtkSignVoxelFilterExecutive : public vtkCompositeDataPipeline
{
public:
  static vtkSignVoxelFilterExecutive* New();
  vtkTypeMacro(vtkSignVoxelFilterExecutive, vtkCompositeDataPipeline);

  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** inInfoVec, vtkInformationVector* outInfoVec) override
  {
    auto* filter = vtkSignVoxelFilter::SafeDownCast(this->GetAlgorithm());
    // the passes whose agreement the other ranks enter: information (its own),
    // update extent and data (the data pass's: the next collective they enter)
    const bool meets = filter &&
      (request->Has(REQUEST_INFORMATION()) || request->Has(REQUEST_UPDATE_EXTENT()) || request->Has(REQUEST_DATA()));
    if (meets)
      filter->Joined = false;
    const vtkTypeBool ok = this->Superclass::ProcessRequest(request, inInfoVec, outInfoVec);
    if (meets && !ok && !filter->Joined && filter->MeetsRanks(inInfoVec))
      filter->JoinRanks(false);
    return ok;
  }

protected:
  vtkSignVoxelFilterExecutive() = default;
  ~vtkSignVoxelFilterExecutive() override = default;
};
vtkStandardNewMacro(vtkSignVoxelFilterExecutive);

vtkExecutive* vtkSignVoxelFilter::CreateDefaultExecutive()
{
  return vtkSignVoxelFilterExecutive::New();
}

bool vtkSignVoxelFilter::MeetsRanks(vtkInformationVector** inputVector) const
{
  // the input's data object exists from the data-object pass on, also when its
  // information or data then failed
  vtkInformation* inInfo = inputVector && inputVector[0] ? inputVector[0]->GetInformationObject(0) : nullptr;
  return this->Distributed() && inInfo &&
    vtkSparseDictionaryVolume::SafeDownCast(inInfo->Get(vtkDataObject::DATA_OBJECT())) != nullptr;
}

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

/// The planes [first, last] along the filter axis that rank r of n filters:
/// its chunk layers [L r / n, L (r + 1) / n) of the L layers (empty: last < first).
void PiecePlanes(int r, int n, std::int64_t planes, std::int64_t edge, std::int64_t& first, std::int64_t& last)
{
  const std::int64_t layers = (planes + edge - 1) / edge;
  first = layers * r / n * edge;
  last = std::min(layers * (r + 1) / n * edge, planes) - 1;
}

// ---- the chunks one rank sends another ---------------------------------------
// A message is a sequence of records: chunk id (int64), uniform flag (int64),
// then one voxel (uniform) or the chunk's edge^3 voxels.

void PackChunk(const lvdif::DictionaryVolume& v, std::int64_t id, std::vector<char>& out)
{
  const std::int64_t head[2] = { id, v.isUniform(id) ? 1 : 0 };
  const std::size_t n = head[1] ? 1 : static_cast<std::size_t>(v.chunkEdge()) * v.chunkEdge() * v.chunkEdge();
  const std::size_t at = out.size();
  out.resize(at + sizeof(head) + n * sizeof(lvdif::Voxel));
  std::memcpy(out.data() + at, head, sizeof(head));
  const lvdif::Voxel u = v.uniformValue(id);
  std::memcpy(out.data() + at + sizeof(head), head[1] ? &u : v.chunkData(id), n * sizeof(lvdif::Voxel));
}

void UnpackChunks(lvdif::DictionaryVolume& v, const std::vector<char>& in)
{
  // a test hook (TestSignVoxelFilterMPI): the rank whose environment has it
  // fails here, as a malformed message or a failed allocation would
  lvdif::require(!std::getenv("LVDIF_TEST_SVF_UNPACK_FAILS"),
    "vtkSignVoxelFilter: unpacking the received chunks failed (LVDIF_TEST_SVF_UNPACK_FAILS is set)");
  const std::size_t full = static_cast<std::size_t>(v.chunkEdge()) * v.chunkEdge() * v.chunkEdge();
  for (std::size_t at = 0; at < in.size();)
  {
    std::int64_t head[2];
    std::memcpy(head, in.data() + at, sizeof(head));
    at += sizeof(head);
    lvdif::require(head[0] >= 0 && head[0] < v.chunkCount(), "vtkSignVoxelFilter: a received chunk id is out of range");
    if (head[1])
    {
      lvdif::Voxel u;
      std::memcpy(&u, in.data() + at, sizeof(u));
      v.fillChunk(head[0], u);
      at += sizeof(u);
    }
    else
    {
      std::memcpy(v.expandChunk(head[0]), in.data() + at, full * sizeof(lvdif::Voxel));
      v.markDirty(head[0]);
      at += full * sizeof(lvdif::Voxel);
    }
  }
}

constexpr int SizeTag = 84721, DataTag = 84722, ReadyTag = 84723;
constexpr vtkIdType Piece = vtkIdType(1) << 28; // bytes per message: far below MPI's int count

/// The buffer for `n` received bytes. A test hook (TestSignVoxelFilterMPI): the
/// rank whose environment has LVDIF_TEST_SVF_RECEIVE_ALLOC_FAILS fails to
/// allocate it, as a rank short of memory would.
std::vector<char> ReceiveBuffer(vtkIdType n)
{
  lvdif::require(n >= 0, "vtkSignVoxelFilter: a rank announced a negative message size");
  if (n > 0 && std::getenv("LVDIF_TEST_SVF_RECEIVE_ALLOC_FAILS"))
    throw std::bad_alloc();
  return std::vector<char>(static_cast<std::size_t>(n));
}

/// One exchange of packed chunks between this rank and `partner` (`leads`: this
/// rank sends first, its partner calls with the opposite). The sizes travel
/// first; each side then allocates its receive buffer and the two tell each
/// other whether that worked (a rank that failed earlier, `ok` false, says no);
/// the payloads travel only when both sides can take them. Before, a receive
/// buffer that could not be allocated threw out of the filter while the
/// partner was still sending to it, or blocked later in its next exchange. A
/// failure here is reported once on this rank (CallCore) and returns false;
/// `got` is then empty. The partner's failure is not this rank's: it leaves
/// `got` empty, and the ranks' agreement after all exchanges fails them all.
bool ExchangeChunks(vtkAlgorithm* self, vtkMultiProcessController* c, int partner, bool leads,
  const std::vector<char>& out, std::vector<char>& got, bool ok)
{
  // the same order on both sides: the leading rank sends, then receives
  auto swap = [&](vtkIdType mine, int tag) {
    vtkIdType theirs = 0;
    if (leads)
    {
      c->Send(&mine, 1, partner, tag);
      c->Receive(&theirs, 1, partner, tag);
    }
    else
    {
      c->Receive(&theirs, 1, partner, tag);
      c->Send(&mine, 1, partner, tag);
    }
    return theirs;
  };
  got.clear();
  const vtkIdType n = swap(ok ? static_cast<vtkIdType>(out.size()) : 0, SizeTag);
  if (ok)
  {
    ok = LVDIFVolumeBridge::CallCore(self, [&] { got = ReceiveBuffer(n); },
      "receiving " + std::to_string(n) + " bytes of chunks from rank " + std::to_string(partner) + ": ");
  }
  const bool partnerReady = swap(ok ? 1 : 0, ReadyTag) != 0;
  if (!ok || !partnerReady)
  {
    got.clear();
    return ok;
  }
  auto sendAll = [&] {
    for (vtkIdType at = 0; at < static_cast<vtkIdType>(out.size()); at += Piece)
      c->Send(out.data() + at, std::min(Piece, static_cast<vtkIdType>(out.size()) - at), partner, DataTag);
  };
  auto receiveAll = [&] {
    for (vtkIdType at = 0; at < n; at += Piece)
      c->Receive(got.data() + at, std::min(Piece, n - at), partner, DataTag);
  };
  if (leads)
  {
    sendAll();
    receiveAll();
  }
  else
  {
    receiveAll();
    sendAll();
  }
  return true;
}

/// True on every rank when `ok` is true on every rank (so that a failure on
/// one rank makes all leave before the next collective step).
bool AllOk(vtkMultiProcessController* c, bool ok)
{
  int mine = ok ? 1 : 0, all = 0;
  c->AllReduce(&mine, &all, 1, vtkCommunicator::MIN_OP);
  return all == 1;
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

void vtkSignVoxelFilter::JoinRanks(int state, int& lowest, int& highest)
{
  // one all-reduce for both (the executive's join for a failed rank is matched with it)
  this->Joined = true;
  int mine[2] = { state, -state }, all[2] = { JOIN_FAILED, JOIN_FAILED };
  this->Controller->AllReduce(mine, all, 2, vtkCommunicator::MIN_OP);
  lowest = all[0];
  highest = -all[1];
}

bool vtkSignVoxelFilter::JoinRanks(bool ok)
{
  int lowest = JOIN_FAILED, highest = JOIN_FAILED;
  this->JoinRanks(ok ? JOIN_READY : JOIN_FAILED, lowest, highest);
  return lowest == JOIN_READY;
}

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
  // without an input the output is an image, so that the executive's input
  // check says what is missing (returning 0 here gave only its cryptic
  // "returned failure for request: REQUEST_DATA_OBJECT")
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0]);
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

int vtkSignVoxelFilter::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  LVDIFVolumeBridge::BeginInformation(outputVector->GetInformationObject(0));
  // the settings first, by Core's one rule: one error, nothing computed
  // (under MPI the executive then joins the ranks' agreement for this rank)
  if (!LVDIFVolumeBridge::CallCore(this, [&] {
        LVDIFVolumeBridge::EnumOption(this->Boundary, "Boundary", { "outside", "free" });
        LVDIFVolumeBridge::DeviceOption(this->Device);
        lvdif::checkSignVoxelFilterParams(this->CoreParams());
      }))
  {
    return LVDIFVolumeBridge::FailInformation(outputVector->GetInformationObject(0));
  }
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (this->MeetsRanks(inputVector) && !this->JoinRanks(true))
  {
    vtkErrorMacro("another rank's input failed: the ranks filter nothing");
    return 0;
  }
  if (inInfo->Has(LVDIFVolumeBridge::CHUNK_EDGE()))
  {
    outputVector->GetInformationObject(0)->Set(LVDIFVolumeBridge::CHUNK_EDGE(), inInfo->Get(LVDIFVolumeBridge::CHUNK_EDGE()));
  }
  return 1;
}

// The scans need whole rows and planes: an image is filtered whole, a sparse
// volume under MPI by chunk layers along the axis (see the header).
int vtkSignVoxelFilter::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  if (LVDIFVolumeBridge::InformationFailed(outputVector->GetInformationObject(0)))
    return 1; // RequestInformation reported why; the Axis may be outside 0..2
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  if (inInfo->Has(SDDP::WHOLE_EXTENT()))
  {
    int ext[6];
    inInfo->Get(SDDP::WHOLE_EXTENT(), ext);
    const bool sparse = vtkSparseDictionaryVolume::SafeDownCast(inInfo->Get(vtkDataObject::DATA_OBJECT())) != nullptr;
    if (sparse && this->Distributed() && inInfo->Has(LVDIFVolumeBridge::CHUNK_EDGE()))
    {
      // this rank's chunk layers and one ghost plane on each side
      const int a = this->Axis, lo = ext[2 * a], hi = ext[2 * a + 1];
      std::int64_t first, last;
      PiecePlanes(this->Controller->GetLocalProcessId(), this->Controller->GetNumberOfProcesses(), hi - lo + 1,
        inInfo->Get(LVDIFVolumeBridge::CHUNK_EDGE()), first, last);
      ext[2 * a] = last < first ? lo : static_cast<int>(std::max<std::int64_t>(lo, lo + first - 1));
      ext[2 * a + 1] = last < first ? lo : static_cast<int>(std::min<std::int64_t>(hi, lo + last + 1));
    }
    inInfo->Set(SDDP::UPDATE_EXTENT(), ext, 6);
  }
  // one piece of one, without ghosts: the extent is the request
  inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), 0);
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), 1);
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  inInfo->Set(SDDP::EXACT_EXTENT(), 1);
  return 1;
}

int vtkSignVoxelFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return this->Produce(inputVector, outputVector) ? 1
                                                  : LVDIFVolumeBridge::FailReported(outputVector->GetInformationObject(0));
}

int vtkSignVoxelFilter::Produce(vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (LVDIFVolumeBridge::InformationFailed(outputVector->GetInformationObject(0)))
    return 0; // RequestInformation reported why (ParaView runs RequestData anyway)
  if (auto* sparse = vtkSparseDictionaryVolume::GetData(inputVector[0]))
  {
    return this->FilterSparse(sparse, vtkSparseDictionaryVolume::GetData(outputVector), outputVector->GetInformationObject(0));
  }
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  if (!input || !output)
  {
    vtkErrorMacro("input and output must be vtkImageData");
    return 0;
  }
  if (LVDIFVolumeBridge::IsEmptyInput(input))
  {
    output->Initialize(); // VTK's rule for an empty input: empty output, no error
    return 1;
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
  // beyond float's range: infinite, which Core's rule refuses (no clamp)
  p.threshold = std::abs(this->Threshold) > std::numeric_limits<float>::max()
    ? static_cast<float>(std::copysign(HUGE_VAL, this->Threshold))
    : static_cast<float>(this->Threshold);
  p.axis = this->Axis;
  p.filters = static_cast<unsigned>(this->Filters);
  p.maxIterations = this->MaxIterations;
  p.boundary = this->Boundary == BOUNDARY_FREE ? lvdif::SvfBoundary::Free : lvdif::SvfBoundary::Outside;
  p.device = LVDIFVolumeBridge::ToDevice(this->Device);
  return p;
}

int vtkSignVoxelFilter::FilterSparse(
  vtkSparseDictionaryVolume* input, vtkSparseDictionaryVolume* output, vtkInformation* outInfo)
{
  // An input without a volume (an upstream that failed and said why, or that
  // made nothing) gives an empty output without an error, as VTK's own filters
  // treat an empty input (vtkContourFilter, vtkCutter): each filter below a
  // failed reader added its own "no dictionary volume" error before.
  const bool hasVolume = input->HasVolume();
  // a distributed run agrees before any work, so that a rank without a volume
  // does not leave the others waiting in the first collective
  int lowest = hasVolume ? JOIN_READY : JOIN_EMPTY, highest = lowest;
  if (this->Distributed())
  {
    this->JoinRanks(lowest, lowest, highest);
  }
  if (highest == JOIN_EMPTY && lowest == JOIN_EMPTY)
  {
    vtkDebugMacro("empty input: empty output");
    output->Initialize();
    return 1;
  }
  if (lowest != JOIN_READY)
  {
    // some ranks hold a volume and others none, or another rank failed
    if (hasVolume)
      vtkErrorMacro("another rank's input failed: the ranks filter nothing");
    else
      vtkErrorMacro("this rank's input holds no volume while another rank's does: the ranks filter nothing");
    output->Initialize();
    return 0;
  }
  lvdif::SignVoxelFilterStats st;
  LVDIFInterrupter interrupter(this);
  const lvdif::SignVoxelFilterParams p = this->CoreParams();
  std::shared_ptr<lvdif::DictionaryVolume> volume;
  int owned[6] = { 0, -1, 0, -1, 0, -1 }; // a generic filter's piece: its block of chunks (else all)
  if (!this->Distributed())
  {
    const bool ok = LVDIFVolumeBridge::CallCore(this, [&] {
      // VTK filters leave their input alone: a copy-on-write clone costs the
      // chunk table, and only the chunks the filters change are copied
      volume = input->GetVolume()->clone();
      st = lvdif::signVoxelFilter(*volume, p, interrupter);
    });
    if (!ok)
    {
      output->Initialize();
      return 0;
    }
  }
  else if (!this->FilterSparsePiece(*input->GetVolume(), outInfo, owned, volume, st))
  {
    output->Initialize();
    return 0;
  }
  // what this rank did (serial: rank 0 of 1, every plane)
  vtkNew<vtkIdTypeArray> piece;
  piece->SetName("svf_piece");
  const int a = this->Axis;
  std::int64_t first = 0, last = input->GetVolume()->dims()[a] - 1;
  if (this->Distributed())
  {
    PiecePlanes(this->Controller->GetLocalProcessId(), this->Controller->GetNumberOfProcesses(),
      input->GetVolume()->dims()[a], input->GetVolume()->chunkEdge(), first, last);
  }
  for (const std::int64_t v : { std::int64_t(this->Distributed() ? this->Controller->GetLocalProcessId() : 0),
         std::int64_t(this->Distributed() ? this->Controller->GetNumberOfProcesses() : 1), first, last,
         input->GetVolume()->expandedChunkCount(), volume ? volume->expandedChunkCount() : std::int64_t(0) })
  {
    piece->InsertNextValue(static_cast<vtkIdType>(v));
  }
  output->SetVolume(std::move(volume));
  if (owned[1] >= owned[0])
  {
    output->SetOwnedChunks(owned);
  }
  output->SetPartitionColors(input->GetPartitionColors());
  AddStats(output, st);
  output->GetFieldData()->AddArray(piece);
  this->UpdateProgress(1.0);
  return 1;
}

bool vtkSignVoxelFilter::FilterSparsePiece(const lvdif::DictionaryVolume& in, vtkInformation* outInfo,
  int ownedChunks[6], std::shared_ptr<lvdif::DictionaryVolume>& volume, lvdif::SignVoxelFilterStats& st)
{
  using SDDP = vtkStreamingDemandDrivenPipeline;
  vtkMultiProcessController* c = this->Controller;
  const int rank = c->GetLocalProcessId(), size = c->GetNumberOfProcesses();
  const lvdif::SignVoxelFilterParams p = this->CoreParams();
  const int a = p.axis;
  std::int64_t first, last;
  PiecePlanes(rank, size, in.dims()[a], in.chunkEdge(), first, last);
  const std::int64_t rows = in.dims()[0] * in.dims()[1] * in.dims()[2] / in.dims()[a];
  LVDIFInterrupter interrupter(this);

  // 1. the sign each row leaves every rank's layers with after SVF1 (identity for an empty piece)
  // (every buffer allocated before the ranks agree: a failed allocation is one
  // error on its rank, not an exception that leaves the others in the all-gather)
  std::vector<std::int8_t> exits, all;
  bool ok = LVDIFVolumeBridge::CallCore(this, [&] {
    exits.resize(static_cast<std::size_t>(3 * rows));
    for (int k = 0; k < 3; ++k)
    {
      std::fill(exits.begin() + k * rows, exits.begin() + (k + 1) * rows, static_cast<std::int8_t>(k - 1));
    }
    if (last >= first && (p.filters & lvdif::Svf1))
    {
      exits = lvdif::svf1ExitSigns(in, p, first, last, interrupter);
    }
    all.resize(exits.size() * static_cast<std::size_t>(size));
  });
  if (!AllOk(c, ok))
  {
    return false;
  }
  c->AllGather(reinterpret_cast<const signed char*>(exits.data()), reinterpret_cast<signed char*>(all.data()),
    static_cast<vtkIdType>(exits.size()));

  // 2. this rank's planes, entered with the signs composed over the ranks before
  ok = LVDIFVolumeBridge::CallCore(this, [&] {
    lvdif::SvfPlanes planes;
    planes.first = first;
    planes.last = last;
    planes.entrySigns = lvdif::svf1BoundarySigns(in, p);
    for (int q = 0; q < rank; ++q)
    {
      const auto from = all.begin() + static_cast<std::ptrdiff_t>(q * exits.size());
      planes.entrySigns = lvdif::svf1Continue(planes.entrySigns, std::vector<std::int8_t>(from, from + exits.size()));
    }
    volume = in.clone();
    if (last >= first)
    {
      st = lvdif::signVoxelFilter(*volume, p, planes, interrupter);
    }
  });
  if (!AllOk(c, ok))
  {
    return false;
  }

  // 3. the extent every rank's consumer asked for; each rank sends its filtered
  // chunks that overlap another's, pairs in a fixed order (no deadlock)
  int req[6] = { 0, static_cast<int>(in.dims()[0] - 1), 0, static_cast<int>(in.dims()[1] - 1), 0,
    static_cast<int>(in.dims()[2] - 1) };
  int owned[6] = { 0, -1, 0, -1, 0, -1 };
  bool ownsChunks = false;
  const int pieces = outInfo->Has(SDDP::UPDATE_NUMBER_OF_PIECES()) ? outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES()) : 1;
  if (pieces > 1)
  {
    // a generic filter's piece: a block of chunks, as the .lvdv reader gives it
    lvdif::VoxelBox region;
    const int piece = outInfo->Has(SDDP::UPDATE_PIECE_NUMBER()) ? outInfo->Get(SDDP::UPDATE_PIECE_NUMBER()) : 0;
    ownsChunks = LVDIFVolumeBridge::PieceChunks(piece, pieces, in.options(), owned, region);
    for (int k = 0; k < 3; ++k)
    {
      req[2 * k] = static_cast<int>(ownsChunks ? region.lo[k] : 0);
      req[2 * k + 1] = static_cast<int>(ownsChunks ? region.hi[k] : -1);
    }
  }
  else if (outInfo->Has(SDDP::UPDATE_EXTENT()))
  {
    outInfo->Get(SDDP::UPDATE_EXTENT(), req);
  }
  std::vector<int> reqs(6 * static_cast<std::size_t>(size));
  c->AllGather(req, reqs.data(), 6);
  auto boxOf = [&](int q) {
    lvdif::VoxelBox b;
    for (int k = 0; k < 3; ++k)
    {
      b.lo[k] = reqs[6 * q + 2 * k];
      b.hi[k] = reqs[6 * q + 2 * k + 1];
    }
    return b;
  };
  lvdif::VoxelBox mine = in.bounds();
  mine.lo[a] = first;
  mine.hi[a] = last;
  // Every rank takes part in every exchange of its pairs, also after its own
  // packing, allocating or unpacking failed (it then sends nothing and keeps
  // nothing): a rank that left the loop early left its next partner waiting in a
  // receive forever (three ranks or more). The ranks agree after the loop.
  ok = true;
  for (int i = 0; i < size; ++i)
    for (int j = i + 1; j < size; ++j)
    {
      if (rank != i && rank != j) continue;
      const int partner = rank == i ? j : i;
      std::vector<char> out;
      const lvdif::VoxelBox wanted = boxOf(partner).intersect(mine);
      if (ok && !wanted.empty())
      {
        ok = LVDIFVolumeBridge::CallCore(
          this, [&] { volume->forEachChunkInBox(wanted, [&](std::int64_t id) { PackChunk(*volume, id, out); }); });
      }
      if (!ok)
      {
        out.clear();
      }
      std::vector<char> got;
      ok = ExchangeChunks(this, c, partner, rank == i, out, got, ok);
      if (ok)
      {
        ok = LVDIFVolumeBridge::CallCore(this, [&] { UnpackChunks(*volume, got); });
      }
    }
  if (ok)
  {
    // chunks outside this rank's request are not its consumer's: drop them
    ok = LVDIFVolumeBridge::CallCore(this, [&] {
      const lvdif::VoxelBox keep = boxOf(rank);
      const lvdif::Voxel outside = volume->outsideVoxel();
      for (std::int64_t id = 0; id < volume->chunkCount(); ++id)
      {
        if (volume->chunkBox(id).intersect(keep).empty() &&
          !(volume->isUniform(id) && volume->uniformValue(id) == outside))
        {
          volume->fillChunk(id, outside);
        }
      }
    });
  }
  if (!AllOk(c, ok))
  {
    return false;
  }
  if (pieces > 1)
  {
    std::copy(owned, owned + 6, ownedChunks);
    if (!ownsChunks)
    {
      volume.reset(); // a piece without chunks: empty
    }
  }

  // 4. the statistics of the whole volume
  vtkIdType flips[8], sums[8];
  int iterations[4];
  for (int k = 0; k < 4; ++k)
  {
    flips[k] = static_cast<vtkIdType>(st.flips[k]);
    flips[4 + k] = static_cast<vtkIdType>(st.planesAtCap[k]);
  }
  c->AllReduce(flips, sums, 8, vtkCommunicator::SUM_OP);
  c->AllReduce(st.iterations.data(), iterations, 4, vtkCommunicator::MAX_OP);
  for (int k = 0; k < 4; ++k)
  {
    st.flips[k] = sums[k];
    st.planesAtCap[k] = sums[4 + k];
    st.iterations[k] = iterations[k];
  }
  return true;
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
