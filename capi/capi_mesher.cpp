// The mesher entry point: anitet_options -> anitet::MesherOptions, the C progress and log
// callbacks and the caller's metric around anitet::Mesher, the result as a new anitet_mesh.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>

#include "caller_sizing.hpp"
#include "handles.hpp"
#include "layers/layers.hpp"
#include "metric/bounded_sizing.hpp"
#include "io/file_bytes.hpp"
#include "pipeline/bl_report.hpp"
#include "pipeline/mesher.hpp"
#include "pipeline/result_json.hpp"
#include "pipeline/stage1.hpp"
#include "prism_cells.hpp"
#include "shim.hpp"

using namespace anitet::capi;

static_assert(ANITET_LAYERS_PUSH == static_cast<int>(anitet::LayerScheme::kPushOnly) &&
                  ANITET_LAYERS_FACE_PUSH == static_cast<int>(anitet::LayerScheme::kFacesThenPush),
              "ANITET_LAYERS_* differ from anitet::LayerScheme");

namespace {

int bad_option(const char* function, const std::string& what) {
  return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(function) + ": options: " + what);
}

// Checks the option values and translates them; ANITET_OK or INVALID_ARGUMENT.
int to_mesher_options(const char* function, const anitet_options& o, anitet::MesherOptions& out) {
  if (o.num_threads < 0) return bad_option(function, "num_threads is negative");
  if (o.layers < 1) return bad_option(function, "layers is " + std::to_string(o.layers) + ", at least 1 needed");
  if (o.layer_scheme != ANITET_LAYERS_PUSH && o.layer_scheme != ANITET_LAYERS_FACE_PUSH) {
    return bad_option(function, "layer_scheme is " + std::to_string(o.layer_scheme) +
                                    ", not ANITET_LAYERS_PUSH (0) or ANITET_LAYERS_FACE_PUSH (1)");
  }
  if (!std::isfinite(o.recovery_max_seconds) || o.recovery_max_seconds < 0.0) {
    return bad_option(function, "recovery_max_seconds must be finite and >= 0");
  }
  if (!(std::isfinite(o.size_scale) && o.size_scale > 0.0)) {
    return bad_option(function, "size_scale must be finite and > 0");
  }
  if (!std::isfinite(o.attempts_seconds) || o.attempts_seconds < 0.0)
    return bad_option(function, "attempts_seconds must be finite and >= 0");
  if (o.recovery != ANITET_RECOVERY_ALL && o.recovery != ANITET_RECOVERY_SPLIT && o.recovery != ANITET_RECOVERY_FUZZY)
    return bad_option(function, "recovery is " + std::to_string(o.recovery) + ", not ANITET_RECOVERY_ALL, _SPLIT or _FUZZY");
  if (anitet::Status st = anitet::metric::check_bounds({o.hmin, o.hmax, o.hgrad}); !st.ok())
    return bad_option(function, st.message());
  if (!std::isfinite(o.max_tets) || o.max_tets < 0.0) return bad_option(function, "max_tets must be finite and >= 0");
  if (o.anisotropic_cycles < 0 || o.anisotropic_cycles > 10)
    return bad_option(function, "anisotropic_cycles is " + std::to_string(o.anisotropic_cycles) + ", not in 0..10");
  if (o.bl_num_patches < 0) return bad_option(function, "bl_num_patches is negative");
  if (o.bl_num_patches > 0) {
    if (o.bl_patches == nullptr) return bad_option(function, "bl_patches is NULL with bl_num_patches > 0");
    if (!(std::isfinite(o.bl_first_height) && o.bl_first_height > 0.0))
      return bad_option(function, "bl_first_height must be finite and > 0 with boundary-layer walls");
    if (!(o.bl_growth >= 1.0 && o.bl_growth <= 10.0)) return bad_option(function, "bl_growth must be in 1..10");
    if (o.bl_layers < 1 || o.bl_layers > 1000) return bad_option(function, "bl_layers must be in 1..1000");
  }
  if (o.bl_num_slide_patches < 0) return bad_option(function, "bl_num_slide_patches is negative");
  if (o.bl_num_slide_patches > 0) {
    if (o.bl_slide_patches == nullptr)
      return bad_option(function, "bl_slide_patches is NULL with bl_num_slide_patches > 0");
    if (o.bl_num_patches == 0)
      return bad_option(function, "bl_slide_patches needs boundary-layer walls (bl_num_patches > 0)");
  }
  if (o.bl_cells != ANITET_BL_CELLS_TETS && o.bl_cells != ANITET_BL_CELLS_PRISMS)
    return bad_option(function, "bl_cells is " + std::to_string(o.bl_cells) +
                                    ", not ANITET_BL_CELLS_TETS (0) or ANITET_BL_CELLS_PRISMS (1)");
  if (o.bl_cells == ANITET_BL_CELLS_PRISMS && o.bl_num_patches == 0)
    return bad_option(function, "bl_cells ANITET_BL_CELLS_PRISMS needs boundary-layer walls (bl_num_patches > 0)");
  if (o.bl_sizing != 0 && (o.bl_num_patches == 0 || !(o.bl_growth > 1.0)))
    return bad_option(function, "bl_sizing needs boundary-layer walls (bl_num_patches > 0) and bl_growth above 1");
  // As `anitet mesh --bl-sizing-growth`: 0 is the layers' own growth, anything else a faster one.
  if (o.bl_sizing_growth != 0.0 &&
      (o.bl_sizing == 0 || !(std::isfinite(o.bl_sizing_growth) && o.bl_sizing_growth >= o.bl_growth))) {
    std::ostringstream what;
    what << "bl_sizing_growth is " << o.bl_sizing_growth << ": it needs bl_sizing 1 and a finite value "
         << "of at least bl_growth (" << o.bl_growth << "), or 0 for the layers' growth";
    return bad_option(function, what.str());
  }
  if (o.push_tasks_min_vertices < 0) return bad_option(function, "push_tasks_min_vertices is negative");
  if (o.bl_mitre != 0 && o.bl_mitre != 1) return bad_option(function, "bl_mitre is " + std::to_string(o.bl_mitre) + ", not 0 or 1");
  if (o.bl_mitre != 0 && o.bl_num_patches == 0)
    return bad_option(function, "bl_mitre needs boundary-layer walls (bl_num_patches > 0)");
  out.validation.merge_duplicate_vertices = o.merge_duplicate_vertices != 0;
  out.validation.orient_shells = o.orient_shells != 0;
  out.validation.check_self_intersections = o.check_self_intersections != 0;
  out.num_threads = o.num_threads;  // every stage in one arena of that size
  out.validation.num_threads = o.num_threads;
  out.refine.num_threads = o.num_threads;
  out.optimize.num_threads = o.num_threads;
  out.layers.layers = o.layers;
  out.layers.scheme = static_cast<anitet::LayerScheme>(o.layer_scheme);
  out.layers.push_tasks_min_vertices = size_t(o.push_tasks_min_vertices);
  if (o.recovery_max_seconds > 0.0) out.recovery.max_seconds = o.recovery_max_seconds;
  out.run_refine = o.refine != 0;
  out.run_optimize = o.optimize != 0;
  out.refine.size_scale = o.size_scale;
  out.attempts_seconds = o.attempts_seconds;
  out.retry_layer_counts = o.retry_layer_counts != 0;
  out.recovery.split_constraints = o.recovery != ANITET_RECOVERY_FUZZY;
  out.recovery.fuzzy_faces = o.recovery != ANITET_RECOVERY_SPLIT;
  out.max_tets = o.max_tets;
  out.anisotropic_cycles = o.anisotropic_cycles;
  if (o.bl_num_patches > 0) {
    anitet::BoundaryLayerOptions& bl = out.layers.boundary_layer;
    bl.wall_patches.assign(o.bl_patches, o.bl_patches + o.bl_num_patches);
    if (o.bl_num_slide_patches > 0)
      bl.slide_patches.assign(o.bl_slide_patches, o.bl_slide_patches + o.bl_num_slide_patches);
    bl.first_height = o.bl_first_height;
    bl.growth = o.bl_growth;
    bl.layers = o.bl_layers;
    bl.mitre = o.bl_mitre != 0;
  }
  out.boundary_layer_sizing = o.bl_sizing != 0;
  out.boundary_layer_sizing_growth = o.bl_sizing_growth;
  return ANITET_OK;
}

