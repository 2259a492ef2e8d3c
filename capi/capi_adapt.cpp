// The adaptation entry points (`anitet adapt` at the C ABI): anitet_adapt_options ->
// anitet::AdaptOptions, the caller's metric (values at the points, or a handle) around
// anitet::adapt_mesh, the fields carried and the UGAWG measures, all in one task arena of
// options->num_threads.
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "adapt/adapt.hpp"
#include "caller_sizing.hpp"
#include "handles.hpp"
#include "metric/field_transfer.hpp"
#include "quality/quality_report.hpp"
#include "shim.hpp"

using namespace anitet::capi;

// No padding in either struct (the Fortran and Python mirrors assume none).
static_assert(offsetof(anitet_adapt_options, ridge_angle_deg) == 4 * sizeof(int32_t) &&
                  offsetof(anitet_adapt_options, progress) == offsetof(anitet_adapt_options, ridge_angle_deg) + 16 &&
                  sizeof(anitet_adapt_options) == offsetof(anitet_adapt_options, progress) + 4 * sizeof(void*),
              "anitet_adapt_options has padding");
static_assert(offsetof(anitet_adapt_stats, vertices_in) == 8 &&
                  offsetof(anitet_adapt_stats, edges_in_range) == offsetof(anitet_adapt_stats, edges) + 8 &&
                  sizeof(anitet_adapt_stats) == offsetof(anitet_adapt_stats, seconds_measure) + sizeof(double),
              "anitet_adapt_stats has padding");

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

int bad(const char* fn, const std::string& what) {
  return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": " + what);
}

// Options after the version and range checks (NULL: the defaults), translated.
int read_adapt_options(const char* fn, const anitet_adapt_options* given, anitet_adapt_options& o,
                       anitet::AdaptOptions& out) {
  const anitet_adapt_options defaults = ANITET_ADAPT_OPTIONS_INIT;
  o = defaults;
  if (given != nullptr) {
    if (given->version < 1 || given->version > ANITET_ADAPT_OPTIONS_VERSION)
      return bad(fn, "options version " + std::to_string(given->version) + " is not supported (1.." +
                         std::to_string(ANITET_ADAPT_OPTIONS_VERSION) +
                         "); initialise with ANITET_ADAPT_OPTIONS_INIT or anitet_adapt_options_init");
    std::memcpy(&o, given, sizeof o);  // version 1 is the whole struct
  }
  if (o.num_threads < 0) return bad(fn, "options: num_threads is negative");
  if (o.max_cycles < 0 || o.max_cycles > 1000)
    return bad(fn, "options: max_cycles is " + std::to_string(o.max_cycles) + ", not in 0..1000");
  if (o.optimize_cycles < 0 || o.optimize_cycles > 100)
    return bad(fn, "options: optimize_cycles is " + std::to_string(o.optimize_cycles) + ", not in 0..100");
  if (!(o.ridge_angle_deg >= 0.0 && o.ridge_angle_deg <= 180.0))
    return bad(fn, "options: ridge_angle_deg must be in 0..180");
  if (o.tensors < ANITET_TENSORS_AUTO || o.tensors > ANITET_TENSORS_LINEAR)
    return bad(fn, "options: tensors is " + std::to_string(o.tensors) +
                       ", not ANITET_TENSORS_AUTO, _LOG_EUCLIDEAN or _LINEAR");
  out.keep_surface = o.keep_surface != 0;
  out.ridge_angle_deg = o.ridge_angle_deg;
  out.max_cycles = o.max_cycles;
  out.optimize_cycles = o.optimize_cycles;
  return ANITET_OK;
}

// The checks every entry point makes before adapting: outputs cleared, handles given, the
// stats version known, fields with one record per point.
int begin(const char* fn, const anitet_mesh* mesh, const anitet_fields* fields, anitet_mesh** out,
          anitet_fields** out_fields, const anitet_adapt_stats* stats) {
  if (out == nullptr) return null_argument(fn, "out");
  *out = nullptr;
  if (out_fields != nullptr) *out_fields = nullptr;
  if (mesh == nullptr) return null_argument(fn, "mesh");
  if (fields != nullptr && out_fields == nullptr) return bad(fn, "fields given but out_fields is NULL");
  if (fields == nullptr && out_fields != nullptr) return bad(fn, "out_fields given but fields is NULL");
  if (stats != nullptr && (stats->version < 1 || stats->version > ANITET_ADAPT_STATS_VERSION))
    return bad(fn, "stats version " + std::to_string(stats->version) + " is not supported (1.." +
                       std::to_string(ANITET_ADAPT_STATS_VERSION) + "); initialise with ANITET_ADAPT_STATS_INIT");
  const size_t nv = mesh->mesh.num_vertices();
  if (fields != nullptr && fields->fields.num_vertices() != nv)
    return bad(fn, "fields hold " + std::to_string(fields->fields.num_vertices()) + " records for a mesh of " +
                       std::to_string(nv) + " points: a field of another mesh");
  return ANITET_OK;
}

