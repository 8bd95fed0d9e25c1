// The triangles by which two meshes differ (vtkChunkActorManager's changed
// boxes and points for vtkPartialRedrawCuller): per triangle a hash of its
// points, point arrays and cell arrays; the hashes of two meshes compared as
// sorted lists.
#include "lvdifTriangleChanges.h"

#include "vtkBoundingBox.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataSetAttributes.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkMath.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cstring>

namespace lvdif
{
namespace render
{
namespace
{
std::uint64_t hashBytes(std::uint64_t h, const void* data, std::size_t n)
{
  // 8 bytes a step (a multiply-xorshift mix), the tail byte by byte: the
  // triangles of a re-meshed chunk are hashed at every replacement
  const auto* b = static_cast<const unsigned char*>(data);
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8)
  {
    std::uint64_t w;
    std::memcpy(&w, b + i, 8);
    h = (h ^ w) * 0x9e3779b97f4a7c15ull;
    h ^= h >> 29;
  }
  for (; i < n; ++i)
  {
    h = (h ^ b[i]) * 1099511628211ull;
  }
  return h;
}

// The arrays of `data` that are hashed per tuple (data arrays: contiguous
// ones by their raw bytes, others through doubles), looked up once per mesh.
struct TupleFields
{
  struct Field
  {
    const unsigned char* Base = nullptr; // contiguous: tuple t at Base + t * Bytes
    std::size_t Bytes = 0;
    vtkDataArray* Generic = nullptr; // otherwise
    int Components = 0;
  };
  std::vector<Field> Fields;
  explicit TupleFields(vtkFieldData* data)
  {
    for (int a = 0; a < data->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* da = vtkDataArray::SafeDownCast(data->GetAbstractArray(a));
      if (!da)
      {
        continue; // string arrays and the like are not drawn
      }
      Field f;
      f.Components = da->GetNumberOfComponents();
      if (da->HasStandardMemoryLayout())
      {
        f.Base = static_cast<const unsigned char*>(da->GetVoidPointer(0));
        f.Bytes = static_cast<std::size_t>(f.Components) * da->GetDataTypeSize();
      }
      else
      {
        f.Generic = da;
      }
      this->Fields.push_back(f);
    }
  }
};

// One tuple of every hashed array.
std::uint64_t hashTuple(std::uint64_t h, const TupleFields& fields, vtkIdType t)
{
  for (const TupleFields::Field& f : fields.Fields)
  {
    if (f.Base)
    {
      h = hashBytes(h, f.Base + static_cast<std::size_t>(t) * f.Bytes, f.Bytes);
    }
    else
    {
      for (int c = 0; c < f.Components; ++c)
      {
        const double v = f.Generic->GetComponent(t, c);
        h = hashBytes(h, &v, sizeof v);
      }
    }
  }
  return h;
}
} // namespace

// Per triangle: a hash of its three points (position and point arrays, the
// cyclic order kept, starting at the smallest) and its cell arrays; false if
// the mesh holds other cells.
bool triangleHashes(vtkPolyData* pd, std::vector<std::uint64_t>& out)
{
  out.clear();
  if (!pd)
  {
    return true;
  }
  if (pd->GetNumberOfVerts() || pd->GetNumberOfLines() || pd->GetNumberOfStrips())
  {
    return false;
  }
  std::vector<std::uint64_t> point(static_cast<std::size_t>(pd->GetNumberOfPoints()));
  vtkDataArray* pts = pd->GetPoints() ? pd->GetPoints()->GetData() : nullptr;
  const TupleFields pointFields(pd->GetPointData()), cellFields(pd->GetCellData());
  for (vtkIdType p = 0; p < pd->GetNumberOfPoints(); ++p)
  {
    std::uint64_t h = 1469598103934665603ull;
    double x[3];
    pts->GetTuple(p, x);
    h = hashBytes(h, x, sizeof x);
    point[static_cast<std::size_t>(p)] = hashTuple(h, pointFields, p);
  }
  vtkCellArray* polys = pd->GetPolys();
  out.reserve(static_cast<std::size_t>(polys->GetNumberOfCells()));
  vtkIdType npts = 0;
  const vtkIdType* ids = nullptr;
  vtkIdType cell = 0;
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids); ++cell)
  {
    if (npts != 3)
    {
      return false;
    }
    std::uint64_t v[3] = { point[static_cast<std::size_t>(ids[0])], point[static_cast<std::size_t>(ids[1])],
      point[static_cast<std::size_t>(ids[2])] };
    std::rotate(v, std::min_element(v, v + 3), v + 3);
    std::uint64_t h = hashBytes(1469598103934665603ull, v, sizeof v);
    out.push_back(hashTuple(h, cellFields, cell)); // polys are the only cells: cell id = poly index
  }
  return true;
}

namespace
{
// Adds a triangle's points to a box and, if given, to a list of points (x, y, z).
void addTriangle(vtkPolyData* pd, vtkIdType t, double b[6], std::vector<double>* points)
{
  const vtkIdType* ids = nullptr;
  vtkIdType npts = 0;
  pd->GetPolys()->GetCellAtId(t, npts, ids);
  for (vtkIdType i = 0; i < npts; ++i)
  {
    double x[3];
    pd->GetPoint(ids[i], x);
    for (int a = 0; a < 3; ++a)
    {
      b[2 * a] = std::min(b[2 * a], x[a]);
      b[2 * a + 1] = std::max(b[2 * a + 1], x[a]);
    }
    if (points)
    {
      points->insert(points->end(), x, x + 3);
    }
  }
}
} // namespace