// The pipeline's messages name the CLI's options where the caller can fix the input that way;
// a caller of the ABI sets the options field instead.
anitet::Status in_abi_words(const anitet::Status& status) {
  std::string message = status.message();
  const std::string cli = "--bl-slide-patches", abi = "options->bl_slide_patches";
  for (size_t at = message.find(cli); at != std::string::npos; at = message.find(cli, at + abi.size()))
    message.replace(at, cli.size(), abi);
  return anitet::Status(status.code(), message);
}

// A run with walls keeps them and the surface it meshed for anitet_mesh_write_bl_columns (the
// surface only when run->slide has none of its own).
void keep_bl_walls(anitet_mesh& mesh, const anitet::MesherOptions& mo, anitet::SurfaceMesh&& meshed) {
  mesh.bl_walls = mo.layers.boundary_layer.wall_patches;
  if (!mesh.bl_walls.empty() && mesh.run->slide.changes.empty()) mesh.bl_surface = std::move(meshed);
}

void log_line(const anitet_options& o, int32_t level, const std::string& text) {
  if (o.log) o.log(level, text.c_str(), o.log_user_data);
}

void log_validation(const anitet_options& o, const anitet::ValidationReport& report) {
  for (const anitet::Repair& r : report.repairs) log_line(o, ANITET_LOG_INFO, "repair: " + r.message);
  for (const anitet::Problem& p : report.problems) {
    log_line(o, p.severity == anitet::Severity::Error ? ANITET_LOG_ERROR : ANITET_LOG_WARNING,
             p.kind + ": " + p.message);
  }
}