// The caller's values at the points, checked: finite, sizes > 0, tensors positive definite.
int metric_values(const char* fn, const double* values, int64_t len, int32_t components, size_t num_points,
                  std::vector<double>& out) {
  if (values == nullptr) return null_argument(fn, "metric");
  if (components != 1 && components != 6)
    return bad(fn, "components is " + std::to_string(components) + ", not 1 or 6");
  const uint64_t needed = uint64_t(components) * num_points;
  if (len < 0 || uint64_t(len) != needed)
    return bad(fn, "metric_len is " + std::to_string(len) + ", not " + std::to_string(components) +
                       " per point of the mesh (" + std::to_string(needed) + ")");
  out.assign(values, values + needed);
  for (size_t p = 0; p < num_points; ++p) {
    const double* m = &out[size_t(components) * p];
    const bool good = components == 1 ? std::isfinite(m[0]) && m[0] > 0.0 : positive_definite(m);
    if (!good)
      return bad(fn, "the metric of point " + std::to_string(p) + " (0-based) is " +
                         (components == 1 ? "not a finite size > 0" : "not a finite positive-definite tensor"));
  }
  return ANITET_OK;
}

void fill_stats(const anitet::AdaptStats& a, const anitet::MetricQuality& q, anitet_adapt_stats& s) {
  s.cycles = a.cycles;
  s.vertices_in = int64_t(a.vertices_in);
  s.tets_in = int64_t(a.tets_in);
  s.boundary_triangles_in = int64_t(a.boundary_triangles_in);
  s.vertices = int64_t(a.vertices_out);
  s.tets = int64_t(a.tets_out);
  s.boundary_triangles = int64_t(a.boundary_triangles_out);
  s.ridge_edges = int64_t(a.ridge_edges);
  s.corners = int64_t(a.corners);
  s.splits = int64_t(a.splits);
  s.surface_splits = int64_t(a.surface_splits);
  s.collapses = int64_t(a.collapses);
  s.surface_collapses = int64_t(a.surface_collapses);
  s.swaps = int64_t(a.swaps);
  s.surface_swaps = int64_t(a.surface_swaps);
  s.moves = int64_t(a.moves);
  s.surface_moves = int64_t(a.surface_moves);
  s.splits_refused = int64_t(a.split_refused);
  s.collapses_refused = int64_t(a.collapse_refused);
  s.edges = int64_t(q.edges);
  s.edges_in_range = q.in_range;
  s.edges_shorter = q.shorter;
  s.edges_longer = q.longer;
  s.edge_length_min = q.edge_length.min;
  s.edge_length_mean = q.edge_length.mean;
  s.edge_length_max = q.edge_length.max;
  s.mean_ratio_min = q.mean_ratio.min;
  s.mean_ratio_mean = q.mean_ratio.mean;
  s.seconds_adapt = a.seconds_total;
  s.seconds_split = a.seconds_split;
  s.seconds_collapse = a.seconds_collapse;
  s.seconds_swap = a.seconds_swap;
  s.seconds_smooth = a.seconds_smooth;
}

