// ParallelFor: every index once, thread indices within the team, exceptions reach the caller,
// nested and concurrent calls, and idle helpers that sleep instead of spinning.
#include "ParallelFor.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include <time.h>

namespace
{
double CpuSeconds(clockid_t clock)
{
  timespec t{};
  clock_gettime(clock, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
} // namespace

TEST(ParallelFor, RunsEveryIndexOnceForAnyThreadsAndChunks)
{
  for (int n : { 0, 1, 7, 100, 1000, 4099 })
    for (int threads : { 1, 2, 3, 8 })
      for (int chunk : { 1, 3, 64, 5000 })
      {
        std::vector<std::atomic<int>> hits(static_cast<std::size_t>(n));
        std::atomic<int> badThread{ 0 };
        gs::ParallelFor(n, threads, chunk, [&](int i, int thread) {
          hits[i].fetch_add(1);
          if (thread < 0 || thread >= threads)
            badThread.fetch_add(1);
        });
        for (int i = 0; i < n; ++i)
          ASSERT_EQ(hits[i].load(), 1) << "n " << n << " threads " << threads << " chunk " << chunk << " index " << i;
        EXPECT_EQ(badThread.load(), 0);
      }
}

TEST(ParallelFor, PerThreadStatesCombineToTheSerialSum)
{
  const int n = 100000;
  const auto partial = gs::ParallelForEachThread<long long>(n, 4, 16, [](int i, long long& sum) { sum += i; });
  long long total = 0;
  for (long long s : partial)
    total += s;
  EXPECT_EQ(partial.size(), 4u);
  EXPECT_EQ(total, static_cast<long long>(n) * (n - 1) / 2);
}

TEST(ParallelFor, AnExceptionReachesTheCallerAndThePoolGoesOn)
{
  std::atomic<int> ran{ 0 };
  EXPECT_THROW(gs::ParallelFor(10000, 2, 1,
                 [&](int i, int) {
                   ran.fetch_add(1);
                   if (i == 50)
                     throw std::runtime_error("item 50");
                 }),
    std::runtime_error);
  EXPECT_LT(ran.load(), 10000); // (the handing out of chunks stopped)
  std::atomic<int> after{ 0 };
  gs::ParallelFor(1000, 2, 8, [&](int, int) { after.fetch_add(1); });
  EXPECT_EQ(after.load(), 1000);
}

TEST(ParallelFor, NestedAndConcurrentCallsRunEveryIndex)
{
  // Nested: the inner loop runs on the thread that calls it.
  std::atomic<long long> inner{ 0 };
  gs::ParallelFor(50, 2, 1, [&](int, int) {
    gs::ParallelFor(100, 2, 1, [&](int j, int thread) {
      EXPECT_EQ(thread, 0);
      inner.fetch_add(j);
    });
  });
  EXPECT_EQ(inner.load(), 50LL * 4950);
  // Concurrent: two threads' loops (one of them serial while the other holds the pool).
  std::atomic<long long> sums[2] = { { 0 }, { 0 } };
  auto loop = [&sums](int k) {
    for (int rep = 0; rep < 200; ++rep)
      gs::ParallelFor(500, 2, 4, [&sums, k](int i, int) { sums[k].fetch_add(i); });
  };
  std::thread a(loop, 0), b(loop, 1);
  a.join();
  b.join();
  EXPECT_EQ(sums[0].load(), 200LL * 124750);
  EXPECT_EQ(sums[1].load(), 200LL * 124750);
}

// Between jobs the helpers sleep: over 100 tiny jobs separated by 2 ms of the caller's sleep,
// the helpers use a small part of those 200 ms (a pool whose workers spin through such gaps, as
// libgomp's do for about 3 ms, uses nearly all of it). CPU time, not speed: a busy machine only
// lowers it.
TEST(ParallelFor, IdleHelpersSleepBetweenJobs)
{
  std::atomic<int> sink{ 0 };
  gs::ParallelFor(64, 2, 1, [&](int i, int) { sink.fetch_add(i); }); // (the helper exists)
  const double process0 = CpuSeconds(CLOCK_PROCESS_CPUTIME_ID), caller0 = CpuSeconds(CLOCK_THREAD_CPUTIME_ID);
  for (int job = 0; job < 100; ++job)
  {
    gs::ParallelFor(64, 2, 1, [&](int i, int) { sink.fetch_add(i); });
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  const double helpers = (CpuSeconds(CLOCK_PROCESS_CPUTIME_ID) - process0) - (CpuSeconds(CLOCK_THREAD_CPUTIME_ID) - caller0);
  EXPECT_LT(helpers, 0.05) << "the helpers used " << helpers << " s of CPU over 100 gaps of 2 ms";
}
