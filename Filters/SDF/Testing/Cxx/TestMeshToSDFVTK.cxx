// vtkMeshToSDF against vtkImplicitPolyDataDistance (an independent oracle:
// VTK's own closest-cell distance) on a sphere source, sub-extents equal to
// the same voxels of the whole image, the grid settings, and clear errors.
#include "vtkMeshToSDF.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
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

#include <cmath>
#include <string>

namespace
{
struct ErrorCatcher
{
  vtkNew<vtkCallbackCommand> cb;
  std::string last;
  explicit ErrorCatcher(vtkObject* o)
  {
    this->cb->SetClientData(this);
    this->cb->SetCallback([](vtkObject*, unsigned long, void* client, void* call) {
      static_cast<ErrorCatcher*>(client)->last = static_cast<const char*>(call);
    });
    o->AddObserver(vtkCommand::ErrorEvent, this->cb);
  }
};
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
  f->WorldUnitsOn();
  f->SetDevice(vtkMeshToSDF::DEVICE_CPU);
  f->Update();
  vtkImageData* img = f->GetOutput();
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
    const double v = sdf->GetTuple1(i);
    worst = std::max(worst, std::fabs(std::fabs(v) - std::fabs(ref)));
    if (std::fabs(ref) > h && (v < 0) != (ref < 0)) ++signDisagree;
  }
  EXPECT_LT(worst, 1e-5);
  EXPECT_EQ(signDisagree, 0);
  auto* deg = vtkIdTypeArray::SafeDownCast(img->GetFieldData()->GetArray("degenerate_triangles"));
  ASSERT_NE(deg, nullptr);
}

TEST(vtkMeshToSDF, SubExtentEqualsWhole)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(12);
  sphere->SetPhiResolution(8);
  vtkNew<vtkMeshToSDF> f;
  f->SetInputConnection(sphere->GetOutputPort());
  f->SetMaxDimension(24);
  f->SetDevice(vtkMeshToSDF::DEVICE_CPU);
  f->Update();
  vtkNew<vtkImageData> whole;
  whole->DeepCopy(f->GetOutput());
  // a fresh filter: only the sub-extent is requested, so only it is computed
  vtkNew<vtkMeshToSDF> g;
  g->SetInputConnection(sphere->GetOutputPort());
  g->SetMaxDimension(24);
  g->SetDevice(vtkMeshToSDF::DEVICE_CPU);
  int ext[6] = { 3, 17, 5, 9, 2, 20 };
  g->UpdateExtent(ext);
  vtkImageData* part = g->GetOutput();
  int got[6];
  part->GetExtent(got);
  for (int a = 0; a < 6; ++a) ASSERT_EQ(got[a], ext[a]);
  ASSERT_EQ(part->GetNumberOfPoints(), 15 * 5 * 19);
  for (int k = ext[4]; k <= ext[5]; ++k)
    for (int j = ext[2]; j <= ext[3]; ++j)
      for (int i = ext[0]; i <= ext[1]; ++i)
      {
        ASSERT_EQ(part->GetScalarComponentAsFloat(i, j, k, 0), whole->GetScalarComponentAsFloat(i, j, k, 0));
      }
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
  f->Update();
  int dims[3];
  f->GetOutput()->GetDimensions(dims);
  EXPECT_EQ(dims[0], 7);
  EXPECT_EQ(dims[1], 9);
  EXPECT_EQ(dims[2], 11);
  EXPECT_DOUBLE_EQ(f->GetOutput()->GetSpacing()[1], 0.25);
  f->UseExplicitGridOff();
  f->SetSampleSpacing(0.1);
  f->SetPadding(1);
  f->Update();
  f->GetOutput()->GetDimensions(dims);
  EXPECT_DOUBLE_EQ(f->GetOutput()->GetSpacing()[0], 0.1);
  EXPECT_GE(dims[0], 12); // diameter 1 / 0.1 + 2 padding + 1
}

TEST(vtkMeshToSDF, ClearErrors)
{
  vtkObject::GlobalWarningDisplayOn(); // ErrorEvent fires only with it on (another test turns it off)
  vtkNew<vtkMeshToSDF> f;
  ErrorCatcher errors(f);
  vtkNew<vtkPolyData> empty;
  f->SetInputData(empty);
  f->UseExplicitGridOn();
  f->Update();
  EXPECT_NE(errors.last.find("empty"), std::string::npos) << errors.last;

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
  EXPECT_EQ(f->GetOutput()->GetPointData()->GetArray("sdf"), nullptr); // cancelled: no sdf array
}
