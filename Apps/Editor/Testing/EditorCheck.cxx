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
//   --mesh M.ply        the exported mesh has triangles inside the volume.
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkImageDifference.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPNGReader.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLImageDataReader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

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

double analytic(int i, int j, int k)
{
  const double c = 31.5, r = 0.35 * 64;
  const double d = std::sqrt((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c)) - r;
  return std::max(-8.0, std::min(8.0, d));
}

// Dictionary quantisation bound used by the Core tests: fine near 0, coarser far out.
double tolerance(double d)
{
  return 1e-3 + 2e-2 * std::fabs(d);
}

void checkSphere(const char* path, bool added)
{
  auto img = readVolume(path);
  int dims[3];
  img->GetDimensions(dims);
  check(dims[0] == 64 && dims[1] == 64 && dims[2] == 64, std::string(path) + " is 64^3");
  auto* sdf = vtkFloatArray::SafeDownCast(img->GetPointData()->GetArray("sdf"));
  auto* rgba = vtkUnsignedCharArray::SafeDownCast(img->GetPointData()->GetArray("rgba"));
  check(sdf && rgba, "sdf and rgba arrays present");
  if (!sdf || !rgba || dims[0] != 64)
    return;
  double worst = 0;
  long outward = 0, gained = 0, coloured = 0, grey = 0;
  vtkIdType id = 0;
  for (int k = 0; k < 64; ++k)
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i, ++id)
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
  const long n = 64L * 64 * 64;
  if (!added)
  {
    std::printf("max excess over the tolerance: %g\n", worst);
    check(worst <= 0, "every voxel equals the analytic sphere (within the dictionary's precision)");
    check(grey == n, "every colour is the default grey (" + std::to_string(grey) + "/" + std::to_string(n) + ")");
  }
  else
  {
    std::printf("voxels moved outwards: %ld, gained material: %ld, brush-coloured: %ld\n", outward, gained, coloured);
    check(outward == 0, "add never removes material");
    check(gained > 100, "the stroke added material");
    check(coloured > 100, "the stroke coloured voxels");
  }
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

int main(int argc, char* argv[])
{
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--sphere") && i + 1 < argc)
      checkSphere(argv[++i], false);
    else if (!std::strcmp(argv[i], "--added") && i + 1 < argc)
      checkSphere(argv[++i], true);
    else if (!std::strcmp(argv[i], "--image") && i + 2 < argc)
    {
      checkImage(argv[i + 1], argv[i + 2]);
      i += 2;
    }
    else if (!std::strcmp(argv[i], "--mesh") && i + 1 < argc)
      checkMesh(argv[++i]);
    else
    {
      std::fprintf(stderr, "usage: %s [--sphere V.vti] [--added V.vti] [--image T.png B.png] [--mesh M.ply]\n", argv[0]);
      return 2;
    }
  }
  return failures == 0 ? 0 : 1;
}
