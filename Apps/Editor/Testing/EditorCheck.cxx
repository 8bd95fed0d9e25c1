// Checks what the editor test wrote, against independent oracles:
//   --sphere V.vti      V is the 64^3 sphere canvas untouched: every decoded
//                       distance matches the analytic sphere (centre 31.5,
//                       radius 0.35*64), saturated at the 8-voxel band, and
//                       every colour is the default grey.
//   --added V.vti       V is that sphere after an Add stroke: no voxel moved
//                       outwards (union never removes material), some voxels
//                       gained material, and some carry the brush colour.
//   --image T.png B.png the screenshot matches the baseline (vtkImageDifference,
//                       as VTK's regression tests); a missing baseline fails
//                       and says where the new image is.
//   --removed V.vti     V is the sphere after a Subtract stroke (Ctrl + Add): no
//                       voxel moved inwards, some lost material.
//   --changed V.vti     V is the sphere after a shaping stroke (smooth, inflate,
//                       grab, flatten, crease, pinch, paint): some voxel differs from the
//                       untouched canvas (distance or colour).
//   --smoothed V.vti    V is the sphere after a smoothing stroke: no distance moved
//                       by more than 0.25 voxel (a crease moves it 1.5) and some moved.
//   --mirror-x V.vti    V is its own mirror image about x = 31.5, voxel by voxel
//                       (distance and colour; a stroke with --mirror x).
//   --volume V.vti      V is a readable 64^3 volume with sdf and rgba (e.g. what
//                       Ctrl+Shift+S saved).
//   --script-shape V.vti  V is sphere.lvs's result: the analytic sphere minus the cube.
//   --script-on-empty V.vti  V is sphere-on-empty.lvs run on the 64^3 start
//                       canvas: its one sphere and nothing else (no starter sphere).
//   --same A.vti B.vti  A and B are the same volume: dimensions, every distance
//                       and every colour equal.
//   --mesh M.ply        the exported mesh has triangles inside the volume.
//   --write-cone-obj F.obj  writes a cone with its apex up (+y) for the upright test.
//   --write-matcap-png F.png  writes a 64 x 64 matcap ramp (red = u, green = v,
//                       blue 200; u, v from the lower left) for --matcap.
//   --write-sphere-obj F.obj   writes a UV sphere (centre MeshC, radius MeshR,
//                       128 x 64 segments) for --open-mesh (runs before the editor).
//   --write-sphere-obj-reversed-cap F.obj   the same sphere with its top quarter's
//                       faces reversed (a damaged export; --mesh-reorient repairs it).
//   --dab-on-uniform V.vti inside|outside X Y Z R   V was a canvas filled
//                       uniformly (Full: inside, Empty: outside) and one dab
//                       of radius R at voxel (X, Y, Z) changed it: some voxel
//                       changed sides, and every one that did lies within
//                       R + 1.5 voxels of (X, Y, Z).
//   --write-stretched-vti F.vti   writes a 48 x 24 x 48 .vti of spacing
//                       (1, 2, 1), a sphere of radius 15 world units in its
//                       middle (sdf in x voxels, grey), for the cursor test.
//   --cursor-aspect T.png RATIO   the pure green pixels (the cursor in a
//                       --color #00ff00 run, drawn unlit) span a box of
//                       height / width = RATIO within 15 %.
//   --inside-view T.png  the model (pixels brighter than the background) is in
//                       the picture and reaches none of its four sides.
//   --tube-thickness T.png RATIO   a --color #00ff00 Dynamic stroke's preview
//                       (translucent green) is at its thickest RATIO times as
//                       tall as the cursor (pure green, the full radius at
//                       the stroke's end) within 20 %.
//   --mesh-sphere V.vti V is that sphere converted by --open-mesh: every voxel's
//                       distance equals the analytic sphere's in voxel units
//                       (world distance / spacing, saturated at the 8-voxel
//                       band) within the tessellation's sagitta plus the
//                       dictionary's precision, and the grid is fitted (64 on
//                       every axis, the box contains the sphere).
#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkImageDifference.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace
{
int failures = 0;
void check(bool ok, const std::string& what)
{
  std::printf("%s: %s\n", ok ? "ok" : "FAILED", what.c_str());
  failures += ok ? 0 : 1;
}

vtkSmartPointer<vtkImageData> readVolume(const char* path)
{
  vtkNew<vtkXMLImageDataReader> r;
  r->SetFileName(path);
  r->Update();
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->ShallowCopy(r->GetOutput());
  return img;
}

// The sphere of the 64^3 "--fill sphere" canvas.
double Cx = 31.5, Cy = 31.5, Cz = 31.5, R = 0.35 * 64;
double CutZ = 1e9, CutH = 0; // optional subtracted cube (centre (Cx, Cy, CutZ), half edge CutH)

double analytic(int i, int j, int k)
{
  double d = std::sqrt((i - Cx) * (i - Cx) + (j - Cy) * (j - Cy) + (k - Cz) * (k - Cz)) - R;
  if (CutH > 0)
  {
    const double qx = std::fabs(i - Cx) - CutH, qy = std::fabs(j - Cy) - CutH, qz = std::fabs(k - CutZ) - CutH;
    const double ox = std::max(qx, 0.0), oy = std::max(qy, 0.0), oz = std::max(qz, 0.0);
    const double cube = std::sqrt(ox * ox + oy * oy + oz * oz) + std::min(std::max(qx, std::max(qy, qz)), 0.0);
    d = std::max(d, -cube);
  }
  return std::max(-8.0, std::min(8.0, d));
}

// Dictionary quantisation bound used by the Core tests: fine near 0, coarser far out.
double tolerance(double d)
{
  return 1e-3 + 2e-2 * std::fabs(d);
}

void checkSphere(const char* path, bool added, int n = 64, bool colours = true)
{
  auto img = readVolume(path);
  int dims[3];
  img->GetDimensions(dims);
  check(dims[0] == n && dims[1] == n && dims[2] == n, std::string(path) + " is " + std::to_string(n) + "^3");
  auto* sdf = vtkFloatArray::SafeDownCast(img->GetPointData()->GetArray("sdf"));
  auto* rgba = vtkUnsignedCharArray::SafeDownCast(img->GetPointData()->GetArray("rgba"));
  check(sdf && rgba, "sdf and rgba arrays present");
  if (!sdf || !rgba || dims[0] != n)
    return;
  double worst = 0;
  long outward = 0, gained = 0, coloured = 0, grey = 0;
  vtkIdType id = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i, ++id)
      {
        const double e = analytic(i, j, k);
        const double v = sdf->GetValue(id);
        worst = std::max(worst, std::fabs(v - e) - tolerance(e));
        outward += v > e + tolerance(e);
        gained += v < e - 0.5;
        const unsigned char* c = rgba->GetPointer(4 * id);
        grey += c[0] == 200 && c[1] == 200 && c[2] == 200 && c[3] == 255;
        coloured += c[0] == 0xe0 && c[1] == 0x50 && c[2] == 0x30;
      }
  const long total = long(n) * n * n;
  if (!added)
  {
    std::printf("max excess over the tolerance: %g\n", worst);
    check(worst <= 0, "every voxel equals the analytic shape (within the dictionary's precision)");
    if (colours)
      check(grey == total, "every colour is the default grey (" + std::to_string(grey) + "/" + std::to_string(total) + ")");
  }
  else
  {
    std::printf("voxels moved outwards: %ld, gained material: %ld, brush-coloured: %ld\n", outward, gained, coloured);
    check(outward == 0, "add never removes material");
    check(gained > 100, "the stroke added material");
    check(coloured > 100, "the stroke coloured voxels");
  }
}

