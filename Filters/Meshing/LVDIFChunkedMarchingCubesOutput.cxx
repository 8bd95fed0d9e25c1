#include "LVDIFChunkedMarchingCubesOutput.h"

#include "lvdif/DictionaryVolume.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkIntArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstring>
#include <functional>
#include <unordered_map>

namespace LVDIFChunkedMarchingCubesOutput
{
namespace
{

/// Growing output arrays; `np`/`nt` are the final sizes (allocated once).
struct Arrays
{
  vtkNew<vtkFloatArray> points, normals;
  vtkNew<vtkUnsignedCharArray> rgba, cornerRgba;
  vtkNew<vtkIntArray> cellIjk;
  // 32-bit cell storage when the ids fit (half the memory of vtkIdType's 64 bits)
  vtkSmartPointer<vtkTypeInt32Array> offsets32, connectivity32;
  vtkSmartPointer<vtkTypeInt64Array> offsets64, connectivity64;
  const Context& ctx;

  Arrays(const Context& c, vtkIdType np, vtkIdType nt)
    : ctx(c)
  {
    points->SetNumberOfComponents(3);
    points->SetNumberOfTuples(np);
    if (ctx.normals)
    {
      normals->SetName("Normals");
      normals->SetNumberOfComponents(3);
      normals->SetNumberOfTuples(np);
    }
    if (ctx.pointColors)
    {
      rgba->SetName("rgba");
      rgba->SetNumberOfComponents(4);
      rgba->SetNumberOfTuples(np);
    }
    if (ctx.cellData)
    {
      cellIjk->SetName("cell_ijk");
      cellIjk->SetNumberOfComponents(3);
      cellIjk->SetNumberOfTuples(nt);
      if (ctx.colors || ctx.palette)
      {
        cornerRgba->SetName("corner_rgba");
        cornerRgba->SetNumberOfComponents(32);
        cornerRgba->SetNumberOfTuples(nt);
      }
    }
    if (np < VTK_INT_MAX && 3 * nt < VTK_INT_MAX)
    {
      offsets32 = vtkSmartPointer<vtkTypeInt32Array>::New();
      connectivity32 = vtkSmartPointer<vtkTypeInt32Array>::New();
      offsets32->SetNumberOfValues(nt + 1);
      connectivity32->SetNumberOfValues(3 * nt);
      for (vtkIdType t = 0; t <= nt; ++t) offsets32->SetValue(t, static_cast<vtkTypeInt32>(3 * t));
    }
    else
    {
      offsets64 = vtkSmartPointer<vtkTypeInt64Array>::New();
      connectivity64 = vtkSmartPointer<vtkTypeInt64Array>::New();
      offsets64->SetNumberOfValues(nt + 1);
      connectivity64->SetNumberOfValues(3 * nt);
      for (vtkIdType t = 0; t <= nt; ++t) offsets64->SetValue(t, 3 * t);
    }
  }

  void setPoint(vtkIdType dst, const lvdif::ChunkMesh& m, std::size_t src)
  {
    std::memcpy(points->GetPointer(3 * dst), m.points[src].data(), 3 * sizeof(float));
    if (ctx.normals) std::memcpy(normals->GetPointer(3 * dst), m.normals[src].data(), 3 * sizeof(float));
    if (ctx.pointColors) std::memcpy(rgba->GetPointer(4 * dst), &m.colors[src], 4);
  }

