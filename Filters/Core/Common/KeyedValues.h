// KeyedValues: a hash table from 64-bit keys to values (the decals' class points per vertex and
// grid reads per edge).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace gs
{

// Values known per key (a vertex, or an edge's two vertices packed in 64 bits; never ~0): open
// addressing with linear probing, no allocation per entry (a node-based map's allocations would
// cost about a tenth of the decals' time).
template <class Value>
class KeyedValues
{
public:
  Value* Find(std::uint64_t key)
  {
    if (Keys.empty())
    {
      return nullptr;
    }
    for (std::size_t i = Slot(key);; i = (i + 1) & (Keys.size() - 1))
    {
      if (Keys[i] == key)
      {
        return &Values[i];
      }
      if (Keys[i] == Empty)
      {
        return nullptr;
      }
    }
  }
  Value& Insert(std::uint64_t key, const Value& value) // (key not there yet)
  {
    if (2 * (Count + 1) > Keys.size())
    {
      Grow();
    }
    std::size_t i = Slot(key);
    while (Keys[i] != Empty)
    {
      i = (i + 1) & (Keys.size() - 1);
    }
    Keys[i] = key;
    Values[i] = value;
    ++Count;
    return Values[i];
  }

private:
  static constexpr std::uint64_t Empty = ~std::uint64_t(0);
  std::size_t Slot(std::uint64_t key) const
  {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> Shift);
  }
  void Grow()
  {
    std::vector<std::uint64_t> keys(std::max<std::size_t>(64, 2 * Keys.size()), Empty);
    std::vector<Value> values(keys.size());
    Shift = 64;
    for (std::size_t n = keys.size(); n > 1; n >>= 1)
    {
      --Shift;
    }
    keys.swap(Keys);
    values.swap(Values);
    Count = 0;
    for (std::size_t i = 0; i < keys.size(); ++i)
    {
      if (keys[i] != Empty)
      {
        Insert(keys[i], values[i]);
      }
    }
  }
  std::vector<std::uint64_t> Keys;
  std::vector<Value> Values;
  std::size_t Count = 0;
  int Shift = 64;
};

} // namespace gs
