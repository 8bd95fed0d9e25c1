// For the VTK modules' tests that run under mpiexec (Filters' and IO's alike):
// one program, every rank runs the same checks; a failed check is printed with
// its rank, and rank 0 prints the line CTest looks for only when no rank failed.
#ifndef LVDIF_MPI_TEST_UTIL_H
#define LVDIF_MPI_TEST_UTIL_H

#include "vtkMPIController.h"
#include "vtkNew.h"

#include <cstdio>

class MPITestRun
{
public:
  /// Initializes MPI and makes this run's controller the global one.
  MPITestRun(int* argc, char*** argv)
  {
    this->Controller->Initialize(argc, argv);
    vtkMultiProcessController::SetGlobalController(this->Controller);
  }
  MPITestRun(const MPITestRun&) = delete;
  MPITestRun& operator=(const MPITestRun&) = delete;

  vtkMPIController* controller() { return this->Controller; }
  int rank() { return this->Controller->GetLocalProcessId(); }
  int ranks() { return this->Controller->GetNumberOfProcesses(); }

  /// Counts (and prints) a failed check of this rank.
  void check(bool ok, const char* what)
  {
    if (!ok)
    {
      std::fprintf(stderr, "rank %d: FAIL %s\n", this->rank(), what);
      ++this->Failures;
    }
  }

  /// Ends a run started wrongly: prints `usage` and finalizes MPI; main's exit code.
  int usage(const char* usage)
  {
    if (this->rank() == 0)
      std::fprintf(stderr, "usage: %s\n", usage);
    this->Controller->Finalize();
    return 1;
  }

  /// Sums every rank's failures; rank 0 prints `okLine` when there are none.
  /// Finalizes MPI; main's exit code.
  int finish(const char* okLine)
  {
    int all = 0;
    this->Controller->AllReduce(&this->Failures, &all, 1, vtkCommunicator::SUM_OP);
    if (this->rank() == 0 && all == 0)
      std::printf("%s\n", okLine);
    this->Controller->Finalize();
    return all == 0 ? 0 : 1;
  }

private:
  vtkNew<vtkMPIController> Controller;
  int Failures = 0;
};

#endif
