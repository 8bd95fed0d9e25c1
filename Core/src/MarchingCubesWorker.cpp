// The background marching cubes thread; see MarchingCubesWorker.h for the
// snapshot semantics.
#include "lvdif/MarchingCubesWorker.h"

#include "lvdif/Error.h"

namespace lvdif
{

MarchingCubesWorker::MarchingCubesWorker(const ChunkedMarchingCubes& mesher)
  : Mesher(mesher)
  , Queued(static_cast<std::size_t>(mesher.chunkCount()), 0)
{
  this->Thread = std::thread([this] { this->run(); });
}

MarchingCubesWorker::~MarchingCubesWorker() { this->shutdown(); }

void MarchingCubesWorker::request(const std::vector<std::int64_t>& chunkIds)
{
  {
    std::lock_guard<std::mutex> lock(this->QueueMutex);
    require(!this->Stop, "marching cubes worker: request after shutdown");
    for (std::int64_t id : chunkIds)
    {
      require(id >= 0 && id < this->Mesher.chunkCount(), "marching cubes worker: chunk id out of range");
      if (!this->Queued[id])
      {
        this->Queued[id] = 1;
        this->Queue.push_back(id);
      }
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

std::vector<ChunkMesh> MarchingCubesWorker::collect()
{
  std::lock_guard<std::mutex> lock(this->QueueMutex);
  std::vector<ChunkMesh> out;
  out.swap(this->Done);
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
  for (;;)
  {
    std::int64_t id;
    {
      std::unique_lock<std::mutex> lock(this->QueueMutex);
      this->Wake.wait(lock, [this] { return this->Stop || !this->Queue.empty(); });
      if (this->Stop) return;
      id = this->Queue.front();
      this->Queue.pop_front();
      this->Queued[id] = 0; // a request from now on means "mesh it again"
      ++this->InFlight;
    }
    ChunkMesh mesh;
    bool ok = true;
    try
    {
      std::unique_ptr<ChunkedMarchingCubes::ChunkInput> input;
      {
        std::lock_guard<std::mutex> source(this->SourceMutex);
        input = this->Mesher.gather(id);
      }
      if (input)
      {
        mesh = this->Mesher.mesh(*input);
      }
      else
      {
        mesh.chunkId = id;
        mesh.chunkCoord = this->Mesher.chunkCoord(id);
        mesh.cells = this->Mesher.chunkCells(id);
      }
    }
    catch (const Error&)
    {
      ok = false; // out of memory for one chunk: leave its previous mesh in place
    }
    {
      std::lock_guard<std::mutex> lock(this->QueueMutex);
      if (ok) this->Done.push_back(std::move(mesh));
      --this->InFlight;
      if (this->Queue.empty() && this->InFlight == 0) this->Idle.notify_all();
    }
  }
}

} // namespace lvdif
