// ParallelFor: the loops of the shape distribution on a pool of threads that sleep when idle.
//
// Why not OpenMP here: the distribution runs hundreds of short parallel loops per second (its
// priority waves), and between them an OpenMP worker of GCC's libgomp spins for about 3 ms before
// it sleeps. On a machine where anything else runs (the render, other filters, a browser) those
// spinning workers take the cores from the thread that has work: with one competing process on
// two cores, two threads ran slower than one. libgomp reads its wait policy (OMP_WAIT_POLICY,
// GOMP_SPINCOUNT) once, when it is loaded, and ParaView loads it before any plugin, so a plugin
// cannot change it. The pool's idle threads spin for at most SpinMicroseconds and then sleep on
// a condition variable; the calling thread never waits for a helper that has not started (a
// helper that wakes after the last chunk is taken does nothing), and chunks shrink as the loop
// ends (guided), so a descheduled helper costs at most the small chunk it holds. Measured
// (DistributionBenchmark --under-load): with one competing process on two cores, 2 threads take
// 0.83-1.16x the time of 1 (median 1.03x over 8 runs), against 2.0-2.4x with OpenMP; alone,
// the same speed as OpenMP. (Running the loops serially while threads are being preempted was
// measured too: no better than this, within the machine's noise.)
//
// Results do not depend on the pool: every index is run exactly once, by whichever thread takes
// its chunk, and the loops write per-index results (or per-thread scratch indexed by `thread`).
#pragma once

#include <algorithm>
#include <functional>
#include <vector>

namespace gs
{

/// Runs body(i, thread) for every i in [0, n), in chunks of consecutive indices taken in order by
/// up to `threads` threads (the caller is thread 0; helpers are 1 .. threads - 1), each chunk a
/// quarter of what is left per thread but at least `chunk`. Runs serially (thread 0) when
/// threads <= 1, n <= chunk, inside another ParallelFor or while another thread's ParallelFor
/// holds the pool. An exception thrown by the body stops the handing out of chunks and is
/// rethrown to the caller once every running chunk has ended.
void ParallelFor(int n, int threads, int chunk, const std::function<void(int i, int thread)>& body);

/// ParallelFor with a default-constructed `State` per thread (scratch, partial sums), passed to
/// body(i, state); returns the states (thread 0's first) for the caller to combine.
template <class State, class Body>
std::vector<State> ParallelForEachThread(int n, int threads, int chunk, Body&& body)
{
  std::vector<State> states(static_cast<std::size_t>(std::max(1, threads)));
  ParallelFor(n, threads, chunk, [&](int i, int thread) { body(i, states[thread]); });
  return states;
}

/// How long an idle helper (or the caller waiting for helpers) spins before it sleeps.
constexpr int SpinMicroseconds = 50;

} // namespace gs
