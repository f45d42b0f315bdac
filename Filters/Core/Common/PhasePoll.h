// PhasePoll: progress and abort for long parallel work (the distributor's rounds, the drawing
// phases, the overlap check). The callback belongs to the calling thread (VTK's UpdateProgress
// and CheckAbort): it is called from that thread only (the caller of ParallelFor), at most every 0.1 s
// (Poll, Skip) or at once (Report); once it returns false, every later Poll and Skip, from any
// thread, is true (the caller, which aborted, discards the result).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <thread>
#include <utility>

namespace gs
{

class PhasePoll
{
public:
  // `progress` may be empty (nothing is polled); `total` items for Skip's fraction.
  explicit PhasePoll(std::function<bool(double)> progress, int total = 0)
    : Progress(std::move(progress))
    , Total(total)
    , Caller(std::this_thread::get_id())
    , Last(std::chrono::steady_clock::now())
  {
  }
  PhasePoll(const PhasePoll&) = delete;
  PhasePoll& operator=(const PhasePoll&) = delete;

  // Whether the work is aborted; on the calling thread, first asks the callback (with
  // `fraction`) when 0.1 s have passed since it last did.
  bool Poll(double fraction)
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
        if (!Progress(fraction))
        {
          Aborted.store(true, std::memory_order_relaxed);
        }
      }
    }
    return Aborted.load(std::memory_order_relaxed);
  }
  // Whether to skip item `done` of Total (the count of items started, for the fraction).
  bool Skip(int done) { return Poll(static_cast<double>(done) / std::max(Total, 1)); }
  // Asks the callback now (from the calling thread); false once aborted.
  bool Report(double fraction)
  {
    if (Progress && !Progress(fraction))
    {
      Aborted.store(true, std::memory_order_relaxed);
    }
    Last = std::chrono::steady_clock::now();
    return !Aborted.load(std::memory_order_relaxed);
  }
  bool WasAborted() const { return Aborted.load(std::memory_order_relaxed); }

private:
  const std::function<bool(double)> Progress;
  const int Total;
  const std::thread::id Caller;
  std::chrono::steady_clock::time_point Last;
  std::atomic<bool> Aborted{ false };
};

} // namespace gs
