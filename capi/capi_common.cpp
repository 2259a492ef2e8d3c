// Library information, errors and options.
#include <cstddef>
#include <cstring>
#include <string>

#include "shim.hpp"

namespace anitet::capi {
namespace {
// The one piece of state the ABI keeps: per thread, by design (see anitet_last_error_message).
thread_local std::string t_last_error;
}  // namespace

int set_error(int code, const std::string& message) {
  t_last_error = message;
  return code;
}

const char* last_error_c_str() { return t_last_error.c_str(); }

size_t options_size(int32_t version) {
  // Each version's struct ends where the next version's first field starts.
  if (version == 1) return offsetof(anitet_options, layers);
  if (version == 2) return offsetof(anitet_options, attempts_seconds);
  if (version == 3) return offsetof(anitet_options, bl_num_slide_patches);
  if (version == 4) return offsetof(anitet_options, bl_sizing_growth);
  return sizeof(anitet_options);
}

int read_options(const char* function, const anitet_options* given, anitet_options& out) {
  const anitet_options defaults = ANITET_OPTIONS_INIT;
  out = defaults;
  if (given == nullptr) return ANITET_OK;
  if (given->version < 1 || given->version > ANITET_OPTIONS_VERSION) {
    return set_error(ANITET_ERR_INVALID_ARGUMENT,
                     std::string(function) + ": options version " + std::to_string(given->version) +
                         " is not supported (1.." + std::to_string(ANITET_OPTIONS_VERSION) +
                         "); initialise with ANITET_OPTIONS_INIT or anitet_options_init");
  }
  // Only the caller's version of the struct exists in its memory; later fields keep defaults.
  std::memcpy(&out, given, options_size(given->version));
  return ANITET_OK;
}

int set_status(const char* function, const Status& status) {
  if (status.ok()) return ok();
  return set_error(static_cast<int>(status.code()), std::string(function) + ": " + status.message());
}

int null_argument(const char* function, const char* argument) {
  return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(function) + ": " + argument + " is NULL");
}

int bad_index_base(const char* function, int32_t index_base) {
  return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(function) + ": index_base is " +
                                                    std::to_string(index_base) + ", not 0 or 1");
}

int too_small(const char* function, const char* argument, int64_t given, uint64_t needed) {
  return set_error(ANITET_ERR_BUFFER_TOO_SMALL, std::string(function) + ": " + argument +
                                                    " holds " + std::to_string(given) +
                                                    " elements, " + std::to_string(needed) +
                                                    " needed");
}

int copy_text(const char* function, const std::string& text, char* buf, int64_t buf_len,
              int64_t* needed) {
  const uint64_t size = text.size() + 1;
  if (needed) *needed = static_cast<int64_t>(size);
  if (buf == nullptr && buf_len == 0) return ok();  // size query
  if (buf == nullptr) return null_argument(function, "buf");
  if (buf_len < 0 || static_cast<uint64_t>(buf_len) < size) return too_small(function, "buf", buf_len, size);
  std::memcpy(buf, text.c_str(), size);
  return ok();
}

}  // namespace anitet::capi

using namespace anitet::capi;

// The header's version macros must describe the library they ship with.
static_assert(ANITET_VERSION_MAJOR == ANITET_BUILD_VERSION_MAJOR &&
                  ANITET_VERSION_MINOR == ANITET_BUILD_VERSION_MINOR &&
                  ANITET_VERSION_PATCH == ANITET_BUILD_VERSION_PATCH,
              "include/anitet.h version macros differ from the CMake project version");

// Version 1 of anitet_options ends after log_user_data: its layout is frozen.
static_assert(offsetof(anitet_options, layers) == 6 * sizeof(int32_t) + 4 * sizeof(void*),
              "the version 1 fields of anitet_options moved");
// Versions 2 and 3 have no padding either (the Fortran and Python mirrors assume none), and
// version 2 ends where version 3 starts.
static_assert(offsetof(anitet_options, recovery_max_seconds) % alignof(double) == 0 &&
                  offsetof(anitet_options, size_scale) % alignof(double) == 0 &&
                  offsetof(anitet_options, attempts_seconds) == offsetof(anitet_options, size_scale) + sizeof(double),
              "anitet_options (version 2) has padding");
static_assert(offsetof(anitet_options, hmin) == offsetof(anitet_options, attempts_seconds) + 16 &&
                  offsetof(anitet_options, bl_patches) == offsetof(anitet_options, anisotropic_cycles) + 8 &&
                  offsetof(anitet_options, bl_first_height) == offsetof(anitet_options, bl_patches) + sizeof(void*) &&
                  offsetof(anitet_options, push_tasks_min_vertices) == offsetof(anitet_options, bl_sizing) + 4 &&
                  offsetof(anitet_options, bl_num_slide_patches) == offsetof(anitet_options, bl_mitre) + sizeof(int32_t),
              "anitet_options (version 3) has padding");