void log_stages(const anitet_options& o, const anitet::MesherResult& r) {
  for (const anitet::StageReport& stage : r.stages) {
    std::ostringstream line;
    line << "stage " << stage.name << ": " << stage.tets << " tets, " << stage.seconds << " s";
    log_line(o, ANITET_LOG_INFO, line.str());
  }
}

// A copy of the caller's surface validated with the options' repairs (the caller's is never
// changed); the report goes to the log callback.
int validated_copy(const char* fn, const anitet_surface& surface, const anitet_options& opt,
                   const anitet::MesherOptions& mo, anitet::SurfaceMesh& out) {
  out = surface.mesh;
  const anitet::ValidationReport report =
      in_arena(opt.num_threads, [&] { return anitet::validate_surface(out, mo.validation); });
  log_validation(opt, report);
  return report.ok() ? ANITET_OK : set_status(fn, report.status());
}

// What every entry point on a surface and options checks first: out given (and cleared), the
// surface given, the options read and converted.
template <class Out>
int begin_run(const char* fn, const anitet_surface* surface, const anitet_options* options, Out** out,
              anitet_options& opt, anitet::MesherOptions& mo) {
  if (out == nullptr) return null_argument(fn, "out");
  *out = nullptr;
  if (surface == nullptr) return null_argument(fn, "surface");
  if (const int code = read_options(fn, options, opt); code != ANITET_OK) return code;
  return to_mesher_options(fn, opt, mo);
}

}  // namespace

