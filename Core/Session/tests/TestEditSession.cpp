// The CPU edit session: undo/redo against a replay oracle, meshes against a
// full re-mesh, scripts (undoable, canvas), recordings, change reports, and the
// remesh rule against brute force.
#include "ErrorTestUtil.h"
#include "SessionTestUtil.h"

#include "lvdif/Cuda.h"
#include "lvdif/Error.h"
#include "lvdif/InputDevice.h"

#include <gtest/gtest.h>

#include <algorithm>

using namespace sessiontest;

namespace
{
lvdif::EditSessionOptions cpuOptions()
{
  lvdif::EditSessionOptions o;
  o.device = lvdif::Device::Cpu;
  return o;
}

/// Two CPU sessions on copies of the 64^3 sphere (chunk edge 16): `tested`,
/// meshed whole into `store`, and `control`, the same edits another way.
struct SessionPair
{
  std::shared_ptr<lvdif::DictionaryVolume> start = sphereVolume(64, 16);
  lvdif::EditSession tested{ start->clone(), cpuOptions() };
  lvdif::EditSession control{ start->clone(), cpuOptions() };
  MeshStore store;
  SessionPair()
  {
    tested.requestAllMeshes();
    tested.waitMeshingIdle();
    store.take(tested.collectMeshes());
  }
};
} // namespace

TEST(EditSession, RandomStrokesUndoRedoEqualReplayAndMeshesEqualFullRemesh)
{
  for (std::uint32_t seed : { 1u, 2u, 3u })
  {
    auto start = sphereVolume(64, 16);
    lvdif::EditSession s(start->clone(), cpuOptions());
    EXPECT_FALSE(s.onDevice());
    EXPECT_EQ(s.notice(), "");
    MeshStore store;
    s.requestAllMeshes();
    const std::vector<Op> ops = randomOps(seed, 40, 64);
    for (std::size_t i = 0; i < ops.size(); ++i)
    {
      apply(s, ops[i]);
      if (i % 7 == 0)
        store.take(s.collectMeshes()); // meshes of intermediate states are superseded later
    }
    s.waitMeshingIdle();
    store.take(s.collectMeshes());
    const auto oracle = replay(*start, ops);
    EXPECT_EQ(decodedDifferences(s.volume(), *oracle), 0) << "seed " << seed;
    std::string problem;
    EXPECT_EQ(compareWithFullRemesh(store, s.volume(), s.mesher().options(), &problem), 0)
      << "seed " << seed << ": " << problem;
  }
}

TEST(EditSession, HeldMeshingMeshesTheUnionOnceAndEqualsSampleBySample)
{
  // A backlog of samples applied with meshing held and released once per
  // "frame": the volume equals the same samples applied one by one with a
  // request each, every chunk the burst invalidated is meshed once, and the
  // meshes equal a full re-mesh of the final volume.
  for (std::uint32_t seed : { 11u, 12u })
  {
    SessionPair pair;
    lvdif::EditSession &held = pair.tested, &oneByOne = pair.control;
    MeshStore& store = pair.store;
    for (const Op& op : randomOps(seed, 12, 64))
    {
      if (op.kind != Op::Stroke)
        continue;
      apply(oneByOne, op);
      held.brush() = op.brush;
      held.stroke() = op.stroke;
      held.beginStroke();
      std::vector<std::int64_t> invalidated;
      std::size_t burst = 0;
      for (std::size_t i = 0; i < op.samples.size(); ++i)
      {
        held.holdMeshing();
        EXPECT_TRUE(held.meshingHeld());
        held.addSample(op.samples[i]);
        const auto& ids = held.lastRequest();
        invalidated.insert(invalidated.end(), ids.begin(), ids.end());
        if (!ids.empty())
          EXPECT_FALSE(held.meshingIdle()) << "held requests count as pending";
        if (++burst == 3 || i + 1 == op.samples.size())
        {
          held.releaseMeshing();
          EXPECT_FALSE(held.meshingHeld());
          held.waitMeshingIdle();
          std::vector<lvdif::ChunkMesh> got = held.collectMeshes();
          std::sort(invalidated.begin(), invalidated.end());
          invalidated.erase(std::unique(invalidated.begin(), invalidated.end()), invalidated.end());
          std::vector<std::int64_t> meshed;
          for (const lvdif::ChunkMesh& m : got)
            meshed.push_back(m.chunkId);
          std::sort(meshed.begin(), meshed.end());
          EXPECT_EQ(meshed, invalidated) << "seed " << seed << ": the burst's union, each chunk once";
          store.take(std::move(got));
          invalidated.clear();
          burst = 0;
        }
      }
      held.endStroke(); // not held: straight to the worker
      held.waitMeshingIdle();
      store.take(held.collectMeshes());
    }
    held.waitMeshingIdle();
    oneByOne.waitMeshingIdle();
    store.take(held.collectMeshes());
    EXPECT_EQ(differences(held.volume(), oneByOne.volume()), 0) << "seed " << seed;
    std::string problem;
    EXPECT_EQ(compareWithFullRemesh(store, held.volume(), held.mesher().options(), &problem), 0)
      << "seed " << seed << ": " << problem;
  }
}

