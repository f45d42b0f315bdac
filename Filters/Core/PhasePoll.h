// PhasePoll: progress and abort for a parallel loop over items (shapes): the callback, which
// belongs to the calling thread (VTK's UpdateProgress and CheckAbort), is called from that
// thread only (OpenMP's master), at most every 0.1 s, with the fraction of items started; once
// it returns false every later Skip is true (the caller, which aborted, discards the result).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <thread>

namespace gs
{

class PhasePoll
{
public:
  PhasePoll(const std::function<bool(double)>& progress, int total)
    : Progress(progress)
    , Total(total)
    , Caller(std::this_thread::get_id())
    , Last(std::chrono::steady_clock::now())
  {
  }
  // Whether to skip item `done` (the count of items started, for the fraction).
  bool Skip(int done)
  {
    if (Aborted.load(std::memory_order_relaxed))
    {
      return true;
    }
    if (Progress && std::this_thread::get_id() == Caller)
    {
      const auto now = std::chrono::steady_clock::now();
      if (std::chrono::duration<double>(now - Last).count() >= 0.1)
      {
        Last = now;
        if (!Progress(static_cast<double>(done) / std::max(Total, 1)))
        {
          Aborted.store(true, std::memory_order_relaxed);
        }
      }
    }
    return Aborted.load(std::memory_order_relaxed);
  }
  bool WasAborted() const { return Aborted.load(std::memory_order_relaxed); }

private:
  const std::function<bool(double)>& Progress;
  const int Total;
  const std::thread::id Caller;
  std::chrono::steady_clock::time_point Last;
  std::atomic<bool> Aborted{ false };
};

} // namespace gs