const double MeshC[3] = { 0.1, -0.2, 0.3 }, MeshR = 1.0;
const int MeshSlices = 128, MeshStacks = 64;

// A closed cone, apex up (+y, as mesh files are usually Y up): the upright test's input.
void writeConeObj(const char* path)
{
  const double pi = std::acos(-1.0);
  const int n = 48;
  std::FILE* f = std::fopen(path, "w");
  if (!f)
  {
    check(false, std::string("cannot write ") + path);
    return;
  }
  std::fprintf(f, "v 0 1 0\nv 0 -1 0\n"); // apex, base centre
  for (int i = 0; i < n; ++i)
    std::fprintf(f, "v %.9g -1 %.9g\n", 0.6 * std::cos(2 * pi * i / n), 0.6 * std::sin(2 * pi * i / n));
  for (int i = 0; i < n; ++i)
  {
    const int a = 3 + i, b = 3 + (i + 1) % n;
    std::fprintf(f, "f 1 %d %d\nf 2 %d %d\n", b, a, a, b); // outward
  }
  std::fclose(f);
  check(true, std::string("wrote ") + path);
}

/// reversedCap: the faces of the top quarter (the pole's fan and the first
/// quarter of the stacks) written clockwise, as a broken export flips a patch.
void writeSphereObj(const char* path, bool reversedCap = false)
{
  const double pi = std::acos(-1.0);
  std::FILE* f = std::fopen(path, "w");
  if (!f)
  {
    check(false, std::string("cannot write ") + path);
    return;
  }
  // poles, then rings of MeshSlices points; outward, counter-clockwise faces
  std::fprintf(f, "v %.9g %.9g %.9g\n", MeshC[0], MeshC[1], MeshC[2] + MeshR);
  std::fprintf(f, "v %.9g %.9g %.9g\n", MeshC[0], MeshC[1], MeshC[2] - MeshR);
  for (int s = 1; s < MeshStacks; ++s)
  {
    const double t = pi * s / MeshStacks;
    for (int l = 0; l < MeshSlices; ++l)
    {
      const double p = 2 * pi * l / MeshSlices;
      std::fprintf(f, "v %.9g %.9g %.9g\n", MeshC[0] + MeshR * std::sin(t) * std::cos(p),
        MeshC[1] + MeshR * std::sin(t) * std::sin(p), MeshC[2] + MeshR * std::cos(t));
    }
  }
  auto ring = [](int s, int l) { return 3 + (s - 1) * MeshSlices + (l % MeshSlices); }; // 1-based
  auto face = [&](bool reversed, int a, int b, int c) {
    if (reversed) std::swap(b, c);
    std::fprintf(f, "f %d %d %d\n", a, b, c);
  };
  for (int l = 0; l < MeshSlices; ++l)
  {
    face(reversedCap, 1, ring(1, l), ring(1, l + 1));
    face(false, 2, ring(MeshStacks - 1, l + 1), ring(MeshStacks - 1, l));
    for (int s = 1; s + 1 < MeshStacks; ++s)
    {
      const bool cap = reversedCap && s < MeshStacks / 4;
      face(cap, ring(s, l), ring(s + 1, l), ring(s + 1, l + 1));
      face(cap, ring(s, l), ring(s + 1, l + 1), ring(s, l + 1));
    }
  }
  std::fclose(f);
  std::printf("wrote %s\n", path);
}