TEST(EditSession, CoarseStrokeMeshesAreRefinedToTheFullMeshes)
{
  // Level of detail during strokes: with coarse meshing on, a stroke's
  // requests are meshed at level 1 (the volume edited as without it: equal to
  // a session with it off); after refineMeshes() the newest mesh of every
  // chunk is the full-resolution one of the final volume.
  for (std::size_t minChunks : { std::size_t(1), std::size_t(4) })
  {
    SessionPair pair;
    lvdif::EditSession &lod = pair.tested, &plain = pair.control;
    MeshStore& store = pair.store;
    std::size_t coarse = 0, full = 0;
    for (const Op& op : randomOps(21, 12, 64))
    {
      if (op.kind != Op::Stroke)
        continue;
      apply(plain, op);
      lod.brush() = op.brush;
      lod.stroke() = op.stroke;
      lod.setCoarseMeshing(minChunks);
      lod.beginStroke();
      for (const lvdif::BrushSample& sample : op.samples)
      {
        lod.holdMeshing();
        lod.addSample(sample);
        lod.releaseMeshing();
        lod.waitMeshingIdle();
        for (const lvdif::ChunkMesh& m : lod.collectMeshes())
        {
          (m.level ? coarse : full)++;
          store.meshes[m.chunkId] = m;
        }
      }
      lod.endStroke();
      lod.setCoarseMeshing(0);
      const std::size_t pending = lod.coarseChunks();
      EXPECT_EQ(lod.refineMeshes(), pending);
      EXPECT_EQ(lod.coarseChunks(), 0u);
      lod.waitMeshingIdle();
      // in completion order: a coarse mesh still in flight at the refine comes before the full one
      store.take(lod.collectMeshes());
      for (const auto& kv : store.meshes)
        EXPECT_EQ(kv.second.level, 0) << "chunk " << kv.first << " still coarse after the refine";
    }
    EXPECT_GT(coarse, 10u) << "the strokes were meshed coarsely";
    if (minChunks > 1)
      EXPECT_GT(full, 0u) << "small requests stay at full resolution";
    EXPECT_EQ(differences(lod.volume(), plain.volume()), 0) << "the level of detail changes no voxel";
    std::string problem;
    EXPECT_EQ(compareWithFullRemesh(store, lod.volume(), lod.mesher().options(), &problem), 0)
      << "min chunks " << minChunks << ": " << problem;
  }
}

TEST(EditSession, WaitMeshingIdleReleasesHeldRequests)
{
  auto v = sphereVolume(64, 16);
  lvdif::EditSession s(v, cpuOptions());
  s.waitMeshingIdle();
  s.collectMeshes();
  s.holdMeshing();
  lvdif::Dab d;
  d.center = { 32, 32, 51 };
  d.radius = 5;
  s.dab(d);
  ASSERT_FALSE(s.lastRequest().empty());
  EXPECT_FALSE(s.meshingIdle());
  s.waitMeshingIdle();
  EXPECT_TRUE(s.meshingIdle());
  EXPECT_EQ(s.collectMeshes().size(), s.lastRequest().size());
}

