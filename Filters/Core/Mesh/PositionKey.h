// One position in space as welding sees it: exactly equal coordinates, -0 equal to +0.
// TriangleMesh welds the points of one position; pieces without global ids (PieceNumbering)
// match the points of one position across processes by the same rule.
#pragma once

#include "Vector.h"

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace gs
{

struct PositionKey
{
  std::uint64_t X = 0, Y = 0, Z = 0;

  static std::uint64_t Bits(double d)
  {
    if (d == 0.0)
    {
      d = 0.0; // -0 and +0 are one position
    }
    std::uint64_t bits;
    static_assert(sizeof(bits) == sizeof(d), "double size");
    std::memcpy(&bits, &d, sizeof(d));
    return bits;
  }
  static PositionKey Of(const Vec3& p) { return { Bits(p.x), Bits(p.y), Bits(p.z) }; }
  bool operator==(const PositionKey& o) const { return X == o.X && Y == o.Y && Z == o.Z; }
  // Mixed so that the low bits (what a power-of-two table keeps) depend on the high ones
  // (exponents and leading mantissa bits).
  std::uint64_t Hash() const
  {
    std::uint64_t h = X ^ (Y * 0x9E3779B97F4A7C15ull) ^ (Z * 0xC2B2AE3D27D4EB4Full);
    h ^= h >> 31;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 29;
    return h;
  }
  struct Hasher
  {
    std::size_t operator()(const PositionKey& k) const
    {
      return static_cast<std::size_t>(k.Hash());
    }
  };
};

} // namespace gs