  void setTriangle(vtkIdType dst, const lvdif::ChunkMesh& m, std::size_t src, const vtkIdType ids[3])
  {
    if (connectivity32)
    {
      vtkTypeInt32* c = connectivity32->GetPointer(3 * dst);
      for (int k = 0; k < 3; ++k) c[k] = static_cast<vtkTypeInt32>(ids[k]);
    }
    else
    {
      vtkTypeInt64* c = connectivity64->GetPointer(3 * dst);
      for (int k = 0; k < 3; ++k) c[k] = ids[k];
    }
    if (!ctx.cellData) return;
    const std::int64_t cell = m.triangleCells[src];
    const std::int64_t nx = ctx.gridDims[0], ny = ctx.gridDims[1];
    const std::int64_t x = cell % nx, y = (cell / nx) % ny, z = cell / (nx * ny);
    int* ijk = cellIjk->GetPointer(3 * dst);
    ijk[0] = static_cast<int>(x) + ctx.extentLo[0];
    ijk[1] = static_cast<int>(y) + ctx.extentLo[1];
    ijk[2] = static_cast<int>(z) + ctx.extentLo[2];
    if (ctx.palette)
    {
      unsigned char* out = cornerRgba->GetPointer(32 * dst);
      for (int q = 0; q < 8; ++q) std::memcpy(out + 4 * q, &ctx.palette[m.cornerColors[src][q]], 4);
    }
    else if (ctx.colors)
    {
      unsigned char* out = cornerRgba->GetPointer(32 * dst);
      for (int q = 0; q < 8; ++q)
      {
        const std::int64_t p = (x + (q & 1)) + nx * ((y + ((q >> 1) & 1)) + ny * (z + ((q >> 2) & 1)));
        std::memcpy(out + 4 * q, &ctx.colors[p], 4);
      }
    }
  }

