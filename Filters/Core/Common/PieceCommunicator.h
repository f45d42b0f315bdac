// What a computation on a surface partitioned over processes needs from its transport: the
// processes' ranks, a personalized exchange of byte buffers and global reductions. The VTK
// layer implements it over vtkMultiProcessController (MPI); the core tests over threads. Every
// operation is collective: every process calls it, in the same order.
#pragma once

#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

namespace gs
{

using ByteBuffer = std::vector<std::uint8_t>;

class PieceCommunicator
{
public:
  virtual ~PieceCommunicator() = default;
  virtual int Rank() const = 0;
  virtual int Size() const = 0;
  // Sends outgoing[q] to every process q (Size() buffers; this process's own is handed back
  // as it is) and returns in incoming[q] what process q sent to this one.
  virtual void Exchange(
    const std::vector<ByteBuffer>& outgoing, std::vector<ByteBuffer>& incoming) = 0;
  // The sum, the minimum and the maximum of a value over the processes.
  virtual std::int64_t Sum(std::int64_t value) = 0;
  virtual double Min(double value) = 0;
  virtual double Max(double value) = 0;
};

// Appends trivially copyable values to a buffer.
class ByteWriter
{
public:
  explicit ByteWriter(ByteBuffer& buffer)
    : Buffer(buffer)
  {
  }
  template <class T>
  void Put(const T& value)
  {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    const std::size_t at = Buffer.size();
    Buffer.resize(at + sizeof(T));
    std::memcpy(Buffer.data() + at, &value, sizeof(T));
  }

private:
  ByteBuffer& Buffer;
};

// Reads back what a ByteWriter wrote, in the same order.
class ByteReader
{
public:
  explicit ByteReader(const ByteBuffer& buffer)
    : Buffer(buffer)
  {
  }
  bool AtEnd() const { return At >= Buffer.size(); }
  // False (and `value` untouched) when the buffer holds too few bytes: a malformed message.
  template <class T>
  bool Get(T& value)
  {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    if (Buffer.size() - At < sizeof(T) || At > Buffer.size())
    {
      return false;
    }
    std::memcpy(&value, Buffer.data() + At, sizeof(T));
    At += sizeof(T);
    return true;
  }

private:
  const ByteBuffer& Buffer;
  std::size_t At = 0;
};

} // namespace gs
