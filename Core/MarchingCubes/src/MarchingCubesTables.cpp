// Builds the marching cubes case table from the face rule documented in
// MarchingCubesTables.h. Derivation of the segment direction: a triangle
// counter-clockwise around its normal n (pointing to the above side) has its
// interior on the left of its boundary; on a cube face seen from outside the
// cube this puts the below corners on the right of each boundary segment. Walking
// the face's corners counter-clockwise (seen from outside), a segment therefore
// starts on an edge where the walk enters a below corner and ends on an edge
// where it leaves the below run.
#include "lvdif/MarchingCubesTables.h"

#include "lvdif/Error.h"

#include <array>
#include <vector>

namespace lvdif
{
namespace
{

int cornerId(const int p[3]) { return p[0] + 2 * p[1] + 4 * p[2]; }

// Triangulates a loop of edge ids without any diagonal joining two vertices that
// lie on one cube face: such a diagonal would lie in the face, where the
// neighbouring cell may draw the same diagonal, making a non-manifold edge.
// Recursive search (loops have at most 12 vertices; the first valid choice wins).
bool triangulate(const std::vector<int>& loop, const bool sharesFace[12][12], std::vector<int>& tris)
{
  const std::size_t n = loop.size();
  if (n < 3) return true;
  if (n == 3)
  {
    tris.insert(tris.end(), loop.begin(), loop.end());
    return true;
  }
  // the triangle on the side (loop[0], loop[n-1]) has its third vertex at m
  for (std::size_t m = 1; m + 1 < n; ++m)
  {
    const bool d0 = m > 1 && sharesFace[loop[0]][loop[m]];
    const bool d1 = m + 2 < n && sharesFace[loop[m]][loop[n - 1]];
    if (d0 || d1) continue;
    std::vector<int> out = tris;
    out.push_back(loop[0]);
    out.push_back(loop[m]);
    out.push_back(loop[n - 1]);
    std::vector<int> left(loop.begin(), loop.begin() + static_cast<std::ptrdiff_t>(m) + 1);
    std::vector<int> right(loop.begin() + static_cast<std::ptrdiff_t>(m), loop.end());
    if (triangulate(left, sharesFace, out) && triangulate(right, sharesFace, out))
    {
      tris = out;
      return true;
    }
  }
  return false;
}

MarchingCubesTables buildTables()
{
  MarchingCubesTables t{};
  int edgeOf[8][8];
  for (auto& row : edgeOf)
    for (int& e : row) e = -1;
  for (int axis = 0; axis < 3; ++axis)
  {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int bu = 0; bu < 2; ++bu)
      for (int bv = 0; bv < 2; ++bv)
      {
        int p[3] = { 0, 0, 0 };
        p[u] = bu;
        p[v] = bv;
        const int a = cornerId(p);
        p[axis] = 1;
        const int b = cornerId(p);
        const int e = 4 * axis + 2 * bu + bv;
        t.edgeCorners[e][0] = static_cast<std::uint8_t>(a);
        t.edgeCorners[e][1] = static_cast<std::uint8_t>(b);
        t.edgeAxis[e] = static_cast<std::uint8_t>(axis);
        edgeOf[a][b] = edgeOf[b][a] = e;
      }
  }
  // faces: corners counter-clockwise seen from outside the cube
  std::array<std::array<int, 4>, 6> faces{};
  for (int axis = 0; axis < 3; ++axis)
  {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side)
    {
      static const int uv[4][2] = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
      std::array<int, 4> c{};
      for (int i = 0; i < 4; ++i)
      {
        int p[3];
        p[axis] = side;
        p[u] = uv[i][0];
        p[v] = uv[i][1];
        // (u, v, axis) is right-handed: counter-clockwise seen from +axis; reverse for the low side
        c[side ? i : 3 - i] = cornerId(p);
      }
      faces[2 * axis + side] = c;
    }
  }
  bool sharesFace[12][12] = {};
  for (const auto& f : faces)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        sharesFace[edgeOf[f[i]][f[(i + 1) % 4]]][edgeOf[f[j]][f[(j + 1) % 4]]] = true;
  for (int cs = 0; cs < 256; ++cs)
  {
    auto below = [cs](int c) { return ((cs >> c) & 1) == 0; };
    int next[12];
    for (int& n : next) n = -1;
    for (const auto& f : faces)
    {
      int entries[2], exits[2], ne = 0, nx = 0;
      for (int i = 0; i < 4; ++i)
      {
        const int a = f[i], b = f[(i + 1) % 4];
        if (!below(a) && below(b)) entries[ne++] = i;
        if (below(a) && !below(b)) exits[nx++] = i;
      }
      for (int k = 0; k < ne; ++k)
      {
        const int i = entries[k];
        // one below run: its exit; two runs (ambiguous face): the exit just before the
        // entry, so the segment cuts off the above corner between them (above separated)
        const int j = ne == 1 ? exits[0] : (i + 3) % 4;
        next[edgeOf[f[i]][f[(i + 1) % 4]]] = edgeOf[f[j]][f[(j + 1) % 4]];
      }
    }
    int n = 0;
    bool seen[12] = {};
    for (int e = 0; e < 12; ++e)
    {
      if (next[e] < 0 || seen[e]) continue;
      std::vector<int> loop;
      for (int x = e; !seen[x]; x = next[x])
      {
        seen[x] = true;
        loop.push_back(x);
      }
      std::vector<int> tris;
      if (!triangulate(loop, sharesFace, tris))
      {
        throw Error(ErrorCode::InvalidArgument, "marching cubes table: no valid triangulation");
      }
      for (std::size_t i = 0; i < tris.size(); ++i) t.triangles[cs][3 * n + i] = static_cast<std::int8_t>(tris[i]);
      n += static_cast<int>(tris.size() / 3);
    }
    t.triangleCount[cs] = static_cast<std::uint8_t>(n);
    for (int k = 3 * n; k < 16; ++k) t.triangles[cs][k] = -1;
  }
  return t;
}

} // namespace

const MarchingCubesTables& marchingCubesTables()
{
  static const MarchingCubesTables tables = buildTables();
  return tables;
}

} // namespace lvdif
