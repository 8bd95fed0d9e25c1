#include "LVDIFInterrupter.h"

#include "vtkAlgorithm.h"

#include <cmath>

LVDIFInterrupter::LVDIFInterrupter(vtkAlgorithm* algorithm, double shift, double scale)
  : Algorithm(algorithm)
  , Shift(shift)
  , Scale(scale)
  , Owner(std::this_thread::get_id())
{
}

void LVDIFInterrupter::start(const char* name)
{
  if (this->Algorithm && std::this_thread::get_id() == this->Owner)
  {
    this->Algorithm->SetProgressText(name);
    this->Last = -1.0; // a new stage's first value goes through, whatever it is
  }
}

void LVDIFInterrupter::progress(double fraction)
{
  if (!this->Algorithm || std::this_thread::get_id() != this->Owner) return;
  const double v = this->Shift + this->Scale * fraction;
  if (v == this->Last) return;
  // Core reports as often as it finishes a row (vtkMeshToSDF sent ~23,000
  // ProgressEvents a second, each one a redraw for ParaView's progress bar):
  // forwarded in steps of 1 % of the filter's progress, as VTK's own filters
  // report, or after MinInterval with any change (an observer that answers an
  // abort request from a ProgressEvent still gets one every quarter second on
  // a long run), and always the end of the range. The abort itself is read
  // by wasInterrupted(), on every row, whatever was forwarded.
  const auto now = std::chrono::steady_clock::now();
  const bool due = this->Last < 0 || std::fabs(v - this->Last) >= Step || v >= this->Shift + this->Scale ||
    now - this->LastTime >= MinInterval;
  if (!due) return;
  this->Last = v;
  this->LastTime = now;
  this->Algorithm->UpdateProgress(v);
}

bool LVDIFInterrupter::wasInterrupted() const
{
  return this->Algorithm && this->Algorithm->GetAbortExecute() != 0;
}

void LVDIFInterrupter::setStage(double shift, double scale)
{
  this->Shift = shift;
  this->Scale = scale;
}
