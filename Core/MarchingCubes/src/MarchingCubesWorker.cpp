// The background marching cubes thread; see MarchingCubesWorker.h for the
// snapshot semantics.
#include "lvdif/MarchingCubesWorker.h"

#include "lvdif/Error.h"

#include <omp.h>

#include <algorithm>

namespace lvdif
{

MarchingCubesWorker::MarchingCubesWorker(const ChunkedMarchingCubes& mesher)
  : Mesher(mesher)
  , Queued(static_cast<std::size_t>(mesher.chunkCount()), 0)
{
  this->Thread = std::thread([this] { this->run(); });
}

MarchingCubesWorker::~MarchingCubesWorker() { this->shutdown(); }

void MarchingCubesWorker::request(const std::vector<std::int64_t>& chunkIds, int level)
{
  require(level == 0 || level == 1, "marching cubes worker: level of detail is not 0 or 1");
  {
    std::lock_guard<std::mutex> lock(this->QueueMutex);
    require(!this->Stop, "marching cubes worker: request after shutdown");
    for (std::int64_t id : chunkIds)
    {
      require(id >= 0 && id < this->Mesher.chunkCount(), "marching cubes worker: chunk id out of range");
      if (!this->Queued[id])
        this->Queue.push_back(id);
      this->Queued[id] = static_cast<char>(level + 1);
    }
  }
  this->Wake.notify_one();
}

void MarchingCubesWorker::requestAll()
{
  std::vector<std::int64_t> all(static_cast<std::size_t>(this->Mesher.chunkCount()));
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<std::int64_t>(i);
  this->request(all);
}

std::vector<ChunkMesh> MarchingCubesWorker::collect(std::vector<std::chrono::steady_clock::time_point>* gatheredAt)
{
  std::lock_guard<std::mutex> lock(this->QueueMutex);
  std::vector<ChunkMesh> out;
  out.swap(this->Done);
  if (gatheredAt)
    gatheredAt->swap(this->DoneGathered);
  this->DoneGathered.clear();
  return out;
}

bool MarchingCubesWorker::idle() const
{
  std::lock_guard<std::mutex> lock(this->QueueMutex);
  return this->Queue.empty() && this->InFlight == 0;
}

void MarchingCubesWorker::waitIdle()
{
  std::unique_lock<std::mutex> lock(this->QueueMutex);
  this->Idle.wait(lock, [this] { return (this->Queue.empty() && this->InFlight == 0) || this->Stop; });
}

void MarchingCubesWorker::cancelPending()
{
  std::lock_guard<std::mutex> lock(this->QueueMutex);
  for (std::int64_t id : this->Queue) this->Queued[id] = 0;
  this->Queue.clear();
  if (this->InFlight == 0) this->Idle.notify_all();
}

void MarchingCubesWorker::shutdown()
{
  {
    std::lock_guard<std::mutex> lock(this->QueueMutex);
    if (this->Stop && !this->Thread.joinable()) return;
    this->Stop = true;
    for (std::int64_t id : this->Queue) this->Queued[id] = 0;
    this->Queue.clear();
  }
  this->Wake.notify_all();
  this->Idle.notify_all();
  if (this->Thread.joinable()) this->Thread.join();
}

void MarchingCubesWorker::run()
{
  // Takes a batch of up to BatchPerThread chunks per OpenMP thread: the batch
  // is gathered under the source lock (a snapshot of one instant, as before),
  // the threads gathering in parallel, then meshed in parallel without the
  // lock. A batch of several chunks a thread spreads the work evenly and pays
  // the parallel regions' start once per batch, not per chunk. A GPU mesher
  // serializes on the device anyway: one chunk at a time.
  constexpr int BatchPerThread = 4;
  const bool gpu = this->Mesher.options().device == Device::Cuda;
  const int threads = gpu ? 1 : std::max(1, omp_get_max_threads());
  const int width = gpu ? 1 : threads * BatchPerThread;
  std::vector<std::int64_t> ids;
  std::vector<int> levels;
  // one reusable input per slot (no allocation per chunk once warm)
  std::vector<ChunkedMarchingCubes::ChunkInput> inputs(static_cast<std::size_t>(width));
  std::vector<char> has(static_cast<std::size_t>(width));
  for (;;)
  {
    ids.clear();
    levels.clear();
    {
      std::unique_lock<std::mutex> lock(this->QueueMutex);
      this->Wake.wait(lock, [this] { return this->Stop || !this->Queue.empty(); });
      if (this->Stop) return;
      while (!this->Queue.empty() && static_cast<int>(ids.size()) < width)
      {
        const std::int64_t id = this->Queue.front();
        this->Queue.pop_front();
        levels.push_back(this->Queued[id] - 1);
        this->Queued[id] = 0; // a request from now on means "mesh it again"
        ids.push_back(id);
      }
      this->InFlight += static_cast<int>(ids.size());
    }
    const int n = static_cast<int>(ids.size());
    std::vector<ChunkMesh> meshes(static_cast<std::size_t>(n));
    std::vector<char> ok(static_cast<std::size_t>(n), 1);
    std::chrono::steady_clock::time_point gathered;
    [[maybe_unused]] const int team = std::min(n, threads); // read only by the pragmas (unused without OpenMP)
    {
      std::lock_guard<std::mutex> source(this->SourceMutex);
      gathered = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(dynamic, 1) num_threads(team) if (team > 1)
      for (int i = 0; i < n; ++i)
      {
        try
        {
          has[i] = this->Mesher.gather(ids[i], inputs[i], levels[i]);
        }
        catch (const Error&)
        {
          ok[i] = 0; // out of memory for one chunk: leave its previous mesh in place
        }
      }
    }
#pragma omp parallel for schedule(dynamic, 1) num_threads(team) if (team > 1)
    for (int i = 0; i < n; ++i)
    {
      if (!ok[i]) continue;
      try
      {
        if (has[i])
        {
          meshes[i] = this->Mesher.mesh(inputs[i]);
        }
        else
        {
          meshes[i].chunkId = ids[i];
          meshes[i].level = levels[i];
          meshes[i].chunkCoord = this->Mesher.chunkCoord(ids[i]);
          meshes[i].cells = this->Mesher.chunkCells(ids[i]);
        }
      }
      catch (const Error&)
      {
        ok[i] = 0;
      }
    }
    {
      std::lock_guard<std::mutex> lock(this->QueueMutex);
      for (int i = 0; i < n; ++i)
        if (ok[i])
        {
          this->Done.push_back(std::move(meshes[i]));
          this->DoneGathered.push_back(gathered);
        }
      this->InFlight -= n;
      if (this->Queue.empty() && this->InFlight == 0) this->Idle.notify_all();
    }
  }
}

} // namespace lvdif