void checkMeshSphere(const char* path)
{
  auto img = readVolume(path);
  int dims[3];
  img->GetDimensions(dims);
  double o[3], sp[3];
  img->GetOrigin(o);
  img->GetSpacing(sp);
  check(dims[0] == 64 && dims[1] == 64 && dims[2] == 64, "the fitted grid is 64^3");
  check(sp[0] == sp[1] && sp[1] == sp[2], "isotropic voxels");
  auto* sdf = vtkFloatArray::SafeDownCast(img->GetPointData()->GetArray("sdf"));
  check(sdf != nullptr, "sdf array present");
  if (!sdf || dims[0] != 64)
    return;
  for (int a = 0; a < 3; ++a)
    check(o[a] < MeshC[a] - MeshR && o[a] + sp[a] * (dims[a] - 1) > MeshC[a] + MeshR, "the grid contains the sphere");
  // A face of the 128 x 64 UV sphere lies at most R (1 - cos(pi / 64)) inside the sphere.
  const double sagitta = MeshR * (1 - std::cos(std::acos(-1.0) / 64)) / sp[0];
  double worst = 0;
  long inside = 0, expectedInside = 0;
  vtkIdType id = 0;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i, ++id)
      {
        const double x = o[0] + i * sp[0] - MeshC[0], y = o[1] + j * sp[1] - MeshC[1], z = o[2] + k * sp[2] - MeshC[2];
        const double e = std::max(-8.0, std::min(8.0, (std::sqrt(x * x + y * y + z * z) - MeshR) / sp[0]));
        const double v = sdf->GetValue(id);
        worst = std::max(worst, std::fabs(v - e) - tolerance(e) - sagitta);
        inside += v < 0;
        expectedInside += e < -sagitta;
      }
  std::printf("sagitta %g voxels; max excess over the tolerance: %g; inside %ld (analytic, beyond the sagitta: %ld)\n",
    sagitta, worst, inside, expectedInside);
  check(worst <= 0, "every voxel equals the analytic sphere's distance (within sagitta + dictionary precision)");
  check(inside >= expectedInside && inside > 1000, "the inside is negative");
}

void checkImage(const char* test, const char* baseline)
{
  if (!std::ifstream(baseline).good())
  {
    check(false, std::string("baseline ") + baseline + " exists (new image: " + test + ")");
    return;
  }
  vtkNew<vtkPNGReader> a, b;
  a->SetFileName(test);
  b->SetFileName(baseline);
  vtkNew<vtkImageDifference> diff;
  diff->SetInputConnection(a->GetOutputPort());
  diff->SetImageConnection(b->GetOutputPort());
  diff->Update();
  const double err = diff->GetThresholdedError();
  std::printf("image error against %s: %g\n", baseline, err);
  check(err <= 10.0, "the screenshot matches the baseline (thresholded error <= 10, VTK's default)");
}

