/**
 * @class   LVDIFInterrupter
 * @brief   adapts lvdif::Interrupter to a vtkAlgorithm's progress and abort
 *
 * Core algorithms report progress through lvdif::Interrupter; this adapter
 * forwards it to vtkAlgorithm::UpdateProgress (scaled into [shift, shift+scale]
 * so one filter can run several stages) and answers wasInterrupted() from
 * vtkAlgorithm::GetAbortExecute(), the only cancel mechanism VTK 9.1 has.
 * Progress is forwarded only from the thread that created the adapter, since
 * observers (e.g. a Qt progress bar) are not prepared for OpenMP worker threads,
 * and only in steps of 1 % of the filter's progress or every quarter second
 * (progress()), whatever rate Core reports at.
 */
#ifndef LVDIFInterrupter_h
#define LVDIFInterrupter_h

#include "lvdif/Interrupter.h"
#include "lvdifFiltersVolumeModule.h"

#include <chrono>
#include <thread>

class vtkAlgorithm;

class LVDIFFILTERSVOLUME_EXPORT LVDIFInterrupter : public lvdif::Interrupter
{
public:
  explicit LVDIFInterrupter(vtkAlgorithm* algorithm, double shift = 0.0, double scale = 1.0);
  void start(const char* name) override;
  void progress(double fraction) override;
  bool wasInterrupted() const override;
  /// Maps the next stage's [0,1] into [shift, shift + scale] of the filter's progress.
  void setStage(double shift, double scale);

private:
  vtkAlgorithm* Algorithm;
  double Shift;
  double Scale;
  std::thread::id Owner;
  static constexpr double Step = 0.01; // the least change forwarded at once
  static constexpr std::chrono::milliseconds MinInterval{ 250 }; // any change after this
  double Last = -1.0;                   // the last value forwarded (-1: none this stage)
  std::chrono::steady_clock::time_point LastTime;
};

#endif
