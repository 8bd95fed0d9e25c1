// vtkMeshToSDF against vtkImplicitPolyDataDistance (an independent oracle:
// VTK's own closest-cell distance) on a sphere source, the band on by default
// (far chunks collapsed, distances saturated), the grid settings, and clear errors.
#include "vtkMeshToSDF.h"
#include "vtkSparseDictionaryVolume.h"
#include "vtkSparseVolumeToImage.h"

#include "lvdif/DictionaryVolume.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkExecutive.h"
#include "vtkCommand.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkImplicitPolyDataDistance.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace
{
struct ErrorCatcher
{
  vtkNew<vtkCallbackCommand> cb;
  std::string last;
  int count = 0; // errors since the test last reset it
  explicit ErrorCatcher(vtkObject* o)
  {
    this->cb->SetClientData(this);
    this->cb->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
      static_cast<ErrorCatcher*>(client)->last = static_cast<const char*>(call);
      ++static_cast<ErrorCatcher*>(client)->count;
    });
    o->AddObserver(vtkCommand::ErrorEvent, this->cb);
  }
};
/// The filter's sparse output made dense (the explicit conversion).
vtkSmartPointer<vtkImageData> dense(vtkMeshToSDF* f)
{
  vtkNew<vtkSparseVolumeToImage> d;
  d->SetInputConnection(f->GetOutputPort());
  d->Update();
  return d->GetOutput();
}
} // namespace

TEST(vtkMeshToSDF, MatchesImplicitPolyDataDistance)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(16);
  sphere->Update();
  vtkNew<vtkMeshToSDF> f;
  f->SetInputConnection(sphere->GetOutputPort());
  f->SetMaxDimension(30);
  f->SetPadding(3);
  f->SetBandWidth(0); // every distance
  f->SetDevice(vtkMeshToSDF::DEVICE_CPU);
  vtkSmartPointer<vtkImageData> img = dense(f);
  vtkDataArray* sdf = img->GetPointData()->GetArray("sdf");
  ASSERT_NE(sdf, nullptr);
  int dims[3];
  img->GetDimensions(dims);
  EXPECT_EQ(dims[0], 30);
  vtkNew<vtkImplicitPolyDataDistance> oracle;
  oracle->SetInput(sphere->GetOutput());
  const double h = img->GetSpacing()[0];
  int signDisagree = 0;
  double worst = 0;
  for (vtkIdType i = 0; i < img->GetNumberOfPoints(); ++i)
  {
    double p[3];
    img->GetPoint(i, p);
    const double ref = oracle->EvaluateFunction(p);
    const double v = sdf->GetTuple1(i) * h; // voxel units
    // the dictionary's quantization: 0.001 voxel near the surface, coarser far away
    const double tol = (std::fabs(ref) <= 4 * h ? 0.0006 : 0.06) * h + 1e-5;
    worst = std::max(worst, std::fabs(std::fabs(v) - std::fabs(ref)) - tol);
    if (std::fabs(ref) > h && (v < 0) != (ref < 0)) ++signDisagree;
  }
  EXPECT_LE(worst, 0.0); // every voxel within its tolerance
  EXPECT_EQ(signDisagree, 0);
  auto* deg = vtkIdTypeArray::SafeDownCast(f->GetOutputDataObject(0)->GetFieldData()->GetArray("degenerate_triangles"));
  ASSERT_NE(deg, nullptr);
}

