// vtkChunkedMarchingCubes against vtkFlyingEdges3D on the same float SDF
// image, in the same process: full extraction of an analytic torus SDF at
// 512^3 and 1024^3. Reported as ratio = FlyingEdges ms / ours ms (>= 1: we are
// at least as fast). Both compute normals; ours in MERGED mode (one point per
// cut edge, like FlyingEdges) with and without the per-triangle arrays, and in
// PARTITIONED mode (one vtkPolyData per 64^3 chunk).
// Usage: bench_chunked_mc [maxN=1024] [repeats=3]   (maxN < 512: that size alone)
#include "BenchCommon.h"

#include "vtkChunkedMarchingCubes.h"

#include "vtkFloatArray.h"
#include "vtkFlyingEdges3D.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <cmath>
#include <cstdlib>
#include <iostream>

namespace
{
vtkSmartPointer<vtkImageData> torusImage(int n)
{
  auto img = vtkSmartPointer<vtkImageData>::New();
  img->SetDimensions(n, n, n);
  vtkNew<vtkFloatArray> sdf;
  sdf->SetName("sdf");
  sdf->SetNumberOfTuples(static_cast<vtkIdType>(n) * n * n);
  float* d = sdf->GetPointer(0);
  const double c = 0.5 * n + 0.37, R = 0.3 * n, r = 0.12 * n;
#pragma omp parallel for schedule(static)
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double x = i - c, y = j - c + 0.21, z = k - c - 0.13;
        const double q = std::sqrt(x * x + y * y) - R;
        d[i + static_cast<vtkIdType>(n) * (j + static_cast<vtkIdType>(n) * k)] =
          static_cast<float>(std::sqrt(q * q + z * z) - r);
      }
  img->GetPointData()->AddArray(sdf);
  return img;
}

vtkIdType triangles(vtkDataObject* d)
{
  if (auto* pd = vtkPolyData::SafeDownCast(d)) return pd->GetNumberOfCells();
  vtkIdType n = 0;
  auto* pds = vtkPartitionedDataSet::SafeDownCast(d);
  for (unsigned int i = 0; i < pds->GetNumberOfPartitions(); ++i) n += pds->GetPartition(i)->GetNumberOfCells();
  return n;
}
} // namespace

static int benchMain(int argc, char** argv)
{
  const int maxN = argc > 1 ? std::atoi(argv[1]) : 1024;
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 3;
  std::cout << "# bench_chunked_mc\n"
            << bench::machineDescription() << "\nvtkSMPTools backend: " << vtkSMPTools::GetBackend()
            << ", threads " << vtkSMPTools::GetEstimatedNumberOfThreads() << "\n\n";
  std::vector<std::vector<std::string>> rows;
  std::vector<int> sizes;
  for (int n : { 512, 1024 })
    if (n <= maxN) sizes.push_back(n);
  if (sizes.empty()) sizes.push_back(maxN); // a quick run on a small volume
  for (int n : sizes)
  {
    auto img = torusImage(n);
    vtkNew<vtkFlyingEdges3D> fe;
    fe->SetInputData(img);
    fe->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "sdf");
    fe->SetValue(0, 0.0);
    fe->ComputeNormalsOn();
    fe->ComputeScalarsOff();
    const int reps = n >= 1024 ? std::max(1, repeats / 2) : repeats;
    const double feMs = bench::medianMs(reps, [&] {
      fe->Modified();
      fe->Update();
    });
    const vtkIdType feTris = fe->GetOutput()->GetNumberOfCells();
    fe->GetOutput()->Initialize(); // free its memory before ours runs
    rows.push_back({ std::to_string(n) + "^3", "vtkFlyingEdges3D", std::to_string(feTris), bench::fmt(feMs, 1), "1.00" });

    struct Variant
    {
      const char* name;
      int mode;
      bool cellArrays;
    };
    for (const Variant& v : { Variant{ "chunked MERGED", vtkChunkedMarchingCubes::MERGED, false },
           Variant{ "chunked MERGED + cell_ijk", vtkChunkedMarchingCubes::MERGED, true },
           Variant{ "chunked PARTITIONED", vtkChunkedMarchingCubes::PARTITIONED, false } })
    {
      vtkNew<vtkChunkedMarchingCubes> mc;
      mc->SetInputData(img);
      mc->SetChunkEdge(64);
      mc->SetOutputMode(v.mode);
      mc->SetComputeCornerColors(v.cellArrays);
      const double ms = bench::medianMs(reps, [&] {
        mc->Modified();
        mc->Update();
      });
      rows.push_back({ std::to_string(n) + "^3", v.name, std::to_string(triangles(mc->GetOutputDataObject(0))),
        bench::fmt(ms, 1), bench::fmt(feMs / ms, 2) });
    }
  }
  bench::printTable({ "volume", "filter", "triangles", "ms", "ratio FE/ours" }, rows);
  return 0;
}

int main(int argc, char** argv) { return bench::guardedMain(argc, argv, benchMain); }
