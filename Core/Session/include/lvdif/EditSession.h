// One editing session: the volume, its editor (brushes, strokes, undo/redo,
// recording, scripts), its chunked marching cubes and the rule that says
// which meshes an edit invalidates. Every front end (vtkLVDIFEditor and so
// Python, the Qt editor, the benchmarks) holds one and orchestrates nothing.
//
// Two chunk words:
//   storage chunk  the volume's chunk (DictionaryVolume::chunkEdge), the unit
//                  of sparse storage, dirty flags, undo snapshots and device slots;
//   mesh chunk     marching cubes' chunk (ChunkedMarchingCubes, meshChunkEdge
//                  cells), the unit of meshing and of the meshes handed out.
// Everything a session reports (changedMeshChunks, lastRequest, the meshes'
// chunkId) is a mesh chunk id.
//
// Where it runs (EditSessionOptions::device):
//   CPU   the volume lives on the host; brushes run there (OpenMP); the mesh
//         chunks an edit invalidates are queued on a MarchingCubesWorker (its own
//         thread); collectMeshes() returns what it finished (never waits).
//   GPU   the volume lives on the device (cuda::DeviceVolume); brushes run there
//         and the history's snapshots stay there (copy on write); the mesh chunks
//         invalidated since the last collectMeshes() are meshed by it on the device
//         in one batched launch straight from the device volume, and only those
//         meshes come back. The host volume is synced lazily: volume() and sync()
//         (saving, CPU-only consumers) copy the changed storage chunks back.
// Auto picks the GPU when one can be used; without one (or when the volume
// does not fit), the session runs on the CPU and notice() says why, once.
// Both give the same voxels bit for bit and the same meshes (tested).
//
// Scripts run through the session's editor: their edits are undoable steps and
// are recorded when recording (one policy for every front end). A script's
// `canvas N` replaces the volume (history cleared, recording ended); `canvas
// fill|clear` refills it (history cleared).
//
// Threading: call a session from one thread (the CPU worker reads the volume
// under its own lock, which the session takes around every write).
#pragma once

