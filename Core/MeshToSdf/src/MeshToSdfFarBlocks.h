// Far blocks of the Normal and PseudoNormal signs, shared by the CPU
// (MeshToSdfFarBlocks.cpp) and the CUDA kernels (MeshToSdfCudaFar.cuh).
// Outside the band a voxel stores only +-band, so it needs only its sign. A
// box of voxels whose centre x is at distance D from the mesh and whose
// half-diagonal is r has every voxel's nearest feature within D + 2r of x;
// if every triangle that close has the whole box strictly on one side of its
// plane, that side is every voxel's sign (the sign is taken against a
// positive combination of the normals of triangles containing the closest
// point, all of them that close), and if D - r is past the band, every voxel
// is the clamped value. A box that fails hands its sub-boxes the few
// candidates that disagreed (the others agree over every sub-box), so most
// sub-boxes and single voxels are decided without a query or a tree walk.
// Margins and the proof: docs/MESH_TO_SDF.md, "Far blocks".
#pragma once

#include "MeshToSdfInternal.h"

#include <cstdint>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf
{

/// Blocks of FarBlock^3 voxels are tried first, those that fail as their 8
/// halves, those as their 8 cells of FarCell^3, those voxel by voxel (by the
/// cell's candidates alone); voxels that fail too get the per-voxel query.
constexpr int FarBlock = 8;
constexpr int FarCell = 2;
/// Triangles less well shaped than this ((|AB|^2 + |AC|^2) / |AB x AC|, about
/// 1 / sin of the smallest angle) make a box undecided: the rounding of their
/// normal and closest point is bounded only for shaped ones.
constexpr double FarKappaMax = 1e4;

/// The margin (world units) of every far-block test: far above the rounding
/// of the positions, normals, closest points and pseudo-normal sums (whose
/// rounding grows with the faces at a vertex, at most `triangles`), far below
/// a voxel. big: the largest |coordinate| of the mesh and the grid.
LVDIF_HD double farMargin(double big, double triangles)
{
  return big * (1e-8 + 1e-15 * triangles);
}

struct FarBox
{
  V3 centre, half; // half extents, grown by the rounding of the centre
  double radius = 0;
};

/// The box of the voxel positions p0 <= p <= p1 (positions computed as the
/// rows compute them are monotonic in the index, so every voxel lies inside).
LVDIF_HD FarBox farBox(V3 p0, V3 p1, double big)
{
  FarBox b;
  b.centre = 0.5 * (p0 + p1);
  const double s = 1e-15 * big;
  b.half = { 0.5 * (p1.x - p0.x) + s, 0.5 * (p1.y - p0.y) + s, 0.5 * (p1.z - p0.z) + s };
  b.radius = norm(b.half);
  return b;
}

/// A triangle as the far blocks test it: its record and, for the
/// PseudoNormal sign, its feature normals (null for the Normal sign, which
/// takes the face plane alone). The callers' triAt(i) returns these.
struct FarTri
{
  const Tri* t;
  const TriNormals* pn;
};

/// Triangle `tri` of a prepared mesh on the CPU (pseudo: with its normals).
inline FarTri farTriOf(const PreparedMesh& mesh, std::size_t tri, bool pseudo)
{
  return { &mesh.tris[tri], pseudo ? &mesh.normals[tri] : nullptr };
}

/// Whether a triangle is shaped: (|AB|^2 + |AC|^2) <= FarKappaMax |AB x AC|.
LVDIF_HD bool farShaped(const Tri& t)
{
  const V3 ab = t.v[1] - t.v[0], ac = t.v[2] - t.v[0];
  return dot(ab, ab) + dot(ac, ac) <= FarKappaMax * norm(cross(ab, ac)); // false for NaN too
}

/// The side (+1 / -1) every point of the box is on, by more than margin +
/// delta, of the plane through a with normal n; 0 when neither.
LVDIF_HD int farPlane(V3 a, V3 n, double delta, const FarBox& box, double margin)
{
  const double g = dot(box.centre - a, n);
  const double spread = std::fabs(n.x) * box.half.x + std::fabs(n.y) * box.half.y + std::fabs(n.z) * box.half.z;
  const double m = margin + delta;
  return g - spread > m ? 1 : (g + spread < -m ? -1 : 0);
}

/// The face plane's allowance of farTriAgrees (region: the rounding band of
/// the closest point's regions, h the smallest height, L bounding |p - vertex|).
LVDIF_HD double farFaceDelta(double faceDot, double reachL, double h)
{
  const double region = 1e-14 * reachL * reachL / h;
  return faceDot * (2 + region / h);
}

/// Whether triangle t leaves every voxel of the box the sign `side` if it is
/// their nearest: each plane its sign may be taken against (the face; with
/// pseudo-normals also its edges' and vertices', through the feature, with
/// their stored normals) puts the box on that side. delta covers where the
/// computed closest point lies on the feature (the sign is taken at it, the
/// plane passes through a vertex): |B-A|.n for an edge (parameter in [0,1]),
/// (|AB.n| + |AC.n|) (2 + region / h) for the face (barycentrics, with their
/// rounding), 0 at a vertex. Also true when t is provably farther than reach
/// from the centre (by its exact distance if shaped, else its bounding box):
/// tested first, since the candidates handed down to sub-boxes (FarState)
/// mostly drop out by it.
LVDIF_HD bool farTriAgrees(const FarTri& ft, bool pseudo, const FarBox& box, double reach, double margin, int side)
{
  const Tri& t = *ft.t;
  if (farShaped(t))
  {
    // |distance to the plane| <= the distance: the cheap bound first
    if (std::fabs(dot(box.centre - t.v[0], t.n)) - margin > reach) return true;
    const V3 d = closestPointOnTriangle(box.centre, t.v[0], t.v[1], t.v[2]).point - box.centre;
    if (dot(d, d) > reach * reach) return true;
    const V3 ab = t.v[1] - t.v[0], ac = t.v[2] - t.v[0];
    // the closest-point routine's region tests and barycentrics round like
    // products of distances: their error in position grows as L^2 / h (L
    // bounds |p - vertex| over the box, h the triangle's smallest height)
    const double area2 = norm(cross(ab, ac));
    const double longest = std::fmax(norm(ab), std::fmax(norm(ac), norm(t.v[2] - t.v[1])));
    const double h = area2 / longest;
    const double reachL = norm(box.centre - t.v[0]) + box.radius + longest;
    const double region = 1e-14 * reachL * reachL / h; // as in farFaceDelta
    // in the face, c' = A + v AB + w AC with |v|, |w| <= 1 + region / h
    const double faceDelta = farFaceDelta(std::fabs(dot(ab, t.n)) + std::fabs(dot(ac, t.n)), reachL, h);
    if (!pseudo) return farPlane(t.v[0], t.n, faceDelta, box, margin) == side;
    // With pseudo-normals only the planes of the features the routine may
    // report for a point of the box count (its region tests, with the
    // rounding band `region`): the face in its prism (the projection inside
    // it); edge k (V_k V_k+1, direction u_k) where the box is not all inside
    // its line, before V_k or past V_k+1 along u_k; vertex k where it is not
    // all past V_k along u_k nor before V_k along u_k-1.
    V3 u[3];
    int line[3]; // 1: the box is all beyond edge k's line, -1: all inside, 0: neither
    for (int k = 0; k < 3; ++k)
    {
      const V3 e = t.v[(k + 1) % 3] - t.v[k];
      u[k] = normalized(e);
      line[k] = farPlane(t.v[k], normalized(cross(e, t.n)), region, box, margin); // in-plane, outward of edge k
    }
    if (line[0] != 1 && line[1] != 1 && line[2] != 1 && farPlane(t.v[0], t.n, faceDelta, box, margin) != side)
      return false;
    for (int k = 0; k < 3; ++k)
    {
      const V3 a = t.v[k], b = t.v[(k + 1) % 3];
      const int alongA = farPlane(a, u[k], region, box, margin); // -1: all before V_k, 1: all past it
      if (line[k] != -1 && alongA != -1 && farPlane(b, u[k], region, box, margin) != 1 &&
        farPlane(a, ft.pn->en[k], std::fabs(dot(b - a, ft.pn->en[k])), box, margin) != side)
        return false;
      if (alongA != 1 && farPlane(a, u[(k + 2) % 3], region, box, margin) != -1 &&
        farPlane(a, ft.pn->vn[k], 0.0, box, margin) != side)
        return false;
    }
    return true;
  }
  const double lo[3] = { std::fmin(t.v[0].x, std::fmin(t.v[1].x, t.v[2].x)),
    std::fmin(t.v[0].y, std::fmin(t.v[1].y, t.v[2].y)), std::fmin(t.v[0].z, std::fmin(t.v[1].z, t.v[2].z)) };
  const double hi[3] = { std::fmax(t.v[0].x, std::fmax(t.v[1].x, t.v[2].x)),
    std::fmax(t.v[0].y, std::fmax(t.v[1].y, t.v[2].y)), std::fmax(t.v[0].z, std::fmax(t.v[1].z, t.v[2].z)) };
  return pointBoxDist2(box.centre, lo, hi) > reach * reach;
}

/// A normal cone of a BVH node: every sign plane normal of every triangle
/// below (face, edges, vertices) lies within angle T of the axis, and every
/// triangle is shaped (ok = 0: no cone).
struct FarCone
{
  double axis[3] = { 0, 0, 0 };
  double cosT = 0, sinT = 1;
  // for the deltas of farTriAgrees below: the largest edge delta, the largest
  // |AB.n| + |AC.n|, the smallest height and the longest edge
  double edgeDelta = 0, faceDot = 0, minHeight = 0, longest = 0;
  int ok = 0;
};

/// +1 / -1 when every point of the box is on that side, by more than margin,
/// of the plane of every triangle under a node (box lo..hi, cone c); else 0.
/// With w = p - v (p in the box, v a vertex in the node's box) and n within T
/// of the axis a: s n.w >= cos T (s a.w) - sin T |w - (a.w) a| when s a.w >= 0.
LVDIF_HD int farConeSide(const FarCone& c, const double lo[3], const double hi[3], const FarBox& box, double margin)
{
  if (!c.ok) return 0;
  const V3 a{ c.axis[0], c.axis[1], c.axis[2] };
  const V3 cw{ box.centre.x - 0.5 * (lo[0] + hi[0]), box.centre.y - 0.5 * (lo[1] + hi[1]),
    box.centre.z - 0.5 * (lo[2] + hi[2]) };
  const V3 hw{ box.half.x + 0.5 * (hi[0] - lo[0]), box.half.y + 0.5 * (hi[1] - lo[1]),
    box.half.z + 0.5 * (hi[2] - lo[2]) };
  const double along = dot(a, cw);
  const double spread = std::fabs(a.x) * hw.x + std::fabs(a.y) * hw.y + std::fabs(a.z) * hw.z;
  const double across = norm(cw - along * a) + norm(hw);
  const double reachL = norm(cw) + norm(hw) + box.radius + c.longest; // bounds |p - vertex| below
  const double m = margin + std::fmax(c.edgeDelta, farFaceDelta(c.faceDot, reachL, c.minHeight));
  if (along - spread > 0 && c.cosT * (along - spread) - c.sinT * across > m) return 1;
  if (-along - spread > 0 && c.cosT * (-along - spread) - c.sinT * across > m) return -1;
  return 0;
}

/// The most candidates a box hands down to its sub-boxes (FarState::list).
constexpr int FarListMax = 64;


/// The walk of the binary BVH (Node: Bvh::Node or the GPU's copy, leaf: its
/// leaf-ordered triangles, at triAt(position)) over the triangles within
/// `reach` of the box's centre, with the node cones, so that a subtree whose
/// cone decides needs no triangle: writes to list the leaf positions of the
/// candidates that do not put the whole box on `side` (farTriAgrees) and
/// returns their count, or -1 when there are more than FarListMax (or the
/// tree is deeper than the stack, or side is 0).
template <typename Node, typename TriAt>
LVDIF_HD int farTreeCollect(const Node* nodes, const FarCone* cones, TriAt&& triAt, bool pseudo, const FarBox& box,
  double reach, double margin, int side, int* list)
{
  if (side == 0) return -1;
  int stack[64];
  int top = 0, count = 0;
  stack[top++] = 0;
  while (top > 0)
  {
    const Node& n = nodes[stack[--top]];
    const int id = static_cast<int>(&n - nodes);
    if (pointBoxDist2(box.centre, n.lo, n.hi) > reach * reach) continue;
    if (farConeSide(cones[id], n.lo, n.hi, box, margin) == side) continue;
    if (n.left < 0)
    {
      for (int i = n.first; i < n.first + n.count; ++i)
        if (!farTriAgrees(triAt(i), pseudo, box, reach, margin, side))
        {
          if (count == FarListMax) return -1;
          list[count++] = i;
        }
      continue;
    }
    if (top + 2 > 64) return -1; // deeper than the stack: undecided, never wrong
    stack[top++] = n.right;
    stack[top++] = n.left;
  }
  return count;
}

/// The candidates of in[0, count) that do not put the box on side (those
/// farther than reach drop out too), written to out (may be in); their count.
template <typename TriAt>
LVDIF_HD int farListFilter(TriAt&& triAt, bool pseudo, const FarBox& box, double reach, double margin, int side,
  const int* in, int count, int* out)
{
  int kept = 0;
  for (int c = 0; c < count; ++c)
    if (!farTriAgrees(triAt(in[c]), pseudo, box, reach, margin, side)) out[kept++] = in[c];
  return kept;
}

/// The radius within which the candidates of a box lie: D (the centre's
/// computed nearest distance, or an upper bound of it) + 2r, plus the margin.
LVDIF_HD double farRadius(double nearestDist, const FarBox& box, double margin)
{
  return nearestDist * (1 + 1e-12) + 2 * box.radius + margin;
}

/// Whether the box lies past the band (world units) by more than the margin.
LVDIF_HD bool farPastBand(double nearestDist, const FarBox& box, double bandWorld, double margin)
{
  return nearestDist * (1 - 1e-12) - box.radius - margin > bandWorld * (1 + 1e-12);
}

/// The sign the mode would give the point p from its nearest triangle t and
/// closest point c (the side a box around p is expected on; 0 on the plane).
LVDIF_HD int farSideAt(const FarTri& t, const Closest& c, V3 p, bool pseudo)
{
  const double g = dot(p - c.point, pseudo ? featureNormal(*t.t, *t.pn, c.feature) : t.t->n);
  return g > 0 ? 1 : (g < 0 ? -1 : 0);
}

/// The offset of a sub-box's centre from the block's (bounds its nearest
/// distance from the block's: the distance is 1-Lipschitz), rounded up.
LVDIF_HD double farOffset(const FarBox& sub, const FarBox& block, double big)
{
  return norm(sub.centre - block.centre) * (1 + 1e-12) + 1e-15 * big;
}

/// An upper bound of the nearest distance of a sub-box's centre from that of
/// the box enclosing it (parentDist: its computed distance, or its own bound).
LVDIF_HD double farChildBound(double parentDist, const FarBox& sub, const FarBox& parent, double big)
{
  return parentDist + farOffset(sub, parent, big);
}

/// What a box tried leaves to its sub-boxes. dHi: its centre's computed
/// nearest distance, or an upper bound of it. past: every voxel of the box
/// lies past the band (so every voxel of a sub-box does). count >= 0: every
/// triangle that may be the reported nearest of a voxel of the box either puts
/// all its voxels on `side` with every sign plane (farTriAgrees) or is one of
/// list[0, count) (leaf positions); -1: no such list.
struct FarState
{
  FarBox box;
  double dHi = 0;
  const Tri* near = nullptr; // the nearest triangle of the last box queried above (or this one)
  int side = 0, past = 0, count = -1;
  int list[FarListMax];
};

/// The nearest query of a box's centre (q.tri < 0: no triangle) as the
/// callers' functor returns it: its distance and the side farSideAt gives.
struct FarQuery
{
  const Tri* tri = nullptr; // null: none
  bool found = false;
  double dist = 0;
  int side = 0;
};

/// The upper bound of the nearest distance of a sub-box's centre from the
/// box `parent` enclosing it: the parent's bound plus the offset, or the
/// distance to the nearest triangle found above (much tighter where that is
/// the sub-box's nearest too).
LVDIF_HD double farSubBound(const FarState& parent, const FarBox& box, double big)
{
  double d = farChildBound(parent.dHi, box, parent.box, big);
  if (parent.near)
  {
    const Tri& t = *parent.near;
    const V3 v = closestPointOnTriangle(box.centre, t.v[0], t.v[1], t.v[2]).point - box.centre;
    d = std::fmin(d, std::sqrt(dot(v, v)) * (1 + 1e-12));
  }
  return d;
}

/// Tries the box st.box (set by the caller) inside the box of `parent` (null
/// for a block): the side (+1 / -1) when all its voxels are side * band,
/// else 0, with st filled for its sub-boxes. A sub-box of a box past the band
/// inherits that and first tests only the parent's list (with its centre's
/// bound, no query): that decides it when every listed triangle agrees with
/// the parent's side over it or lies beyond its reach. Otherwise it gets its
/// own query: within the band by it, undecided; with the parent's side, its
/// list filtered again with the tighter reach; else a walk of the tree. A box
/// certainly within the band by its parent's bound is not queried.
template <typename Node, typename TriAt, typename Nearest>
LVDIF_HD int farTryBox(const Node* nodes, const FarCone* cones, TriAt&& triAt, Nearest&& nearest, bool pseudo,
  double bandWorld, double margin, double big, const FarState* parent, FarState& st)
{
  st.count = -1;
  st.side = 0;
  st.past = 0;
  st.near = nullptr;
  if (parent)
  {
    st.dHi = farSubBound(*parent, st.box, big);
    st.near = parent->near;
    if (!parent->past)
    {
      // certainly within the band: no query (a shortcut: undecided is never wrong)
      if (st.dHi - st.box.radius <= bandWorld) return 0;
    }
    else
    {
      st.past = 1;
      if (parent->count >= 0)
      {
        st.side = parent->side;
        st.count = farListFilter(triAt, pseudo, st.box, farRadius(st.dHi, st.box, margin), margin, st.side,
          parent->list, parent->count, st.list);
        if (st.count == 0) return st.side;
      }
    }
  }
  const FarQuery q = nearest(st.box.centre);
  if (!q.found)
  {
    // no triangle: nothing is decided below either
    st.dHi = 0;
    st.past = 0;
    st.count = -1;
    return 0;
  }
  st.dHi = q.dist;
  st.near = q.tri;
  if (!st.past) st.past = farPastBand(q.dist, st.box, bandWorld, margin) ? 1 : 0;
  if (!st.past)
  {
    st.count = -1;
    return 0;
  }
  const double reach = farRadius(q.dist, st.box, margin);
  if (st.count > 0 && q.side == st.side)
    st.count = farListFilter(triAt, pseudo, st.box, reach, margin, st.side, st.list, st.count, st.list);
  else
  {
    st.side = q.side;
    st.count = farTreeCollect(nodes, cones, triAt, pseudo, st.box, reach, margin, st.side, st.list);

  }
  return st.count == 0 ? st.side : 0;
}

/// A voxel (box: its position alone) of a cell left undecided (state cell):
/// the cell's side when the cell is past the band and every triangle on its
/// list agrees at the voxel or lies beyond its reach, else 0. No query: a
/// voxel's query is the per-voxel computation itself.
template <typename TriAt>
LVDIF_HD int farVoxelSide(TriAt&& triAt, bool pseudo, double margin, double big, const FarState& cell, const FarBox& box)
{
  if (!cell.past || cell.count < 0 || cell.side == 0) return 0;
  const double reach = farRadius(farSubBound(cell, box, big), box, margin);
  for (int c = 0; c < cell.count; ++c)
    if (!farTriAgrees(triAt(cell.list[c]), pseudo, box, reach, margin, cell.side)) return 0;
  return cell.side;
}

/// Records the box of edge^3 voxels at o (clipped to n) as side * band
/// (set: as below); returns its voxel count.
template <typename Set>
LVDIF_HD long long farFill(const long long o[3], long long edge, const long long n[3], int side, Set&& set)
{
  long long count = 1;
  for (int a = 0; a < 3; ++a) count *= (o[a] + edge < n[a] ? o[a] + edge : n[a]) - o[a];
  for (long long z = o[2]; z < o[2] + edge && z < n[2]; z += FarCell)
    for (long long y = o[1]; y < o[1] + edge && y < n[1]; y += FarCell)
      for (long long x = o[0]; x < o[0] + edge && x < n[0]; x += FarCell)
      {
        const long long cell[3] = { x / FarCell, y / FarCell, z / FarCell };
        set(cell, side, 0xff);
      }
  return count;
}

/// The far voxels of a block (voxel origin v0, box-relative; n: the box's
/// size): FarBlock^3 voxels tried whole, then its 8 halves, their 8 cells of
/// FarCell^3 and the cells' voxels, each level inside a box the level before
/// left undecided (farTryBox). boxOf(origin, edge, FarBox&): the box of
/// edge^3 voxels there (clipped to n); set(cell, sign, mask): the voxels
/// `mask` of a cell (cell = origin / FarCell, bit x + 2 y + 4 z of the voxel
/// inside it) are sign * band. The levels are apart so that the GPU runs them
/// as its threads see fit (a thread per block, then per half and per cell of
/// a block left undecided). Each returns the voxels decided.
/// Voxel v (bit x + 2 y + 4 z) of a cell (origin o2) that its own test left
/// undecided (state s2): the cell's side when its list alone decides the
/// voxel (farVoxelSide), else 0 (also outside n).
template <typename TriAt, typename BoxOf>
LVDIF_HD int farCellVoxel(TriAt&& triAt, bool pseudo, double margin, double big, const FarState& s2,
  const long long o2[3], int v, const long long n[3], BoxOf&& boxOf)
{
  const long long o3[3] = { o2[0] + (v & 1), o2[1] + ((v >> 1) & 1), o2[2] + (v >> 2) };
  if (o3[0] >= n[0] || o3[1] >= n[1] || o3[2] >= n[2]) return 0;
  FarBox voxel;
  boxOf(o3, 1LL, voxel);
  return farVoxelSide(triAt, pseudo, margin, big, s2, voxel);
}

/// One cell (origin o2) of a half left undecided (state s1), with its voxels.
template <typename Node, typename TriAt, typename Nearest, typename BoxOf, typename Set>
LVDIF_HD long long farClassifyCell(const Node* nodes, const FarCone* cones, TriAt&& triAt, Nearest&& nearest,
  bool pseudo, double bandWorld, double margin, double big, const FarState& s1, const long long o2[3],
  const long long n[3], BoxOf&& boxOf, Set&& set)
{
  if (o2[0] >= n[0] || o2[1] >= n[1] || o2[2] >= n[2]) return 0;
  FarState s2;
  boxOf(o2, static_cast<long long>(FarCell), s2.box);
  const int r2 = farTryBox(nodes, cones, triAt, nearest, pseudo, bandWorld, margin, big, &s1, s2);
  if (r2 != 0) return farFill(o2, FarCell, n, r2, set);
  if (!s2.past || s2.count < 0) return 0;
  // the cell's voxels, by its list alone
  long long decided = 0;
  int mask = 0;
  for (int v = 0; v < 8; ++v)
    if (farCellVoxel(triAt, pseudo, margin, big, s2, o2, v, n, boxOf) != 0)
    {
      mask |= 1 << v;
      ++decided;
    }
  if (mask != 0)
  {
    const long long cell[3] = { o2[0] / FarCell, o2[1] / FarCell, o2[2] / FarCell };
    set(cell, s2.side, mask);
  }
  return decided;
}

/// The origin of cell q (bit x + 2 y + 4 z) of the half at o1.
LVDIF_HD void farCellOrigin(const long long o1[3], int q, long long o2[3])
{
  o2[0] = o1[0] + FarCell * (q & 1);
  o2[1] = o1[1] + FarCell * ((q >> 1) & 1);
  o2[2] = o1[2] + FarCell * (q >> 2);
}

/// One half (origin o1) of a block left undecided (state s0), with its cells
/// and their voxels.
template <typename Node, typename TriAt, typename Nearest, typename BoxOf, typename Set>
LVDIF_HD long long farClassifyHalf(const Node* nodes, const FarCone* cones, TriAt&& triAt, Nearest&& nearest,
  bool pseudo, double bandWorld, double margin, double big, const FarState& s0, const long long o1[3],
  const long long n[3], BoxOf&& boxOf, Set&& set)
{
  constexpr long long Half = FarBlock / 2;
  FarState s1;
  boxOf(o1, Half, s1.box);
  const int r1 = farTryBox(nodes, cones, triAt, nearest, pseudo, bandWorld, margin, big, &s0, s1);
  if (r1 != 0) return farFill(o1, Half, n, r1, set);
  long long decided = 0;
  for (int q = 0; q < 8; ++q)
  {
    long long o2[3];
    farCellOrigin(o1, q, o2);
    decided += farClassifyCell(nodes, cones, triAt, nearest, pseudo, bandWorld, margin, big, s1, o2, n, boxOf, set);
  }
  return decided;
}

/// A whole block: its own test, then its halves (farClassifyHalf).
template <typename Node, typename TriAt, typename Nearest, typename BoxOf, typename Set>
LVDIF_HD long long farClassifyBlock(const Node* nodes, const FarCone* cones, TriAt&& triAt, Nearest&& nearest,
  bool pseudo, double bandWorld, double margin, double big, const long long v0[3], const long long n[3],
  BoxOf&& boxOf, Set&& set)
{
  FarState s0;
  boxOf(v0, static_cast<long long>(FarBlock), s0.box);
  const int r0 = farTryBox(nodes, cones, triAt, nearest, pseudo, bandWorld, margin, big, nullptr, s0);
  if (r0 != 0) return farFill(v0, FarBlock, n, r0, set);
  constexpr long long Half = FarBlock / 2;
  long long decided = 0;
  for (int h = 0; h < 8; ++h)
  {
    const long long o1[3] = { v0[0] + Half * (h & 1), v0[1] + Half * ((h >> 1) & 1), v0[2] + Half * (h >> 2) };
    if (o1[0] >= n[0] || o1[1] >= n[1] || o1[2] >= n[2]) continue;
    decided += farClassifyHalf(nodes, cones, triAt, nearest, pseudo, bandWorld, margin, big, s0, o1, n, boxOf, set);
  }
  return decided;
}
static_assert(FarBlock == 4 * FarCell && FarCell == 2, "levels: block, halves, cells of 2^3, voxels");

/// The far voxels of a box of voxels (box-relative): per cell of FarCell^3
/// voxels (cx + count[0] * (cy + count[1] * cz)) the voxels in mask (bit
/// x + 2 y + 4 z inside the cell) are sign * band; the others (mask 0 for
/// all of them when sign is 0) are computed one by one.
struct FarCells
{
  std::int64_t count[3] = { 0, 0, 0 };
  std::vector<std::int8_t> sign;
  std::vector<std::uint8_t> mask;
};

/// The largest |coordinate| of the mesh and of the grid's voxel positions.
double farScale(const PreparedMesh& mesh, const GridGeometry& grid);

/// The normal cones of the BVH's nodes over the sign planes of `tris`.
std::vector<FarCone> farCones(const Bvh& bvh, const PreparedMesh& mesh);

/// CPU: fills cells for `box` (on OpenMP threads); returns the voxels decided.
/// pseudo: PseudoNormal (else Normal) signs.
std::int64_t classifyFarCells(const NearestIndex& index, const Bvh& bvh, const std::vector<FarCone>& cones,
  const PreparedMesh& mesh, const GridGeometry& grid, const VoxelBox& box, double bandWorld, bool pseudo,
  FarCells& cells);

/// CPU, the signs not taken from the nearest triangle (WindingNumber,
/// Unsigned: the sign pass comes after): fills cells with +1 where every voxel
/// is past the band, so +band before its sign, by the same blocks and halves
/// (not cells: the band bricks take the rest) and the same margins
/// (farPastBand) without the side test; returns the voxels decided. Each box
/// costs one query bounded a little past the band.
std::int64_t classifyBandCells(const NearestIndex& index, const PreparedMesh& mesh, const GridGeometry& grid,
  const VoxelBox& box, double bandWorld, FarCells& cells);

} // namespace detail::meshtosdf
} // namespace lvdif