// What the two entry points share once the metric is in hand: `adapt(options)` runs
// anitet::adapt_mesh; then the fields are carried and the output measured, all inside one task
// arena. `sizing`: the caller's metric handle, whose failures are turned into errors.
template <class Adapt>
int run(const char* fn, const anitet_mesh& in, const anitet_fields* fields, const anitet_adapt_options* options,
        const CallerSizing* sizing, Adapt&& adapt, anitet_mesh** out, anitet_fields** out_fields,
        anitet_adapt_stats* stats) {
  const auto t0 = Clock::now();
  anitet_adapt_options o;
  anitet::AdaptOptions ao;
  if (const int code = read_adapt_options(fn, options, o, ao); code != ANITET_OK) return code;
  const auto progress = [&o](const char* stage, double fraction) {
    return !o.progress || o.progress(fraction, stage, o.progress_user_data) == 0;
  };
  // The adaptation's share of the fractions is [0, 0.9); a failed metric stops it at the next sweep.
  ao.progress = [&](const std::string& stage, double fraction) {
    return !(sizing && sizing->failed()) && progress(stage.c_str(), 0.9 * fraction);
  };
  if (o.log) ao.log = [&o](const std::string& line) { o.log(ANITET_LOG_INFO, line.c_str(), o.log_user_data); };
  const auto cancelled = [&](const char* stage) {
    return set_error(ANITET_ERR_CANCELLED, std::string(fn) + ": cancelled by the progress callback at " + stage);
  };

  return in_arena(o.num_threads, [&]() -> int {
    anitet::Result<anitet::AdaptResult> r = adapt(ao);
    if (sizing && sizing->failed()) return bad(fn, sizing->failure());
    if (!r.ok()) {
      if (r.status().code() == anitet::Error::Cancelled) return cancelled("adaptation");
      return set_status(fn, r.status());
    }
    auto mesh = std::make_unique<anitet_mesh>();
    mesh->mesh = std::move(r->mesh);
    mesh->patch_names = in.patch_names;
    mesh->patch_types = in.patch_types;
    std::unique_ptr<anitet_fields> carried;
    double seconds_transfer = 0.0;
    if (fields != nullptr) {
      if (!progress("transfer", 0.9)) return cancelled("transfer");
      const auto t1 = Clock::now();
      anitet::metric::TransferReport report;
      anitet::Result<anitet::VertexFields> moved = anitet::metric::transfer_fields(
          in.mesh, fields->fields, mesh->mesh.xyz, static_cast<anitet::metric::TensorInterpolation>(o.tensors),
          &report);
      if (!moved.ok()) return set_status(fn, moved.status());
      carried = std::make_unique<anitet_fields>();
      carried->fields = std::move(moved).value();
      carried->transfer = std::make_unique<anitet::metric::TransferReport>(std::move(report));
      seconds_transfer = since(t1);
    }
    if (stats != nullptr) {
      if (!progress("measure", 0.95)) return cancelled("measure");
      const auto t2 = Clock::now();
      anitet::Result<anitet::QualityReport> q = anitet::compute_quality_report(mesh->mesh, nullptr);
      if (!q.ok()) return set_status(fn, q.status());
      anitet_adapt_stats full = ANITET_ADAPT_STATS_INIT;
      fill_stats(r->stats, q->metric, full);
      full.seconds_transfer = seconds_transfer;
      full.seconds_measure = since(t2);
      full.seconds = since(t0);
      full.version = stats->version;
      std::memcpy(stats, &full, sizeof full);  // version 1 is the whole struct
    }
    if (!progress("done", 1.0)) return cancelled("done");
    *out = mesh.release();
    if (out_fields != nullptr) *out_fields = carried.release();
    return ok();
  });
}

}  // namespace

extern "C" {

int anitet_adapt_options_init(anitet_adapt_options* options, int32_t version) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (options == nullptr) return null_argument(fn, "options");
    if (version < 1 || version > ANITET_ADAPT_OPTIONS_VERSION)
      return bad(fn, "version " + std::to_string(version) + " is not supported (1.." +
                         std::to_string(ANITET_ADAPT_OPTIONS_VERSION) + ")");
    const anitet_adapt_options defaults = ANITET_ADAPT_OPTIONS_INIT;
    *options = defaults;  // version 1 is the whole struct
    options->version = version;
    return ok();
  });
}

int anitet_adapt(const anitet_mesh* mesh, const double* metric, int64_t metric_len, int32_t components,
                 const anitet_fields* fields, const anitet_adapt_options* options, anitet_mesh** out,
                 anitet_fields** out_fields, anitet_adapt_stats* stats) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (const int code = begin(fn, mesh, fields, out, out_fields, stats); code != ANITET_OK) return code;
    std::vector<double> values;
    if (const int code = metric_values(fn, metric, metric_len, components, mesh->mesh.num_vertices(), values);
        code != ANITET_OK)
      return code;
    return run(
        fn, *mesh, fields, options, nullptr,
        [&](const anitet::AdaptOptions& ao) { return anitet::adapt_mesh(mesh->mesh, values, ao); }, out, out_fields,
        stats);
  });
}

int anitet_adapt_to_metric(const anitet_mesh* mesh, const anitet_metric* metric, const anitet_fields* fields,
                           const anitet_adapt_options* options, anitet_mesh** out, anitet_fields** out_fields,
                           anitet_adapt_stats* stats) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (const int code = begin(fn, mesh, fields, out, out_fields, stats); code != ANITET_OK) return code;
    if (metric == nullptr) return null_argument(fn, "metric");
    const CallerSizing sizing(*metric, bounding_diagonal(mesh->mesh.xyz));
    return run(
        fn, *mesh, fields, options, &sizing,
        [&](const anitet::AdaptOptions& ao) { return anitet::adapt_mesh(mesh->mesh, sizing, ao); }, out, out_fields,
        stats);
  });
}

}  // extern "C"