#include "lvdif/ChunkedMarchingCubes.h"
#include "lvdif/Editor.h"
#include "lvdif/Script.h"

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lvdif
{

class MarchingCubesWorker;

struct EditSessionOptions
{
  /// Cpu, or Auto/Cuda: the GPU when one can be used (else the CPU with a notice).
  Device device = Device::Auto;
  /// Cells per mesh chunk edge, 16..256; 0: the volume's storage chunk edge (at least 16).
  int meshChunkEdge = 0;
  /// Keep meshes (the CPU worker, or meshing on the device). Off: the session
  /// still reports which mesh chunks changed, but meshes nothing.
  bool meshing = true;
  /// Marching cubes settings other than chunkEdge and device (iso, normals, colours, corner colours).
  MarchingCubesOptions meshOptions;
  /// History bounds (on the device: DeviceVolume::Options::historyBytes / minHistorySteps).
  UndoStack::Options undo;
  /// Device bytes the resident volume may use (0: half of the free device memory).
  std::uint64_t maxDeviceBytes = 0;
};

/// The remesh rule: the mesh chunks whose meshes can change after `edit`
/// (an Editor call's lastWrite()) when these storage chunks are dirty (changed
/// since the last request): chunksAffectedBy of each changed storage chunk's own box
/// (edit.changedChunkBoxes; edit.changedBox where those are not known), exact for what the
/// edit wrote, and the storage-chunk rule (chunksAffectedByStorageChunks) for
/// dirty storage chunks the edit does not name (undo, redo, a script's canvas).
/// Both inputs increasing; the result sorted and unique.
std::vector<std::int64_t> meshChunksToRemesh(const ChunkedMarchingCubes& mc,
  const std::vector<std::int64_t>& dirtyStorageChunks, const EditResult& edit);

class EditSession
{
public:
  using Clock = std::chrono::steady_clock;

  explicit EditSession(std::shared_ptr<DictionaryVolume> volume, const EditSessionOptions& options = {});
  ~EditSession();
  EditSession(const EditSession&) = delete;
  EditSession& operator=(const EditSession&) = delete;

  // ---- the volume ---------------------------------------------------------
  /// Replaces the volume: history cleared, an open recording ends, brush kept;
  /// on the GPU the new volume is uploaded. Every mesh chunk counts as changed.
  void setVolume(std::shared_ptr<DictionaryVolume> volume);
  /// The host volume, synced first (on the GPU: the changed storage chunks come back).
  DictionaryVolume& volume();
  std::shared_ptr<DictionaryVolume> sharedVolume();
  /// The host copy as it is, without a sync: its geometry, options and
  /// dictionaries are always current; on the GPU its voxels lag until sync().
  const DictionaryVolume& hostVolume() const { return *this->Vol; }
  /// Brings the host copy up to date (nothing to do on the CPU).
  void sync();
  /// Storage chunks changed on the device and not yet on the host.
  std::size_t pendingStorageChunks() const;
  /// True when the volume lives on the GPU.
  bool onDevice() const { return this->Dev != nullptr; }
  /// Why the session runs on the CPU although the GPU was asked for ("" otherwise).
  const std::string& notice() const { return this->Notice; }
  const EditSessionOptions& options() const { return this->Opts; }
  /// Changes whenever the volume object is replaced (setVolume, a script's canvas N).
  int generation() const { return this->Generation; }
  /// Counts the calls that changed voxels (edits, undo, redo, scripts, replacing the volume).
  std::uint64_t changeCount() const { return this->Changes; }

  // ---- brush and edits ------------------------------------------------------
  BrushSettings& brush() { return this->Ed->brush; }
  StrokeSettings& stroke() { return this->Ed->stroke; }
  /// The editor (for InputDevice::pump and read-only queries; edit through the session).
  Editor& editor() { return *this->Ed; }

  EditResult dab(const Dab& d);
  EditResult strokeThrough(const std::vector<BrushSample>& samples);
  EditResult applyDabs(const std::vector<Dab>& dabs, BrushKind kind);
  void beginStroke();
  EditResult addSample(const BrushSample& s);
  EditResult endStroke();
  bool strokeOpen() const { return this->Ed->strokeOpen(); }
  /// Editor::pump under the session's lock; an interactive front end passes its
  /// frame budget as maxMillis so a flooding device cannot hold the frame.
  std::size_t pump(InputDevice& device, std::size_t maxSamples = 1024, int timeoutMs = 0, int maxMillis = -1);

  bool undo();
  bool redo();
  bool canUndo() const { return !this->Ed->strokeOpen() && this->Ed->canUndo(); }
  bool canRedo() const { return !this->Ed->strokeOpen() && this->Ed->canRedo(); }
  std::size_t undoCount() const { return this->Ed->undoCount(); }

  void startRecording() { this->Ed->startRecording(); }
  Recording stopRecording() { return this->Ed->stopRecording(); }
  bool recording() const { return this->Ed->recording(); }
  void play(const Recording& r, Interrupter& interrupter = nullInterrupter());

  /// Runs a script (docs/SCRIPTING.md) through this session's editor (see the
  /// header comment). Syntax errors change nothing; a run-time error keeps the
  /// edits made before it (each undoable) and throws ScriptError.
  /// options.canvas gives the options of a volume `canvas N` makes.
  void runScript(const std::string& source, const ScriptOptions& options = ScriptOptions());

  // ---- meshes -----------------------------------------------------------------
  const ChunkedMarchingCubes& mesher() const { return *this->Mesher; }
  int meshChunkEdge() const { return this->Mesher->options().chunkEdge; }
  /// Asks for the mesh of every mesh chunk (after opening a volume).
  void requestAllMeshes();
  /// The chunk meshes ready now, one per mesh chunk (a later one supersedes an
  /// earlier; an empty mesh means the chunk lost its surface). CPU: what the
  /// worker finished since the last call (never waits). GPU: meshes the chunks
  /// invalidated since the last call, on the device, in one batch. With
  /// `gatheredAt`: when each mesh's input was read (it shows every edit made
  /// before that time and none after).
  std::vector<ChunkMesh> collectMeshes(std::vector<Clock::time_point>* gatheredAt = nullptr);
  /// False while meshes are being made or held (holdMeshing) for a later release.
  bool meshingIdle() const;
  /// Releases held requests, then waits for the CPU worker.
  void waitMeshingIdle();
  /// Batching for a front end that applies several samples per frame (a
  /// backlog of input): from now on the mesh chunks that edits invalidate are
  /// gathered (lastRequest() still names each edit's own) and reach the CPU
  /// worker together at releaseMeshing(), so a chunk that a burst of samples
  /// touches again and again is meshed once, from the volume after all of
  /// them, instead of once per sample while the next samples are applied. The
  /// edits themselves are applied at once, exactly as without holding. On the
  /// GPU nothing changes (the device meshes at collectMeshes anyway).
  void holdMeshing() { this->Holding = true; }
  /// Hands the held requests to the worker (one request, their union).
  void releaseMeshing();
  bool meshingHeld() const { return this->Holding; }
  /// Level of detail for interactive strokes (CPU worker only; on the GPU
  /// nothing changes): from now on, a request of at least `minChunks` mesh
  /// chunks at once (one edit's, or a released hold's union) is meshed
  /// coarsely (ChunkMesh::level 1, ChunkedMarchingCubes::extractChunkCoarse:
  /// 1/8 of the cells), smaller ones at full resolution; 0 (the default): never
  /// coarse, 1: always. The volume is edited exactly as without it; only the
  /// meshes differ until refineMeshes().
  void setCoarseMeshing(std::size_t minChunks);
  std::size_t coarseMeshing() const { return this->CoarseMin; }
  /// Asks for the full-resolution mesh of every chunk whose last request was
  /// coarse (each supersedes that chunk's coarse mesh); returns how many. A
  /// front end calls it when the stroke ends, after releaseMeshing(). The
  /// request reaches the worker once it has finished what is queued (so the
  /// stroke's last coarse meshes are shown first): at once when it is idle,
  /// else at the next collectMeshes() that finds it idle, waitMeshingIdle(),
  /// or the next setCoarseMeshing(n > 0); meshingIdle() is false until then.
  std::size_t refineMeshes();
  /// Mesh chunks whose last request was coarse (refineMeshes would ask for them).
  std::size_t coarseChunks() const { return this->CoarseCount; }
  /// The mesh chunks the last edit call invalidated, and when (right after the edit).
  const std::vector<std::int64_t>& lastRequest() const { return this->LastRequest; }
  Clock::time_point lastRequestTime() const { return this->LastRequestAt; }
  /// Every mesh chunk invalidated since the last call (increasing; for change events).
  std::vector<std::int64_t> takeChangedMeshChunks();

private:
  void build(std::shared_ptr<DictionaryVolume> volume, const BrushSettings* brush, const StrokeSettings* stroke);
  void teardown();
  /// Queues the meshes invalidated by the last editor call (`edit` = its lastWrite()).
  void afterEdit(const EditResult& edit, bool changed);
  void request(const std::vector<std::int64_t>& ids);
  /// Hands one request to the CPU worker at the level setCoarseMeshing says.
  void toWorker(const std::vector<std::int64_t>& ids);
  /// Hands the pending refinement (refineMeshes) to the worker.
  void startRefine();
  std::unique_lock<std::mutex> lockSource();

  EditSessionOptions Opts;
  std::string Notice;
  std::shared_ptr<DictionaryVolume> Vol;
  std::unique_ptr<cuda::DeviceVolume> Dev;
  std::unique_ptr<Editor> Ed;
  std::unique_ptr<ChunkedMarchingCubes> Mesher;
  std::unique_ptr<MarchingCubesWorker> Worker;
  bool Holding = false;
  std::vector<std::int64_t> Held;        // CPU: held requests (sorted), for releaseMeshing
  std::size_t CoarseMin = 0;             // CPU: requests of this many chunks are coarse (0: never)
  std::vector<char> CoarseMark;          // CPU: per mesh chunk, 1 when its last request was coarse
  std::size_t CoarseCount = 0;           // CPU: chunks marked
  std::vector<std::int64_t> Refine;      // CPU: chunks to refine once the worker is idle (refineMeshes)
  std::vector<std::int64_t> DeviceQueue; // GPU: mesh chunks to mesh at the next collect (sorted)
  PackedChunkMeshes Packed;              // GPU: the device meshes' page-locked block (reused)
  std::vector<std::int64_t> Changed;     // since takeChangedMeshChunks
  std::vector<std::int64_t> LastRequest;
  Clock::time_point LastRequestAt;
  int Generation = 0;
  std::uint64_t Changes = 0;
};

} // namespace lvdif
