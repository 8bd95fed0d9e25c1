// The warnings of a mesh-to-SDF call (MeshToSdfWarnings.h).
#include "MeshToSdfWarnings.h"

#include "MeshToSdfInternal.h"
#include "MeshToSdfOrientation.h"
#include "MeshToSdfParallelSort.h"
#include "lvdif/Memory.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace lvdif
{
namespace detail::meshtosdf
{

/// How deep inside a voxel must lie to count for warnIfNothingInside (a
/// negative distance): 1 voxel (`oneVoxel` in output units), since open
/// sheets are lined with a film of inside voxels, or half the band when the
/// band is narrower: every inside voxel then saturates at -band (before, a
/// closed mesh with --band 1 got the "no surface" warning).
float deepInsideLimit(float oneVoxel, float band)
{
  return -std::min(oneVoxel, 0.5f * band);
}

namespace
{

/// stats.warnings when some parts of the mesh vanish while others do not: a
/// connected part (faces joined by welded vertices) smaller than a voxel on
/// every axis whose open bounds hold no grid point on some axis has no voxel
/// centre inside it, so it leaves no surface (a small detached part was lost without
/// a word). A part larger than a voxel that still holds no voxel centre (a
/// thin wire or plate) is not detected.
void warnIfPartsVanish(const MeshToSdfPrepared& mesh, const GridGeometry& grid, MeshToSdfStats& stats)
{
  const std::vector<std::array<float, 6>>& box = mesh.impl().partBounds();
  std::size_t vanish = 0;
  for (const auto& b : box)
  {
    bool small = true, between = false;
    for (int a = 0; a < 3; ++a)
    {
      const double h = grid.spacing[a], lo = (b[a] - grid.origin[a]) / h, hi = (b[3 + a] - grid.origin[a]) / h;
      small = small && b[3 + a] - b[a] < h;
      // no grid point k with lo < k < hi: one on the bounds is on the part's
      // surface at most, never inside it (a fitted grid puts one on the mesh's
      // bounds, and a centred axis one on its middle). Within a thousandth of a
      // voxel (the distances' finest step) counts as on the bounds: the fitted
      // grid's point on them came out a hair inside in double arithmetic
      // (29.000000000000004 against 29), and a small part far from the rest,
      // which sets the bounds, vanished without the warning.
      const double t = 1e-3;
      between = between || std::floor(lo + t) + 1 >= hi - t;
    }
    vanish += small && between;
  }
  if (vanish == 0) return;
  std::ostringstream w;
  w << "mesh to SDF: " << vanish << " of " << box.size()
    << " parts of the mesh (faces joined by shared vertices) are smaller than a voxel (spacing "
    << std::min({ grid.spacing[0], grid.spacing[1], grid.spacing[2] })
    << ") and hold no voxel centre, so they leave no surface; use more voxels (a higher resolution / --dims)";
  stats.warnings.push_back(w.str());
}

/// Exact duplicate faces (the same three welded corners) of a prepared mesh,
/// for the warnings: a duplicate's edges do not cancel against its
/// neighbours', so each isolated one adds 3 to boundaryEdges (edges of
/// non-zero net multiplicity), and a closed box with two faces duplicated was
/// reported with "8 boundary edges" (and, when nothing was inside, as "open").
struct DuplicateFaces
{
  std::size_t copies = 0;  // faces beyond the first of each group (what removing the duplicates removes)
  std::size_t opposed = 0; // faces cancelled by a copy of opposite orientation (group size - |net|)
  std::size_t stacked = 0; // same-orientation copies beyond the first (sum of |net| - 1)
  /// boundaryEdges of the mesh with every group kept once, in its net
  /// orientation; where the copies cancel, in whichever orientation closes
  /// the edge (the re-orientation's choice: a double-sided mesh whose copies
  /// came first in some pairs was said to keep hundreds of boundary edges)
  std::size_t boundaryWithout = 0;
};

/// Counts the duplicate groups by a sort of the faces' sorted corner ids and
/// the edges of the mesh with each group kept once by a sort of their uses
/// (on the OpenMP threads; called only for a mesh with boundary edges or
/// edges of more than two faces, or a field with nothing inside: a clean
/// closed mesh's call never pays for it).
DuplicateFaces duplicateFaces(const PreparedMesh& m)
{
  DuplicateFaces d;
  const std::size_t n = m.welded.size();
  requireMemory(static_cast<std::uint64_t>(n) * 64, "mesh to SDF: the duplicate-face count of the warnings");
  const std::vector<std::array<std::uint32_t, 4>> key = facesByCornerSet(m.welded); // sorted ids, triangle
  auto parity = [&](const std::array<std::uint32_t, 4>& k) { return cornerParity(m.welded[k[3]], k); };
  struct Use
  {
    std::uint32_t lo, hi;
    int dir; // +1 lo -> hi, -1 hi -> lo, 0 either (a group whose copies cancel)
  };
  std::vector<Use> uses;
  uses.reserve(3 * n);
  auto addFace = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, bool free) {
    const std::uint32_t v[3] = { a, b, c };
    for (int k = 0; k < 3; ++k)
    {
      const std::uint32_t p = v[k], q = v[(k + 1) % 3];
      uses.push_back({ std::min(p, q), std::max(p, q), free ? 0 : (p < q ? 1 : -1) });
    }
  };
  for (std::size_t g = 0; g < n;)
  {
    std::size_t g1 = g;
    int net = 0;
    for (; g1 < n && key[g1][0] == key[g][0] && key[g1][1] == key[g][1] && key[g1][2] == key[g][2]; ++g1)
      net += parity(key[g1]);
    const std::size_t size = g1 - g, absNet = static_cast<std::size_t>(std::abs(net));
    d.copies += size - 1;
    d.opposed += size - absNet;
    d.stacked += absNet > 1 ? absNet - 1 : 0;
    // the group once: its net orientation, or free where the copies cancel
    if (net >= 0)
      addFace(key[g][0], key[g][1], key[g][2], net == 0);
    else
      addFace(key[g][0], key[g][2], key[g][1], false);
    g = g1;
  }
  if (d.copies == 0)
  {
    d.boundaryWithout = m.boundaryEdges;
    return d;
  }
  std::vector<std::array<std::uint32_t, 3>> sorted(uses.size()); // lo, hi, dir + 1 (a total order with ties)
  for (std::size_t i = 0; i < uses.size(); ++i)
    sorted[i] = { uses[i].lo, uses[i].hi, static_cast<std::uint32_t>(uses[i].dir + 1) };
  parallelSort(sorted, std::less<std::array<std::uint32_t, 3>>());
  for (std::size_t e = 0; e < sorted.size();)
  {
    std::size_t e1 = e;
    int mult = 0, free = 0;
    for (; e1 < sorted.size() && sorted[e1][0] == sorted[e][0] && sorted[e1][1] == sorted[e][1]; ++e1)
    {
      const int dir = static_cast<int>(sorted[e1][2]) - 1;
      mult += dir;
      free += dir == 0;
    }
    // the free uses can cancel mult when there are enough of them, of its parity
    d.boundaryWithout += !(std::abs(mult) <= free && (mult + free) % 2 == 0);
    e = e1;
  }
  return d;
}

/// The option that keeps each duplicate group once and orients the faces
/// (the winding-number sign of the re-oriented mesh), as every front end names it.
constexpr const char* ReorientOption =
  "--reorient, lvdif-editor --mesh-reorient, ReorientFaces, the editor's \"Re-orient faces\"";

/// What a mesh's duplicate faces do, in one sentence for the warnings:
/// counts, that the mesh is closed without them where it is, and what the
/// sign makes of them.
std::string describeDuplicates(const PreparedMesh& m, const DuplicateFaces& d)
{
  std::ostringstream w;
  w << d.copies << " of the mesh's " << m.tris.size() << " faces are exact duplicates of another face (the same three corners)";
  if (d.stacked > 0) w << ": " << d.stacked << " doubled in the same orientation";
  if (d.opposed > 0)
    w << (d.stacked > 0 ? ", and " : ": ") << d.opposed << " faces are cancelled by exact duplicates of opposite orientation";
  if (d.boundaryWithout == 0)
  {
    w << "; the mesh is closed once each is kept once";
    if (m.boundaryEdges > 0)
      w << " (its " << m.boundaryEdges << " edges of non-zero net multiplicity are the duplicates' edges, not holes)";
  }
  else
    w << "; with each kept once the mesh still has " << d.boundaryWithout << " boundary edges";
  return w.str();
}

} // namespace

/// stats.warnings when a signed field over the whole grid has no voxel
/// inside (`inside`: voxels deeper than deepInsideLimit inside the surface);
/// when some voxel is inside, the parts that vanish (warnIfPartsVanish).
/// Returns true when its warning named the mesh's duplicate faces (then
/// warnIfFacesDuplicated says nothing more).
bool warnIfNothingInside(const MeshToSdfPrepared& mesh, const GridGeometry& grid, const MeshToSdfOptions& options,
  std::int64_t inside, MeshToSdfStats& stats)
{
  if (options.sign == SignMode::Unsigned) return false;
  if (inside > 0)
  {
    warnIfPartsVanish(mesh, grid, stats);
    return false;
  }
  const double h = std::min({ grid.spacing[0], grid.spacing[1], grid.spacing[2] });
  std::ostringstream w;
  // duplicates that cancel every face of a closed mesh leave a winding number
  // of 0 everywhere: not an open mesh, nor voxels too large (what it said)
  const DuplicateFaces dup = duplicateFaces(mesh.impl().mesh);
  if (dup.copies > 0 && (dup.boundaryWithout == 0 || dup.opposed > 0))
  {
    w << "mesh to SDF: no voxel is inside the mesh (deeper than 1 voxel): " << describeDuplicates(mesh.impl().mesh, dup)
      << "; faces and their reversed copies cancel, so the "
      << (options.sign == SignMode::WindingNumber ? "winding number is 0 there" : "sign reads cancelled normals there")
      << " and meshing the field gives no surface (at most slivers within a voxel of the mesh); remove the duplicated faces";
    const PreparedMesh& m = mesh.impl().mesh;
    if (m.boundaryEdges > 0 || m.crowdedEdges > 0)
      w << ", or use the winding-number sign with the faces re-oriented, which keeps each duplicate once (" << ReorientOption << ")";
    else // every copy is alone with its face (no edge of more than two faces): kept once, a lone face
      w << " (re-orienting the faces cannot help: each duplicated face is alone with its copies, and a lone face encloses "
           "nothing)";
    stats.warnings.push_back(w.str());
    return true;
  }
  if (dup.boundaryWithout > 0)
  {
    w << "mesh to SDF: no voxel is inside the mesh (deeper than 1 voxel): it is open (" << dup.boundaryWithout
      << " boundary edges" << (dup.copies > 0 ? " once its duplicate faces are kept once" : "") << ") and encloses no volume deeper than one voxel at any voxel centre"
      << (options.sign == SignMode::WindingNumber ? " (|winding number| >= 1/2 nowhere farther than one voxel from the mesh, as for a single open sheet)"
                                                  : "")
      << ", so meshing the field gives no surface (at most slivers within a voxel of the mesh); close the mesh, or use the "
         "pseudo-normal sign (--sign pseudo, lvdif-editor --mesh-sign pseudo, vtkMeshToSDF's PSEUDO_NORMAL, the "
         "editor's \"Pseudo-normal\": each "
         "side of a sheet gets its own sign) or the unsigned distance meshed at a positive iso-value (a shell "
         "around the sheet; vtkMeshToSDF's UNSIGNED, not in lvdif mesh-to-sdf)";
  }
  else
  {
    // an explicit grid may lie beside the mesh, or over a part of its bounds
    // that is outside it: not a matter of the voxels' size
    const PreparedMesh& m = mesh.impl().mesh;
    bool reaches = true, covers = true;
    std::ostringstream spans;
    spans.precision(6);
    spans << "the voxel centres span ";
    for (int a = 0; a < 3; ++a)
    {
      const double g0 = grid.origin[a], g1 = grid.origin[a] + grid.spacing[a] * static_cast<double>(grid.dims[a] - 1);
      reaches = reaches && g0 <= m.hi[a] && g1 >= m.lo[a];
      covers = covers && g0 <= m.lo[a] && g1 >= m.hi[a];
      spans << (a ? " x " : "") << "[" << g0 << ", " << g1 << "]";
    }
    spans << ", the mesh ";
    for (int a = 0; a < 3; ++a) spans << (a ? " x " : "") << "[" << m.lo[a] << ", " << m.hi[a] << "]";
    w << "mesh to SDF: no voxel centre lies inside the mesh (deeper than 1 voxel): ";
    if (!reaches)
      w << "the grid does not reach the mesh (" << spans.str()
        << "), so meshing the field gives no surface (at most slivers within a voxel of the mesh); place the grid over the mesh, or "
           "let it be fitted to the mesh";
    else if (!covers)
      w << "the grid covers only a part of the mesh's bounds, and no voxel centre there is inside (" << spans.str()
        << "), so meshing the field gives no surface (at most slivers within a voxel of the mesh); place the grid over the whole "
           "mesh, or let it be fitted to the mesh";
    else
      w << "the voxels (spacing " << h
        << ") are larger than the mesh's parts, so meshing the field gives no surface (at most slivers within a voxel of the mesh); "
           "use more voxels (a higher resolution / --dims) or less padding";
  }
  stats.warnings.push_back(w.str());
  return false;
}

/// stats.warnings when the mesh has exact duplicate faces, unless
/// warnIfNothingInside named them (`said`) or the call keeps each duplicate
/// once (reorientFaces). A mesh with boundary edges (isolated duplicates
/// count 3 each): any duplicates (same-orientation ones gave no word at all,
/// and the CLI's "8 boundary edges" read as an open mesh). A closed mesh:
/// only copies of opposite orientation, which cancel whole closed parts
/// (winding number 0 there; the normal and pseudo-normal signs read
/// cancelled normals: a sphere at 128^3 had 358k of its 2M voxels of the
/// wrong pseudo-normal sign, without a word); looked for only when some edge has more than two faces, as every
/// duplicate that is not alone with its copies makes, so a clean closed mesh
/// pays nothing. Doubled in one orientation, a closed part's field is
/// unchanged (|w| >= 1/2 as before): not named.
void warnIfFacesDuplicated(
  const MeshToSdfPrepared& mesh, const MeshToSdfOptions& options, MeshToSdfStats& stats, bool said)
{
  const PreparedMesh& m = mesh.impl().mesh;
  const bool closed = m.boundaryEdges == 0;
  if (said || (closed && (m.crowdedEdges == 0 || options.sign == SignMode::Unsigned)) ||
    (options.sign == SignMode::WindingNumber && options.reorientFaces))
    return;
  const DuplicateFaces dup = duplicateFaces(m);
  if (dup.copies == 0 || (closed && dup.opposed == 0)) return;
  std::ostringstream w;
  w << "mesh to SDF: " << describeDuplicates(m, dup) << "; ";
  switch (options.sign)
  {
  case SignMode::WindingNumber:
    w << "the winding number counts each face as often as it appears (a doubled face twice, a face and its reversed "
         "copy not at all)";
    if (closed)
      w << ", so the closed parts whose faces all have reversed copies are empty (winding number 0 inside)";
    else
      w << ", and the exact field of such faces is slower to compute";
    break;
  case SignMode::Unsigned:
    w << "the unsigned distance is the same with or without them";
    break;
  default:
    w << "the " << (options.sign == SignMode::Normal ? "normal" : "pseudo-normal")
      << " sign sums their normals with their neighbours' (a face and its reversed copy cancel), so it may be wrong "
         "next to them";
    if (closed)
      w << "; where every face of a closed part has a reversed copy, the normals of its edges and vertices cancel and "
           "the sign can be wrong far from the mesh too (the winding number of such faces as given is 0: they bound no "
           "volume)";
    break;
  }
  w << "; remove the duplicated faces, or use the winding-number sign with the faces re-oriented, which keeps each "
       "duplicate once"
    << (closed ? "" : " and is faster") << " (" << ReorientOption << ")";
  stats.warnings.push_back(w.str());
}

/// stats.warnings when the faces' orientation is inconsistent and the sign
/// cannot be what the user means. Winding sign without reorientFaces: faces
/// reversed against their neighbours (the orientation pass's F; under each the
/// winding number drops below 1/2, w_M = w_M+ - 2 w_t, which carves an extra
/// surface into the solid); the exact field of the faces as given is also several times
/// slower to compute than the re-oriented one (docs/MESH_TO_SDF.md, "Damaged
/// meshes"). Normal and pseudo-normal signs: edges whose two faces run them
/// the same way (the prepared mesh's orientation seams), near which those
/// signs read the reversed faces' normals.
void warnIfFacesReversed(const MeshToSdfPrepared& mesh, const MeshToSdfOptions& options, MeshToSdfStats& stats)
{
  constexpr const char* option = ReorientOption;
  if (options.sign == SignMode::Normal || options.sign == SignMode::PseudoNormal)
  {
    const std::size_t seams = mesh.impl().mesh.orientationSeams;
    if (seams == 0) return;
    std::ostringstream m;
    m << "mesh to SDF: " << seams << " edges join faces of opposite orientation (faces reversed against their "
      << "neighbours), so the " << (options.sign == SignMode::Normal ? "normal" : "pseudo-normal")
      << " sign is wrong on the far side of the reversed faces"
      << (options.svfFilters != 0 ? " (the sign voxel filters that ran may have repaired part of it)" : "")
      << "; if the faces bound one solid, use the winding-number sign with its faces re-oriented (" << option << ")";
    stats.warnings.push_back(m.str());
    return;
  }
  if (options.sign != SignMode::WindingNumber || options.reorientFaces || !mesh.impl().hasWindingSigner()) return;
  double unused = 0;
  const detail::meshtosdf::WindingSigner& w = mesh.impl().windingSigner(unused);
  // (duplicates of opposite orientation: warnIfFacesDuplicated, for every sign)
  const std::size_t reversed = w.reversedFaces();
  if (reversed == 0) return;
  const double faces = static_cast<double>(std::max<std::size_t>(1, mesh.triangles()));
  std::ostringstream m;
  m.precision(3);
  m << "mesh to SDF: the faces' orientation is inconsistent: ";
  {
    m << reversed << " of " << mesh.triangles() << " faces (" << 100.0 * static_cast<double>(reversed) / faces
      << " %) run against their neighbours, so the winding number of the faces as given falls below 1/2 under "
         "them and the field has extra surfaces inside the solid there";
  }
  m << ", and the exact field of such faces is slower to compute; if the faces bound one solid, re-orient them ("
    << option << "), which is also faster";
  stats.warnings.push_back(m.str());
}

} // namespace detail::meshtosdf
} // namespace lvdif