TEST(EditSession, ChangedMeshChunksCoverEveryMeshThatChanged)
{
  auto v = sphereVolume(64, 16);
  lvdif::EditSession s(v, cpuOptions());
  lvdif::MarchingCubesOptions mo = s.mesher().options();
  s.takeChangedMeshChunks(); // the initial "everything"
  const std::vector<Op> ops = randomOps(7, 12, 64);
  for (const Op& op : ops)
  {
    auto snapshot = s.volume().clone();
    lvdif::ChunkedMarchingCubes mcBefore(*snapshot, mo);
    apply(s, op);
    const std::vector<std::int64_t> changed = s.takeChangedMeshChunks();
    EXPECT_TRUE(std::is_sorted(changed.begin(), changed.end()));
    lvdif::ChunkedMarchingCubes mcAfter(s.volume(), mo);
    for (std::int64_t id = 0; id < mcAfter.chunkCount(); ++id)
    {
      if (std::binary_search(changed.begin(), changed.end(), id))
        continue;
      EXPECT_EQ(compare(mcBefore.extractChunk(id), mcAfter.extractChunk(id)), "")
        << "mesh chunk " << id << " changed but was not reported";
    }
  }
}

TEST(EditSession, RemeshRuleCoversBruteForce)
{
  // every mesh chunk whose mesh differs after a dab is named by the rule
  auto v = sphereVolume(64, 16);
  lvdif::MarchingCubesOptions mo;
  mo.chunkEdge = 16;
  for (int k = 0; k < 6; ++k)
  {
    auto before = v->clone();
    lvdif::BrushSettings b;
    b.op = k % 2 ? lvdif::BrushOp::Subtract : lvdif::BrushOp::Add;
    lvdif::Dab d;
    d.center = { 20.0 + 4 * k, 32.0, 44.0 - 3 * k };
    d.radius = 3 + k;
    v->takeDirtyChunks();
    const lvdif::EditResult r = lvdif::applyDab(*v, d, b);
    lvdif::ChunkedMarchingCubes mcBefore(*before, mo), mcAfter(*v, mo);
    const std::vector<std::int64_t> ids = lvdif::meshChunksToRemesh(mcAfter, v->takeDirtyChunks(), r);
    for (std::int64_t id = 0; id < mcAfter.chunkCount(); ++id)
      if (!std::binary_search(ids.begin(), ids.end(), id))
        EXPECT_EQ(compare(mcBefore.extractChunk(id), mcAfter.extractChunk(id)), "") << "dab " << k << " chunk " << id;
  }
}

TEST(EditSession, ScriptEditsAreUndoable)
{
  auto v = sphereVolume(48, 16);
  lvdif::EditSession s(v, cpuOptions());
  const auto before = s.volume().clone();
  s.runScript("op subtract\nsphere 24 24 34 6\nop add\ncube 10 10 10 4");
  EXPECT_GT(differences(s.volume(), *before), 0);
  EXPECT_EQ(s.undoCount(), 2u); // one step per edit command
  EXPECT_TRUE(s.undo());
  EXPECT_TRUE(s.undo());
  EXPECT_EQ(differences(s.volume(), *before), 0);
  EXPECT_TRUE(s.redo());
  EXPECT_TRUE(s.redo());
  // the oracle: the same two primitives applied directly
  auto oracle = before->clone();
  lvdif::BrushSettings b;
  b.op = lvdif::BrushOp::Subtract;
  lvdif::Dab d;
  d.center = { 24, 24, 34 };
  d.radius = 6;
  lvdif::applyDab(*oracle, d, b);
  b.op = lvdif::BrushOp::Add;
  d.shape = lvdif::BrushShape::Cube;
  d.center = { 10, 10, 10 };
  d.radius = 4;
  lvdif::applyDab(*oracle, d, b);
  EXPECT_EQ(decodedDifferences(s.volume(), *oracle), 0);
}

TEST(EditSession, ScriptErrorKeepsEarlierEditsAndSyntaxErrorChangesNothing)
{
  auto v = sphereVolume(48, 16);
  lvdif::EditSession s(v, cpuOptions());
  const auto before = s.volume().clone();
  EXPECT_THROW(s.runScript("sphere 24 24 24 5\nsphere 1 2"), lvdif::ScriptError); // arity: a syntax error
  EXPECT_EQ(differences(s.volume(), *before), 0);
  EXPECT_EQ(s.undoCount(), 0u);
  try
  {
    s.runScript("sphere 24 24 34 5\nx = 1 / 0\nsphere 1 1 1 sqrt(-1)");
  }
  catch (const lvdif::ScriptError&)
  {
  }
  EXPECT_EQ(s.undoCount(), 1u);
  EXPECT_GT(differences(s.volume(), *before), 0);
  EXPECT_TRUE(s.undo());
  EXPECT_EQ(differences(s.volume(), *before), 0);
}

