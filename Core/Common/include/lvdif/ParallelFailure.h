// The first exception of a parallel loop's bodies, thrown again after the
// loop: an exception that leaves an OpenMP region terminates the process (a
// chunk expanded past LVDIF_MEMORY_LIMIT aborted pvpython, ParaView's server
// and the CLI with "terminate called after throwing an instance of
// 'lvdif::Error'"). Bodies after a failure are skipped.
#pragma once

#include <atomic>
#include <exception>
#include <mutex>

namespace lvdif
{

class ParallelFailure
{
public:
  /// Runs body() unless a body failed already; keeps its exception if it throws.
  template <typename Body>
  void run(Body&& body)
  {
    if (this->failed()) return;
    try
    {
      body();
    }
    catch (...)
    {
      std::lock_guard<std::mutex> lock(this->Lock);
      if (!this->First) this->First = std::current_exception();
      this->Failed.store(true, std::memory_order_relaxed);
    }
  }
  bool failed() const { return this->Failed.load(std::memory_order_relaxed); }
  /// After the loop: the first exception, if any, thrown again.
  void rethrow()
  {
    if (this->First) std::rethrow_exception(this->First);
  }

private:
  std::atomic<bool> Failed{ false };
  std::mutex Lock;
  std::exception_ptr First;
};

} // namespace lvdif
