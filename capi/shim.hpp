// Internal helpers of the C ABI shims: the thread-local last error, the try/catch wrapper every
// entry point goes through, and argument checks that set a message naming the function.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include <tbb/task_arena.h>

#include "anitet.h"
#include "core/status.hpp"

namespace anitet::capi {

// Stores the message of the last call on this thread and returns its code.
int set_error(int code, const std::string& message);
int set_status(const char* function, const Status& status);
inline int ok() { return set_error(ANITET_OK, std::string()); }
const char* last_error_c_str();

// Bytes of an anitet_options struct of `version` (a valid one).
size_t options_size(int32_t version);
// Options after the version check; NULL gives the defaults. Reads only the caller's version.
int read_options(const char* function, const anitet_options* given, anitet_options& out);

// Runs body() (returning int) and turns any escaping exception into an error code: no exception
// ever crosses the C ABI.
template <class F>
int guard(const char* function, F&& body) noexcept {
  try {
    return body();
  } catch (const std::bad_alloc&) {
    return set_error(ANITET_ERR_OUT_OF_MEMORY, std::string(function) + ": out of memory");
  } catch (const std::exception& e) {
    try {
      return set_error(ANITET_ERR_INTERNAL, std::string(function) + ": internal error: " + e.what());
    } catch (...) {
      return ANITET_ERR_INTERNAL;
    }
  } catch (...) {
    return set_error(ANITET_ERR_INTERNAL, std::string(function) + ": internal error");
  }
}

// Runs f in a task arena of `threads` threads (0: all cores), as the pipeline runs its stages:
// the one mechanism behind every num_threads of the ABI (and the CLI's --threads).
template <class F>
auto in_arena(int32_t threads, F&& f) {
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  return arena.execute(std::forward<F>(f));
}

int null_argument(const char* function, const char* argument);
int bad_index_base(const char* function, int32_t index_base);
// ANITET_ERR_BUFFER_TOO_SMALL naming the sizes.
int too_small(const char* function, const char* argument, int64_t given, uint64_t needed);

// Copies `values` (converted by f) into a caller buffer after the length check.
template <class T, class U, class F>
int fill(const char* function, const char* argument, const std::vector<T>& values, U* buf,
         int64_t buf_len, F&& f) {
  if (values.empty()) return ok();  // nothing to write: a NULL buffer is fine
  if (buf == nullptr) return null_argument(function, argument);
  if (buf_len < 0 || uint64_t(buf_len) < values.size()) return too_small(function, argument, buf_len, values.size());
  std::transform(values.begin(), values.end(), buf, f);
  return ok();
}

const auto kSame = [](auto v) { return v; };

// Copies a string into a caller buffer (NUL included), with the size query rule of the header.
int copy_text(const char* function, const std::string& text, char* buf, int64_t buf_len,
              int64_t* needed);

// Converts count*arity caller indices counted from base into 0-based ones; BAD_INDEX otherwise.
inline int convert_indices(const char* function, const char* element, const int32_t* in, int64_t count,
                           int arity, int64_t num_points, int32_t base, std::vector<uint32_t>& out) {
  out.resize(static_cast<size_t>(count * arity));
  for (int64_t i = 0; i < count * arity; ++i) {
    const int64_t v = int64_t(in[i]) - base;
    if (v < 0 || v >= num_points) {
      return set_error(ANITET_ERR_BAD_INDEX,
                       std::string(function) + ": " + element + " " + std::to_string(i / arity + base) +
                           " refers to vertex " + std::to_string(in[i]) + ", not in [" +
                           std::to_string(base) + ", " + std::to_string(num_points - 1 + base) + "]");
    }
    out[size_t(i)] = static_cast<uint32_t>(v);
  }
  return ANITET_OK;
}

}  // namespace anitet::capi
