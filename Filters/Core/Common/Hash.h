// FNV-1a, 64 bits: content hashes for caches (the saddle vertex graph's mesh hash and file
// checksum, the Shape Distributor's lattices). Not cryptographic.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gs
{

struct Hasher
{
  std::uint64_t H = 1469598103934665603ull;
  void Add(const void* data, std::size_t n)
  {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i)
    {
      H ^= p[i];
      H *= 1099511628211ull;
    }
  }
  template <typename T>
  void AddValue(const T& v)
  {
    Add(&v, sizeof(T));
  }
  template <typename T>
  void AddVector(const std::vector<T>& v)
  {
    if (!v.empty())
    {
      Add(v.data(), v.size() * sizeof(T));
    }
  }
};

} // namespace gs
