// The Shape Distributor's random numbers: counter-based, so that every draw is a function of
// (seed, kind, round, index) and not of the thread that makes it or of the order of draws.
#pragma once

#include <cstdint>

namespace gs
{
namespace distribution
{

inline std::uint64_t Mix(std::uint64_t x)
{
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// Counter-based generator: the stream of (seed, kind, round, index) is independent of threads.
/// Kinds: 1 random candidates, 2 Greedy proposals, 3 probes, 4 Greedy candidates, 5 pool
/// candidates, 6 pool counts.
struct Random
{
  std::uint64_t State;
  Random(std::uint64_t seed, std::uint64_t kind, std::uint64_t round, std::uint64_t index)
    : State(Mix(Mix(Mix(seed ^ Mix(kind)) ^ round) ^ index))
  {
  }
  double Uniform()
  {
    State = Mix(State);
    return static_cast<double>(State >> 11) * (1.0 / 9007199254740992.0);
  }
};

} // namespace distribution
} // namespace gs
