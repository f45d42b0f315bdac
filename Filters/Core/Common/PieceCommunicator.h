// What a computation on a surface partitioned over processes needs from its transport: the
// processes' ranks, a personalized exchange of byte buffers and global reductions. The VTK
// layer implements it over vtkMultiProcessController (MPI); the core tests over threads. Every
// operation is collective: every process calls it, in the same order.
#pragma once

#include <cassert>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
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

// The collective patterns built on a communicator.

// Collective. The first process (in rank order) whose `message` is not empty: its rank, and its
// message in `text`; -1 (and `text` empty) when every message is empty.
inline int FirstMessage(PieceCommunicator& comm, const std::string& message, std::string& text)
{
  text.clear();
  const double none = std::numeric_limits<double>::max();
  const double first = comm.Min(message.empty() ? none : static_cast<double>(comm.Rank()));
  if (first == none)
  {
    return -1;
  }
  std::vector<ByteBuffer> out(static_cast<std::size_t>(comm.Size())), in;
  if (comm.Rank() == static_cast<int>(first))
  {
    for (ByteBuffer& b : out)
    {
      b.assign(message.begin(), message.end());
    }
  }
  comm.Exchange(out, in);
  const ByteBuffer& bytes = in[static_cast<std::size_t>(first)];
  text.assign(bytes.begin(), bytes.end());
  return static_cast<int>(first);
}

// Collective. The sum of `value` over the processes, added in rank order (the same on every
// process).
inline double SumOverProcesses(PieceCommunicator& comm, double value)
{
  std::vector<ByteBuffer> out(static_cast<std::size_t>(comm.Size())), in;
  for (ByteBuffer& b : out)
  {
    ByteWriter(b).Put(value);
  }
  comm.Exchange(out, in);
  double sum = 0.0;
  for (int q = 0; q < comm.Size(); ++q)
  {
    double v = 0.0;
    ByteReader(q == comm.Rank() ? out[static_cast<std::size_t>(q)] : in[static_cast<std::size_t>(q)])
      .Get(v);
    sum += v;
  }
  return sum;
}

// Collective. Whether every process goes on: false on every process when the progress callback
// of any (called with `fraction`; an empty callback goes on) returns false.
template <class Progress>
bool EveryProcessGoesOn(PieceCommunicator& comm, const Progress& progress, double fraction)
{
  const bool goOn = !progress || progress(fraction);
  return comm.Max(goOn ? 0.0 : 1.0) == 0.0;
}

// What the other processes sent (incoming[q], q not this process), read as records that each
// start with a tag: read(tag, reader) reads one record and returns false when it is malformed,
// which ends that process's buffer (every record names what the receiver holds: a malformed
// one is a broken invariant, not an input error).
template <class Read>
void ReadTaggedRecords(PieceCommunicator& comm, const std::vector<ByteBuffer>& incoming, Read&& read)
{
  for (std::size_t q = 0; q < incoming.size(); ++q)
  {
    if (static_cast<int>(q) == comm.Rank())
    {
      continue;
    }
    ByteReader r(incoming[q]);
    std::uint8_t tag = 0;
    while (r.Get(tag))
    {
      const bool readable = read(tag, r);
      assert(readable);
      if (!readable)
      {
        break;
      }
    }
  }
}

// What the other processes sent (incoming[q], q not this process), read as (global id, value)
// pairs: take(id, value) for each.
template <class Take>
void ReadIdValuePairs(PieceCommunicator& comm, const std::vector<ByteBuffer>& incoming, Take&& take)
{
  for (std::size_t q = 0; q < incoming.size(); ++q)
  {
    if (static_cast<int>(q) == comm.Rank())
    {
      continue;
    }
    ByteReader r(incoming[q]);
    std::int64_t id = 0;
    double value = 0.0;
    while (r.Get(id) && r.Get(value))
    {
      take(id, value);
    }
  }
}

// Collective. Exchange whose buffers carry each sender's `count` at their end (taken off on
// arrival): returns the sum of the counts over the processes, so that rounds of exchanges know
// when to end without a reduction of their own.
inline std::int64_t ExchangeCounting(PieceCommunicator& comm, std::vector<ByteBuffer>& outgoing,
  std::vector<ByteBuffer>& incoming, std::int64_t count)
{
  for (ByteBuffer& b : outgoing)
  {
    ByteWriter(b).Put(count);
  }
  comm.Exchange(outgoing, incoming);
  std::int64_t sum = count;
  for (std::size_t q = 0; q < incoming.size(); ++q)
  {
    if (static_cast<int>(q) != comm.Rank() && incoming[q].size() >= sizeof(std::int64_t))
    {
      std::int64_t theirs = 0;
      std::memcpy(&theirs, incoming[q].data() + incoming[q].size() - sizeof theirs, sizeof theirs);
      sum += theirs;
      incoming[q].resize(incoming[q].size() - sizeof theirs);
    }
  }
  return sum;
}

// Collective. For each item i of `values` (as many on every process), the smallest value over
// the processes into `smallest` and the rank holding it into the result (the lowest such rank
// on a tie; -1 where no value is below infinity).
inline std::vector<int> SmallestOverProcesses(
  PieceCommunicator& comm, const std::vector<double>& values, std::vector<double>& smallest)
{
  std::vector<ByteBuffer> out(static_cast<std::size_t>(comm.Size())), in;
  for (ByteBuffer& b : out)
  {
    ByteWriter w(b);
    for (const double v : values)
    {
      w.Put(v);
    }
  }
  comm.Exchange(out, in);
  std::vector<int> rank(values.size(), -1);
  smallest.assign(values.size(), std::numeric_limits<double>::infinity());
  for (int q = 0; q < comm.Size(); ++q)
  {
    const std::size_t from = static_cast<std::size_t>(q);
    ByteReader r(q == comm.Rank() ? out[from] : in[from]);
    for (std::size_t i = 0; i < values.size(); ++i)
    {
      double v = std::numeric_limits<double>::infinity();
      if (r.Get(v) && v < smallest[i])
      {
        smallest[i] = v;
        rank[i] = q;
      }
    }
  }
  return rank;
}

// Collective. Each process asks others about ids: asks[q] the ids it asks process q about
// (none of itself); answer(q, id) is the value it gives process q about `id`, called in the
// order q asked. Returns, per process q, the values q gave, in the order asked.
template <class Answer>
std::vector<std::vector<double>> AskProcesses(PieceCommunicator& comm,
  const std::vector<std::vector<std::int64_t>>& asks, const Answer& answer)
{
  const std::size_t size = static_cast<std::size_t>(comm.Size());
  std::vector<ByteBuffer> requests(size), asked, answers(size), answered;
  for (std::size_t q = 0; q < size && q < asks.size(); ++q)
  {
    ByteWriter w(requests[q]);
    for (const std::int64_t id : asks[q])
    {
      w.Put(id);
    }
  }
  comm.Exchange(requests, asked);
  for (std::size_t q = 0; q < size; ++q)
  {
    ByteReader r(asked[q]);
    ByteWriter w(answers[q]);
    std::int64_t id = 0;
    while (static_cast<int>(q) != comm.Rank() && r.Get(id))
    {
      w.Put(static_cast<double>(answer(static_cast<int>(q), id)));
    }
  }
  comm.Exchange(answers, answered);
  std::vector<std::vector<double>> values(size);
  for (std::size_t q = 0; q < size; ++q)
  {
    ByteReader r(answered[q]);
    double v = 0.0;
    while (static_cast<int>(q) != comm.Rank() && r.Get(v))
    {
      values[q].push_back(v);
    }
  }
  return values;
}

} // namespace gs