TEST(EditSession, ScriptErrorInsideAStrokeEndsTheStroke)
{
  // A run-time error between 'begin' and 'end' used to leave the session's
  // stroke open: no undo ("finish the open stroke first"), no new stroke.
  auto v = sphereVolume(48, 16);
  lvdif::EditSession s(v, cpuOptions());
  const auto before = s.volume().clone();
  EXPECT_THROW(s.runScript("radius 4\nbegin\npoint 10 24 34\npoint 38 24 34\nprint zz\nend"), lvdif::ScriptError);
  EXPECT_FALSE(s.strokeOpen());
  ASSERT_EQ(s.undoCount(), 1u); // the stroke's points so far, as at the end of a script
  // the oracle: the same two samples as one stroke, dab by dab on a copy
  auto oracle = before->clone();
  lvdif::StrokeSettings st;
  st.radius = 4;
  lvdif::BrushSample a, b;
  a.position = { 10, 24, 34 };
  b.position = { 38, 24, 34 };
  lvdif::applyDabs(*oracle, lvdif::strokeDabs({ a, b }, st), lvdif::BrushSettings());
  EXPECT_EQ(decodedDifferences(s.volume(), *oracle), 0);
  EXPECT_TRUE(s.undo());
  EXPECT_EQ(differences(s.volume(), *before), 0);
  s.beginStroke(); // the session takes new strokes again
  s.addSample(a);
  s.endStroke();
  EXPECT_EQ(s.undoCount(), 1u);

  // cancelled while a Basic stroke collects its points: the stroke is closed
  // and none of its dabs is applied after the cancel (all of them wait for 'end')
  struct CancelLater : lvdif::Interrupter
  {
    mutable int checks = 0;
    bool wasInterrupted() const override { return ++checks > 3; }
  } cancel;
  lvdif::ScriptOptions o;
  o.interrupter = &cancel;
  const auto beforeCancel = s.volume().clone();
  const std::size_t steps = s.undoCount();
  errortest::errorMessageOf(
    [&] { s.runScript("kind basic\nbegin\nfor i in 0..100000 { point 10 + i % 28, 24, 34 }\nend", o); },
    lvdif::ErrorCode::Cancelled);
  EXPECT_FALSE(s.strokeOpen());
  EXPECT_EQ(s.undoCount(), steps);
  EXPECT_EQ(differences(s.volume(), *beforeCancel), 0);
}

TEST(EditSession, StrokeThroughIsTheEditorsStroke)
{
  // The session made its own dabs for strokeThrough: a pinch stroke lost its
  // stroke direction (each dab pinched radially) and the editor's dab budget was not applied.
  auto v = sphereVolume(48, 16);
  lvdif::BrushSample a, b;
  a.position = { 14, 24, 34 };
  b.position = { 34, 24, 34 };
  lvdif::EditSession s(v->clone(), cpuOptions());
  s.brush().op = lvdif::BrushOp::Pinch;
  s.stroke().radius = 6;
  s.strokeThrough({ a, b });
  // the oracle: the same stroke's dabs, each directed along the stroke (the pinch rule, Brush.h)
  auto oracle = v->clone();
  std::vector<lvdif::Dab> dabs = lvdif::strokeDabs({ a, b }, s.stroke());
  ASSERT_GT(dabs.size(), 2u);
  for (std::size_t i = 0; i < dabs.size(); ++i)
  {
    const lvdif::Dab& from = dabs[i == 0 ? 0 : i - 1];
    const lvdif::Dab& to = dabs[i == 0 ? 1 : i];
    for (int k = 0; k < 3; ++k)
      dabs[i].vec[k] = to.center[k] - from.center[k];
  }
  lvdif::applyDabs(*oracle, dabs, s.brush());
  EXPECT_EQ(differences(s.volume(), *oracle), 0);

  s.editor().limits.maxDabsPerEdit = 3;
  EXPECT_THROW(s.strokeThrough({ a, b }), lvdif::Error); // the editor's budget: 14 dabs > 3
  EXPECT_EQ(s.undoCount(), 1u);
}

TEST(EditSession, ScriptCanvasReplacesTheVolumeAndKeepsTheScriptsBrush)
{
  lvdif::EditSession s(sphereVolume(32, 16), cpuOptions());
  const int g = s.generation();
  s.takeChangedMeshChunks();
  s.runScript("canvas 40\nradius 5\nsphere 20 20 20 8");
  EXPECT_NE(s.generation(), g);
  EXPECT_EQ(s.volume().dims()[0], 40);
  EXPECT_EQ(s.stroke().radius, 5);
  EXPECT_LT(s.volume().sdf(20, 20, 20), 0.0f);
  EXPECT_EQ(static_cast<std::int64_t>(s.takeChangedMeshChunks().size()), s.mesher().chunkCount());
  s.waitMeshingIdle();
  s.runScript("canvas clear");
  EXPECT_GT(s.volume().sdf(20, 20, 20), 0.0f);
  EXPECT_EQ(s.undoCount(), 0u); // a refill is not undoable: the history is gone
}

