// Surfaces: creation from caller arrays or a file, accessors, validation.
#include <cmath>
#include <memory>
#include <string>

#include "handles.hpp"
#include "io/surface_io.hpp"
#include "shim.hpp"
#include "validate/validate.hpp"

using namespace anitet::capi;

namespace {

// A validation problem or repair as a log line.
void log_report(const anitet_options& options, const anitet::ValidationReport& report) {
  if (options.log == nullptr) return;
  for (const anitet::Repair& r : report.repairs) {
    options.log(ANITET_LOG_INFO, ("repair: " + r.message).c_str(), options.log_user_data);
  }
  for (const anitet::Problem& p : report.problems) {
    const int32_t level =
        p.severity == anitet::Severity::Error ? ANITET_LOG_ERROR : ANITET_LOG_WARNING;
    options.log(level, (p.kind + ": " + p.message).c_str(), options.log_user_data);
  }
}

int cancelled(const char* function, const char* stage) {
  return set_error(ANITET_ERR_CANCELLED, std::string(function) + ": cancelled by the progress callback (stage " +
                                             stage + ")");
}

}  // namespace

extern "C" {

int anitet_surface_create(const double* xyz, int64_t num_points, const int32_t* tri,
                          int64_t num_triangles, const int32_t* patch, int32_t index_base,
                          anitet_surface** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    if (num_points < 0 || num_triangles < 0) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": negative count");
    }
    if (num_points == 0 || num_triangles == 0) {
      return set_error(ANITET_ERR_EMPTY_INPUT, std::string(fn) + ": no point or no triangle");
    }
    if (xyz == nullptr) return null_argument(fn, "xyz");
    if (tri == nullptr) return null_argument(fn, "tri");
    if (num_points > int64_t(INT32_MAX)) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": too many points for int32_t indices");
    }
    auto surface = std::make_unique<anitet_surface>();
    anitet::SurfaceMesh& m = surface->mesh;
    m.xyz.assign(xyz, xyz + 3 * num_points);
    m.tri.resize(static_cast<size_t>(3 * num_triangles));
    for (int64_t i = 0; i < 3 * num_triangles; ++i) {
      const int64_t v = int64_t(tri[i]) - index_base;
      if (v < 0 || v >= num_points) {
        return set_error(ANITET_ERR_BAD_INDEX,
                         std::string(fn) + ": triangle " + std::to_string(i / 3 + index_base) +
                             " refers to vertex " + std::to_string(tri[i]) + ", not in [" +
                             std::to_string(index_base) + ", " +
                             std::to_string(num_points - 1 + index_base) + "]");
      }
      m.tri[size_t(i)] = static_cast<uint32_t>(v);
    }
    if (patch) m.patch.assign(patch, patch + num_triangles);
    else m.patch.assign(static_cast<size_t>(num_triangles), 0);
    *out = surface.release();
    return ok();
  });
}

int anitet_surface_read(const char* path, anitet_surface** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (path == nullptr) return null_argument(fn, "path");
    anitet::Result<anitet::SurfaceMesh> read = anitet::read_surface(std::string(path));
    if (!read.ok()) return set_status(fn, read.status());
    auto surface = std::make_unique<anitet_surface>();
    surface->mesh = std::move(read).value();
    *out = surface.release();
    return ok();
  });
}

void anitet_surface_destroy(anitet_surface* surface) { delete surface; }

int anitet_surface_get_counts(const anitet_surface* surface, int64_t* num_points,
                              int64_t* num_triangles) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (surface == nullptr) return null_argument(fn, "surface");
    if (num_points) *num_points = static_cast<int64_t>(surface->mesh.num_vertices());
    if (num_triangles) *num_triangles = static_cast<int64_t>(surface->mesh.num_triangles());
    return ok();
  });
}

int anitet_surface_get_points(const anitet_surface* surface, double* xyz, int64_t xyz_len) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (surface == nullptr) return null_argument(fn, "surface");
    if (xyz == nullptr) return null_argument(fn, "xyz");
    const auto& v = surface->mesh.xyz;
    if (xyz_len < 0 || uint64_t(xyz_len) < v.size()) return too_small(fn, "xyz", xyz_len, v.size());
    std::copy(v.begin(), v.end(), xyz);
    return ok();
  });
}

int anitet_surface_get_triangles(const anitet_surface* surface, int32_t* tri, int64_t tri_len,
                                 int32_t index_base) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (surface == nullptr) return null_argument(fn, "surface");
    if (tri == nullptr) return null_argument(fn, "tri");
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    const auto& v = surface->mesh.tri;
    if (tri_len < 0 || uint64_t(tri_len) < v.size()) return too_small(fn, "tri", tri_len, v.size());
    for (size_t i = 0; i < v.size(); ++i) tri[i] = static_cast<int32_t>(v[i]) + index_base;
    return ok();
  });
}

int anitet_surface_get_patches(const anitet_surface* surface, int32_t* patch, int64_t patch_len) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (surface == nullptr) return null_argument(fn, "surface");
    if (patch == nullptr) return null_argument(fn, "patch");
    const auto& v = surface->mesh.patch;
    if (patch_len < 0 || uint64_t(patch_len) < v.size()) return too_small(fn, "patch", patch_len, v.size());
    std::copy(v.begin(), v.end(), patch);
    return ok();
  });
}

int anitet_surface_validate(anitet_surface* surface, const anitet_options* options) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (surface == nullptr) return null_argument(fn, "surface");
    anitet_options opt;
    if (const int code = read_options(fn, options, opt); code != ANITET_OK) return code;
    if (opt.progress && opt.progress(0.0, "validate", opt.progress_user_data) != 0) {
      return cancelled(fn, "validate");
    }
    anitet::ValidationOptions vo;
    vo.merge_duplicate_vertices = opt.merge_duplicate_vertices != 0;
    vo.orient_shells = opt.orient_shells != 0;
    vo.check_self_intersections = opt.check_self_intersections != 0;
    vo.num_threads = opt.num_threads;
    surface->report.reset();
    surface->report = anitet::validate_surface(surface->mesh, vo);
    log_report(opt, *surface->report);
    if (opt.progress && opt.progress(1.0, "validate", opt.progress_user_data) != 0) {
      return cancelled(fn, "validate");
    }
    return set_status(fn, surface->report->status());
  });
}

int anitet_surface_problem_count(const anitet_surface* surface, int32_t code, int64_t* count) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (surface == nullptr) return null_argument(fn, "surface");
    if (count == nullptr) return null_argument(fn, "count");
    *count = 0;
    if (!surface->report) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": the surface was not validated");
    }
    *count = static_cast<int64_t>(surface->report->count(static_cast<anitet::Error>(code)));
    return ok();
  });
}

int anitet_surface_validation_json(const anitet_surface* surface, char* buf, int64_t buf_len,
                                   int64_t* needed) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (needed) *needed = 0;
    if (surface == nullptr) return null_argument(fn, "surface");
    if (!surface->report) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": the surface was not validated");
    }
    return copy_text(fn, anitet::report_to_json(*surface->report), buf, buf_len, needed);
  });
}

}  // extern "C"
