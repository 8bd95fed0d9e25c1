// Removing every chunk actor is linear in the number of chunks (opening a new
// canvas after a large one stalled the editor: 30,000 chunks took minutes).
// The work is counted, not timed, on two structures VTK scans from the start:
//
// - The renderer's props: vtkRenderer::RemoveActor finds the prop by a scan of
//   its list (vtkViewport::HasViewProp, vtkCollection::RemoveItem). The chunks
//   are added in descending id order (as meshes may come); the scans' length is
//   read from the list itself (an observer of its ModifiedEvent sees where each
//   removal changed it). The manager removed its actors in chunk id order, the
//   reverse of the list: n^2 / 2 steps. Bound: n steps (plus the few props not
//   the manager's, which stand before them).
// - The VBO cache: VTK 9.1 releases a VBO by scanning every entry of the cache
//   it was made in (vtkOpenGLVertexBufferObjectCache::RemoveVBO). The chunk
//   mappers made theirs in the context's cache, one entry per array of every
//   chunk (6 n: all of them scanned for each of the 6 n buffers released).
//   Bound: the context's cache holds no chunk's array, and each chunk mapper's
//   own cache only its own arrays (at most 8).
#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkChunkActorManager.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLVertexBufferObjectCache.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkTetrahedralColorMapper.h"
#include "ChunkTestData.h"
#include "RenderTestHarness.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace lvdiftest;

namespace
{
/// The number of arrays a VBO cache holds (its map is protected: read through
/// a member pointer named in a class derived from it).
struct CacheEntries : vtkOpenGLVertexBufferObjectCache
{
  static std::size_t of(vtkOpenGLVertexBufferObjectCache* cache)
  {
    constexpr auto map = &CacheEntries::MappedVBOs;
    return cache ? (cache->*map).size() : 0;
  }
};

std::vector<vtkProp*> propsOf(vtkRenderer* ren)
{
  std::vector<vtkProp*> out;
  vtkPropCollection* props = ren->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* p = props->GetNextProp(it))
    out.push_back(p);
  return out;
}

/// Counts the list steps of removals from a renderer's props: at each change
/// of the list, the index of the first prop that differs from before.
struct ScanCounter
{
  vtkRenderer* Ren = nullptr;
  std::vector<vtkProp*> Before;
  long long Steps = 0;
  long long Removals = 0;
  void changed()
  {
    std::vector<vtkProp*> now = propsOf(this->Ren);
    if (now.size() + 1 != this->Before.size())
    {
      this->Before = now;
      return; // not a removal of one
    }
    std::size_t i = 0;
    while (i < now.size() && now[i] == this->Before[i])
      ++i;
    this->Steps += static_cast<long long>(i) + 1;
    ++this->Removals;
    this->Before = now;
  }
};
} // namespace

int TestRemoveManyChunks(int, char*[])
{
  int failures = 0;
  auto check = checkCounter(failures);
  auto window = makeTestWindow(200, 200);
  vtkNew<vtkRenderer> ren;
  window->AddRenderer(ren);
  // a prop that is not the manager's, added before its chunks (as the editor's brush)
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> other;
  other->SetMapper(sphereMapper);
  ren->AddActor(other);
  window->Render();
  auto* gl = vtkOpenGLRenderWindow::SafeDownCast(window);
  check(gl != nullptr, "an OpenGL render window");
  if (!gl)
    return EXIT_FAILURE;
  const std::size_t sharedBefore = CacheEntries::of(gl->GetVBOCache());

  // one small chunk mesh (with the tetrahedral contract: the chunk mappers'
  // extra arrays) shown by n chunk ids, added from the highest id down
  auto img = sdfImage(6, [](double x, double y, double z) {
    return std::sqrt((x - 2.5) * (x - 2.5) + (y - 2.5) * (y - 2.5) + (z - 2.5) * (z - 2.5)) - 1.6;
  });
  vtkSmartPointer<vtkPolyData> mesh = contractMesh(img, checkerColor);
  // LVDIF_TEST_CHUNKS: another number of chunks, to measure (the time is printed, never checked)
  const char* given = std::getenv("LVDIF_TEST_CHUNKS");
  const int n = given && std::atoi(given) > 0 ? std::atoi(given) : 1500;
  vtkNew<vtkChunkActorManager> mgr;
  mgr->SetRenderer(ren);
  for (int id = n - 1; id >= 0; --id)
  {
    vtkNew<vtkPolyData> copy;
    copy->DeepCopy(mesh); // arrays of its own, as every chunk's
    mgr->SetChunk(id, copy);
  }
  window->Render();
  check(mgr->GetNumberOfChunks() == n, "every chunk is shown");

  const std::size_t shared = CacheEntries::of(gl->GetVBOCache());
  std::printf("the context's VBO cache: %zu arrays before the chunks, %zu with %d chunks shown\n", sharedBefore, shared, n);
  check(shared == sharedBefore, "the context's VBO cache holds no chunk's array");
  std::size_t largestOwn = 0;
  for (vtkIdType id = 0; id < n; ++id)
  {
    auto* m = vtkTetrahedralColorMapper::SafeDownCast(mgr->GetChunkActor(id)->GetMapper());
    largestOwn = std::max(largestOwn, m ? CacheEntries::of(m->GetOwnVBOCache()) : 1000);
  }
  std::printf("the largest chunk mapper's own VBO cache: %zu arrays\n", largestOwn);
  check(largestOwn >= 1 && largestOwn <= 8, "each chunk's buffers are in its mapper's own small cache");

  ScanCounter counter;
  counter.Ren = ren;
  counter.Before = propsOf(ren);
  vtkNew<vtkCallbackCommand> cb;
  cb->SetClientData(&counter);
  cb->SetCallback([](vtkObject*, unsigned long, void* cd, void*) { static_cast<ScanCounter*>(cd)->changed(); });
  ren->GetViewProps()->AddObserver(vtkCommand::ModifiedEvent, cb);
  const bool counting = n <= 5000; // the counter itself is quadratic
  if (!counting)
    ren->GetViewProps()->RemoveAllObservers();
  const auto t0 = std::chrono::steady_clock::now();
  mgr->RemoveAllChunks();
  std::printf("RemoveAllChunks of %d chunks: %.1f ms\n", n,
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  ren->GetViewProps()->RemoveAllObservers();
  if (!counting)
  {
    std::printf("%s\n", failures ? "FAILED" : "passed (removal not counted)");
    return failures ? EXIT_FAILURE : EXIT_SUCCESS;
  }
  std::printf("removals seen: %lld, list steps: %lld (bound %d)\n", counter.Removals, counter.Steps, 3 * n);
  check(counter.Removals == n, "each chunk actor left the renderer once");
  check(counter.Steps <= 3LL * n, "removing n chunk actors scans O(n) list entries, not O(n^2)");
  check(mgr->GetNumberOfChunks() == 0 && propsOf(ren).size() == 1, "only the other prop is left");
  window->Render();
  check(CacheEntries::of(gl->GetVBOCache()) == sharedBefore, "the context's VBO cache is as before");

  std::printf("%s\n", failures ? "FAILED" : "passed");
  return failures ? EXIT_FAILURE : EXIT_SUCCESS;
}
