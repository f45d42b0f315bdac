// Shared by the benchmark programs: a wall clock and the median of repeated timings.
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace gs_bench
{

// Seconds on a steady clock (differences only).
inline double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The median of `v` (0 when empty).
inline double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

} // namespace gs_bench
