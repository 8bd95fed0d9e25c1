// A background marching cubes worker (paper Sect. 3.3: the kernel runs in its
// own thread so the interactive thread never waits for it).
//
// Snapshot semantics: the worker copies the input of a batch of chunks
// (ChunkedMarchingCubes::gather, its threads in parallel) while holding
// sourceMutex(), then meshes the copies without the lock. Whoever writes the volume (or float grid) holds
// sourceMutex() during the write. Each finished chunk mesh therefore reflects
// the volume as it was at one instant between two locked edits; different
// chunks may reflect different instants. To converge, the editing thread
// requests (again) every chunk its edit touched after the edit; a chunk
// requested while it is being meshed is meshed once more afterwards, so the
// last mesh collected for every chunk reflects the last edit.
//
// Results: collect() never blocks on meshing; it returns the meshes finished
// since the previous call in completion order (a later mesh of a chunk
// supersedes an earlier one; an empty mesh means "the chunk has no surface
// any more").
#pragma once

#include "lvdif/ChunkedMarchingCubes.h"

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

namespace lvdif
{

class MarchingCubesWorker
{
public:
  /// Starts the thread. `mesher` (and its source) must outlive the worker.
  explicit MarchingCubesWorker(const ChunkedMarchingCubes& mesher);
  /// Drops pending work and joins the thread.
  ~MarchingCubesWorker();
  MarchingCubesWorker(const MarchingCubesWorker&) = delete;
  MarchingCubesWorker& operator=(const MarchingCubesWorker&) = delete;

  /// Hold this while writing the source (and while calling takeDirtyChunks).
  std::mutex& sourceMutex() { return this->SourceMutex; }

  /// Queues marching cubes chunk ids; ids already queued are not queued twice.
  /// `level`: 0 full resolution, 1 coarse (ChunkedMarchingCubes::
  /// extractChunkCoarse; ChunkMesh::level says which a mesh is). A chunk
  /// queued again takes the level of the latest request.
  void request(const std::vector<std::int64_t>& chunkIds, int level = 0);
  /// Queues every chunk (cheap for empty ones: a range test).
  void requestAll();
  /// The meshes finished since the last call (never waits for meshing). With
  /// `gatheredAt`, also when each mesh's input was read from the source (under
  /// sourceMutex()): a mesh shows every write made under that mutex before this
  /// time and none after it (for exact edit-to-mesh latency).
  std::vector<ChunkMesh> collect(std::vector<std::chrono::steady_clock::time_point>* gatheredAt = nullptr);
  /// True when nothing is queued or being meshed.
  bool idle() const;
  /// Blocks until idle() (for tests and scripts).
  void waitIdle();
  /// Drops queued requests (a chunk being meshed still finishes).
  void cancelPending();
  /// Stops and joins the thread; requests made afterwards throw Error(InvalidArgument).
  void shutdown();

private:
  void run();

  const ChunkedMarchingCubes& Mesher;
  std::mutex SourceMutex;
  mutable std::mutex QueueMutex;
  std::condition_variable Wake, Idle;
  std::deque<std::int64_t> Queue;
  std::vector<char> Queued; // 0: not queued; else the requested level + 1
  std::vector<ChunkMesh> Done;
  std::vector<std::chrono::steady_clock::time_point> DoneGathered; // parallel to Done
  int InFlight = 0;
  bool Stop = false;
  std::thread Thread;
};

} // namespace lvdif
