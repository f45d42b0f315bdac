#include "ParallelFor.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace gs
{
namespace
{

void CpuRelax()
{
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

// Spins until `done()` or SpinMicroseconds have passed; whether `done()` became true.
template <class Done>
bool SpinBriefly(Done done)
{
  const auto start = std::chrono::steady_clock::now();
  for (int k = 1;; ++k)
  {
    if (done())
    {
      return true;
    }
    CpuRelax();
    if ((k & 63) == 0 &&
      std::chrono::steady_clock::now() - start > std::chrono::microseconds(SpinMicroseconds))
    {
      return done();
    }
  }
}

thread_local bool InsideJob = false;

class Pool
{
public:
  // The pool, when no other thread's job holds it.
  std::unique_lock<std::mutex> TryAcquire() { return std::unique_lock<std::mutex>(Owner, std::try_to_lock); }

  void Run(int n, int threads, int chunk, const std::function<void(int, int)>& body)
  {
    Grow(threads - 1);
    {
      std::lock_guard<std::mutex> lock(Mutex);
      Body = &body;
      Count = n;
      Chunk = chunk;
      Wanted = threads - 1;
      Threads = threads;
      Next.store(0);
      Closed = false;
      Running = 0;
      Error = nullptr;
      Generation.fetch_add(1);
    }
    Wake.notify_all();
    Work(0);
    std::unique_lock<std::mutex> lock(Mutex);
    Closed = true; // helpers that have not joined yet stay out
    if (Running > 0)
    {
      lock.unlock();
      SpinBriefly([this] { return Running.load() == 0; });
      lock.lock();
      Done.wait(lock, [this] { return Running == 0; });
    }
    Body = nullptr;
    if (Error)
    {
      std::exception_ptr e = Error;
      Error = nullptr;
      std::rethrow_exception(e);
    }
  }

private:
  void Grow(int helpers)
  {
    while (Helpers < helpers)
    {
      const int index = Helpers + 1;
      std::thread([this, index] { HelperLoop(index); }).detach();
      ++Helpers;
    }
  }

  // Takes chunks until none is left (or an error stops the job).
  void Work(int thread)
  {
    InsideJob = true;
    for (;;)
    {
      // Guided: a share of what is left (at least Chunk), so that the last chunks are small and
      // no thread is left waiting long for another's.
      int begin = Next.load(), end = 0;
      do
      {
        if (begin >= Count)
        {
          break;
        }
        end = begin + std::max(Chunk, (Count - begin) / (4 * Threads));
        end = std::min(end, Count);
      } while (!Next.compare_exchange_weak(begin, end));
      if (begin >= Count)
      {
        break;
      }
      try
      {
        for (int i = begin; i < end; ++i)
        {
          (*Body)(i, thread);
        }
      }
      catch (...)
      {
        std::lock_guard<std::mutex> lock(Mutex);
        if (!Error)
        {
          Error = std::current_exception();
        }
        Next.store(Count);
      }
    }
    InsideJob = false;
  }

  void HelperLoop(int index)
  {
    unsigned long long seen = Generation.load();
    for (;;)
    {
      SpinBriefly([&] { return Generation.load() != seen; });
      std::unique_lock<std::mutex> lock(Mutex);
      Wake.wait(lock, [&] { return Generation.load() != seen; });
      seen = Generation.load();
      if (Closed || index > Wanted)
      {
        continue; // not wanted, or every chunk was taken before this helper woke
      }
      ++Running;
      lock.unlock();
      Work(index);
      lock.lock();
      if (--Running == 0 && Closed)
      {
        lock.unlock();
        Done.notify_one();
      }
    }
  }

  std::mutex Owner; // held by the thread whose job runs
  std::mutex Mutex; // guards the job's fields below, except the atomics
  std::condition_variable Wake, Done;
  int Helpers = 0; // (detached: they sleep until the process ends)
  std::atomic<unsigned long long> Generation{ 0 };
  std::atomic<int> Next{ 0 };
  std::atomic<int> Running{ 0 }; // helpers in the job (changed under Mutex; atomic for the spin)
  const std::function<void(int, int)>* Body = nullptr;
  int Count = 0, Chunk = 1, Threads = 1, Wanted = 0;
  bool Closed = true;
  std::exception_ptr Error;
};

// Never destroyed: helpers may sleep in it while the process exits.
Pool& ThePool()
{
  static Pool* pool = new Pool;
  return *pool;
}

} // namespace

void ParallelFor(int n, int threads, int chunk, const std::function<void(int, int)>& body)
{
  chunk = std::max(1, chunk);
  threads = std::max(1, std::min(threads, (n + chunk - 1) / chunk));
  if (n <= 0)
  {
    return;
  }
  if (threads > 1 && !InsideJob)
  {
    Pool& pool = ThePool();
    std::unique_lock<std::mutex> owner = pool.TryAcquire();
    if (owner.owns_lock())
    {
      pool.Run(n, threads, chunk, body);
      return;
    }
  }
  const bool outer = InsideJob;
  InsideJob = true;
  try
  {
    for (int i = 0; i < n; ++i)
    {
      body(i, 0);
    }
  }
  catch (...)
  {
    InsideJob = outer;
    throw;
  }
  InsideJob = outer;
}

} // namespace gs
