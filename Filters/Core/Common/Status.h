// How a core call that can fail says how it went: Status (ok, an error with a message for the
// user, or aborted by the caller's progress callback), and Result<T>, a Status that carries a
// value when ok. In the spirit of absl::Status / absl::StatusOr: the filters hand Message() to
// vtkErrorMacro as it is, and say nothing on IsAborted().
#pragma once

#include <cassert>
#include <string>
#include <utility>

namespace gs
{

class [[nodiscard]] Status
{
public:
  /// Ok.
  Status() = default;
  /// Failed: `message` says why, in words for the user (not empty, no final full stop).
  static Status Error(std::string message)
  {
    assert(!message.empty());
    return Status(Code::Error, std::move(message));
  }
  /// Stopped because a progress callback returned false: not an error to report.
  static Status Aborted() { return Status(Code::Aborted, "aborted"); }

  bool Ok() const { return this->Kind == Code::Ok; }
  bool IsAborted() const { return this->Kind == Code::Aborted; }
  /// Why it failed ("aborted" when aborted); empty when ok.
  const std::string& Message() const { return this->Text; }

private:
  enum class Code : unsigned char
  {
    Ok,
    Error,
    Aborted
  };
  Status(Code kind, std::string text)
    : Kind(kind)
    , Text(std::move(text))
  {
  }
  Code Kind = Code::Ok;
  std::string Text;
};

/// A Status with, when Ok(), a value (read with * and ->). Made from a value (ok) or from a
/// failed Status, so that `return Status::Error("...")` works in a function returning Result<T>.
template <typename T>
class [[nodiscard]] Result : public Status
{
public:
  Result(T&& value)
    : Val(std::move(value))
  {
  }
  Result(Status failure)
    : Status(std::move(failure))
  {
    assert(!this->Ok());
  }

  /// The value (only when Ok()); std::move(*result) takes it out.
  T& operator*() { return this->Val; }
  const T& operator*() const { return this->Val; }
  T* operator->() { return &this->Val; }
  const T* operator->() const { return &this->Val; }

private:
  T Val{};
};

} // namespace gs
