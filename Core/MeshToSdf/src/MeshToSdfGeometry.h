// Internal geometry of mesh to SDF (double precision): vectors, the prepared
// triangle record, the exact closest point on a triangle with the feature it
// lies on, the solid angle of a triangle, point/box distances.
#pragma once

#include "lvdif/HostDevice.h"
#include "lvdif/Memory.h"

#include <array>
#include <cmath>
#include <cstdint>

// Shared by the CPU code and the CUDA kernels (MeshToSdfCuda.cu).

namespace lvdif
{
namespace detail::meshtosdf
{

constexpr double FourPi = 12.566370614359172; // solid angle of the whole sphere

struct V3
{
  double x = 0, y = 0, z = 0;
  LVDIF_HD double operator[](int a) const { return a == 0 ? x : (a == 1 ? y : z); }
};
LVDIF_HD V3 operator+(V3 a, V3 b) { return { a.x + b.x, a.y + b.y, a.z + b.z }; }
LVDIF_HD V3 operator-(V3 a, V3 b) { return { a.x - b.x, a.y - b.y, a.z - b.z }; }
LVDIF_HD V3 operator*(double s, V3 a) { return { s * a.x, s * a.y, s * a.z }; }
LVDIF_HD double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
LVDIF_HD V3 cross(V3 a, V3 b) { return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x }; }
LVDIF_HD double norm(V3 a) { return std::sqrt(dot(a, a)); }
LVDIF_HD V3 normalized(V3 a)
{
  const double n = norm(a);
  return n > 0 ? (1.0 / n) * a : V3{};
}

/// (B - A) x (C - A): the face normal times twice the area.
LVDIF_HD V3 faceCross(const V3 v[3]) { return cross(v[1] - v[0], v[2] - v[0]); }
/// The record's unit normal from faceCross and its norm: one expression for
/// the host's records and the device's leaf copies (the same bits).
LVDIF_HD V3 unitFaceNormal(V3 c, double len) { return (1.0 / len) * c; }

/// Which feature of triangle (A, B, C) the closest point lies on.
enum Feature : std::uint8_t
{
  FeatVertA,
  FeatVertB,
  FeatVertC,
  FeatEdgeAB,
  FeatEdgeBC,
  FeatEdgeCA,
  FeatFace
};

/// A non-degenerate triangle ready for queries: what every sign mode reads
/// (112 bytes). The normals that only some modes read live in arrays of
/// their own beside the records (TriNormals, CornerNormals), allocated
/// only for those modes: a 13.3M-triangle mesh's records are 1.5 GB
/// instead of 4.4 GB when all of it was one 328-byte record, and the
/// host build faults in and writes that much less.
struct Tri
{
  V3 v[3];
  V3 n; // unit face normal, (B-A)x(C-A) direction
  double area = 0;
  std::uint32_t source = 0; // index in the input mesh
};

/// The pseudo-normals of a triangle's features (Baerentzen & Aanaes 2005):
/// en of edges AB, BC, CA, vn (angle-weighted) of vertices A, B, C. Read by
/// the PseudoNormal sign and the far blocks of the Normal/PseudoNormal signs.
struct TriNormals
{
  V3 en[3];
  V3 vn[3];
};

/// The input mesh's vertex normals at a triangle's corners A, B, C (the
/// Normal sign with useVertexNormals).
struct CornerNormals
{
  V3 n[3];
};

/// The triangle records of a mesh: a LargeVector, whose resizeLarge
/// constructs the records on the threads (Memory.h).
using TriList = LargeVector<Tri>;

/// A triangle's vertices and unit normal: the compact copy the BVH keeps in
/// leaf order (the GPU reads these 96 bytes rather than the 328-byte Tri).
struct LeafTri
{
  V3 v[3];
  V3 n;
};

struct Closest
{
  V3 point;
  double b1 = 0, b2 = 0; // barycentric weights of B and C
  Feature feature = FeatFace;
};

/// Closest point of triangle (a, b, c) to p by Voronoi regions, after Ericson,
/// "Real-Time Collision Detection" (2005), Sect. 5.1.5. Every region test is
/// done in order, so the edge-AB region uses its own parameter d1/(d1-d3)
/// (the original code took the AC parameter there, spec section 1.4).
LVDIF_HD Closest closestPointOnTriangle(V3 p, V3 a, V3 b, V3 c)
{
  const V3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0)
  {
    return { a, 0, 0, FeatVertA };
  }
  const V3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3)
  {
    return { b, 1, 0, FeatVertB };
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
  {
    const double v = d1 / (d1 - d3);
    return { a + v * ab, v, 0, FeatEdgeAB };
  }
  const V3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6)
  {
    return { c, 0, 1, FeatVertC };
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
  {
    const double w = d2 / (d2 - d6);
    return { a + w * ac, 0, w, FeatEdgeCA };
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
  {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return { b + w * (c - b), 1 - w, w, FeatEdgeBC };
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return { a + v * ab + w * ac, v, w, FeatFace };
}

/// Signed solid angle of triangle (a, b, c) seen from p (positive when p is
/// behind the triangle's front), Van Oosterom & Strackee (1983).
LVDIF_HD double solidAngle(V3 p, V3 a, V3 b, V3 c)
{
  const V3 x = a - p, y = b - p, z = c - p;
  const double lx = norm(x), ly = norm(y), lz = norm(z);
  const double num = dot(x, cross(y, z));
  const double den = lx * ly * lz + dot(x, y) * lz + dot(x, z) * ly + dot(y, z) * lx;
  return 2.0 * std::atan2(num, den);
}

/// atan2 from +, -, *, / and sqrt only: IEEE-rounded alike on the CPU and the
/// GPU (contraction off on both), so both give the same bits, unlike the
/// libm and CUDA atan2 (a few ulps apart). Within a few ulps of atan2; any
/// signed zero and finite input. Range reduction atan(a) = pi/4 +
/// atan((a - 1) / (a + 1)) above tan(pi/8), then one halving
/// atan(t) = 2 atan(t / (1 + sqrt(1 + t^2))), then the Taylor series to
/// u^23 (|u| <= 0.2: remainder < 4e-18).
LVDIF_HD double portableAtan2(double y, double x)
{
  const double ay = y < 0 ? -y : y, ax = x < 0 ? -x : x;
  if (ay == 0 && ax == 0) return 0.0;
  const bool steep = ay > ax;
  double a = steep ? ax / ay : ay / ax, off = 0;
  if (a > 0.41421356237309503)
  {
    a = (a - 1) / (a + 1);
    off = 0.7853981633974483;
  }
  const double u = a / (1 + std::sqrt(1 + a * a)), u2 = u * u;
  double series = 1.0 / 23;
  for (int k = 21; k >= 1; k -= 2) series = 1.0 / k - u2 * series;
  double r = off + 2 * (u * series);
  if (steep) r = 1.5707963267948966 - r;
  if (x < 0 || (x == 0 && std::signbit(x))) r = 3.141592653589793 - r;
  return std::signbit(y) ? -r : r;
}

/// solidAngle with portableAtan2: the same bits on the CPU and the GPU
/// (the winding sign's last resort, where w is within rounding of +-1/2).
LVDIF_HD double solidAngleCanonical(V3 p, V3 a, V3 b, V3 c)
{
  const V3 x = a - p, y = b - p, z = c - p;
  const double lx = norm(x), ly = norm(y), lz = norm(z);
  const double num = dot(x, cross(y, z));
  const double den = lx * ly * lz + dot(x, y) * lz + dot(x, z) * ly + dot(y, z) * lx;
  return 2.0 * portableAtan2(num, den);
}

/// Squared distance from p to the box [lo, hi] (0 inside).
LVDIF_HD double pointBoxDist2(V3 p, const double lo[3], const double hi[3])
{
  double s = 0;
  for (int a = 0; a < 3; ++a)
  {
    const double q = p[a];
    const double d = q < lo[a] ? lo[a] - q : (q > hi[a] ? q - hi[a] : 0.0);
    s += d * d;
  }
  return s;
}

/// The pseudo-normal of the feature the closest point lies on (t's face
/// normal in the face, pn's edge or vertex normal elsewhere).
LVDIF_HD V3 featureNormal(const Tri& t, const TriNormals& pn, Feature f)
{
  switch (f)
  {
    case FeatVertA: return pn.vn[0];
    case FeatVertB: return pn.vn[1];
    case FeatVertC: return pn.vn[2];
    case FeatEdgeAB: return pn.en[0];
    case FeatEdgeBC: return pn.en[1];
    case FeatEdgeCA: return pn.en[2];
    default: return t.n;
  }
}

/// The normal the Normal sign takes at a closest point (b1, b2: barycentric
/// weights of B and C): the mesh's vertex normals interpolated where given
/// (corners non-null and non-zero), else the face normal.
/// The sign of a normal-based sign mode at p from its closest point c and the
/// normal n there: -1 inside (behind n), +1 otherwise.
LVDIF_HD float normalSign(V3 p, V3 c, V3 n) { return dot(p - c, n) < 0 ? -1.0f : 1.0f; }

LVDIF_HD V3 interpolatedNormal(const Tri& t, const CornerNormals* corners, double b1, double b2)
{
  if (corners && dot(corners->n[0], corners->n[0]) > 0)
  {
    const double b0 = 1 - b1 - b2;
    return b0 * corners->n[0] + b1 * corners->n[1] + b2 * corners->n[2];
  }
  return t.n;
}

} // namespace detail::meshtosdf
} // namespace lvdif
