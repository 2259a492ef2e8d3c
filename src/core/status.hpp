// Errors as values: every fallible library function returns a Status or a Result<T>.
// The numeric codes are the C ABI's error codes: never renumber one, only add new ones.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

namespace anitet {

enum class Error : int32_t {
  Ok = 0,
  InvalidArgument = -1,
  FileNotFound = -2,       // cannot open a file for reading or writing
  Parse = -3,              // malformed or truncated file contents
  UnsupportedFormat = -4,  // unknown extension or format variant
  EmptyInput = -5,         // no points or no triangles
  BufferTooSmall = -6,     // a caller's buffer (C ABI) cannot hold the result
  // Surface validation (one code per defect kind).
  NonFiniteCoordinate = -10,
  DegenerateTriangle = -11,
  DuplicateTriangle = -12,
  OpenBoundary = -13,
  NonManifoldEdge = -14,
  NonManifoldVertex = -15,
  InconsistentOrientation = -16,
  SelfIntersection = -17,
  IntersectingShells = -18,
  BadIndex = -19,  // a triangle refers to a vertex that does not exist
  // Meshing.
  NotImplemented = -30,
  Cancelled = -31,
  DuplicatePoint = -32,
  RecoveryFailed = -33,
  InvalidMesh = -34,
  OutOfMemory = -40,
  Internal = -99,
};

// Short stable name of an error code ("open_boundary"), for JSON and logs.
const char* error_name(Error e);

class Status {
 public:
  Status() = default;
  Status(Error code, std::string message) : code_(code), message_(std::move(message)) {}
  static Status success() { return Status(); }

  bool ok() const { return code_ == Error::Ok; }
  Error code() const { return code_; }
  const std::string& message() const { return message_; }

 private:
  Error code_ = Error::Ok;
  std::string message_;
};

// A value or the Status that explains why there is none.
template <class T>
class Result {
 public:
  Result(T value) : value_(std::move(value)) {}  // NOLINT: implicit on purpose
  Result(Status status) : status_(std::move(status)) {}  // NOLINT
  Result(Error code, std::string message) : status_(code, std::move(message)) {}

  bool ok() const { return value_.has_value(); }
  const Status& status() const { return status_; }
  T& value() & { return *value_; }
  const T& value() const& { return *value_; }
  T&& value() && { return std::move(*value_); }
  T* operator->() { return &*value_; }
  const T* operator->() const { return &*value_; }

 private:
  std::optional<T> value_;
  Status status_;
};

}  // namespace anitet
