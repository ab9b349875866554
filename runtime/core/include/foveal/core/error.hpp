#pragma once
// Errors cross module boundaries as values (Result<T>), never as exceptions.
#include <string>
#include <utility>
#include <variant>

namespace foveal {

enum class ErrorKind {
  bad_input,    ///< malformed file, row, field or argument: exit code 2 in the CLI
  io,           ///< the OS refused (open, read, write, rename)
  unsupported,  ///< valid but not handled (unknown format version, extension)
  device,       ///< a device failed or vanished
  internal,
};

/// An error with a message that already names where (file:line: field) and what.
struct Error {
  ErrorKind kind = ErrorKind::internal;
  std::string message;
};

inline Error bad_input(std::string msg) { return {ErrorKind::bad_input, std::move(msg)}; }
inline Error io_error(std::string msg) { return {ErrorKind::io, std::move(msg)}; }

/// Either a value or an Error. Small on purpose: std::expected is C++23.
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}       // NOLINT: implicit by design
  Result(Error error) : v_(std::move(error)) {}   // NOLINT
  bool ok() const { return v_.index() == 0; }
  explicit operator bool() const { return ok(); }
  T& value() & { return std::get<0>(v_); }
  const T& value() const& { return std::get<0>(v_); }
  T&& value() && { return std::get<0>(std::move(v_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T&& operator*() && { return std::move(*this).value(); }
  const Error& error() const { return std::get<1>(v_); }

 private:
  std::variant<T, Error> v_;
};

template <>
class [[nodiscard]] Result<void> {
 public:
  Result() = default;
  Result(Error error) : err_(std::move(error)), failed_(true) {}  // NOLINT
  bool ok() const { return !failed_; }
  explicit operator bool() const { return ok(); }
  const Error& error() const { return err_; }

 private:
  Error err_;
  bool failed_ = false;
};

using Status = Result<void>;

}  // namespace foveal