TEST(vtkMeshToSDF, BandOnByDefaultCollapsesFarChunks)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(16);
  sphere->Update();
  vtkNew<vtkMeshToSDF> f;
  f->SetInputConnection(sphere->GetOutputPort());
  f->SetMaxDimension(96);
  f->SetDevice(vtkMeshToSDF::DEVICE_CPU);
  f->Update();
  EXPECT_EQ(f->GetBandWidth(), 8.0); // as `lvdif mesh-to-sdf`
  auto* sparse = vtkSparseDictionaryVolume::SafeDownCast(f->GetOutputDataObject(0));
  ASSERT_NE(sparse, nullptr);
  ASSERT_TRUE(sparse->HasVolume());
  EXPECT_EQ(sparse->GetChunkEdge(), 32);
  EXPECT_FALSE(sparse->GetPartitionsBuilt()); // nothing dense was made
  // the chunks far inside and outside are one value each
  EXPECT_LT(sparse->GetNumberOfExpandedChunks(), sparse->GetNumberOfChunks());
  EXPECT_LT(sparse->GetVolumeMemoryBytes(), 0.5 * sparse->GetDenseImageBytes());
  vtkSmartPointer<vtkImageData> img = dense(f);
  vtkNew<vtkImplicitPolyDataDistance> oracle;
  oracle->SetInput(sphere->GetOutput());
  const double h = img->GetSpacing()[0];
  vtkDataArray* sdf = img->GetPointData()->GetArray("sdf");
  int bad = 0;
  for (vtkIdType i = 0; i < img->GetNumberOfPoints(); i += 7)
  {
    double p[3];
    img->GetPoint(i, p);
    const double ref = oracle->EvaluateFunction(p) / h;
    const double expected = std::max(-8.0, std::min(8.0, ref));
    const double tol = std::fabs(expected) <= 4 ? 0.0006 : 0.06;
    bad += std::fabs(std::fabs(sdf->GetTuple1(i)) - std::fabs(expected)) > tol + 1e-4;
  }
  EXPECT_EQ(bad, 0);
}

TEST(vtkMeshToSDF, ExplicitGridAndSpacing)
{
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkMeshToSDF> f;
  f->SetInputConnection(sphere->GetOutputPort());
  f->UseExplicitGridOn();
  f->SetDimensions(7, 9, 11);
  f->SetOrigin(-1, -1, -1);
  f->SetSpacing(0.3, 0.25, 0.2);
  f->SetDevice(vtkMeshToSDF::DEVICE_CPU);
  vtkSmartPointer<vtkImageData> img = dense(f);
  int dims[3];
  img->GetDimensions(dims);
  EXPECT_EQ(dims[0], 7);
  EXPECT_EQ(dims[1], 9);
  EXPECT_EQ(dims[2], 11);
  EXPECT_DOUBLE_EQ(img->GetSpacing()[1], 0.25);
  f->UseExplicitGridOff();
  f->SetSampleSpacing(0.1);
  f->SetPadding(1);
  img = dense(f);
  img->GetDimensions(dims);
  EXPECT_DOUBLE_EQ(img->GetSpacing()[0], 0.1);
  EXPECT_GE(dims[0], 12); // diameter 1 / 0.1 + 2 padding + 1

  // a flat mesh without padding: 2 points (one cell) on its flat axis, by
  // MaxDimension and by SampleSpacing alike (it got 1: nothing to mesh)
  vtkNew<vtkPolyData> sheet;
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(0, 0, 0.5);
  pts->InsertNextPoint(1, 0, 0.5);
  pts->InsertNextPoint(0, 1, 0.5);
  vtkNew<vtkCellArray> tri;
  const vtkIdType ids[3] = { 0, 1, 2 };
  tri->InsertNextCell(3, ids);
  sheet->SetPoints(pts);
  sheet->SetPolys(tri);
  f->SetInputData(sheet);
  f->SetPadding(0);
  for (double spacing : { 0.0, 0.1 })
  {
    f->SetSampleSpacing(spacing);
    img = dense(f);
    img->GetDimensions(dims);
    EXPECT_EQ(dims[2], 2) << "SampleSpacing " << spacing;
    EXPECT_NEAR(img->GetOrigin()[2] + 0.5 * img->GetSpacing()[2], 0.5, 1e-9) << "SampleSpacing " << spacing;
  }
}