  vtkSmartPointer<vtkPolyData> finish()
  {
    auto pd = vtkSmartPointer<vtkPolyData>::New();
    vtkNew<vtkPoints> pts;
    pts->SetData(points);
    pd->SetPoints(pts);
    vtkNew<vtkCellArray> polys;
    if (connectivity32)
      polys->SetData(offsets32, connectivity32);
    else
      polys->SetData(offsets64, connectivity64);
    pd->SetPolys(polys);
    if (ctx.normals) pd->GetPointData()->SetNormals(normals);
    if (ctx.pointColors) pd->GetPointData()->AddArray(rgba);
    if (ctx.cellData)
    {
      pd->GetCellData()->AddArray(cellIjk);
      if (ctx.colors || ctx.palette) pd->GetCellData()->AddArray(cornerRgba);
    }
    return pd;
  }
};

/// True when the cut edge lies in a face plane of the chunk's cell box (it is
/// then shared with a neighbouring chunk).
bool onChunkFace(std::uint64_t edgeId, const lvdif::VoxelBox& cells, const lvdif::Index3& dims)
{
  const int axis = static_cast<int>(edgeId % 3);
  const std::int64_t lin = static_cast<std::int64_t>(edgeId / 3);
  const std::int64_t p[3] = { lin % dims[0], (lin / dims[0]) % dims[1], lin / (dims[0] * dims[1]) };
  for (int b = 0; b < 3; ++b)
  {
    if (b != axis && (p[b] == cells.lo[b] || p[b] == cells.hi[b] + 1)) return true;
  }
  return false;
}

} // namespace

vtkSmartPointer<vtkPolyData> ChunkToPolyData(const lvdif::ChunkMesh& m, const Context& ctx)
{
  Arrays a(ctx, static_cast<vtkIdType>(m.points.size()), static_cast<vtkIdType>(m.triangles.size()));
  for (std::size_t i = 0; i < m.points.size(); ++i) a.setPoint(static_cast<vtkIdType>(i), m, i);
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
  {
    const vtkIdType ids[3] = { m.triangles[t][0], m.triangles[t][1], m.triangles[t][2] };
    a.setTriangle(static_cast<vtkIdType>(t), m, t, ids);
  }
  return a.finish();
}

vtkSmartPointer<vtkPolyData> VolumeChunkToPolyData(const lvdif::ChunkMesh& mesh, const lvdif::DictionaryVolume& volume)
{
  Context ctx;
  ctx.gridDims = volume.dims();
  ctx.palette = volume.colors().colors().data();
  ctx.normals = mesh.normals.size() == mesh.points.size();
  ctx.pointColors = mesh.colors.size() == mesh.points.size();
  ctx.cellData = mesh.cornerColors.size() == mesh.triangles.size() && mesh.triangleCells.size() == mesh.triangles.size();
  return ChunkToPolyData(mesh, ctx);
}

vtkSmartPointer<vtkPolyData> MergeChunks(const std::vector<lvdif::ChunkMesh>& meshes, const Context& ctx)
{
  // pass 1: which points are new (first seen), and the index each maps to
  std::vector<std::vector<vtkIdType>> remap(meshes.size());
  std::unordered_map<std::uint64_t, vtkIdType> shared;
  vtkIdType np = 0, nt = 0;
  for (std::size_t c = 0; c < meshes.size(); ++c)
  {
    const lvdif::ChunkMesh& m = meshes[c];
    remap[c].resize(m.points.size());
    for (std::size_t i = 0; i < m.points.size(); ++i)
    {
      if (onChunkFace(m.edgeIds[i], m.cells, ctx.gridDims))
      {
        auto it = shared.emplace(m.edgeIds[i], np);
        remap[c][i] = it.second ? np++ : -1 - it.first->second; // negative: a duplicate
      }
      else
      {
        remap[c][i] = np++;
      }
    }
    nt += static_cast<vtkIdType>(m.triangles.size());
  }
  // pass 2: fill
  Arrays a(ctx, np, nt);
  vtkIdType t0 = 0;
  for (std::size_t c = 0; c < meshes.size(); ++c)
  {
    const lvdif::ChunkMesh& m = meshes[c];
    std::vector<vtkIdType>& r = remap[c];
    for (std::size_t i = 0; i < m.points.size(); ++i)
    {
      if (r[i] >= 0)
        a.setPoint(r[i], m, i);
      else
        r[i] = -1 - r[i];
    }
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
    {
      const vtkIdType ids[3] = { r[m.triangles[t][0]], r[m.triangles[t][1]], r[m.triangles[t][2]] };
      a.setTriangle(t0 + static_cast<vtkIdType>(t), m, t, ids);
    }
    t0 += static_cast<vtkIdType>(m.triangles.size());
  }
  return a.finish();
}

vtkSmartPointer<vtkPolyData> MergeBatches(
  const std::function<std::vector<lvdif::ChunkMesh>(std::size_t, int)>& batch, std::size_t batches, const Context& ctx)
{
  // pass 1: count the points off the chunk faces and collect the face points'
  // edge ids, sorted and unique (16 bytes a face point with their ids below; a
  // hash map took about 40, and it is held while the output is filled)
  std::vector<std::uint64_t> faces, mine;
  vtkIdType inner = 0, nt = 0;
  for (std::size_t b = 0; b < batches; ++b)
  {
    mine.clear();
    for (const lvdif::ChunkMesh& m : batch(b, 0))
    {
      for (std::size_t i = 0; i < m.points.size(); ++i)
      {
        if (onChunkFace(m.edgeIds[i], m.cells, ctx.gridDims))
          mine.push_back(m.edgeIds[i]);
        else
          ++inner;
      }
      nt += static_cast<vtkIdType>(m.triangles.size());
    }
    std::sort(mine.begin(), mine.end());
    mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
    faces.insert(faces.end(), mine.begin(), mine.end()); // a point on a batch's border comes twice
  }
  std::vector<std::uint64_t>().swap(mine);
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  faces.shrink_to_fit();
  std::vector<vtkIdType> faceIds(faces.size(), -1);
  // pass 2: the same batches again, numbered on the fly (a face point takes an
  // id when first met), so nothing depends on the order chunks come in
  Arrays a(ctx, inner + static_cast<vtkIdType>(faces.size()), nt);
  vtkIdType np = 0, t0 = 0;
  std::vector<vtkIdType> r;
  for (std::size_t b = 0; b < batches; ++b)
  {
    for (const lvdif::ChunkMesh& m : batch(b, 1))
    {
      r.resize(m.points.size());
      for (std::size_t i = 0; i < m.points.size(); ++i)
      {
        if (onChunkFace(m.edgeIds[i], m.cells, ctx.gridDims))
        {
          const auto at = std::lower_bound(faces.begin(), faces.end(), m.edgeIds[i]);
          vtkIdType& id = faceIds[static_cast<std::size_t>(at - faces.begin())];
          if (id < 0)
          {
            id = np++;
            a.setPoint(id, m, i);
          }
          r[i] = id;
        }
        else
        {
          r[i] = np++;
          a.setPoint(r[i], m, i);
        }
      }
      for (std::size_t t = 0; t < m.triangles.size(); ++t)
      {
        const vtkIdType ids[3] = { r[m.triangles[t][0]], r[m.triangles[t][1]], r[m.triangles[t][2]] };
        a.setTriangle(t0 + static_cast<vtkIdType>(t), m, t, ids);
      }
      t0 += static_cast<vtkIdType>(m.triangles.size());
    }
  }
  return a.finish();
}

} // namespace LVDIFChunkedMarchingCubesOutput
