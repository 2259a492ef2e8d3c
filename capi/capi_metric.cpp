// Metric fields: uniform, analytic (a caller callback), and the fields of metric/ (a .vdb grid, a
// .sol on a background mesh, or per-point values on a background mesh given as a handle).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "caller_sizing.hpp"
#include "handles.hpp"
#include "io/volume_io.hpp"
#include "metric/bounded_sizing.hpp"
#include "mesh2d/sizing2.hpp"
#include "metric/metric_field.hpp"
#include "metric/sol_field.hpp"
#include "shim.hpp"

using namespace anitet::capi;

namespace {

// The lower-case extension of the file name in `path` (".vdb"), "" without one.
std::string extension(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  const size_t dot = path.rfind('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return std::string();
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

anitet_metric* new_field_metric(std::shared_ptr<const anitet::SizingField> field) {
  auto metric = std::make_unique<anitet_metric>();
  metric->kind = anitet_metric::Kind::Field;
  metric->field = std::move(field);
  return metric.release();
}

// A .sol or .solb on a background mesh: `background`, or when NULL the mesh read from
// `background_name` (after the .sol, whose errors come first): the interpolating field.
int sol_metric_on(const char* fn, const std::string& path, const anitet::VolumeMesh* background,
                  const std::string& background_name, anitet_metric** out) {
  anitet::Result<anitet::metric::SolField> sol = anitet::metric::read_sol(path);
  if (!sol.ok()) return set_status(fn, sol.status());
  if (sol->dimension == 2) {  // a 2D field on a 2D .mesh, for anitet_mesh2d_run
    if (background != nullptr) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": " + path +
                                                         " is two-dimensional (Dimension 2): it goes on a 2D .mesh file, not on a volume mesh");
    }
    anitet::Result<std::unique_ptr<anitet::SizingField>> f2 = anitet::mesh2d::read_background_field(path, background_name);
    if (!f2.ok()) return set_status(fn, f2.status());
    *out = new_field_metric(std::shared_ptr<const anitet::SizingField>(std::move(f2.value())));
    return ok();
  }
  anitet::Result<anitet::VolumeMesh> read = anitet::VolumeMesh();
  if (background == nullptr) {
    read = anitet::read_volume_mesh(background_name);
    if (!read.ok()) return set_status(fn, read.status());
    background = &read.value();
  }
  anitet::Result<anitet::metric::BackgroundMeshField> field =
      anitet::metric::BackgroundMeshField::create(*background, sol.value());
  if (!field.ok()) {
    return set_error(static_cast<int>(field.status().code()),
                     std::string(fn) + ": " + path + " on " + background_name + ": " + field.status().message());
  }
  *out = new_field_metric(
      std::make_shared<const anitet::metric::BackgroundMeshField>(std::move(field.value())));
  return ok();
}

// The grid behind a field metric, when it is one (a .vdb, or the surface's default field).
const anitet::metric::MetricField* grid_of(const anitet_metric& m) {
  if (m.kind != anitet_metric::Kind::Field) return nullptr;
  const anitet::SizingField* f = m.field.get();
  if (const auto* owner = dynamic_cast<const anitet::metric::OwningField*>(f)) f = &owner->top();
  return dynamic_cast<const anitet::metric::MetricField*>(f);
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
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (path == nullptr) return null_argument(fn, "path");
    const std::string file(path);
    const std::string ext = extension(file);
    if (ext == ".vdb") {
      if (background_mesh_path != nullptr) {
        return set_error(ANITET_ERR_INVALID_ARGUMENT,
                         std::string(fn) + ": " + file +
                             ": a .vdb needs no background mesh (background_mesh_path must be NULL)");
      }
      anitet::Result<anitet::metric::MetricField> field = anitet::metric::read_metric_vdb(file);
      if (!field.ok()) return set_status(fn, field.status());
      *out = new_field_metric(
          std::make_shared<const anitet::metric::MetricField>(std::move(field.value())));
      return ok();
    }
    if (ext == ".sol" || ext == ".solb") {
      if (background_mesh_path == nullptr) {
        return set_error(ANITET_ERR_INVALID_ARGUMENT,
                         std::string(fn) + ": " + file + ": a " + ext +
                             " needs its background mesh (background_mesh_path is NULL)");
      }
      return sol_metric_on(fn, file, nullptr, background_mesh_path, out);
    }
    return set_error(ANITET_ERR_UNSUPPORTED_FORMAT,
                     std::string(fn) + ": " + file + ": expected a .vdb, .sol or .solb file");
  });
}

