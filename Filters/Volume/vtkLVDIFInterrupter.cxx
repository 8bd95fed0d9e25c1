#include "vtkLVDIFInterrupter.h"

#include "vtkAlgorithm.h"

vtkLVDIFInterrupter::vtkLVDIFInterrupter(vtkAlgorithm* algorithm, double shift, double scale)
  : Algorithm(algorithm)
  , Shift(shift)
  , Scale(scale)
  , Owner(std::this_thread::get_id())
{
}

void vtkLVDIFInterrupter::start(const char* name)
{
  if (this->Algorithm && std::this_thread::get_id() == this->Owner)
  {
    this->Algorithm->SetProgressText(name);
  }
}

void vtkLVDIFInterrupter::progress(double fraction)
{
  if (this->Algorithm && std::this_thread::get_id() == this->Owner)
  {
    this->Algorithm->UpdateProgress(this->Shift + this->Scale * fraction);
  }
}

bool vtkLVDIFInterrupter::wasInterrupted() const
{
  return this->Algorithm && this->Algorithm->GetAbortExecute() != 0;
}

void vtkLVDIFInterrupter::setStage(double shift, double scale)
{
  this->Shift = shift;
  this->Scale = scale;
}