TEST(EditSession, RecordingPlaysBackBitExactInAnotherSession)
{
  auto start = sphereVolume(48, 16);
  lvdif::EditSession a(start->clone(), cpuOptions());
  a.startRecording();
  const std::vector<Op> ops = randomOps(11, 15, 48);
  for (const Op& op : ops)
    apply(a, op);
  a.runScript("op subtract\nsphere 10 30 20 4");
  const lvdif::Recording r = a.stopRecording();
  lvdif::EditSession b(start->clone(), cpuOptions());
  b.play(r);
  EXPECT_EQ(differences(a.volume(), b.volume()), 0);
  // the player's edits are undoable like any other
  EXPECT_GT(b.undoCount(), 0u);
}

// A playback that applies nothing is no change (the editor's document stays
// unmodified); one that fails after applying records is (they stay applied).
// Before, every failed playback counted as a change, a refused one too.
TEST(EditSession, RefusedPlaybackIsNoChange)
{
  lvdif::EditSession a(sphereVolume(48, 16), cpuOptions());
  a.startRecording();
  lvdif::Dab d;
  d.center = { 24, 24, 40 };
  d.radius = 4;
  a.dab(d);
  const lvdif::Recording r = a.stopRecording();
  ASSERT_EQ(r.records.size(), 1u);

  // another canvas: refused up front
  lvdif::EditSession other(sphereVolume(32, 16), cpuOptions());
  const std::uint64_t changes = other.changeCount();
  EXPECT_THROW(other.play(r), lvdif::Error);
  EXPECT_EQ(other.changeCount(), changes);
  EXPECT_EQ(other.undoCount(), 0u);

  // the same canvas, with an undo or a redo that has nothing to act on
  auto with = [&](lvdif::EditRecord::Type type, bool first) {
    lvdif::Recording out = r;
    lvdif::EditRecord e;
    e.type = type;
    out.records.insert(first ? out.records.begin() : out.records.end(), e);
    return out;
  };
  lvdif::EditSession b(sphereVolume(48, 16), cpuOptions());
  const std::uint64_t bChanges = b.changeCount();
  // first: nothing applied
  EXPECT_THROW(b.play(with(lvdif::EditRecord::Type::Undo, true)), lvdif::Error);
  EXPECT_EQ(b.changeCount(), bChanges);
  EXPECT_EQ(b.undoCount(), 0u);
  // after the dab: the dab stays, a change
  EXPECT_THROW(b.play(with(lvdif::EditRecord::Type::Redo, false)), lvdif::Error);
  EXPECT_EQ(b.changeCount(), bChanges + 1);
  EXPECT_EQ(b.undoCount(), 1u);
  EXPECT_EQ(differences(a.volume(), b.volume()), 0);
}

TEST(EditSession, SetVolumeKeepsTheBrushAndClearsHistory)
{
  lvdif::EditSession s(sphereVolume(32, 16), cpuOptions());
  s.stroke().radius = 7;
  s.brush().color = lvdif::Rgba{ 1, 2, 3, 255 };
  lvdif::Dab d;
  d.center = { 16, 16, 26 };
  d.radius = 4;
  s.dab(d);
  EXPECT_TRUE(s.canUndo());
  s.setVolume(sphereVolume(48, 16));
  EXPECT_FALSE(s.canUndo());
  EXPECT_EQ(s.stroke().radius, 7);
  EXPECT_EQ(s.brush().color.g, 2);
  EXPECT_EQ(s.volume().dims()[0], 48);
}

