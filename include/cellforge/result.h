// Errors as values: Status for operations that return nothing, Result<T> for the
// rest. A refused operation returns an Error whose message names the violated
// precondition and the ids involved; the model is left as it was.
#pragma once

#include <cassert>
#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace cellforge {

enum class ErrorCode {
  kInvalidId,     // a handle that names no live entity
  kPrecondition,  // an operator's precondition does not hold
  kInvalidInput,  // malformed input data (indices, counts, coordinates)
  kParse,         // a file or script could not be read
  kIo,            // the operating system refused a read or write
  kUnsupported,   // valid request the component cannot represent
  kDatabase,      // the model database reported an error
};

struct Error {
  ErrorCode code = ErrorCode::kPrecondition;
  std::string message;
};

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : data_(std::move(value)) {}      // NOLINT: implicit by design
  Result(Error error) : data_(std::move(error)) {}  // NOLINT

  bool ok() const { return data_.index() == 0; }
  explicit operator bool() const { return ok(); }
  T& value() & {
    assert(ok());
    return std::get<0>(data_);
  }
  const T& value() const& {
    assert(ok());
    return std::get<0>(data_);
  }
  T&& value() && {
    assert(ok());
    return std::get<0>(std::move(data_));
  }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  const Error& error() const {
    assert(!ok());
    return std::get<1>(data_);
  }

 private:
  std::variant<T, Error> data_;
};

class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(Error error) : error_(std::move(error)) {}  // NOLINT: implicit by design
  static Status Ok() { return {}; }

  bool ok() const { return !error_.has_value(); }
  explicit operator bool() const { return ok(); }
  const Error& error() const {
    assert(!ok());
    return *error_;
  }

 private:
  std::optional<Error> error_;
};

inline Error precondition(std::string message) {
  return Error{ErrorCode::kPrecondition, std::move(message)};
}

}  // namespace cellforge