TEST(vtkMeshToSDF, ClearErrors)
{
  vtkObject::GlobalWarningDisplayOn(); // ErrorEvent fires only with it on (another test turns it off)
  vtkNew<vtkMeshToSDF> f;
  ErrorCatcher errors(f);
  // an empty mesh (what a failed reader leaves) gives an empty volume without an
  // error, as VTK's filters treat an empty input: ParaView runs the filters below a
  // failed reader, and each added an error of its own ("the input mesh is empty")
  vtkNew<vtkPolyData> empty;
  f->SetInputData(empty);
  f->UseExplicitGridOn();
  EXPECT_EQ(f->GetExecutive()->Update(), 1);
  EXPECT_TRUE(errors.last.empty()) << errors.last;
  auto* emptyOut = vtkSparseDictionaryVolume::SafeDownCast(f->GetOutputDataObject(0));
  EXPECT_TRUE(emptyOut && !emptyOut->HasVolume());

  vtkNew<vtkPolyData> lines;
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(0, 0, 0);
  pts->InsertNextPoint(1, 0, 0);
  lines->SetPoints(pts);
  vtkNew<vtkCellArray> cells;
  const vtkIdType ids[2] = { 0, 1 };
  cells->InsertNextCell(2, ids);
  lines->SetLines(cells);
  errors.last.clear();
  f->SetInputData(lines);
  f->Update();
  EXPECT_NE(errors.last.find("no polygons"), std::string::npos) << errors.last;

  vtkNew<vtkSphereSource> sphere;
  sphere->Update();
  f->SetInputData(sphere->GetOutput());
  f->SetDimensions(1 << 20, 1 << 20, 1 << 20); // refused before allocating
  errors.last.clear();
  f->Update();
  EXPECT_NE(errors.last.find("limit"), std::string::npos) << errors.last;

  // a NaN band width (a computed value gone wrong) is an error: it silently
  // meant "no band", every chunk kept expanded
  f->SetDimensions(16, 16, 16);
  f->SetBandWidth(std::numeric_limits<double>::quiet_NaN());
  errors.last.clear();
  f->Update();
  EXPECT_NE(errors.last.find("BandWidth"), std::string::npos) << errors.last;
  f->SetBandWidth(0); // documented: no band
  errors.last.clear();
  f->Update();
  EXPECT_TRUE(errors.last.empty()) << errors.last;

  // a bad Padding is refused by name on both fitted grids, as a bad BandWidth
  // (docs/USER_GUIDE.md): a negative one was clamped to 0 silently, NaN read
  // "SampleSpacing gives more than 2^20 points along an axis"
  f->UseExplicitGridOff();
  for (double padding : { std::numeric_limits<double>::quiet_NaN(), -1.0, std::numeric_limits<double>::infinity() })
  {
    f->SetPadding(padding);
    EXPECT_TRUE(std::isnan(padding) ? std::isnan(f->GetPadding()) : f->GetPadding() == padding) << "clamped";
    for (double sampleSpacing : { 0.1, 0.0 })
    {
      f->SetSampleSpacing(sampleSpacing);
      errors.last.clear();
      errors.count = 0;
      f->Update();
      EXPECT_EQ(errors.count, 1) << padding << " " << sampleSpacing;
      EXPECT_NE(errors.last.find("Padding must be a finite number of voxels >= 0, not "), std::string::npos)
        << padding << " " << sampleSpacing << ": " << errors.last;
    }
  }
  // a Max Dimension too small for the Padding names both properties (it read
  // "fit grid: padding leaves no voxel for the mesh (maxDim - 1 - 2 * padding < 1)")
  f->SetPadding(2);
  f->SetSampleSpacing(0);
  f->SetMaxDimension(5);
  errors.last.clear();
  f->Update();
  EXPECT_NE(errors.last.find("Max Dimension 5 leaves no voxel for the mesh inside 2 voxels of Padding"),
    std::string::npos) << errors.last;
  EXPECT_EQ(errors.last.find("maxDim"), std::string::npos) << errors.last;
  f->SetMaxDimension(6); // 2 x Padding + 2: one cell for the mesh
  errors.last.clear();
  f->Update();
  EXPECT_TRUE(errors.last.empty()) << errors.last;
  f->SetPadding(2);
  f->SetSampleSpacing(0.1);
  errors.last.clear();
  f->Update();
  EXPECT_TRUE(errors.last.empty()) << errors.last;

  // the fitted grid of an empty mesh: an empty volume, no error (it was "no points")
  vtkNew<vtkMeshToSDF> fitted;
  ErrorCatcher fittedErrors(fitted);
  fitted->SetInputData(empty);
  EXPECT_EQ(fitted->GetExecutive()->Update(), 1);
  EXPECT_TRUE(fittedErrors.last.empty()) << fittedErrors.last;
  // a mesh of one point (zero-size bounds): the message names the class once
  // (vtkErrorMacro's prefix; it read "vtkMeshToSDF (0x..): vtkMeshToSDF: ...")
  vtkNew<vtkPolyData> point;
  vtkNew<vtkPoints> onePoint;
  for (int i = 0; i < 3; ++i) onePoint->InsertNextPoint(0.5, 0.5, 0.5);
  point->SetPoints(onePoint);
  vtkNew<vtkCellArray> tri;
  const vtkIdType triIds[3] = { 0, 1, 2 };
  tri->InsertNextCell(3, triIds);
  point->SetPolys(tri);
  fitted->SetInputData(point);
  fitted->Update();
  EXPECT_NE(fittedErrors.last.find("zero size"), std::string::npos) << fittedErrors.last;
  EXPECT_EQ(fittedErrors.last.find("vtkMeshToSDF: "), std::string::npos) << fittedErrors.last;
}

