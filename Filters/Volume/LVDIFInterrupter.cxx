#include "LVDIFInterrupter.h"

#include "vtkAlgorithm.h"

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
  }
}

void LVDIFInterrupter::progress(double fraction)
{
  if (this->Algorithm && std::this_thread::get_id() == this->Owner)
  {
    this->Algorithm->UpdateProgress(this->Shift + this->Scale * fraction);
  }
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
