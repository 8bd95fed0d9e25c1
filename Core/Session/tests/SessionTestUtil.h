// Helpers of the session tests: seeded random edit sequences, a replay oracle
// for the volume (the surviving edits applied from scratch with lvdif::applyDabs,
// no undo stack involved), and a comparison of chunk meshes that does not depend
// on vertex order (the CPU numbers vertices in sweep order, CUDA in point order).
#pragma once

#include "lvdif/AnalyticFill.h"
#include "lvdif/EditSession.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace sessiontest
{

inline std::shared_ptr<lvdif::DictionaryVolume> sphereVolume(std::int64_t n, int edge)
{
  lvdif::VolumeOptions o;
  o.dims = { n, n, n };
  o.chunkEdge = edge;
  auto v = std::make_shared<lvdif::DictionaryVolume>(o);
  const double c = 0.5 * (n - 1);
  lvdif::fillFromFunction(*v, lvdif::sphereSdf(c, c, c, 0.3 * n));
  v->takeDirtyChunks();
  return v;
}

/// One operation of a random session.
struct Op
{
  enum Kind
  {
    Stroke,
    Dab,
    Undo,
    Redo
  } kind = Stroke;
  lvdif::BrushSettings brush;
  lvdif::StrokeSettings stroke;
  std::vector<lvdif::BrushSample> samples; // Stroke: the samples; Dab: the first is the centre
};

/// A seeded sequence of strokes (every brush kind, add/subtract/paint, sphere and
/// cube, blends), single dabs, undo and redo, inside an n^3 volume.
inline std::vector<Op> randomOps(std::uint32_t seed, int count, double n)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Op> ops;
  for (int i = 0; i < count; ++i)
  {
    Op op;
    const double r = u(rng);
    op.kind = r < 0.15 ? Op::Undo : r < 0.25 ? Op::Redo : r < 0.4 ? Op::Dab : Op::Stroke;
    op.brush.op = static_cast<lvdif::BrushOp>(static_cast<int>(u(rng) * 3) % 3);
    op.brush.color = lvdif::Rgba{ static_cast<std::uint8_t>(u(rng) * 255), static_cast<std::uint8_t>(u(rng) * 255),
      static_cast<std::uint8_t>(u(rng) * 255), 255 };
    op.brush.blend = u(rng) < 0.3 ? 2.0 * u(rng) : 0.0;
    op.stroke.kind = static_cast<lvdif::BrushKind>(1 + static_cast<int>(u(rng) * 3) % 3);
    op.stroke.shape = u(rng) < 0.7 ? lvdif::BrushShape::Sphere : lvdif::BrushShape::Cube;
    op.stroke.radius = 2 + 0.1 * n * u(rng);
    std::array<double, 3> p{ n * (0.15 + 0.7 * u(rng)), n * (0.15 + 0.7 * u(rng)), n * (0.15 + 0.7 * u(rng)) };
    const int samples = op.kind == Op::Dab ? 1 : 2 + static_cast<int>(u(rng) * 8);
    for (int s = 0; s < samples; ++s)
    {
      lvdif::BrushSample b;
      b.position = p;
      b.pressure = u(rng) < 0.5 ? -1 : 0.3 + 0.7 * u(rng);
      b.buttons = 1;
      b.time = 0.02 * s;
      op.samples.push_back(b);
      for (int a = 0; a < 3; ++a)
        p[a] = std::min(n - 1.0, std::max(0.0, p[a] + 0.06 * n * (u(rng) - 0.5)));
    }
    ops.push_back(op);
  }
  return ops;
}

/// Applies one operation to a session the way a front end does (samples one by one).
inline void apply(lvdif::EditSession& s, const Op& op)
{
  if (op.kind == Op::Undo)
  {
    s.undo();
    return;
  }
  if (op.kind == Op::Redo)
  {
    s.redo();
    return;
  }
  s.brush() = op.brush;
  s.stroke() = op.stroke;
  if (op.kind == Op::Dab)
  {
    lvdif::Dab d;
    d.shape = op.stroke.shape;
    d.center = op.samples[0].position;
    d.radius = op.stroke.radius;
    s.dab(d);
    return;
  }
  s.beginStroke();
  for (const lvdif::BrushSample& b : op.samples)
    s.addSample(b);
  s.endStroke();
}

/// Voxels whose 4 bytes differ (two volumes that added the same colours in the same order).
inline std::int64_t differences(const lvdif::DictionaryVolume& a, const lvdif::DictionaryVolume& b)
{
  std::int64_t n = 0;
  const auto& d = a.dims();
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
        n += a.get(x, y, z) != b.get(x, y, z) ? 1 : 0;
  return n;
}

/// Voxels whose SDF key or colour (RGBA through each volume's own colour
/// dictionary) differ: for a replay, whose dictionary lacks the undone edits' colours.
inline std::int64_t decodedDifferences(const lvdif::DictionaryVolume& a, const lvdif::DictionaryVolume& b)
{
  std::int64_t n = 0;
  const auto& d = a.dims();
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
      {
        const lvdif::Voxel u = a.get(x, y, z), v = b.get(x, y, z);
        n += u.sdf != v.sdf || a.colors()[u.color].packed() != b.colors()[v.color].packed() ? 1 : 0;
      }
  return n;
}