static_assert(offsetof(anitet_options, bl_slide_patches) == offsetof(anitet_options, bl_num_slide_patches) + 8 &&
                  offsetof(anitet_options, bl_sizing_growth) == offsetof(anitet_options, bl_slide_patches) + sizeof(void*),
              "anitet_options (version 4) has padding");
static_assert(sizeof(anitet_options) == offsetof(anitet_options, bl_sizing_growth) + sizeof(double),
              "anitet_options (version 5) has padding");
static_assert(offsetof(anitet_run_stats, slide_junction_columns) == offsetof(anitet_run_stats, bl_max_height_error) + sizeof(double) &&
                  offsetof(anitet_run_stats, bl_prisms) == offsetof(anitet_run_stats, slide_triangles_added) + sizeof(int64_t) &&
                  sizeof(anitet_run_stats) == offsetof(anitet_run_stats, bl_prism_tets_left) + sizeof(int64_t) &&
                  offsetof(anitet_run_stats, vertices) == 8 * sizeof(int32_t) &&
                  offsetof(anitet_run_stats, bl_wall_vertices) == offsetof(anitet_run_stats, bl_layers) + 8,
              "anitet_run_stats has padding");

// The header's codes are anitet::Error's values: never renumber either.
#define ANITET_SAME_CODE(c, e) static_assert(c == static_cast<int>(anitet::Error::e), #c)
ANITET_SAME_CODE(ANITET_OK, Ok);
ANITET_SAME_CODE(ANITET_ERR_INVALID_ARGUMENT, InvalidArgument);
ANITET_SAME_CODE(ANITET_ERR_FILE_NOT_FOUND, FileNotFound);
ANITET_SAME_CODE(ANITET_ERR_PARSE, Parse);
ANITET_SAME_CODE(ANITET_ERR_UNSUPPORTED_FORMAT, UnsupportedFormat);
ANITET_SAME_CODE(ANITET_ERR_EMPTY_INPUT, EmptyInput);
ANITET_SAME_CODE(ANITET_ERR_BUFFER_TOO_SMALL, BufferTooSmall);
ANITET_SAME_CODE(ANITET_ERR_NON_FINITE_COORDINATE, NonFiniteCoordinate);
ANITET_SAME_CODE(ANITET_ERR_DEGENERATE_TRIANGLE, DegenerateTriangle);
ANITET_SAME_CODE(ANITET_ERR_DUPLICATE_TRIANGLE, DuplicateTriangle);
ANITET_SAME_CODE(ANITET_ERR_OPEN_BOUNDARY, OpenBoundary);
ANITET_SAME_CODE(ANITET_ERR_NON_MANIFOLD_EDGE, NonManifoldEdge);
ANITET_SAME_CODE(ANITET_ERR_NON_MANIFOLD_VERTEX, NonManifoldVertex);
ANITET_SAME_CODE(ANITET_ERR_INCONSISTENT_ORIENTATION, InconsistentOrientation);
ANITET_SAME_CODE(ANITET_ERR_SELF_INTERSECTION, SelfIntersection);
ANITET_SAME_CODE(ANITET_ERR_INTERSECTING_SHELLS, IntersectingShells);
ANITET_SAME_CODE(ANITET_ERR_BAD_INDEX, BadIndex);
ANITET_SAME_CODE(ANITET_ERR_NOT_IMPLEMENTED, NotImplemented);
ANITET_SAME_CODE(ANITET_ERR_CANCELLED, Cancelled);
ANITET_SAME_CODE(ANITET_ERR_DUPLICATE_POINT, DuplicatePoint);
ANITET_SAME_CODE(ANITET_ERR_RECOVERY_FAILED, RecoveryFailed);
ANITET_SAME_CODE(ANITET_ERR_INVALID_MESH, InvalidMesh);
ANITET_SAME_CODE(ANITET_ERR_OUT_OF_MEMORY, OutOfMemory);
ANITET_SAME_CODE(ANITET_ERR_INTERNAL, Internal);
#undef ANITET_SAME_CODE

extern "C" {

const char* anitet_version(void) { return ANITET_VERSION_STRING; }

int32_t anitet_version_number(void) { return ANITET_VERSION_NUMBER; }

const char* anitet_last_error_message(void) {
  try {
    return anitet::capi::last_error_c_str();
  } catch (...) {
    return "";
  }
}

const char* anitet_error_name(int32_t code) {
  return anitet::error_name(static_cast<anitet::Error>(code));
}

int anitet_set_last_error(int32_t code, const char* message) {
  try {
    return set_error(code, message ? std::string(message) : std::string());
  } catch (...) {
    return code;
  }
}

int anitet_options_init(anitet_options* options, int32_t version) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (options == nullptr) return null_argument(fn, "options");
    anitet_options wanted = ANITET_OPTIONS_INIT;
    wanted.version = version;
    anitet_options resolved;
    const int code = read_options(fn, &wanted, resolved);
    if (code != ANITET_OK) return code;
    std::memcpy(options, &resolved, options_size(version));  // never past the caller's version
    return ok();
  });
}

}  // extern "C"