// Counts voxels farther out / farther in than the untouched sphere, and colour changes.
void compareWithSphere(const char* path, long& outward, long& inward, long& recoloured)
{
  outward = inward = recoloured = 0;
  auto img = readVolume(path);
  int dims[3];
  img->GetDimensions(dims);
  auto* sdf = vtkFloatArray::SafeDownCast(img->GetPointData()->GetArray("sdf"));
  auto* rgba = vtkUnsignedCharArray::SafeDownCast(img->GetPointData()->GetArray("rgba"));
  check(sdf && rgba && dims[0] == 64 && dims[1] == 64 && dims[2] == 64, std::string(path) + " is the 64^3 canvas");
  if (!sdf || !rgba || dims[0] != 64)
    return;
  vtkIdType id = 0;
  for (int k = 0; k < 64; ++k)
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i, ++id)
      {
        const double e = analytic(i, j, k), v = sdf->GetValue(id);
        outward += v > e + tolerance(e) + 0.05;
        inward += v < e - tolerance(e) - 0.05;
        const unsigned char* c = rgba->GetPointer(4 * id);
        recoloured += !(c[0] == 200 && c[1] == 200 && c[2] == 200);
      }
}

void checkMirrorX(const char* path)
{
  auto img = readVolume(path);
  int dims[3];
  img->GetDimensions(dims);
  auto* sdf = vtkFloatArray::SafeDownCast(img->GetPointData()->GetArray("sdf"));
  auto* rgba = vtkUnsignedCharArray::SafeDownCast(img->GetPointData()->GetArray("rgba"));
  check(sdf && rgba, "sdf and rgba arrays present");
  if (!sdf || !rgba)
    return;
  long differ = 0, changed = 0;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        const vtkIdType a = i + dims[0] * (j + vtkIdType(dims[1]) * k);
        const vtkIdType b = (dims[0] - 1 - i) + dims[0] * (j + vtkIdType(dims[1]) * k);
        differ += sdf->GetValue(a) != sdf->GetValue(b) ||
          std::memcmp(rgba->GetPointer(4 * a), rgba->GetPointer(4 * b), 4) != 0;
        changed += std::fabs(sdf->GetValue(a) - analytic(i, j, k)) > 0.5;
      }
  check(changed > 100, "the stroke changed the sphere (" + std::to_string(changed) + " voxels)");
  check(differ == 0, "the volume is its own mirror image in x (" + std::to_string(differ) + " voxels differ)");
}

void checkMesh(const char* path)
{
  vtkNew<vtkPLYReader> r;
  r->SetFileName(path);
  r->Update();
  vtkPolyData* pd = r->GetOutput();
  double b[6];
  pd->GetBounds(b);
  check(pd->GetNumberOfPolys() > 1000, "the exported mesh has triangles (" + std::to_string(pd->GetNumberOfPolys()) + ")");
  check(b[0] >= 0 && b[1] <= 63 && b[2] >= 0 && b[3] <= 63 && b[4] >= 0 && b[5] <= 63, "the mesh lies in the volume");
}
} // namespace

void checkDabOnUniform(const char* path, bool inside, const double c[3], double r)
{
  auto img = readVolume(path);
  int dims[3];
  img->GetDimensions(dims);
  auto* sdf = vtkFloatArray::SafeDownCast(img->GetPointData()->GetArray("sdf"));
  check(sdf != nullptr, std::string(path) + " has an sdf array");
  if (!sdf)
    return;
  long changed = 0, astray = 0;
  double farthest = 0;
  vtkIdType id = 0;
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i, ++id)
        if ((sdf->GetValue(id) < 0) != inside)
        {
          ++changed;
          const double d = std::sqrt((i - c[0]) * (i - c[0]) + (j - c[1]) * (j - c[1]) + (k - c[2]) * (k - c[2]));
          farthest = std::max(farthest, d);
          astray += d > r + 1.5;
        }
  std::printf("voxels that changed sides: %ld, the farthest %g voxels from the dab's centre\n", changed, farthest);
  check(changed > 0, "the brush changed the uniform canvas");
  check(astray == 0, "every change lies within the dab at the expected point (" + std::to_string(astray) + " beyond it)");
}

void writeStretchedVti(const char* path)
{
  vtkNew<vtkImageData> img;
  img->SetDimensions(48, 24, 48);
  img->SetSpacing(1, 2, 1);
  vtkNew<vtkFloatArray> sdf;
  sdf->SetName("sdf");
  vtkNew<vtkUnsignedCharArray> rgba;
  rgba->SetName("rgba");
  rgba->SetNumberOfComponents(4);
  for (int k = 0; k < 48; ++k)
    for (int j = 0; j < 24; ++j)
      for (int i = 0; i < 48; ++i)
      {
        const double x = i - 23.5, y = 2 * j - 23, z = k - 23.5;
        sdf->InsertNextValue(static_cast<float>(std::max(-8.0, std::min(8.0, std::sqrt(x * x + y * y + z * z) - 15))));
        rgba->InsertNextTuple4(200, 200, 200, 255);
      }
  img->GetPointData()->AddArray(sdf);
  img->GetPointData()->AddArray(rgba);
  vtkNew<vtkXMLImageDataWriter> w;
  w->SetFileName(path);
  w->SetInputData(img);
  check(w->Write() == 1, std::string("wrote the stretched volume ") + path);
}