extern "C" {

int anitet_mesher_run(const anitet_surface* surface, const anitet_metric* metric,
                      const anitet_options* options, anitet_mesh** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    anitet_options opt;
    anitet::MesherOptions mo;
    if (const int code = begin_run(fn, surface, options, out, opt, mo); code != ANITET_OK) return code;
    std::unique_ptr<CallerSizing> sizing;
    if (metric != nullptr) {
      sizing = std::make_unique<CallerSizing>(*metric, bounding_diagonal(surface->mesh.xyz));
      mo.sizing = sizing.get();
      if (!mo.run_refine && !mo.run_optimize) {
        log_line(opt, ANITET_LOG_WARNING,
                 "refinement and optimization are off: the metric only goes to the mesh's vertices");
      }
    }
    // The caller's callback, and a stop at the first stage boundary after a metric failure.
    if (opt.progress || sizing) {
      mo.progress = [&opt, &sizing](const std::string& stage, double fraction) {
        if (sizing && sizing->failed()) return false;
        return !opt.progress || opt.progress(fraction, stage.c_str(), opt.progress_user_data) == 0;
      };
    }
    const auto metric_failed = [&] {
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": " + sizing->failure());
    };

    // Validation here rather than in Mesher::run: its report goes to the log callback.
    if (mo.progress && !mo.progress("validate", 0.0)) {
      return set_error(ANITET_ERR_CANCELLED,
                       std::string(fn) + ": cancelled by the progress callback before validation");
    }
    anitet::SurfaceMesh repaired;
    if (const int code = validated_copy(fn, *surface, opt, mo, repaired); code != ANITET_OK) return code;
    // hmin, hmax, hgrad: the field (the caller's, or the surface's default grid) bounded and graded.
    std::unique_ptr<anitet::SizingField> bounded;
    const anitet::metric::SizeBounds bounds{opt.hmin, opt.hmax, opt.hgrad};
    if (bounds.any() && (mo.run_refine || mo.run_optimize)) {
      anitet::Result<std::unique_ptr<anitet::SizingField>> built = in_arena(opt.num_threads, [&] {
        return anitet::metric::bounded_sizing_field(repaired, mo.sizing, bounds, mo.surface_sizing);
      });
      if (!built.ok()) return set_status(fn, built.status());
      bounded = std::move(built).value();
      mo.sizing = bounded.get();
    }

    anitet::Result<anitet::MesherResult> run = anitet::Mesher(mo).run_validated(repaired);
    if (sizing && sizing->failed()) return metric_failed();
    if (!run.ok()) {
      const int code = set_status(fn, in_abi_words(run.status()));
      log_line(opt, ANITET_LOG_ERROR, anitet_last_error_message());
      return code;
    }
    log_stages(opt, run.value());
    for (const anitet::Notice& n : run->notices) log_line(opt, ANITET_LOG_WARNING, "notice: " + n.message);
    auto mesh = std::make_unique<anitet_mesh>();
    mesh->mesh = std::move(run->mesh);
    mesh->run = std::make_unique<anitet::MesherResult>(std::move(run).value());
    keep_bl_walls(*mesh, mo, std::move(repaired));
    if (opt.bl_cells == ANITET_BL_CELLS_PRISMS)
      if (anitet::Status st = make_prism_cells(*mesh); !st.ok())
        return set_error(ANITET_ERR_INTERNAL, std::string(fn) + ": bl_cells prisms: " + st.message());
    if (sizing) {
      // The metric the mesh was made for, at its vertices (anitet_mesh_get_metric, .sol).
      anitet::VolumeMesh& v = mesh->mesh;
      v.vertex_metric.resize(6 * v.num_vertices());
      for (size_t i = 0; i < v.num_vertices(); ++i) sizing->metric(&v.xyz[3 * i], &v.vertex_metric[6 * i]);
      if (sizing->failed()) return metric_failed();
    }
    *out = mesh.release();
    return ok();
  });
}

int anitet_layers_run(const anitet_surface* surface, const anitet_options* options, anitet_mesh** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    anitet_options opt;
    anitet::MesherOptions mo;
    if (const int code = begin_run(fn, surface, options, out, opt, mo); code != ANITET_OK) return code;
    if (opt.bl_cells == ANITET_BL_CELLS_PRISMS)
      return bad_option(fn, "bl_cells ANITET_BL_CELLS_PRISMS applies to anitet_mesher_run (the whole pipeline); "
                            "stage 1's tets are in region 1");
    const auto start = std::chrono::steady_clock::now();
    if (opt.progress && opt.progress(0.0, "validate", opt.progress_user_data) != 0)
      return set_error(ANITET_ERR_CANCELLED, std::string(fn) + ": cancelled by the progress callback before validation");
    anitet::SurfaceMesh repaired;
    if (const int code = validated_copy(fn, *surface, opt, mo, repaired); code != ANITET_OK) return code;
    if (opt.progress && opt.progress(0.05, "layers", opt.progress_user_data) != 0)
      return set_error(ANITET_ERR_CANCELLED, std::string(fn) + ": cancelled at stage 'layers'");
    anitet::Result<anitet::Stage1Result> built =
        in_arena(opt.num_threads, [&] { return anitet::run_stage1(repaired, mo.layers); });
    if (!built.ok()) {
      const anitet::Status failed(built.status().code(), "stage 1 (layers): " + built.status().message());
      const int code = set_status(fn, in_abi_words(failed));
      log_line(opt, ANITET_LOG_ERROR, anitet_last_error_message());
      return code;
    }
    // The run's record: stage 1's figures and the boundary layer measured on T1.
    auto run = std::make_unique<anitet::MesherResult>();
    run->layers = built->layers.stats;
    run->layers_used = mo.layers.layers;
    run->boundary_layer = built->boundary_layer;
    run->slide = std::move(built->slide);
    run->stages.push_back({"layers", built->layers.stats.seconds, built->layers.stats.tets});
    run->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    log_stages(opt, *run);
    auto mesh = std::make_unique<anitet_mesh>();
    mesh->mesh = std::move(built->mesh);
    mesh->run = std::move(run);
    keep_bl_walls(*mesh, mo, std::move(repaired));
    if (opt.progress && opt.progress(1.0, "done", opt.progress_user_data) != 0)
      return set_error(ANITET_ERR_CANCELLED, std::string(fn) + ": cancelled at stage 'done'");
    *out = mesh.release();
    return ok();
  });
}

