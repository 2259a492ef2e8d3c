// Exit codes of the `anitet` command-line tool: one per failure class, stable for scripts.
#pragma once

#include "core/status.hpp"

namespace anitet::cli {

constexpr int kExitOk = 0;
constexpr int kExitInternal = 1;        // an unexpected failure inside the tool
constexpr int kExitUsage = 2;           // bad command line
constexpr int kExitReadError = 3;       // a file cannot be read, parsed or written
constexpr int kExitInvalidInput = 4;    // the input is read but invalid (e.g. an open surface)
constexpr int kExitNotImplemented = 5;  // the requested stage does not exist yet

// The exit code of a file that could not be read: a file that cannot be opened is a read/write
// error (3); one that was read but is malformed, or holds what anitet does not read (a bad index,
// no triangle, an unsupported variant), is invalid input (4); bad options are usage errors.
inline int exit_code_of_read(anitet::Error e) {
  switch (e) {
    case anitet::Error::FileNotFound: return kExitReadError;
    case anitet::Error::InvalidArgument: return kExitUsage;
    case anitet::Error::NotImplemented: return kExitNotImplemented;
    case anitet::Error::OutOfMemory:
    case anitet::Error::Internal: return kExitInternal;
    default: return kExitInvalidInput;
  }
}

// A stable name of each code, for JSON ("internal_error", "usage", ...).
inline const char* exit_code_name(int code) {
  switch (code) {
    case kExitOk: return "ok";
    case kExitInternal: return "internal_error";
    case kExitUsage: return "usage";
    case kExitReadError: return "read_write_error";
    case kExitInvalidInput: return "invalid_input";
    case kExitNotImplemented: return "not_implemented";
    default: return "error";
  }
}

}  // namespace anitet::cli