// The one smallest canvas of every editor: 2 voxels per axis (the session's
// marching cubes needs a cell), refused with checkCanvasDimensions' message
// (before, the mesher's own words); a refused setVolume keeps the session.
TEST(EditSession, RefusesAVolumeThinnerThanTwoVoxelsAndKeepsItsOwn)
{
  lvdif::VolumeOptions o;
  o.dims = { 8, 1, 8 };
  o.chunkEdge = 8;
  auto thin = std::make_shared<lvdif::DictionaryVolume>(o);
  const std::string rule = lvdif::DictionaryVolume::checkCanvasDimensions(o.dims);
  ASSERT_NE(rule, "");
  EXPECT_EQ(errortest::errorMessageOf([&] { lvdif::EditSession refused(thin, cpuOptions()); },
              lvdif::ErrorCode::InvalidArgument),
    rule);
  lvdif::EditSession s(sphereVolume(32, 16), cpuOptions());
  EXPECT_THROW(s.setVolume(thin), lvdif::Error);
  EXPECT_EQ(s.volume().dims()[1], 32);
  lvdif::Dab d;
  d.center = { 16, 16, 26 };
  d.radius = 4;
  EXPECT_GT(s.dab(d).changedVoxels, 0); // the session still edits its volume
  o.dims = { 2, 2, 2 };
  EXPECT_EQ(lvdif::DictionaryVolume::checkCanvasDimensions(o.dims), "");
  EXPECT_NO_THROW(lvdif::EditSession(std::make_shared<lvdif::DictionaryVolume>(o), cpuOptions()));
}

TEST(EditSession, AutoWithoutAGpuRunsOnTheCpuWithOneNotice)
{
  if (lvdif::resolveDevice(lvdif::Device::Cuda) == lvdif::Device::Cuda)
    GTEST_SKIP() << "a GPU is present";
  lvdif::EditSessionOptions o;
  o.device = lvdif::Device::Auto;
  lvdif::EditSession s(sphereVolume(32, 16), o);
  EXPECT_FALSE(s.onDevice());
  EXPECT_NE(s.notice(), "");
  lvdif::Dab d;
  d.center = { 16, 16, 26 };
  d.radius = 4;
  EXPECT_GT(s.dab(d).changedVoxels, 0);
}

// The CPU path is quiet: sessions that fall back from Auto print at most the
// process's one notice (resolveDevice's), none in a build without CUDA, while
// notice() still says why. Before, every session asked resolveDevice for Cuda
// whatever its options: a CPU-only build printed "built without CUDA" for an
// Auto session, and the editor printed the session's notice beside it.
TEST(EditSession, AutoFallbackPrintsAtMostOneNotice)
{
  if (lvdif::cuda::available())
    GTEST_SKIP() << "a GPU is present";
  lvdif::EditSessionOptions o;
  o.device = lvdif::Device::Auto;
  testing::internal::CaptureStderr();
  {
    lvdif::EditSession a(sphereVolume(32, 16), o);
    EXPECT_NE(a.notice(), "");
    lvdif::EditSession b(sphereVolume(32, 16), o);
  }
  const std::string err = testing::internal::GetCapturedStderr();
  if (lvdif::cuda::compiled())
    EXPECT_LE(std::count(err.begin(), err.end(), '\n'), 1) << err;
  else
    EXPECT_EQ(err, "");
}

TEST(EditSession, MeshingOffStillReportsChangedMeshChunks)
{
  lvdif::EditSessionOptions o = cpuOptions();
  o.meshing = false;
  lvdif::EditSession s(sphereVolume(32, 16), o);
  s.takeChangedMeshChunks();
  lvdif::Dab d;
  d.center = { 16, 16, 26 };
  d.radius = 4;
  s.dab(d);
  EXPECT_FALSE(s.takeChangedMeshChunks().empty());
  EXPECT_TRUE(s.collectMeshes().empty());
  EXPECT_TRUE(s.meshingIdle());
}

TEST(EditSession, PumpStopsAtItsTimeBudget)
{
  // every sample is a slow drill dab; a budget of 0 ms stops after the first
  auto v = sphereVolume(64, 16);
  lvdif::EditSession s(v, cpuOptions());
  s.stroke().kind = lvdif::BrushKind::Drill;
  std::uint64_t produced = 0;
  lvdif::ScriptDevice dev([&](std::uint64_t i, lvdif::BrushSample& b) {
    produced = i + 1;
    b.position = { 10.0 + 0.5 * double(i % 80), 32, 32 };
    b.buttons = 1;
    return i < 500;
  });
  EXPECT_EQ(s.pump(dev, 1000, 0, 0), 1u);
  EXPECT_EQ(produced, 1u);
  // without a budget the same call takes everything up to maxSamples
  EXPECT_EQ(s.pump(dev, 100, 0), 100u);
  EXPECT_EQ(produced, 101u);
}