/// A screenshot's pixels (RGB), or nullptr (a failed check) if it is none.
vtkSmartPointer<vtkImageData> readPicture(const char* path, int dims[3])
{
  vtkNew<vtkPNGReader> r;
  r->SetFileName(path);
  r->Update();
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->ShallowCopy(r->GetOutput());
  img->GetDimensions(dims);
  const bool rgb = img->GetNumberOfScalarComponents() >= 3;
  check(rgb, std::string(path) + " is an RGB picture");
  return rgb ? img : nullptr;
}

/// Two exported meshes hold the same triangles (as coordinate triples, each
/// rotated to start at its smallest point, orientation kept), bit for bit.
void checkSameMesh(const char* a, const char* b)
{
  auto triangles = [](const char* path) {
    vtkNew<vtkPLYReader> r;
    r->SetFileName(path);
    r->Update();
    vtkPolyData* pd = r->GetOutput();
    std::vector<std::array<float, 9>> tris;
    vtkCellArray* polys = pd->GetPolys();
    vtkNew<vtkIdList> ids;
    for (polys->InitTraversal(); polys->GetNextCell(ids);)
    {
      if (ids->GetNumberOfIds() != 3)
        continue;
      std::array<std::array<float, 3>, 3> p;
      for (int k = 0; k < 3; ++k)
      {
        double x[3];
        pd->GetPoint(ids->GetId(k), x);
        p[k] = { static_cast<float>(x[0]), static_cast<float>(x[1]), static_cast<float>(x[2]) };
      }
      const int first = static_cast<int>(std::min_element(p.begin(), p.end()) - p.begin());
      std::array<float, 9> t;
      for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c)
          t[3 * k + c] = p[(first + k) % 3][c];
      tris.push_back(t);
    }
    std::sort(tris.begin(), tris.end());
    return tris;
  };
  const auto ta = triangles(a), tb = triangles(b);
  std::printf("triangles: %zu in %s, %zu in %s\n", ta.size(), a, tb.size(), b);
  check(ta.size() > 1000, std::string(a) + " has triangles");
  check(ta == tb, std::string(a) + " and " + b + " hold the same triangles");
}

/// Two screenshots differ in more than `least` pixels (a channel off by more than 8).
void checkImagesDiffer(const char* a, const char* b, long least)
{
  int da[3], db[3];
  auto ia = readPicture(a, da), ib = readPicture(b, db);
  if (!ia || !ib)
    return;
  long differ = 0;
  if (da[0] == db[0] && da[1] == db[1])
  {
    const int ca = ia->GetNumberOfScalarComponents(), cb = ib->GetNumberOfScalarComponents();
    auto* pa = static_cast<unsigned char*>(ia->GetScalarPointer());
    auto* pb = static_cast<unsigned char*>(ib->GetScalarPointer());
    for (long i = 0; i < static_cast<long>(da[0]) * da[1]; ++i)
    {
      bool d = false;
      for (int c = 0; c < 3; ++c)
        d = d || std::abs(int(pa[ca * i + c]) - int(pb[cb * i + c])) > 8;
      differ += d;
    }
  }
  else
    differ = -1;
  std::printf("pixels that differ between %s and %s: %ld\n", a, b, differ);
  check(differ > least, std::string(a) + " and " + b + " differ in more than " + std::to_string(least) + " pixels");
}

/// How many pixels of the picture at `path` pass `is` (RGB bytes; -1 when it
/// cannot be read), and their bounding
/// box in lo, hi (columns, rows; lo > hi when none).
template <typename Is>
long pixelBox(const char* path, int dims[3], Is is, int lo[2], int hi[2])
{
  const auto img = readPicture(path, dims);
  if (!img)
    return -1; // readPicture said why
  lo[0] = dims[0], lo[1] = dims[1], hi[0] = hi[1] = -1;
  long count = 0;
  for (int j = 0; j < dims[1]; ++j)
    for (int i = 0; i < dims[0]; ++i)
      if (is(static_cast<const unsigned char*>(img->GetScalarPointer(i, j, 0))))
      {
        ++count;
        lo[0] = std::min(lo[0], i);
        lo[1] = std::min(lo[1], j);
        hi[0] = std::max(hi[0], i);
        hi[1] = std::max(hi[1], j);
      }
  return count;
}