namespace
{
class AbortMeshToSdf : public vtkCommand
{
public:
  static AbortMeshToSdf* New() { return new AbortMeshToSdf; }
  void Execute(vtkObject* caller, unsigned long, void*) override
  {
    static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    ++this->Calls;
  }
  int Calls = 0;
};
} // namespace

TEST(vtkMeshToSDF, AbortStopsAndProgressIsReported)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(16);
  sphere->SetPhiResolution(12);
  vtkNew<vtkMeshToSDF> f;
  f->SetInputConnection(sphere->GetOutputPort());
  f->SetMaxDimension(48);
  f->SetDevice(vtkMeshToSDF::DEVICE_CPU);
  vtkNew<AbortMeshToSdf> cb;
  f->AddObserver(vtkCommand::ProgressEvent, cb);
  f->Update();
  EXPECT_GT(cb->Calls, 0);
  auto* sparse = vtkSparseDictionaryVolume::SafeDownCast(f->GetOutputDataObject(0));
  EXPECT_FALSE(sparse && sparse->HasVolume()); // cancelled: no volume
}

namespace
{
/// Every ProgressEvent's value; optionally sets AbortExecute at the first
/// value of at least abortFrom.
struct ProgressLog
{
  vtkNew<vtkCallbackCommand> cb;
  std::vector<double> values;
  double abortFrom = 2.0; // never
  explicit ProgressLog(vtkAlgorithm* a)
  {
    this->cb->SetClientData(this);
    this->cb->SetCallback([](vtkObject* caller, unsigned long, void* client, void* call) {
      auto* self = static_cast<ProgressLog*>(client);
      self->values.push_back(*static_cast<double*>(call));
      if (self->values.back() >= self->abortFrom) static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    });
    a->AddObserver(vtkCommand::ProgressEvent, this->cb);
  }
};
} // namespace