inline std::vector<lvdif::Dab> dabsOf(const Op& op)
{
  if (op.kind != Op::Dab)
    return lvdif::strokeDabs(op.samples, op.stroke);
  lvdif::Dab d;
  d.shape = op.stroke.shape;
  d.center = op.samples[0].position;
  d.radius = op.stroke.radius;
  return { d };
}

/// The replay oracle: the state after the operations, computed without any undo
/// machinery. The surviving edits (an edit that changes no voxel is no step:
/// it neither counts for undo nor drops the redo list) are applied from scratch
/// to a copy of the start volume with lvdif::applyDabs.
inline std::unique_ptr<lvdif::DictionaryVolume> replay(const lvdif::DictionaryVolume& start, const std::vector<Op>& ops)
{
  std::vector<const Op*> done, undone;
  auto rebuild = [&] {
    auto v = start.clone();
    for (const Op* op : done)
      lvdif::applyDabs(*v, dabsOf(*op), op->brush);
    return v;
  };
  auto current = start.clone();
  for (const Op& op : ops)
  {
    if (op.kind == Op::Undo)
    {
      if (!done.empty())
      {
        undone.push_back(done.back());
        done.pop_back();
        current = rebuild();
      }
    }
    else if (op.kind == Op::Redo)
    {
      if (!undone.empty())
      {
        done.push_back(undone.back());
        undone.pop_back();
        current = rebuild();
      }
    }
    else if (lvdif::applyDabs(*current, dabsOf(op), op.brush).changedVoxels > 0)
    {
      done.push_back(&op);
      undone.clear();
    }
  }
  return current;
}

/// A chunk mesh in a vertex-order independent form: per cut edge (edge id) the
/// point, normal and colour bits; the triangles as edge-id triples rotated to
/// start at the smallest id (orientation kept).
struct Canon
{
  std::map<std::uint64_t, std::array<std::uint32_t, 7>> vertices;
  std::multiset<std::array<std::uint64_t, 3>> triangles;
  std::multiset<std::pair<std::int64_t, std::array<lvdif::ColorKey, 8>>> cells;
};

inline Canon canon(const lvdif::ChunkMesh& m)
{
  Canon c;
  for (std::size_t i = 0; i < m.points.size(); ++i)
  {
    std::array<std::uint32_t, 7> v{};
    std::memcpy(&v[0], &m.points[i], 12);
    if (!m.normals.empty())
      std::memcpy(&v[3], &m.normals[i], 12);
    if (!m.colors.empty())
      std::memcpy(&v[6], &m.colors[i], 4);
    c.vertices[m.edgeIds[i]] = v;
  }
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
  {
    std::array<std::uint64_t, 3> e{ m.edgeIds[m.triangles[t][0]], m.edgeIds[m.triangles[t][1]],
      m.edgeIds[m.triangles[t][2]] };
    int first = 0;
    for (int k = 1; k < 3; ++k)
      if (e[k] < e[first])
        first = k;
    c.triangles.insert({ e[first], e[(first + 1) % 3], e[(first + 2) % 3] });
    std::array<lvdif::ColorKey, 8> keys{};
    if (!m.cornerColors.empty())
      keys = m.cornerColors[t];
    c.cells.insert({ m.triangleCells.empty() ? -1 : m.triangleCells[t], keys });
  }
  return c;
}

/// "" when the meshes are equal (same vertices bit for bit, same triangles), else what differs.
inline std::string compare(const lvdif::ChunkMesh& a, const lvdif::ChunkMesh& b)
{
  const Canon x = canon(a), y = canon(b);
  std::ostringstream s;
  if (x.vertices != y.vertices)
    s << "vertices differ (" << x.vertices.size() << " vs " << y.vertices.size() << ") ";
  if (x.triangles != y.triangles)
    s << "triangles differ (" << x.triangles.size() << " vs " << y.triangles.size() << ") ";
  if (x.cells != y.cells)
    s << "triangle cells or corner colours differ ";
  return s.str();
}

/// Keeps the newest mesh of every mesh chunk a session handed out.
struct MeshStore
{
  std::map<std::int64_t, lvdif::ChunkMesh> meshes;
  void take(std::vector<lvdif::ChunkMesh>&& ms)
  {
    for (lvdif::ChunkMesh& m : ms)
      meshes[m.chunkId] = std::move(m);
  }
};

/// Compares every mesh chunk of the store with a full CPU re-mesh of `volume`
/// (a fresh mesher, the same options); returns the number of differing chunks.
inline int compareWithFullRemesh(const MeshStore& store, const lvdif::DictionaryVolume& volume,
  const lvdif::MarchingCubesOptions& options, std::string* firstProblem)
{
  lvdif::MarchingCubesOptions o = options;
  o.device = lvdif::Device::Cpu;
  lvdif::ChunkedMarchingCubes mc(volume, o);
  int bad = 0;
  for (std::int64_t id = 0; id < mc.chunkCount(); ++id)
  {
    const lvdif::ChunkMesh full = mc.extractChunk(id);
    const auto it = store.meshes.find(id);
    std::string d;
    if (it == store.meshes.end())
      d = full.empty() ? "" : "no mesh handed out for a chunk with a surface";
    else
      d = compare(it->second, full);
    if (!d.empty())
    {
      if (!bad && firstProblem)
        *firstProblem = "mesh chunk " + std::to_string(id) + ": " + d;
      ++bad;
    }
  }
  return bad;
}

} // namespace sessiontest
