// Under `mpirun -np 2` (and 3): the ranks of a distributed sparse vtkSignVoxelFilter
// meet in collectives and pair exchanges; when one rank's input fails (its
// information, its data, or it holds no volume), its chunk exchange throws or it
// cannot allocate the buffer of the chunks it receives, that rank still joins
// them as failed, so every rank's Update fails and none
// waits forever. Before, the healthy rank waited in the
// first all-reduce for the failed one (the test timed out). Also the good
// case: both ranks filter and agree on the whole volume's statistics.
#include "LVDIFVolumeBridge.h"
#include "MPITestUtil.h"
#include "vtkDataObjectAlgorithm.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkSignVoxelFilter.h"
#include "vtkSparseDictionaryVolume.h"

#include "lvdif/AnalyticFill.h"
#include "lvdif/DictionaryVolume.h"

#include <cstdio>
#include <cstdlib>
#include <memory>

namespace
{
lvdif::VolumeOptions sourceOptions()
{
  lvdif::VolumeOptions o;
  o.dims = { 32, 24, 20 };
  o.chunkEdge = 8;
  return o;
}
}

/// A sparse volume source (a sphere) that can fail on purpose.
class FailingSparseSource : public vtkDataObjectAlgorithm
{
public:
  static FailingSparseSource* New();
  vtkTypeMacro(FailingSparseSource, vtkDataObjectAlgorithm);
  enum
  {
    Good,
    FailInformation,
    FailData,
    NoVolume
  };
  int Mode = Good;

protected:
  FailingSparseSource() { this->SetNumberOfInputPorts(0); }
  int RequestDataObject(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    LVDIFVolumeBridge::EnsureSparseOutput(out);
    return 1;
  }
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    if (this->Mode == FailInformation)
    {
      vtkErrorMacro("test: this rank's information fails");
      return 0;
    }
    LVDIFVolumeBridge::SetSparseInformation(out->GetInformationObject(0), sourceOptions());
    return 1;
  }
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    if (this->Mode == FailData)
    {
      vtkErrorMacro("test: this rank's data fails");
      return 0;
    }
    if (this->Mode == NoVolume)
      return 1; // a sparse data object without a volume
    auto v = std::make_shared<lvdif::DictionaryVolume>(sourceOptions());
    lvdif::fillFromFunction(*v, lvdif::sphereSdf(15.5, 11.5, 9.5, 8.0));
    vtkSparseDictionaryVolume::GetData(out)->SetVolume(v);
    return 1;
  }
};
vtkStandardNewMacro(FailingSparseSource);

int main(int argc, char* argv[])
{
  MPITestRun test(&argc, &argv);
  vtkMPIController* c = test.controller();
  const int rank = test.rank();
  if (test.ranks() < 2)
    return test.usage("mpirun -np 2 (or more) TestSignVoxelFilterMPI");
  // one Update of source -> sign filter on every rank; rank 1's source in `mode`
  auto run = [&](int mode, vtkIdType* ranksOut) {
    vtkNew<FailingSparseSource> source;
    source->Mode = rank == 1 ? mode : int(FailingSparseSource::Good);
    vtkNew<vtkSignVoxelFilter> svf;
    svf->SetController(c);
    svf->SetDevice(vtkSignVoxelFilter::DEVICE_CPU);
    svf->SetInputConnection(source->GetOutputPort());
    const int ok = svf->GetExecutive()->Update();
    auto* out = vtkSparseDictionaryVolume::SafeDownCast(svf->GetOutputDataObject(0));
    auto* st = out ? vtkIdTypeArray::SafeDownCast(out->GetFieldData()->GetArray("svf_piece")) : nullptr;
    if (ranksOut)
      *ranksOut = st ? st->GetValue(1) : -1; // the number of ranks the filter ran on
    return ok;
  };

  vtkIdType ranks = 0;
  test.check(run(FailingSparseSource::Good, &ranks) == 1, "both inputs good: Update succeeds");
  test.check(ranks == test.ranks(), "both inputs good: the filter ran on every rank");
  // no rank's input holds a volume (a reader that failed everywhere): an empty
  // output and success on every rank, as VTK's filters treat an empty input
  {
    vtkNew<FailingSparseSource> source;
    source->Mode = FailingSparseSource::NoVolume;
    vtkNew<vtkSignVoxelFilter> svf;
    svf->SetController(c);
    svf->SetInputConnection(source->GetOutputPort());
    const int ok = svf->GetExecutive()->Update();
    auto* out = vtkSparseDictionaryVolume::SafeDownCast(svf->GetOutputDataObject(0));
    test.check(ok == 1 && out && !out->HasVolume(), "no rank holds a volume: an empty output, no failure");
  }

  vtkObject::GlobalWarningDisplayOff(); // the expected errors
  test.check(run(FailingSparseSource::FailData, nullptr) == 0, "rank 1's data fails: Update fails on every rank");
  test.check(run(FailingSparseSource::NoVolume, nullptr) == 0, "rank 1 holds no volume: Update fails on every rank");
  test.check(run(FailingSparseSource::FailInformation, nullptr) == 0,
    "rank 1's information fails: Update fails on every rank");
  // rank 1's unpacking of the first chunks it receives throws: it still takes
  // part in its later exchanges (with three ranks, rank 2 waits for rank 1's
  // chunks after rank 0's; before, it waited forever) and every rank fails
  if (rank == 1)
    setenv("LVDIF_TEST_SVF_UNPACK_FAILS", "1", 1);
  test.check(run(FailingSparseSource::Good, nullptr) == 0, "rank 1's chunk exchange fails: Update fails on every rank");
  if (rank == 1)
    unsetenv("LVDIF_TEST_SVF_UNPACK_FAILS");
  // rank 1 cannot allocate the buffer for the chunks it receives: one error on
  // rank 1, no payload sent to it, every rank fails and none waits. Before, the
  // std::bad_alloc escaped the filter (the run aborted) while rank 1's partners
  // were still sending to it.
  if (rank == 1)
    setenv("LVDIF_TEST_SVF_RECEIVE_ALLOC_FAILS", "1", 1);
  test.check(run(FailingSparseSource::Good, nullptr) == 0,
    "rank 1 cannot allocate its receive buffer: Update fails on every rank");
  if (rank == 1)
    unsetenv("LVDIF_TEST_SVF_RECEIVE_ALLOC_FAILS");
  // the ranks still meet after the failures
  test.check(run(FailingSparseSource::Good, &ranks) == 1, "good again: Update succeeds");

  return test.finish("SignVoxelFilter MPI OK");
}