int anitet_bl_first_height(double yplus, double reynolds, double ref_length, double* h0) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (h0 == nullptr) return null_argument(fn, "h0");
    anitet::Result<double> h = anitet::first_height_from_yplus(yplus, reynolds, ref_length);
    if (!h.ok()) return set_status(fn, h.status());
    *h0 = h.value();
    return ok();
  });
}

int anitet_metric_create_surface_sizing(const anitet_surface* surface, const anitet_options* options,
                                        anitet_metric** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    anitet_options opt;
    anitet::MesherOptions mo;
    if (const int code = begin_run(fn, surface, options, out, opt, mo); code != ANITET_OK) return code;
    anitet::SurfaceMesh repaired;
    if (const int code = validated_copy(fn, *surface, opt, mo, repaired); code != ANITET_OK) return code;
    anitet::Result<std::unique_ptr<anitet::SizingField>> built = in_arena(opt.num_threads, [&] {
      return anitet::metric::bounded_sizing_field(repaired, nullptr, {opt.hmin, opt.hmax, opt.hgrad}, mo.surface_sizing);
    });
    if (!built.ok()) return set_status(fn, built.status());
    auto metric = std::make_unique<anitet_metric>();
    metric->kind = anitet_metric::Kind::Field;
    metric->field = std::shared_ptr<const anitet::SizingField>(std::move(built).value());
    *out = metric.release();
    return ok();
  });
}

