// Progress and cancellation for long work, in the spirit of OpenVDB's
// util::NullInterrupter: algorithms call start(), then progress(fraction)
// from the thread that owns the loop, and stop by throwing
// Error(Cancelled) once wasInterrupted() is true.
#pragma once

#include "lvdif/Error.h"

#include <atomic>

namespace lvdif
{

class Interrupter
{
public:
  virtual ~Interrupter() = default;
  /// A new stage of work begins; name is a short label ("distance", "sign").
  virtual void start(const char* /*name*/) {}
  /// Fraction of the current stage done, in [0, 1]. Called from one thread.
  virtual void progress(double /*fraction*/) {}
  /// True once the caller wants the work abandoned. Safe from any thread.
  virtual bool wasInterrupted() const { return false; }
  virtual void end() {}

  /// Throws Error(Cancelled) if interrupted; algorithms call this at chunk granularity.
  void checkInterrupt() const
  {
    if (this->wasInterrupted())
    {
      throw Error(ErrorCode::Cancelled, "operation cancelled");
    }
  }
};

/// An interrupter that never interrupts; the default argument of every algorithm.
Interrupter& nullInterrupter();

/// An interrupter that another thread can cancel (used by the CLI and tests).
class CancelFlagInterrupter : public Interrupter
{
public:
  void cancel() { this->Flag.store(true); }
  bool wasInterrupted() const override { return this->Flag.load(); }

private:
  std::atomic<bool> Flag{ false };
};

} // namespace lvdif