int anitet_metric_create_from_points(const anitet_mesh* background, const double* values,
                                     int64_t num_values, int32_t components, anitet_metric** out) {
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
    const anitet::VolumeMesh& mesh = background->mesh;
    const uint64_t needed = uint64_t(components) * mesh.num_vertices();
    if (num_values < 0 || uint64_t(num_values) != needed) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT,
                       std::string(fn) + ": num_values is " + std::to_string(num_values) + ", not " +
                           std::to_string(components) + " per point of the background mesh (" +
                           std::to_string(needed) + ")");
    }
    anitet::metric::SolField sol;
    sol.components = components;
    sol.values.assign(values, values + needed);
    for (uint64_t i = 0; i < needed; ++i) {
      if (!std::isfinite(sol.values[i]) || (components == 1 && !(sol.values[i] > 0.0))) {
        const char* what = components == 1 ? "not a finite size > 0" : "not finite";
        return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": the value of point " +
                                                          std::to_string(i / components) +
                                                          " (0-based) is " + what);
      }
    }
    anitet::Result<anitet::metric::BackgroundMeshField> field =
        anitet::metric::BackgroundMeshField::create(mesh, sol);
    if (!field.ok()) return set_status(fn, field.status());
    *out = new_field_metric(
        std::make_shared<const anitet::metric::BackgroundMeshField>(std::move(field.value())));
    return ok();
  });
}

void anitet_metric_destroy(anitet_metric* metric) { delete metric; }

int anitet_metric_evaluate(const anitet_metric* metric, double x, double y, double z, double m[6]) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (metric == nullptr) return null_argument(fn, "metric");
    if (m == nullptr) return null_argument(fn, "m");
    if (metric->kind == anitet_metric::Kind::Field) {
      if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) {
        return set_error(ANITET_ERR_INVALID_ARGUMENT,
                         std::string(fn) + ": the point has a coordinate that is not finite");
      }
      const double p[3] = {x, y, z};
      metric->field->metric(p, m);
      return ok();
    }
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

int anitet_metric_read_on_mesh(const char* path, const anitet_mesh* background, anitet_metric** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (path == nullptr) return null_argument(fn, "path");
    if (background == nullptr) return null_argument(fn, "background");
    const std::string file(path), ext = extension(file);
    if (ext != ".sol" && ext != ".solb")
      return set_error(ANITET_ERR_UNSUPPORTED_FORMAT, std::string(fn) + ": " + file + ": expected a .sol or .solb file");
    return sol_metric_on(fn, file, &background->mesh, "the background mesh", out);
  });
}

int anitet_metric_write(const anitet_metric* metric, const anitet_surface* box_of, const char* path) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (metric == nullptr) return null_argument(fn, "metric");
    if (path == nullptr) return null_argument(fn, "path");
    const std::string file(path);
    if (extension(file) != ".vdb")
      return set_error(ANITET_ERR_UNSUPPORTED_FORMAT, std::string(fn) + ": " + file + ": expected a .vdb path");
    if (const anitet::metric::MetricField* grid = grid_of(*metric))
      return set_status(fn, anitet::metric::write_metric_vdb(*grid, file));
    if (box_of == nullptr)
      return set_error(ANITET_ERR_INVALID_ARGUMENT,
                       std::string(fn) + ": box_of is NULL: this metric is not a grid, so it is sampled over a "
                                         "surface's box");
    const CallerSizing sizing(*metric, bounding_diagonal(box_of->mesh.xyz));
    anitet::Result<anitet::metric::MetricField> sampled = anitet::metric::sample_on_surface_box(sizing, box_of->mesh);
    if (sizing.failed()) return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": " + sizing.failure());
    if (!sampled.ok()) return set_status(fn, sampled.status());
    return set_status(fn, anitet::metric::write_metric_vdb(sampled.value(), file));
  });
}

}  // extern "C"