void checkCursorAspect(const char* path, double ratio)
{
  int dims[3], lo[2], hi[2];
  const long count =
    pixelBox(path, dims, [](const unsigned char* p) { return p[1] > 150 && p[0] < 90 && p[2] < 90; }, lo, hi);
  if (count < 0)
    return;
  check(count > 20, "the cursor is in the picture (" + std::to_string(count) + " pixels)");
  if (count <= 20)
    return;
  const double w = hi[0] - lo[0] + 1, h = hi[1] - lo[1] + 1;
  std::printf("cursor: %g x %g pixels, height / width %g (expected %g)\n", w, h, h / w, ratio);
  check(std::fabs(h / w - ratio) <= 0.15 * ratio, "the cursor's height / width is the spacing's");
}

void checkInsideView(const char* path)
{
  // the model: a pixel brighter than the background gradient (at most 51 in
  // every channel: Background (0.16, 0.17, 0.2), Background2 darker)
  int dims[3], lo[2], hi[2];
  const long count =
    pixelBox(path, dims, [](const unsigned char* p) { return std::max(p[0], std::max(p[1], p[2])) > 70; }, lo, hi);
  if (count < 0)
    return;
  std::printf("model: %ld pixels in columns %d..%d, rows %d..%d of %d x %d\n", count, lo[0], hi[0], lo[1], hi[1],
    dims[0], dims[1]);
  check(count > 1000, "the model is in the picture");
  check(lo[0] > 0 && hi[0] < dims[0] - 1, "the model is whole in the view's width (it reaches no side)");
  check(lo[1] > 0 && hi[1] < dims[1] - 1, "the model is whole in the view's height (it reaches neither end)");
}

void checkTubeThickness(const char* path, double ratio)
{
  int dims[3];
  const auto img = readPicture(path, dims);
  if (!img)
    return;
  // the cursor: unlit pure green; the tube: green blended at 0.45 over the scene
  int cursorLo = dims[1], cursorHi = -1, cursorLeft = dims[0];
  std::vector<int> tubeLo(dims[0], dims[1]), tubeHi(dims[0], -1);
  for (int j = 0; j < dims[1]; ++j)
    for (int i = 0; i < dims[0]; ++i)
    {
      const auto* p = static_cast<unsigned char*>(img->GetScalarPointer(i, j, 0));
      if (p[1] > 230 && p[0] < 40 && p[2] < 40)
      {
        cursorLo = std::min(cursorLo, j);
        cursorHi = std::max(cursorHi, j);
        cursorLeft = std::min(cursorLeft, i);
      }
      else if (p[1] <= 230 && p[1] > p[0] + 60 && p[1] > p[2] + 60)
      {
        tubeLo[i] = std::min(tubeLo[i], j);
        tubeHi[i] = std::max(tubeHi[i], j);
      }
    }
  int thickest = 0;
  for (int i = 0; i < cursorLeft; ++i) // left of the cursor: the tube alone
    thickest = std::max(thickest, tubeHi[i] - tubeLo[i] + 1);
  const int cursor = cursorHi - cursorLo + 1;
  check(cursor > 4 && thickest > 4, "the cursor and the preview are in the picture (" + std::to_string(cursor) +
      " and " + std::to_string(thickest) + " pixels tall)");
  if (cursor <= 4 || thickest <= 4)
    return;
  std::printf("preview %d pixels tall at its thickest, cursor %d: ratio %g (expected %g)\n", thickest, cursor,
    double(thickest) / cursor, ratio);
  check(std::fabs(double(thickest) / cursor - ratio) <= 0.2 * ratio, "the preview's section is the dabs'");
}

void writeMatcapPng(const char* path)
{
  vtkNew<vtkImageData> img;
  img->SetDimensions(64, 64, 1);
  img->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i)
    {
      auto* p = static_cast<unsigned char*>(img->GetScalarPointer(i, j, 0));
      p[0] = static_cast<unsigned char>(4 * i + 2);
      p[1] = static_cast<unsigned char>(4 * j + 2);
      p[2] = 200;
    }
  vtkNew<vtkPNGWriter> w;
  w->SetFileName(path);
  w->SetInputData(img);
  w->Write();
  check(w->GetErrorCode() == 0, std::string("wrote the matcap ramp ") + path);
}

