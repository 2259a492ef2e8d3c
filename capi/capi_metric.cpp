// Metric fields. Reading metric files and per-point metrics on a background mesh are not part of
// the library yet: they say ANITET_ERR_NOT_IMPLEMENTED, never a silent no-op.
#include <cmath>
#include <memory>
#include <string>

#include "handles.hpp"
#include "shim.hpp"

using namespace anitet::capi;

namespace {
int not_implemented(const char* function, const char* what) {
  return set_error(ANITET_ERR_NOT_IMPLEMENTED, std::string(function) + ": " + what +
                                                   " is not implemented in anitet " +
                                                   ANITET_VERSION_STRING);
}
}  // namespace

extern "C" {

int anitet_metric_create_uniform(double size, anitet_metric** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (!(std::isfinite(size) && size > 0.0)) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT,
                       std::string(fn) + ": size must be finite and positive");
    }
    auto metric = std::make_unique<anitet_metric>();
    metric->kind = anitet_metric::Kind::Uniform;
    metric->size = size;
    *out = metric.release();
    return ok();
  });
}

int anitet_metric_create_analytic(anitet_metric_fn callback, void* user_data, anitet_metric** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (callback == nullptr) return null_argument(fn, "callback");
    auto metric = std::make_unique<anitet_metric>();
    metric->kind = anitet_metric::Kind::Analytic;
    metric->fn = callback;
    metric->user_data = user_data;
    *out = metric.release();
    return ok();
  });
}

int anitet_metric_read(const char* path, const char* background_mesh_path, anitet_metric** out) {
  (void)background_mesh_path;
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (path == nullptr) return null_argument(fn, "path");
    return not_implemented(fn, "reading a metric file (.vdb, .sol)");
  });
}

int anitet_metric_create_from_points(const anitet_mesh* background, const double* values,
                                     int64_t num_values, int32_t components, anitet_metric** out) {
  (void)num_values;
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (background == nullptr) return null_argument(fn, "background");
    if (values == nullptr) return null_argument(fn, "values");
    if (components != 1 && components != 6) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": components is " +
                                                        std::to_string(components) + ", not 1 or 6");
    }
    return not_implemented(fn, "a per-point metric on a background mesh");
  });
}

void anitet_metric_destroy(anitet_metric* metric) { delete metric; }

int anitet_metric_evaluate(const anitet_metric* metric, double x, double y, double z, double m[6]) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (metric == nullptr) return null_argument(fn, "metric");
    if (m == nullptr) return null_argument(fn, "m");
    if (metric->kind == anitet_metric::Kind::Uniform) {
      const double d = 1.0 / (metric->size * metric->size);  // unit length = size
      const double tensor[6] = {d, 0.0, d, 0.0, 0.0, d};
      std::copy(tensor, tensor + 6, m);
      return ok();
    }
    const int code = metric->fn(x, y, z, m, metric->user_data);
    if (code != 0) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": the metric callback returned " +
                                                        std::to_string(code) + " at (" + std::to_string(x) +
                                                        ", " + std::to_string(y) + ", " + std::to_string(z) + ")");
    }
    return ok();
  });
}

}  // extern "C"