// The triangle hashes of a mesh, sorted, with their triangles' indices.
SortedTriangleHashes sortedWithIndex(const std::vector<std::uint64_t>& order)
{
  SortedTriangleHashes sorted(order.size());
  for (std::size_t t = 0; t < order.size(); ++t)
  {
    sorted[t] = { order[t], static_cast<vtkIdType>(t) };
  }
  std::sort(sorted.begin(), sorted.end());
  return sorted;
}

// ChangedBounds with the triangles' hashes known (sortedWithIndex of each
// mesh's triangleHashes): one walk over both sorted lists; the triangles of
// each hash whose count differs between the meshes are the changed ones.
bool changedBoundsOf(vtkPolyData* before, const SortedTriangleHashes& sb, vtkPolyData* after,
  const SortedTriangleHashes& sa, double bounds[6], std::vector<double>* points)
{
  vtkMath::UninitializeBounds(bounds);
  double b[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  bool any = false;
  std::size_t i = 0, j = 0;
  while (i < sb.size() || j < sa.size())
  {
    const std::uint64_t h = j == sa.size() || (i < sb.size() && sb[i].first < sa[j].first) ? sb[i].first : sa[j].first;
    const std::size_t i0 = i, j0 = j;
    for (; i < sb.size() && sb[i].first == h; ++i)
    {
    }
    for (; j < sa.size() && sa[j].first == h; ++j)
    {
    }
    if (i - i0 != j - j0)
    {
      any = true;
      for (std::size_t k = i0; k < i; ++k)
      {
        addTriangle(before, sb[k].second, b, points);
      }
      for (std::size_t k = j0; k < j; ++k)
      {
        addTriangle(after, sa[k].second, b, points);
      }
    }
  }
  if (!any)
  {
    return false;
  }
  std::copy(b, b + 6, bounds);
  return true;
}

namespace
{
// The same numeric type, tuples, components and bytes (data arrays of the
// standard memory layout only; bit, string and variant arrays never compare equal).
bool sameValues(vtkAbstractArray* x, vtkAbstractArray* y)
{
  if (x == y)
  {
    return true;
  }
  if (!vtkDataArray::SafeDownCast(x) || !vtkDataArray::SafeDownCast(y) || x->GetDataType() != y->GetDataType() ||
    x->GetDataType() == VTK_BIT || x->GetNumberOfComponents() != y->GetNumberOfComponents() ||
    x->GetNumberOfTuples() != y->GetNumberOfTuples() || !x->HasStandardMemoryLayout() ||
    !y->HasStandardMemoryLayout())
  {
    return false;
  }
  const std::size_t bytes =
    static_cast<std::size_t>(x->GetNumberOfValues()) * static_cast<std::size_t>(x->GetDataTypeSize());
  return bytes == 0 || std::memcmp(x->GetVoidPointer(0), y->GetVoidPointer(0), bytes) == 0;
}

bool sameName(const char* x, const char* y)
{
  return (x == nullptr) == (y == nullptr) && (!x || std::strcmp(x, y) == 0);
}

bool sameAttributes(vtkDataSetAttributes* x, vtkDataSetAttributes* y)
{
  if (x->GetNumberOfArrays() != y->GetNumberOfArrays())
  {
    return false;
  }
  int ix[vtkDataSetAttributes::NUM_ATTRIBUTES], iy[vtkDataSetAttributes::NUM_ATTRIBUTES];
  x->GetAttributeIndices(ix);
  y->GetAttributeIndices(iy);
  if (!std::equal(ix, ix + vtkDataSetAttributes::NUM_ATTRIBUTES, iy))
  {
    return false;
  }
  for (int i = 0; i < x->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* ax = x->GetAbstractArray(i);
    vtkAbstractArray* ay = y->GetAbstractArray(i);
    if (!sameName(ax->GetName(), ay->GetName()) || !sameValues(ax, ay))
    {
      return false;
    }
  }
  return true;
}

bool sameCells(vtkCellArray* x, vtkCellArray* y)
{
  const vtkIdType nx = x ? x->GetNumberOfCells() : 0;
  const vtkIdType ny = y ? y->GetNumberOfCells() : 0;
  if (nx != ny)
  {
    return false;
  }
  return nx == 0 ||
    (sameValues(x->GetOffsetsArray(), y->GetOffsetsArray()) &&
      sameValues(x->GetConnectivityArray(), y->GetConnectivityArray()));
}
} // namespace

bool sameMesh(vtkPolyData* a, vtkPolyData* b)
{
  if (!a || !b)
  {
    return false;
  }
  if (a == b)
  {
    return true;
  }
  vtkPoints* pa = a->GetPoints();
  vtkPoints* pb = b->GetPoints();
  if ((pa == nullptr) != (pb == nullptr) || (pa && !sameValues(pa->GetData(), pb->GetData())))
  {
    return false;
  }
  if (a->GetFieldData()->GetNumberOfArrays() || b->GetFieldData()->GetNumberOfArrays())
  {
    return false;
  }
  return sameCells(a->GetPolys(), b->GetPolys()) && sameCells(a->GetVerts(), b->GetVerts()) &&
    sameCells(a->GetLines(), b->GetLines()) && sameCells(a->GetStrips(), b->GetStrips()) &&
    sameAttributes(a->GetPointData(), b->GetPointData()) && sameAttributes(a->GetCellData(), b->GetCellData());
}

bool unionBounds(vtkPolyData* before, vtkPolyData* after, double bounds[6])
{
  vtkMath::UninitializeBounds(bounds);
  vtkBoundingBox box;
  for (vtkPolyData* pd : { before, after })
  {
    if (pd && pd->GetNumberOfPoints())
    {
      box.AddBounds(pd->GetBounds());
    }
  }
  if (!box.IsValid())
  {
    return false;
  }
  box.GetBounds(bounds);
  return true;
}

} // namespace render
} // namespace lvdif