int main(int argc, char* argv[])
{
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--sphere") && i + 1 < argc)
      checkSphere(argv[++i], false);
    else if (!std::strcmp(argv[i], "--script-shape") && i + 1 < argc)
    {
      // Data/Testing sphere.lvs: canvas 48, sphere (24,24,24) r 15, cube cut at z 40, half edge 6.
      Cx = Cy = Cz = 24;
      R = 15;
      CutZ = 40;
      CutH = 6;
      checkSphere(argv[++i], false, 48, false);
    }
    else if (!std::strcmp(argv[i], "--script-on-empty") && i + 1 < argc)
    {
      // sphere-on-empty.lvs: sphere (20,40,24) r 10 on the empty 64^3 canvas
      Cx = 20;
      Cy = 40;
      Cz = 24;
      R = 10;
      checkSphere(argv[++i], false, 64, false);
    }
    else if (!std::strcmp(argv[i], "--added") && i + 1 < argc)
      checkSphere(argv[++i], true);
    else if (!std::strcmp(argv[i], "--image") && i + 2 < argc)
    {
      checkImage(argv[i + 1], argv[i + 2]);
      i += 2;
    }
    else if (!std::strcmp(argv[i], "--removed") && i + 1 < argc)
    {
      long out = 0, in = 0, col = 0;
      compareWithSphere(argv[++i], out, in, col);
      check(in == 0, "no voxel gained material (" + std::to_string(in) + ")");
      check(out > 100, "the stroke removed material (" + std::to_string(out) + " voxels)");
    }
    else if (!std::strcmp(argv[i], "--changed") && i + 1 < argc)
    {
      long out = 0, in = 0, col = 0;
      compareWithSphere(argv[++i], out, in, col);
      check(out + in + col > 50, "the stroke changed the canvas (" + std::to_string(out) + " out, " +
          std::to_string(in) + " in, " + std::to_string(col) + " recoloured)");
    }
    else if (!std::strcmp(argv[i], "--smoothed") && i + 1 < argc)
    {
      auto img = readVolume(argv[++i]);
      auto* sdf = vtkFloatArray::SafeDownCast(img->GetPointData()->GetArray("sdf"));
      double worst = 0;
      long moved = 0;
      if (sdf && sdf->GetNumberOfTuples() == 64 * 64 * 64)
      {
        vtkIdType id = 0;
        for (int k = 0; k < 64; ++k)
          for (int j = 0; j < 64; ++j)
            for (int a = 0; a < 64; ++a, ++id)
            {
              const double e = analytic(a, j, k), dv = std::fabs(sdf->GetValue(id) - e);
              if (std::fabs(e) < 4)
                worst = std::max(worst, dv);
              moved += dv > tolerance(e);
            }
      }
      check(worst <= 0.25, "no distance near the surface moved more than 0.25 (" + std::to_string(worst) + ")");
      check(moved > 20, "the stroke smoothed something (" + std::to_string(moved) + " voxels)");
    }
    else if (!std::strcmp(argv[i], "--mirror-x") && i + 1 < argc)
      checkMirrorX(argv[++i]);
    else if (!std::strcmp(argv[i], "--same") && i + 2 < argc)
    {
      auto a = readVolume(argv[i + 1]), b = readVolume(argv[i + 2]);
      i += 2;
      int da[3], db[3];
      a->GetDimensions(da);
      b->GetDimensions(db);
      auto* sa = vtkFloatArray::SafeDownCast(a->GetPointData()->GetArray("sdf"));
      auto* sb = vtkFloatArray::SafeDownCast(b->GetPointData()->GetArray("sdf"));
      auto* ca = vtkUnsignedCharArray::SafeDownCast(a->GetPointData()->GetArray("rgba"));
      auto* cb = vtkUnsignedCharArray::SafeDownCast(b->GetPointData()->GetArray("rgba"));
      const bool shaped = da[0] == db[0] && da[1] == db[1] && da[2] == db[2] && sa && sb && ca && cb &&
        sa->GetNumberOfValues() == sb->GetNumberOfValues() && ca->GetNumberOfValues() == cb->GetNumberOfValues();
      check(shaped, "both volumes have the same dimensions, sdf and rgba");
      if (shaped)
      {
        vtkIdType differ = 0;
        for (vtkIdType v = 0; v < sa->GetNumberOfValues(); ++v)
          differ += sa->GetValue(v) != sb->GetValue(v) || std::memcmp(ca->GetPointer(4 * v), cb->GetPointer(4 * v), 4) != 0;
        std::printf("voxels that differ: %lld\n", static_cast<long long>(differ));
        check(differ == 0, "every distance and colour equal");
      }
    }
    else if ((!std::strcmp(argv[i], "--starter-extent") || !std::strcmp(argv[i], "--dot-extent")) && i + 1 < argc)
    {
      // the starter shape of a --fill sphere canvas spans 2 x min(64, 0.35 n) voxels
      // (+-1) on each axis: on 256 x 16 x 40 it was a sphere of 11 voxels across;
      // --dot-extent: that sphere (the starter before session 24), the smallest axis's on every axis
      const bool dot = !std::strcmp(argv[i], "--dot-extent");
      auto img = readVolume(argv[++i]);
      int dims[3];
      img->GetDimensions(dims);
      auto* sdf = vtkFloatArray::SafeDownCast(img->GetPointData()->GetArray("sdf"));
      check(sdf != nullptr, std::string(argv[i]) + " has an sdf array");
      if (!sdf)
        continue;
      int lo[3] = { dims[0], dims[1], dims[2] }, hi[3] = { -1, -1, -1 };
      vtkIdType id = 0;
      for (int k = 0; k < dims[2]; ++k)
        for (int j = 0; j < dims[1]; ++j)
          for (int ii = 0; ii < dims[0]; ++ii, ++id)
            if (sdf->GetValue(id) < 0)
            {
              const int p[3] = { ii, j, k };
              for (int a = 0; a < 3; ++a)
                lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
            }
      const double least = 2 * std::min({ 64.0, 0.35 * dims[0], 0.35 * dims[1], 0.35 * dims[2] });
      for (int a = 0; a < 3; ++a)
      {
        const double want = dot ? least : 2 * std::min(64.0, 0.35 * dims[a]), got = hi[a] - lo[a] + 1;
        check(std::fabs(got - want) <= 1.5 && std::fabs((lo[a] + hi[a]) - (dims[a] - 1)) <= 1,
          std::string(argv[i]) + ": the starter shape spans " + std::to_string(int(got)) + " voxels on axis " +
            "xyz"[a] + ", centred; want about " + std::to_string(want));
      }
    }
    else if (!std::strcmp(argv[i], "--volume") && i + 1 < argc)
    {
      auto img = readVolume(argv[++i]);
      int dims[3];
      img->GetDimensions(dims);
      check(dims[0] == 64 && img->GetPointData()->GetArray("sdf") && img->GetPointData()->GetArray("rgba"),
        std::string(argv[i]) + " is a 64^3 volume with sdf and rgba");
    }
    else if (!std::strcmp(argv[i], "--write-cone-obj") && i + 1 < argc)
      writeConeObj(argv[++i]);
    else if (!std::strcmp(argv[i], "--write-matcap-png") && i + 1 < argc)
      writeMatcapPng(argv[++i]);
    else if (!std::strcmp(argv[i], "--write-sphere-obj") && i + 1 < argc)
      writeSphereObj(argv[++i]);
    else if (!std::strcmp(argv[i], "--write-sphere-obj-reversed-cap") && i + 1 < argc)
      writeSphereObj(argv[++i], true);
    else if (!std::strcmp(argv[i], "--dab-on-uniform") && i + 6 < argc)
    {
      const double c[3] = { std::atof(argv[i + 3]), std::atof(argv[i + 4]), std::atof(argv[i + 5]) };
      checkDabOnUniform(argv[i + 1], !std::strcmp(argv[i + 2], "inside"), c, std::atof(argv[i + 6]));
      i += 6;
    }
    else if (!std::strcmp(argv[i], "--write-stretched-vti") && i + 1 < argc)
      writeStretchedVti(argv[++i]);
    else if (!std::strcmp(argv[i], "--cursor-aspect") && i + 2 < argc)
    {
      checkCursorAspect(argv[i + 1], std::atof(argv[i + 2]));
      i += 2;
    }
    else if (!std::strcmp(argv[i], "--inside-view") && i + 1 < argc)
      checkInsideView(argv[++i]);
    else if (!std::strcmp(argv[i], "--tube-thickness") && i + 2 < argc)
    {
      checkTubeThickness(argv[i + 1], std::atof(argv[i + 2]));
      i += 2;
    }
    else if (!std::strcmp(argv[i], "--mesh-sphere") && i + 1 < argc)
      checkMeshSphere(argv[++i]);
    else if (!std::strcmp(argv[i], "--mesh") && i + 1 < argc)
      checkMesh(argv[++i]);
    else if (!std::strcmp(argv[i], "--same-mesh") && i + 2 < argc)
    {
      checkSameMesh(argv[i + 1], argv[i + 2]);
      i += 2;
    }
    else if (!std::strcmp(argv[i], "--images-differ") && i + 3 < argc)
    {
      checkImagesDiffer(argv[i + 1], argv[i + 2], std::atol(argv[i + 3]));
      i += 3;
    }
    else
    {
      std::fprintf(stderr, "usage: %s [--sphere V.vti] [--added V.vti] [--script-shape V.vti] [--image T.png B.png] [--mesh M.ply] [--write-sphere-obj F.obj] [--write-sphere-obj-reversed-cap F.obj] [--mesh-sphere V.vti]\n", argv[0]);
      return 2;
    }
  }
  return failures == 0 ? 0 : 1;
}