// Core reports progress after every row: a run sent ~23,000 ProgressEvents a
// second (each a redraw of ParaView's progress bar). Now they come in steps of
// 1 % (or a quarter second apart), as VTK's own filters report: at most ~100
// (and a few timed ones) per run, never going back, ending at 1.
TEST(vtkMeshToSDF, ProgressEventsComeInOnePercentStepsAndEndAtOne)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(24);
  vtkNew<vtkMeshToSDF> f;
  f->SetInputConnection(sphere->GetOutputPort());
  f->SetMaxDimension(160); // 160 x 160 x 160: 25,600 rows, each one a report of Core's
  f->SetDevice(vtkMeshToSDF::DEVICE_CPU);
  ProgressLog log(f);
  f->Update();
  auto* sparse = vtkSparseDictionaryVolume::SafeDownCast(f->GetOutputDataObject(0));
  ASSERT_TRUE(sparse && sparse->HasVolume());
  ASSERT_FALSE(log.values.empty());
  EXPECT_LE(log.values.size(), 200u);
  EXPECT_GE(log.values.size(), 10u) << "the bar still moves";
  for (std::size_t i = 1; i < log.values.size(); ++i) EXPECT_GE(log.values[i], log.values[i - 1]) << i;
  EXPECT_EQ(log.values.back(), 1.0);
}

// An abort requested from a ProgressEvent (as ParaView's progress handler
// does) still stops the run early: no volume, and no event after it past the
// point where it was asked.
TEST(vtkMeshToSDF, AbortStopsAThrottledRunEarly)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(24);
  vtkNew<vtkMeshToSDF> f;
  f->SetInputConnection(sphere->GetOutputPort());
  f->SetMaxDimension(160);
  f->SetDevice(vtkMeshToSDF::DEVICE_CPU);
  ProgressLog log(f);
  log.abortFrom = 0.05;
  f->Update();
  auto* sparse = vtkSparseDictionaryVolume::SafeDownCast(f->GetOutputDataObject(0));
  EXPECT_FALSE(sparse && sparse->HasVolume()); // cancelled: no volume
  ASSERT_FALSE(log.values.empty());
  EXPECT_GE(log.values.back(), 0.05);
  EXPECT_LT(log.values.back(), 0.2) << "the run went on after the abort";
}

// A piece (UpdatePiece, as a pvbatch rank) or a smaller update extent computes
// only the storage chunks holding its voxels (Core's chunkRegion), and those
// chunks hold exactly the whole run's keys; the others stay untouched (+band).
TEST(vtkMeshToSDF, PiecesComputeTheirChunksOnlyWithTheWholeRunsValues)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(16);
  auto make = [&] {
    auto f = vtkSmartPointer<vtkMeshToSDF>::New();
    f->SetInputConnection(sphere->GetOutputPort());
    f->SetMaxDimension(40);
    f->SetChunkEdge(8);
    f->SetDevice(vtkMeshToSDF::DEVICE_CPU);
    return f;
  };
  auto whole = make();
  whole->Update();
  auto* w = vtkSparseDictionaryVolume::SafeDownCast(whole->GetOutputDataObject(0));
  ASSERT_TRUE(w && w->HasVolume());
  const lvdif::DictionaryVolume& wv = *w->GetVolume();
  auto computedChunks = [](vtkAlgorithm* a) {
    return vtkIdTypeArray::SafeDownCast(a->GetOutputDataObject(0)->GetFieldData()->GetArray("mesh_to_sdf_chunks"))->GetValue(0);
  };
  EXPECT_EQ(computedChunks(whole), wv.chunkCount());
  // every voxel of the chunks a run computed equals the whole run's; the others are +band
  auto compare = [&](vtkMeshToSDF* f, const lvdif::VoxelBox& chunks, const std::string& what) {
    auto* s = vtkSparseDictionaryVolume::SafeDownCast(f->GetOutputDataObject(0));
    ASSERT_TRUE(s && s->HasVolume()) << what;
    const lvdif::DictionaryVolume& v = *s->GetVolume();
    long wrong = 0, untouched = 0;
    for (std::int64_t id = 0; id < v.chunkCount(); ++id)
    {
      const lvdif::Index3 c = v.chunkCoord(id);
      const bool in = chunks.contains(c[0], c[1], c[2]);
      const lvdif::VoxelBox b = v.chunkBox(id);
      for (std::int64_t z = b.lo[2]; z <= b.hi[2]; ++z)
        for (std::int64_t y = b.lo[1]; y <= b.hi[1]; ++y)
          for (std::int64_t x = b.lo[0]; x <= b.hi[0]; ++x)
          {
            if (in)
              wrong += v.get(x, y, z) != wv.get(x, y, z);
            else
              untouched += v.get(x, y, z) == v.outsideVoxel();
          }
    }
    EXPECT_EQ(wrong, 0) << what;
    EXPECT_EQ(computedChunks(f), chunks.voxelCount()) << what;
    EXPECT_LT(chunks.voxelCount(), v.chunkCount()) << what;
    EXPECT_GT(untouched, 0) << what;
  };
  const lvdif::Index3 cc = wv.chunkCounts();
  for (int n : { 2, 3 })
  {
    for (int p = 0; p < n; ++p)
    {
      auto f = make();
      f->UpdatePiece(p, n, 0);
      auto* s = vtkSparseDictionaryVolume::SafeDownCast(f->GetOutputDataObject(0));
      ASSERT_TRUE(s && s->HasVolume());
      int owned[6];
      s->GetOwnedChunks(owned);
      // its chunks plus the next ones, whose first layer of points its partitions share
      lvdif::VoxelBox chunks;
      for (int a = 0; a < 3; ++a)
      {
        chunks.lo[a] = owned[2 * a];
        chunks.hi[a] = std::min<std::int64_t>(owned[2 * a + 1] + 1, cc[a] - 1);
      }
      compare(f, chunks, "piece " + std::to_string(p) + " of " + std::to_string(n));
    }
  }
  // a sub-extent: the chunks holding it
  int sub[6] = { 3, 12, 9, 20, 17, 17 };
  auto f = make();
  f->UpdateInformation();
  f->UpdateExtent(sub);
  lvdif::VoxelBox chunks;
  for (int a = 0; a < 3; ++a)
  {
    chunks.lo[a] = sub[2 * a] / 8;
    chunks.hi[a] = sub[2 * a + 1] / 8;
  }
  compare(f, chunks, "extent");
}