namespace {

// Copies the fields of `version` from the full struct into the caller's.
void fill_run_stats(const anitet_mesh& mesh, anitet_run_stats& s) {
  const anitet::MesherResult& r = *mesh.run;
  const anitet::VolumeMesh& m = mesh.mesh;
  s.layers_used = r.layers_used;
  s.layers_retries = int32_t(r.layers_retries);
  // RecoveryStats::strategy numbers the variants (recovery_strategy_name): 3-5 split constraints.
  const bool recovered = std::any_of(r.stages.begin(), r.stages.end(), [](const anitet::StageReport& st) {
    return st.name == "recovery" || st.name == "recovery (retry)";
  });
  s.recovery_strategy = !recovered                 ? 0
                        : r.recovery.strategy >= 3 ? ANITET_RECOVERY_SPLIT
                                                   : ANITET_RECOVERY_FUZZY;
  s.refine_passes = r.refine.passes;
  s.refine_stopped_at_pass_cap = r.refine.stopped_at_pass_cap ? 1 : 0;
  s.anisotropic_cycles = r.anisotropic_cycles;
  s.num_notices = int32_t(r.notices.size());
  s.vertices = int64_t(m.num_vertices());
  s.tets = int64_t(m.num_tets());
  s.steiner_on_front_edges = int64_t(r.recovery.steiner_on_edges);
  s.steiner_on_front_faces = int64_t(r.recovery.steiner_on_faces);
  s.refine_splits = int64_t(r.refine.splits);
  s.refine_collapses = int64_t(r.refine.collapses);
  s.flat_tets_left = int64_t(r.optimize.flat_left);
  s.metric_not_spd = int64_t(r.refine.metric_not_spd);
  s.seconds = r.seconds;
  s.estimated_tets = r.estimated_tets;
  s.edges_in_range = r.refine.length_in_range;
  s.metric_radius_ratio_mean = r.metric_quality.tets > 0 ? r.metric_quality.mean : 0.0;
  s.metric_radius_ratio_min = r.metric_quality.tets > 0 ? r.metric_quality.min : 0.0;
  const anitet::BoundaryLayerReport& bl = r.boundary_layer;
  s.bl_layers = bl.layers;
  s.reserved0 = 0;
  s.bl_wall_vertices = int64_t(bl.wall_vertices);
  s.bl_full_columns = int64_t(bl.full_columns);
  s.bl_nominal_columns = int64_t(bl.nominal_columns);
  s.bl_reduced_vertices = int64_t(bl.reduced_vertices);
  s.bl_tets = int64_t(bl.tets);
  s.bl_first_height_min = bl.first_height_min;
  s.bl_first_height_mean = bl.first_height_mean;
  s.bl_first_height_max = bl.first_height_max;
  s.bl_growth_mean = bl.growth_mean;
  s.bl_max_height_error = bl.max_height_error;
  s.slide_junction_columns = int64_t(r.slide.junction_vertices);
  s.slide_lowered_columns = int64_t(r.slide.reduced_columns);
  for (const anitet::SlidePatchChange& c : r.slide.changes)
    s.slide_triangles_added += int64_t(c.triangles_after) - int64_t(c.triangles_before);
  s.bl_prisms = int64_t(mesh.prism_stats.prisms);
  s.bl_prism_tets_left = int64_t(mesh.prism_stats.kept_tets);
}

// Bytes of an anitet_run_stats of `version` (a valid one): each version's struct ends where the
// next version's first field starts.
size_t run_stats_size(int32_t version) {
  if (version == 1) return offsetof(anitet_run_stats, slide_junction_columns);
  if (version == 2) return offsetof(anitet_run_stats, bl_prisms);
  return sizeof(anitet_run_stats);
}

int no_run(const char* fn) {
  return set_error(ANITET_ERR_INVALID_ARGUMENT,
                   std::string(fn) + ": the mesh was not made by anitet_mesher_run (read or created from arrays)");
}

}  // namespace

int anitet_mesh_get_run_stats(const anitet_mesh* mesh, anitet_run_stats* out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (out == nullptr) return null_argument(fn, "out");
    if (out->version < 1 || out->version > ANITET_RUN_STATS_VERSION)
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": run stats version " +
                                                        std::to_string(out->version) + " is not supported (1.." +
                                                        std::to_string(ANITET_RUN_STATS_VERSION) + ")");
    if (!mesh->run) return no_run(fn);
    anitet_run_stats full = ANITET_RUN_STATS_INIT;
    fill_run_stats(*mesh, full);
    full.version = out->version;
    std::memcpy(out, &full, run_stats_size(out->version));  // never past the caller's version
    return ok();
  });
}

int anitet_mesh_run_json(const anitet_mesh* mesh, char* buf, int64_t buf_len, int64_t* needed) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (!mesh->run) return no_run(fn);
    return copy_text(fn, anitet::mesher_result_json(*mesh->run), buf, buf_len, needed);
  });
}

int anitet_mesh_write_bl_columns(const anitet_mesh* mesh, const char* path) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (path == nullptr) return null_argument(fn, "path");
    if (!mesh->run) return no_run(fn);
    if (mesh->bl_walls.empty())
      return set_error(ANITET_ERR_INVALID_ARGUMENT,
                       std::string(fn) + ": the mesh has no boundary layer (its run had no walls, options->bl_num_patches 0)");
    const anitet::MesherResult& r = *mesh->run;
    const anitet::SurfaceMesh& meshed = r.slide.changes.empty() ? mesh->bl_surface : r.slide.surface;
    return set_status(fn, anitet::write_file_bytes(path, anitet::bl_columns_csv(r.boundary_layer, meshed, mesh->bl_walls)));
  });
}

}  // extern "C"