// The reversed-faces warning is about the mesh, so a run split into pieces
// (pvbatch ranks) prints it once, from piece 0, like a whole run; a clean mesh
// prints none (negative control).
TEST(vtkMeshToSDF, PiecesWarnOnceAboutReversedFaces)
{
  vtkObject::GlobalWarningDisplayOn(); // WarningEvent fires only with it on
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(16);
  sphere->Update();
  vtkNew<vtkPolyData> damaged; // the faces of the top cap reversed
  damaged->DeepCopy(sphere->GetOutput());
  damaged->BuildCells();
  vtkIdType reversed = 0;
  for (vtkIdType c = 0; c < damaged->GetNumberOfCells(); ++c)
  {
    double b[6];
    damaged->GetCellBounds(c, b);
    if (b[4] > 0.3)
    {
      damaged->ReverseCell(c);
      ++reversed;
    }
  }
  ASSERT_GT(reversed, 10);
  auto warningsOf = [](vtkPolyData* mesh, int pieces) {
    int count = 0;
    for (int p = 0; p < pieces; ++p)
    {
      vtkNew<vtkMeshToSDF> f;
      f->SetInputData(mesh);
      f->SetMaxDimension(40);
      f->SetChunkEdge(8);
      f->SetDevice(vtkMeshToSDF::DEVICE_CPU);
      vtkNew<vtkCallbackCommand> cb;
      cb->SetClientData(&count);
      cb->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
        if (std::string(static_cast<const char*>(call)).find("orientation") != std::string::npos)
          ++*static_cast<int*>(client);
      });
      f->AddObserver(vtkCommand::WarningEvent, cb);
      if (pieces > 1)
        f->UpdatePiece(p, pieces, 0);
      else
        f->Update();
    }
    return count;
  };
  EXPECT_EQ(warningsOf(damaged, 1), 1);
  EXPECT_EQ(warningsOf(damaged, 3), 1);
  EXPECT_EQ(warningsOf(sphere->GetOutput(), 3), 0);
}
