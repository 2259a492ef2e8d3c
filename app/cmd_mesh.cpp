// `anitet mesh IN -o OUT`: its options, and the whole pipeline (validate, layers with an optional boundary layer,
// recovery, coupling, refinement, optimization) with the sizing field of the metric options
// (metric_options.hpp), then the mesh written and its quality report printed (the same as
// `anitet quality OUT --surface IN`, measured in the local frame with --geodetic).

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include <nlohmann/json.hpp>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "commands.hpp"
#include "cli_util.hpp"
#include "exit_codes.hpp"
#include "core/bl_prisms.hpp"
#include "io/file_bytes.hpp"
#include "io/volume_io.hpp"
#include "metric/metric_field.hpp"
#include "metric_options.hpp"
#include "pipeline/bl_report.hpp"
#include "pipeline/mesher.hpp"
#include "pipeline/result_json.hpp"
#include "quality/html_report.hpp"
#include "quality/quality_report.hpp"
#include "surface_check.hpp"

namespace anitet::cli {

namespace {

// The optimizer's counts, as both the text summary and the HTML report give them.
std::string optimization_counts(const OptimizeStats& o) {
  return std::to_string(o.moves) + " CVT moves, " + std::to_string(o.flips23) + " 2-3 flips, " +
         std::to_string(o.edge_removals) + " edge removals, " + std::to_string(o.perturbations) +
         " sliver perturbations, " + std::to_string(o.collapses) + " sliver collapses, " +
         std::to_string(o.flat_found - o.flat_left) + " of " + std::to_string(o.flat_found) +
         " tets flat to rounding opened";
}

// "slide patches: 2 'inlet' 384 -> 2112 triangles (+1728), ...; N junction columns, M reduced".
std::string slide_text(const SlideReport& slide, const PatchNames& names) {
  std::string text = "slide patches (re-triangulated where the layers slide):";
  for (const SlidePatchChange& c : slide.changes) {
    text += (&c == &slide.changes.front() ? " " : ", ") + std::to_string(c.label) + " '" + patch_name(names, c.label) +
            "' " + std::to_string(c.triangles_before) + " -> " + std::to_string(c.triangles_after) + " triangles (+" +
            std::to_string(int64_t(c.triangles_after) - int64_t(c.triangles_before)) + ")";
  }
  return text + "; " + std::to_string(slide.junction_vertices) + " junction columns, " +
         std::to_string(slide.reduced_columns) + " lowered";
}

// The run's figures for the HTML report's "Meshing run" table.
std::vector<std::pair<std::string, std::string>> run_rows(const MesherResult& r, const PatchNames& names) {
  auto fixed = [](double x, const char* format) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, x);
    return std::string(buf);
  };
  std::vector<std::pair<std::string, std::string>> rows;
  rows.emplace_back("total time", fixed(r.seconds, "%.3f s") + " (" +
                                      fixed(r.seconds > 0 ? double(r.mesh.num_tets()) / r.seconds : 0.0, "%.0f") +
                                      " tets/s)");
  for (const StageReport& st : r.stages)
    rows.emplace_back("stage " + st.name, fixed(st.seconds, "%.3f s") + ", " + std::to_string(st.tets) + " tets");
  rows.emplace_back("advancing-front layers", std::to_string(r.layers_used) +
                                          (r.layers_retries ? " (after " + std::to_string(r.layers_retries) + " retries)" : ""));
  rows.emplace_back("stage 2 Steiner points on S1", std::to_string(r.recovery.steiner_on_edges) + " on edges, " +
                                                        std::to_string(r.recovery.steiner_on_faces) + " in faces (" +
                                                        recovery_strategy_name(r.recovery.strategy) + ")");
  rows.emplace_back("stage 2 time", "Delaunay " + fixed(r.recovery.seconds_delaunay, "%.3f s") + ", recovery " +
                                        fixed(r.recovery.seconds_recovery, "%.3f s") + ", carving " +
                                        fixed(r.recovery.seconds_carve, "%.3f s"));
  if (r.boundary_layer.layers > 0)
    rows.emplace_back("boundary layer", std::to_string(r.boundary_layer.layers) + " layers on " +
                                            std::to_string(r.boundary_layer.wall_vertices) + " wall vertices, " +
                                            std::to_string(r.boundary_layer.tets) + " tets; first height " +
                                            fixed(r.boundary_layer.first_height_min, "%.4g") + " .. " +
                                            fixed(r.boundary_layer.first_height_max, "%.4g"));
  if (r.boundary_layer.layers > 0)
    rows.emplace_back("boundary layer cells",
                      std::to_string(r.boundary_layer.full_columns) + " full columns, " +
                          std::to_string(r.boundary_layer.nominal_columns) + " within 10% of h0 r^i; max growth " +
                          fixed(r.boundary_layer.max_neighbour_growth, "%.3f") + "; non-orthogonality max " +
                          fixed(r.boundary_layer.non_orthogonality_max, "%.1f deg") + ", skewness max " +
                          fixed(r.boundary_layer.skewness_max, "%.2f") + "; reduced columns " +
                          std::to_string(r.boundary_layer.reduced_vertices));
  if (!r.slide.changes.empty()) rows.emplace_back("slide patches", slide_text(r.slide, names));
  rows.emplace_back("refinement", std::to_string(r.refine.splits) + " splits, " + std::to_string(r.refine.collapses) +
                                      " collapses; " + fixed(100.0 * r.refine.length_in_range, "%.1f") +
                                      "% of edges in [1/sqrt2, sqrt2]");
  rows.emplace_back("optimization", optimization_counts(r.optimize));
  for (const Notice& n : r.notices) rows.emplace_back("notice", n.message);
  return rows;
}

// The exit code of a library error: bad options (InvalidArgument) are usage errors, files that
// cannot be opened read errors, malformed ones invalid input (exit_code_of_read).
int exit_code_of(Error e) {
  switch (e) {
    case Error::InvalidArgument: return kExitUsage;
    case Error::NotImplemented: return kExitNotImplemented;
    case Error::FileNotFound:
    case Error::Parse:
    case Error::BadIndex:
    case Error::EmptyInput:
    case Error::UnsupportedFormat: return exit_code_of_read(e);
    default: return kExitInternal;
  }
}

}  // namespace

namespace {

// The memory a run takes per tet at its peak (bench/results/scale: 127 bytes at 10^7 tets and 187
// at 10^6 since issue 49's mem6 branch, 174-194 at 10^7 before), with room to spare.
constexpr double kBytesPerTet = 200;

// MemAvailable of /proc/meminfo, in bytes; 0 when it cannot be read.
double available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0;
  while (in >> key) {
    if (key == "MemAvailable:" && in >> kb) return kb * 1024.0;
    in.ignore(256, '\n');
  }
  return 0;
}

// --verbose: every stage's figures, then the full quality report.
void print_details(const MesherResult& r, const QualityReport& quality) {
  const BoundaryLayerReport& bl = r.boundary_layer;
  std::cout << "details:\n";
  if (r.estimated_tets > 0)
  std::cout << "  tets estimated before refinement: " << std::llround(r.estimated_tets) << " (made: " << r.mesh.num_tets()
            << ")\n";
  for (const StageReport& s : r.stages)
    std::cout << "  stage " << s.name << ": " << format_seconds(s.seconds) << ", " << s.tets << " tets"
              << (s.peak_bytes > 0 ? ", peak memory so far " + std::to_string(std::llround(s.peak_bytes / 1048576.0)) + " MB"
                                   : std::string())
              << "\n";
  if (bl.layers > 0) {
    std::cout << "  boundary layer: " << bl.layers << " layers on " << bl.wall_vertices << " wall vertices, "
              << bl.tets << " tets, " << bl.vertices << " vertices kept fixed; " << bl.full_columns
              << " full columns, " << bl.nominal_columns << " within 10% of h0 r^i (max error "
              << bl.max_height_error << "); reduced vertices " << bl.reduced_vertices << " ("
              << 100.0 * r.layers.bl_reduced_share << "%); first height min " << bl.first_height_min
              << " mean " << bl.first_height_mean << " max " << bl.first_height_max << "; growth "
              << bl.growth_mean << "; BL vertices moved after stage 1 by at most " << bl.max_displacement
              << "; " << format_seconds(r.layers.bl_seconds) << "\n";
    std::cout << "  boundary layer: wall vertices by layers reached:";
    for (size_t i = 0; i < bl.columns_reaching.size(); ++i)
      if (bl.columns_reaching[i] > 0) std::cout << " " << i << ": " << bl.columns_reaching[i];
    std::cout << "\n  boundary layer: heights per layer (min / mean / max):";
    for (size_t i = 0; i < bl.layer_height_mean.size(); ++i)
      std::cout << (i % 4 == 0 ? "\n   " : ";") << " " << i << ": " << bl.layer_height_min[i] << " / "
                << bl.layer_height_mean[i] << " / " << bl.layer_height_max[i];
    std::cout << "\n  boundary layer: max growth between neighbouring layers " << bl.max_neighbour_growth
              << "; dual faces " << bl.dual_faces << ": non-orthogonality max " << bl.non_orthogonality_max
              << " deg, mean " << bl.non_orthogonality_mean << ", " << bl.non_orthogonal_faces
              << " above 70; skewness max " << bl.skewness_max << ", " << bl.skew_faces << " above 4\n";
  }
  std::cout << "  stage 2 Steiner points on S1: " << r.recovery.steiner_on_edges << " on edges, "
            << r.recovery.steiner_on_faces << " in faces (" << recovery_strategy_name(r.recovery.strategy)
            << "); coupling split " << r.couple.edge_split_tets
            << " T1 tets and re-coned " << r.couple.faces_reconed << " S1 faces\n"
            << "  stage 2 time: Delaunay " << format_seconds(r.recovery.seconds_delaunay) << ", recovery "
            << format_seconds(r.recovery.seconds_recovery) << ", carving " << format_seconds(r.recovery.seconds_carve) << "\n"
            << "  refinement: " << r.refine.passes << " passes, " << r.refine.splits << " splits (" << r.refine.parallel_splits << " by the slab tasks), "
            << r.refine.collapses << " collapses (" << r.refine.split_rejected << " splits put off, "
            << r.refine.collapse_rejected << " collapses refused); normalized edge length mean " << r.refine.length_mean
            << ", " << 100.0 * r.refine.length_in_range << "% in [1/sqrt2, sqrt2]"
            << (r.anisotropic_cycles > 0 ? " (anisotropic metric: refinement and optimization ran " +
                                                std::to_string(1 + r.anisotropic_cycles) + " times)"
                                          : std::string())
            << "\n"
            << "  refinement time: edge lists " << format_seconds(r.refine.seconds_edges) << ", split choice "
            << format_seconds(r.refine.seconds_choice) << ", insertion " << format_seconds(r.refine.seconds_insertion) << ", collapses "
            << format_seconds(r.refine.seconds_collapses) << ""
            << (r.refine.seconds_flips > 0.0 ? ", metric flips " + format_seconds(r.refine.seconds_flips)
                                             : std::string())
            << "\n"
            << "  optimization: " << optimization_counts(r.optimize) << "; radius ratio min " << r.optimize.before.min << " -> "
            << r.optimize.after.min << ", mean " << r.optimize.before.mean << " -> " << r.optimize.after.mean
            << "\n"
            << "  optimization time: summaries and metrics " << format_seconds(r.optimize.seconds_setup) << ", CVT "
            << format_seconds(r.optimize.seconds_cvt) << ", flips " << format_seconds(r.optimize.seconds_flips) << ", slivers "
            << format_seconds(r.optimize.seconds_slivers) << ", certification " << format_seconds(r.optimize.seconds_certify) << "\n";
  if (r.metric_quality.tets > 0) {
    const QualitySummary& mq = r.metric_quality;
    std::cout << "  in the metric (anisotropic field; the report below is Euclidean): radius ratio mean "
              << mq.mean << " min " << mq.min << ", below 0.1: " << mq.below_01 << " ("
              << 100.0 * double(mq.below_01) / double(mq.tets) << "%), below 0.4: " << mq.below_04 << " ("
              << 100.0 * double(mq.below_04) / double(mq.tets) << "%)\n";
  }
  std::cout << quality_report_text(quality);
}

// The default report: about a dozen lines, what most runs need to know.
void print_summary(const MeshArgs& args, const MesherResult& r, const QualityReport& q, bool report_written) {
  const double rate = r.seconds > 0 ? double(r.mesh.num_tets()) / r.seconds : 0.0;
  std::cout << "anitet mesh: " << args.input << " -> " << args.output << ": " << r.mesh.num_vertices()
            << " vertices, " << r.mesh.num_tets() << " tets in " << format_seconds(r.seconds) << " ("
            << std::llround(rate) << " tets/s)\n";
  std::cout << "  stages:";
  for (const StageReport& st : r.stages)
    if (st.name != "output" && st.seconds >= 0.0005) std::cout << " " << st.name << " " << format_seconds(st.seconds) << ",";
  std::cout << " report " << format_seconds(q.seconds) << "\n";
  const SurfaceMatchReport& sm = q.surface;
  std::cout << "  surface kept exactly: " << (sm.boundary_constrained ? "YES" : "NO") << " ("
            << sm.input_triangles - sm.input_triangles_missing << " of " << sm.input_triangles
            << " input triangles are faces of the mesh, " << sm.steiner_points_on_boundary
            << " points added on the surface)\n";
  std::cout << "  valid: " << (q.valid ? "YES" : "NO") << " (" << q.nonpositive_tets << " inverted or flat tets, "
            << q.faces_shared_by_more_than_two << " faces of three tets)\n";
  char line[400];
  std::snprintf(line, sizeof line,
                "  radius ratio: mean %.3f, min %.3f (touching the surface: mean %.3f, min %.3f; interior: "
                "mean %.3f, min %.3f)\n",
                q.radius_ratio.mean, q.radius_ratio.min, sm.touching_surface.radius_ratio.mean,
                sm.touching_surface.radius_ratio.min, sm.interior.radius_ratio.mean, sm.interior.radius_ratio.min);
  std::cout << line;
  std::snprintf(line, sizeof line,
                "  dihedral angles %.1f to %.1f deg; %.2f%% of tets above radius ratio 0.4, %.2f%% below 0.1\n",
                q.min_dihedral_deg, q.max_dihedral_deg, 100.0 * q.good_fraction, 100.0 * q.bad_fraction);
  std::cout << line;
  const BoundaryLayerReport& bl = r.boundary_layer;
  if (bl.layers > 0) {
    // The BL's tets are thin by design (their own regions, from couple.bodies on): the rest alone.
    size_t tets = 0;
    double sum = 0.0, low = 1.0;
    for (const RegionQuality& rq : q.by_region)
      if (rq.region < int32_t(r.couple.bodies) && rq.quality.tets > 0) {
        tets += rq.quality.tets;
        sum += rq.quality.radius_ratio.mean * double(rq.quality.tets);
        low = std::min(low, rq.quality.radius_ratio.min);
      }
    if (tets > 0) {
      std::snprintf(line, sizeof line, "  outside the boundary layer: %zu tets, radius ratio mean %.3f, min %.3f\n", tets,
                    sum / double(tets), low);
      std::cout << line;
    }
  }
  if (bl.layers > 0) {
    std::cout << "  boundary layer: " << bl.layers << " layers on " << bl.wall_vertices << " wall vertices, "
              << bl.full_columns << " full columns (" << std::llround(bl.wall_vertices ? 100.0 * double(bl.full_columns) / double(bl.wall_vertices) : 0.0)
              << "%), first height " << bl.first_height_min << " .. " << bl.first_height_max << "\n";
    std::snprintf(line, sizeof line,
                  "  boundary layer cells: heights within 10%% of h0 r^i in %zu full columns, max growth between "
                  "layers %.3f; non-orthogonality max %.1f deg (mean %.1f), skewness max %.2f\n",
                  bl.nominal_columns, bl.max_neighbour_growth, bl.non_orthogonality_max, bl.non_orthogonality_mean,
                  bl.skewness_max);
    std::cout << line;
    std::snprintf(line, sizeof line,
                  "  boundary layer top: first interior tets' height over the BL tets' on %zu faces: median %.2f, "
                  "90%% below %.2f, %.0f%% within 1.5 (their mean edge / BL height: %.1f)\n",
                  bl.transition_faces, bl.transition_ratio_median, bl.transition_ratio_p90,
                  bl.transition_faces ? 100.0 * double(bl.transition_within_1_5) / double(bl.transition_faces) : 0.0,
                  bl.transition_edge_ratio_mean);
    std::cout << line;
  }
  if (!r.slide.changes.empty()) std::cout << "  " << slide_text(r.slide, args.patch_names) << "\n";
  if (r.metric_quality.tets > 0) {
    // The output's share (after optimization) when the optimizer measured it, else refinement's.
    const double in_range = r.optimize.anisotropic ? r.optimize.length_in_range_after : r.refine.length_in_range;
    std::snprintf(line, sizeof line,
                  "  in the metric: %.1f%% of edges in [1/sqrt2, sqrt2]; radius ratio mean %.3f, min %.3f\n",
                  100.0 * in_range, r.metric_quality.mean, r.metric_quality.min);
    std::cout << line;
  }
  for (const Notice& n : r.notices) std::cout << "  notice: " << n.message << "\n";
  if (!args.report_html.empty() && report_written) std::cout << "  html report: " << args.report_html << "\n";
}

}  // namespace

namespace {

// `anitet mesh`'s steps, in the order run() takes them.
class MeshCommand {
 public:
  explicit MeshCommand(MeshArgs& args) : args_(args) {}

  int run() {
    if (const int code = read_input(); code != kExitOk) return code;
    if (const int code = mesher_options(); code != kExitOk) return code;
    if (const int code = user_field(); code != kExitOk) return code;
    if (const int code = distributed_options(); code != kExitOk) return code;
    ProgressLine bar(!args_.quiet && !args_.json && (!distributed_ || distributed_->rank == 0));
    options_.progress = [&bar](const std::string& stage, double fraction) { return bar.update(stage, fraction); };
    Result<MesherResult> run = Mesher(options_).run_validated(checked_.surface);
    if (!run.ok()) return mesher_failed(run.status());
    if (distributed_ && distributed_->rank != 0) return kExitOk;  // rank 0 writes and reports
    MesherResult& r = run.value();
    if (distributed_) r.anisotropic_cycles = cycles_run_;
    if (in_pieces_) return report_pieces(r);
    // A field built here, before the pipeline, is its sizing stage given to it ready: its time counts.
    if (field_seconds_ > 0.0) {
      for (StageReport& st : r.stages)
        if (st.name == "sizing") st.seconds += field_seconds_;
      r.seconds += field_seconds_;
    }
    return write_and_report(r);
  }

 private:
  // Read and validate the surface, the patch names; with --geodetic, the surface to a local frame
  // in metres (validated again there: the checks are geometric).
  int read_input() {
    if (const int code = check_output_paths(args_); code != kExitOk) return code;
    if (const int code = load_and_validate("mesh", args_.input, checked_); code != kExitOk) return code;
    // The OpenVDB module (the sizing field's) opens on another core from here (60-90 ms of
    // relocations). Not before the checks: their first TBB calls initialize TBB, which opens
    // libraries too and would wait for the loader's lock.
    if ((!(args_.no_refine && args_.no_optimize) || wants_sizing_field(args_.metric)) &&
        tbb::this_task_arena::max_concurrency() > 1)
      preload_.emplace();
    if (const int code = check_patch_names(args_, checked_); code != kExitOk) return code;
    if (args_.metric.geodetic_output) input_xyz_ = checked_.surface.xyz;
    Result<std::optional<geo::GeoFrame>> frame = prepare_geodetic(args_.metric, checked_.surface);
    if (!frame.ok()) {
      std::cerr << kCmd << ": --geodetic: '" << args_.input << "': " << frame.status().message() << "\n";
      return exit_code_of(frame.status().code());
    }
    frame_ = frame.value();
    if (frame_) {
      checked_.report = validate_surface(checked_.surface);
      if (!checked_.report.ok()) {
        print_invalid_surface("mesh", args_.input + " (in the local frame)", checked_);
        return kExitInvalidInput;
      }
    }
    return kExitOk;
  }

  int mesher_options() {
    MesherOptions& o = options_;
    o.num_threads = args_.threads;
    free_bytes_ = available_memory_bytes();
    o.max_tets = args_.max_tets >= 0 ? args_.max_tets : free_bytes_ > 0 ? free_bytes_ / kBytesPerTet : 0.0;
    o.layers.layers = args_.layers;
    o.attempts_seconds = args_.attempts_seconds;
    o.retry_layer_counts = !args_.no_layer_retries;
    o.recovery = recovery_options(args_);
    o.layers.scheme = args_.layer_scheme == "faces" ? LayerScheme::kFacesThenPush : LayerScheme::kPushOnly;
    o.layers.push_tasks_min_vertices = args_.push_tasks_min_vertices;
    if (!args_.bl_patches.empty()) {
      if (!(args_.bl_first_height > 0.0)) {
        std::cerr << kCmd << ": --bl-patches needs --bl-first-height (or --bl-yplus)\n";
        return kExitUsage;
      }
      BoundaryLayerOptions& bl = o.layers.boundary_layer;
      bl.wall_patches.assign(args_.bl_patches.begin(), args_.bl_patches.end());
      bl.slide_patches.assign(args_.bl_slide_patches.begin(), args_.bl_slide_patches.end());
      bl.first_height = args_.bl_first_height;
      bl.growth = args_.bl_growth;
      bl.layers = args_.bl_layers;
      bl.mitre = args_.bl_mitre;
    }
    if (args_.bl_sizing && (args_.bl_patches.empty() || !(args_.bl_growth > 1.0))) {
      std::cerr << kCmd << ": --bl-sizing needs --bl-patches and --bl-growth above 1\n";
      return kExitUsage;
    }
    if (args_.bl_sizing_growth != 0.0 && (!args_.bl_sizing || !(args_.bl_sizing_growth >= args_.bl_growth))) {
      std::cerr << kCmd << ": --bl-sizing-growth needs --bl-sizing and a value of at least --bl-growth ("
                << args_.bl_growth << ")\n";
      return kExitUsage;
    }
    o.boundary_layer_sizing = args_.bl_sizing;
    o.boundary_layer_sizing_growth = args_.bl_sizing_growth;
    o.refine.size_scale = args_.size;
    o.run_refine = !args_.no_refine;
    o.run_optimize = !args_.no_optimize;
    o.anisotropic_cycles = args_.anisotropic_cycles;
    return kExitOk;
  }

  // The sizing field: the user's (--metric, bounds, gradation) or, when only its output is asked
  // for, the default grid built here; else the Mesher builds the default grid itself.
  int user_field() {
    if (!wants_sizing_field(args_.metric)) return kExitOk;
    const auto t0 = std::chrono::steady_clock::now();
    Result<std::unique_ptr<SizingField>> built = build_sizing_field(
        args_.metric, checked_.surface, frame_ ? &*frame_ : nullptr, options_.surface_sizing);
    if (!built.ok()) {
      std::cerr << kCmd << ": sizing field: " << built.status().message() << " [" << error_name(built.status().code())
                << "]\n";
      return exit_code_of(built.status().code());
    }
    field_ = std::move(built).value();
    options_.sizing = field_.get();
    field_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return kExitOk;
  }

  // anitet-mpi: stages 3b and 3c in parts, one per rank.
  int distributed_options() {
    distributed_ = distributed_run();
    if (!distributed_) return kExitOk;
    if (args_.no_refine || args_.no_optimize) {
      std::cerr << kCmd << ": with MPI, refinement and optimization both run (they are what the ranks share)\n";
      return kExitUsage;
    }
    in_pieces_ = is_pvtu_path(args_.output) && distributed_->stage3_parts;
    if (in_pieces_) {
      // A prism is three BL tets merged with the columns' vertex origins, on the whole mesh; the
      // ranks write their own tets only.
      if (args_.bl_cells == "prisms") {
        if (distributed_->rank == 0)
          std::cerr << kCmd << ": --bl-cells prisms is not possible with a .pvtu output (each rank writes its own "
                       "tets, no rank holds the whole mesh): write a .vtu or an OpenFOAM polyMesh (rank 0 gathers "
                       "the mesh) or leave the layers as tets\n";
        return kExitNotImplemented;
      }
      options_.stage3_leaves_no_mesh = true;
      options_.stage3 = [this](TetMesh& mesh, const SizingField& f, RefineStats& refine, OptimizeStats& optimize) {
        return distributed_->stage3_parts(mesh, f, options_.refine, options_.optimize, cycles(), checked_.surface,
                                          args_.output, refine, optimize);
      };
      return kExitOk;
    }
    if (distributed_->rank == 0 && !args_.output.empty())
      std::cerr << kCmd << ": note: with an output other than .pvtu, rank 0 gathers the whole mesh after every round "
                   "(-o NAME.pvtu writes one piece per rank without a gather)\n";
    options_.stage3 = [this](TetMesh& mesh, const SizingField& f, RefineStats& refine, OptimizeStats& optimize) {
      return distributed_->stage3(mesh, f, options_.refine, options_.optimize, cycles(), refine, optimize);
    };
    return kExitOk;
  }

  // The pipeline's anisotropic cycles, for the rounds in parts (they count those run in cycles_run_).
  CycleOptions cycles() {
    return {options_.anisotropic_cycles, options_.anisotropic_cycle_gain, options_.anisotropic_cycle_optimizer_gain,
            &cycles_run_};
  }

  // anitet-mpi with a .pvtu output: the ranks wrote their pieces; rank 0 reports the whole.
  int report_pieces(const MesherResult& r) const {
    const QualitySummary& q = r.optimize.after;
    if (args_.json) {
      nlohmann::json out;
      out["output"] = args_.output;
      out["tets"] = q.tets;
      out["radius_ratio"] = {{"mean", q.mean}, {"min", q.min}, {"below_0.1", q.below_01}};
      out["seconds"] = r.seconds;
      if (const BoundaryLayerReport& bl = r.boundary_layer; bl.layers > 0)
        out["boundary_layer"] = {{"layers", bl.layers},
                                 {"wall_vertices", bl.wall_vertices},
                                 {"tets", bl.tets},
                                 {"full_columns", bl.full_columns},
                                 {"nominal_columns", bl.nominal_columns},
                                 {"first_height_min", bl.first_height_min},
                                 {"first_height_max", bl.first_height_max},
                                 {"measured", "before the rounds (the layers stay frozen through them)"}};
      std::cout << out.dump(2) << "\n";
    } else if (!args_.quiet) {
      std::printf("%s: %zu tets in %d pieces; radius ratio mean %.4f, min %.4f; %.1f s\n", args_.output.c_str(), q.tets,
                  distributed_->ranks, q.mean, q.min, r.seconds);
      const BoundaryLayerReport& bl = r.boundary_layer;
      if (bl.layers > 0)
        std::printf("  boundary layer: %d layers on %zu wall vertices, %zu tets, %zu full columns, %zu within 10%% of "
                    "h0 r^i, first height %.4g .. %.4g (measured before the rounds, which keep the layers frozen; "
                    "the cell and transition figures need the whole mesh: not measured with .pvtu)\n",
                    bl.layers, bl.wall_vertices, bl.tets, bl.full_columns, bl.nominal_columns, bl.first_height_min,
                    bl.first_height_max);
    }
    if (!args_.bl_columns.empty())
      if (Status st = write_bl_columns(r); !st.ok()) {
        std::cerr << kCmd << ": cannot write '" << args_.bl_columns << "': " << st.message() << "\n";
        return kExitReadError;
      }
    return kExitOk;
  }

  int mesher_failed(const Status& st) const {
    std::cerr << kCmd << ": meshing '" << args_.input << "' failed: " << st.message() << " [" << error_name(st.code())
              << "]\n";
    if (st.message().find("the sizing field asks for about") != std::string::npos) {
      char hint[200];
      if (args_.max_tets >= 0)
        std::snprintf(hint, sizeof hint, "--max-tets %.3g", args_.max_tets);
      else
        std::snprintf(hint, sizeof hint, "the %.1f GB of free memory at about %.0f bytes a tet", free_bytes_ / 1e9,
                      kBytesPerTet);
      std::cerr << kCmd << ": the limit is " << hint << ": a larger --size or --hmin makes fewer tets; "
                << "--max-tets 0 removes the limit\n";
    }
    const Error e = st.code();  // bad options (e.g. a wall patch no triangle has): usage
    return e == Error::NotImplemented ? kExitNotImplemented : e == Error::InvalidArgument ? kExitUsage : kExitInternal;
  }

  // The surface the mesh must keep: the input, its slide patches re-triangulated when walls meet
  // them (the run's; the rest of it is the input's, exactly).
  const SurfaceMesh& meshed_surface(const MesherResult& r) const {
    return r.slide.changes.empty() ? checked_.surface : r.slide.surface;
  }

  // The quality report, measured in the local frame against the surface that was meshed (with
  // --report, by the HTML report, which gives the same report); a report file that cannot be
  // written goes to not_written_.
  Result<QualityReport> measure(const MesherResult& r) {
    if (args_.report_html.empty())
      return tbb::this_task_arena::isolate([&] { return compute_quality_report(r.mesh, &meshed_surface(r)); });
    HtmlReportOptions html_options;
    html_options.title = "anitet mesh: " + std::filesystem::path(args_.input).filename().string();
    html_options.mesh_name = args_.output;
    html_options.surface_name = args_.input;
    for (size_t k = 0; k < 3 && k < args_.report_cut.size(); ++k) html_options.cut[k] = args_.report_cut[k];
    html_options.run_rows = run_rows(r, args_.patch_names);
    Result<HtmlReport> html = tbb::this_task_arena::isolate(
        [&] { return quality_report_html(r.mesh, &meshed_surface(r), QualityOptions(), html_options); });
    if (!html.ok()) return html.status();
    if (Status st = write_file_bytes(args_.report_html, html.value().html); !st.ok()) {
      std::cerr << kCmd << ": cannot write report '" << args_.report_html << "': " << st.message() << "\n";
      not_written_.push_back(args_.report_html);
    }
    return std::move(html).value().report;
  }

  // The mesh files, written beside the report's measures unless --geodetic-output converts the mesh
  // after them (both only read the mesh, and their times are of the same order: run together, one
  // hides most of the other). The writer is a task of the run's arena (--threads bounds it; on one
  // thread it runs at the wait, after the report); the report is measured isolated, so that its
  // parallel loops' waits do not take the writer up and run it nested.
  int write_and_report(MesherResult& r) {
    const bool write_now = !args_.metric.geodetic_output;
    int write_code = kExitOk;
    tbb::task_group writer;
    std::optional<VolumeMesh> with_prisms;
    if (write_now) {
      if (Status st = merge_prisms(r, with_prisms); !st.ok()) return internal_error(st);
      writer.run([&] { write_code = write_outputs(args_, with_prisms ? *with_prisms : r.mesh); });
    }
    struct WaitWriter {
      tbb::task_group& group;
      ~WaitWriter() { group.wait(); }
    } wait_writer{writer};
    Result<QualityReport> quality = measure(r);
    if (!quality.ok()) {
      std::cerr << kCmd << ": cannot measure the mesh: " << quality.status().message() << "\n";
      return kExitInternal;
    }
    if (field_) {
      if (Status st = write_metric_outputs(args_.metric, *field_, checked_.surface, r.mesh); !st.ok()) {
        std::cerr << kCmd << ": cannot write the sizing field: " << st.message() << "\n";
        for (const std::string& path : {args_.metric.write_metric, args_.metric.write_sizing})
          if (!path.empty()) not_written_.push_back(path);
      }
    }
    if (Status st = restore_geodetic(args_.metric, frame_, r.mesh); !st.ok()) {
      std::cerr << kCmd << ": --geodetic-output: " << st.message() << "\n";
      return kExitInternal;
    }
    // The input's vertices are written back exactly as read (the round trip through the local
    // frame is exact only to ~1e-9 m), so the output keeps the input surface bit for bit.
    for (size_t v = 0; v < r.input_vertex.size() && 3 * v + 2 < input_xyz_.size(); ++v)
      if (r.input_vertex[v] != TetMesh::kNone) std::copy_n(&input_xyz_[3 * v], 3, &r.mesh.xyz[3 * size_t(r.input_vertex[v])]);
    if (!args_.bl_columns.empty()) {
      if (Status st = write_bl_columns(r); !st.ok()) {
        std::cerr << kCmd << ": cannot write '" << args_.bl_columns << "': " << st.message() << "\n";
        not_written_.push_back(args_.bl_columns);
      }
    }
    writer.wait();
    if (!write_now) {
      if (Status st = merge_prisms(r, with_prisms); !st.ok()) return internal_error(st);
      write_code = write_outputs(args_, with_prisms ? *with_prisms : r.mesh);
    }
    if (write_code != kExitOk) return write_code;
    if (!not_written_.empty()) {
      // The meshes are complete; say so, and which files are not, before the run's report.
      std::string list;
      for (const std::string& p : not_written_) list += (list.empty() ? "'" : ", '") + p + "'";
      std::cerr << kCmd << ": the mesh files are written and complete; not written: " << list << "\n";
    }
    if (args_.json) {
      print_json(r, quality.value());
    } else if (!args_.quiet) {
      print_summary(args_, r, quality.value(), not_written_.empty());
      if (prisms_) print_prisms(*prisms_);
      if (args_.verbose) {
        print_details(r, quality.value());
        if (const double peak = peak_resident_bytes(); peak > 0)
          std::printf("  peak memory of the run (report and writing included): %.0f MB, %.0f bytes per tet\n",
                      peak / 1048576.0, peak / double(std::max<size_t>(r.mesh.num_tets(), 1)));
      }
      else std::cout << "  (-v: every stage's figures and the full quality report)\n";
    }
    return not_written_.empty() ? kExitOk : kExitReadError;
  }

  // --bl-cells prisms: the prisms and pyramids written and why the other BL tets are left as tets.
  static void print_prisms(const PrismMergeStats& p) {
    std::cout << "  written with --bl-cells prisms: " << p.prisms << " prisms (3 BL tets each), " << p.pyramids
              << " pyramids (2 each, where a column stopped), " << p.kept_tets << " of " << p.bl_tets
              << " BL tets left as tets";
    if (p.kept_tets > 0)
      std::cout << ": " << tets_in_no_cell(p) << " in no prism or pyramid, the cells beside them ("
                << p.beside_other_cells << ") and beside those through their layer (" << p.beside_kept
                << "): a quad cannot face tets";
    std::cout << "\n";
  }
  static size_t tets_in_no_cell(const PrismMergeStats& p) {
    return p.kept_tets - 3 * (p.exact_prisms - p.prisms) - 2 * (p.exact_pyramids - p.pyramids);
  }

  // --bl-columns FILE: one CSV line per wall vertex (bl_columns_csv).
  Status write_bl_columns(const MesherResult& r) const {
    return write_file_bytes(args_.bl_columns, bl_columns_csv(r.boundary_layer, meshed_surface(r), args_.bl_patches));
  }

  // --bl-cells prisms: the mesh to write, each BL prism's three tets merged into one prism cell
  // (the report measures the tets).
  Status merge_prisms(const MesherResult& r, std::optional<VolumeMesh>& out) {
    if (args_.bl_cells != "prisms") return Status::success();
    out = r.mesh;
    Result<PrismMergeStats> merged = merge_bl_prisms(*out, r.bl_vertex_origin, r.bl_first_region);
    if (!merged.ok()) return merged.status();
    prisms_ = merged.value();
    return Status::success();
  }

  int internal_error(const Status& st) const {
    std::cerr << kCmd << ": internal error: " << st.message() << "\n";
    return kExitInternal;
  }

  // The run's figures (mesher_result_json, as the C ABI gives them), the files and the quality.
  void print_json(const MesherResult& r, const QualityReport& quality) const {
    nlohmann::json out = nlohmann::json::parse(mesher_result_json(r));
    out["input"] = args_.input;
    out["output"] = args_.output;
    out["also_write"] = args_.also_write;
    out["report"] = args_.report_html;
    out["boundary_layer"]["first_height"] = args_.bl_first_height;
    out["boundary_layer"]["yplus"] = args_.bl_yplus;
    if (prisms_) {
      out["boundary_layer"]["cells"] = "prisms";
      out["boundary_layer"]["prisms"] = prisms_->prisms;
      out["boundary_layer"]["pyramids"] = prisms_->pyramids;
      out["boundary_layer"]["tets_kept"] = prisms_->kept_tets;
      out["boundary_layer"]["tets_kept_in_no_prism"] = tets_in_no_cell(*prisms_);
      out["boundary_layer"]["prisms_kept_beside_other_cells"] = prisms_->beside_other_cells;
      out["boundary_layer"]["prisms_kept_beside_kept"] = prisms_->beside_kept;
    }
    out["quality"] = nlohmann::json::parse(quality_report_json(quality));
    out["ok"] = not_written_.empty();
    out["not_written"] = not_written_;
    std::cout << out.dump(1) << "\n";
  }

  static constexpr const char* kCmd = "anitet mesh";
  MeshArgs& args_;
  CheckedSurface checked_;
  std::optional<metric::VdbModulePreload> preload_;
  std::vector<double> input_xyz_;  // the input's coordinates as read (--geodetic-output)
  std::optional<PrismMergeStats> prisms_;  // --bl-cells prisms: the merge's figures
  std::optional<geo::GeoFrame> frame_;
  MesherOptions options_;
  double free_bytes_ = 0;
  std::unique_ptr<SizingField> field_;
  double field_seconds_ = 0.0;  // a field built here, before the pipeline
  const DistributedRun* distributed_ = nullptr;
  bool in_pieces_ = false;  // anitet-mpi writing a .pvtu: no whole mesh anywhere
  int cycles_run_ = 0;      // anitet-mpi: the anisotropic cycles the rounds in parts ran
  std::vector<std::string> not_written_;  // the report or metric files that could not be written
};

}  // namespace

int run_mesh_pipeline(MeshArgs& args) { return MeshCommand(args).run(); }

namespace {

// Options that would do nothing in the combination given are refused, never ignored: each rule
// names an option that was given and what it needs.
int check_mesh_option_combinations(const CLI::App& cmd, const MeshArgs& a) {
  auto given = [&](const char* name) { return cmd.count(name) > 0; };
  struct Rule {
    const char* option;
    bool applies;
    const char* needs;
  };
  const bool bl = !a.bl_patches.empty(), layers_only = a.stop_after == "layers";
  const bool no_stage3 = a.no_refine && a.no_optimize;
  const Rule rules[] = {
      {"--bl-first-height", !bl, "--bl-patches (the walls the boundary layer grows on)"},
      {"--bl-yplus", !bl, "--bl-patches (the walls the boundary layer grows on)"},
      {"--bl-growth", !bl, "--bl-patches (the walls the boundary layer grows on)"},
      {"--bl-layers", !bl, "--bl-patches (the walls the boundary layer grows on)"},
      {"--bl-slide-patches", !bl, "--bl-patches (the walls the boundary layer grows on)"},
      {"--bl-cells", !bl, "--bl-patches (the walls the boundary layer grows on)"},
      {"--bl-columns", !bl, "--bl-patches (the walls the boundary layer grows on)"},
      {"--bl-mitre", !bl, "--bl-patches (the walls the boundary layer grows on)"},
      {"--bl-cells", layers_only, "the whole pipeline (--stop-after layers writes stage 1's tets)"},
      {"--bl-reynolds", !(a.bl_yplus > 0.0), "--bl-yplus (it turns y+ into a first height)"},
      {"--bl-ref-length", !(a.bl_yplus > 0.0), "--bl-yplus (it turns y+ into a first height)"},
      {"--background", a.metric.metric.empty(), "a .sol --metric (it is the mesh the .sol's values are at)"},
      {"--origin", !a.metric.geodetic, "--geodetic"},
      {"--geo-frame", !a.metric.geodetic, "--geodetic"},
      {"--geodetic-output", !a.metric.geodetic, "--geodetic"},
      {"--size", no_stage3 || layers_only, "refinement or optimization (it scales their sizing field)"},
      {"--anisotropic-cycles", a.no_refine || a.no_optimize || layers_only, "both refinement and optimization"},
      {"--no-refine", layers_only, "the whole pipeline (--stop-after layers stops before refinement)"},
      {"--no-optimize", layers_only, "the whole pipeline (--stop-after layers stops before optimization)"},
      {"--recovery", layers_only, "stage 2 (--stop-after layers stops before it)"},
      {"--attempts-seconds", layers_only, "stage 2 (--stop-after layers stops before it)"},
      {"--no-layer-retries", layers_only, "stage 2 (--stop-after layers stops before it)"},
  };
  for (const Rule& r : rules) {
    if (r.applies && given(r.option)) {
      std::cerr << "anitet mesh: " << r.option << " would do nothing here: it needs " << r.needs << "\n";
      return kExitUsage;
    }
  }
  return kExitOk;
}

}  // namespace

CLI::App* add_mesh_command(CLI::App& app, MeshArgs& args) {
  args.command = "mesh";
  CLI::App* cmd = app.add_subcommand(
      "mesh", "Fill a closed surface with tetrahedra, keeping the surface exactly (every input triangle a "
              "face of the mesh, no point added on it): advancing-front layers, Delaunay with boundary "
              "recovery, coupling, refinement and coarsening to the sizing field, CVT and sliver removal");
  add_mesh_io_options(cmd, args);
  const char* io = "Input and output";
  CLI::Option* mesh_report =
      cmd->add_option("--report", args.report_html,
                      "Also write the HTML quality report here (run figures, histograms, cut views)")
          ->group(io);
  cmd->add_option("--cut", args.report_cut, "Cut planes of the HTML report: x,y,z as fractions of the box")
      ->expected(3)
      ->delimiter(',')
      ->capture_default_str()
      ->check(in_range(0.0, 1.0))
      ->needs(mesh_report)
      ->group(io);
  cmd->add_flag("--json", args.json, "Print the report as JSON (on failure too: {\"ok\": false, ...})")->group(io);
  cmd->add_flag("-v,--verbose", args.verbose, "Print every stage's figures and the full quality report")->group(io);

  const char* stages = "Stages";
  cmd->add_option("--front-layers", args.layers,
                  "Advancing-front layers of stage 1: the paper's layers that hide the surface from the "
                  "Delaunay stage (not boundary layers: those are --bl-*)")
      ->capture_default_str()
      ->check(in_range(1, 50))
      ->group(stages);
  cmd->add_option("--layers", args.deprecated_layers, "Deprecated name of --front-layers")
      ->check(in_range(1, 50))
      ->group("");  // hidden
  cmd->add_option("--stop-after", args.stop_after,
                  "Stop after a stage and write its result: 'layers' writes T1 (stage 1) to the output, "
                  "with S1 as one more patch, and S1 to OUTSTEM.front.off")
      ->check(CLI::IsMember({"layers"}))
      ->group(stages);
  cmd->add_option("--attempts-seconds", args.attempts_seconds,
                  "Wall time for stages 1-2 and the coupling, run again with other layer counts and "
                  "recovery strategies when S1 is not recovered; no attempt starts after it (0: no limit)")
      ->capture_default_str()
      ->check(non_negative())
      ->group(stages);
  cmd->add_flag("--no-layer-retries", args.no_layer_retries,
                "When S1 is not recovered, try the other recovery strategies with the given "
                "--front-layers count only, not with other counts")
      ->group(stages);
  cmd->add_option("--layer-scheme", args.layer_scheme,
                  "Stage 1 scheme: push (prism layers, each front vertex pushed off in turn) or faces "
                  "(the paper's: a tet on every face, then vertex pushes)")
      ->capture_default_str()
      ->check(CLI::IsMember({"push", "faces"}))
      ->group(stages);
  cmd->add_option("--push-tasks-min-vertices", args.push_tasks_min_vertices,
                  "Stage 1 pushes a layer on two tasks, one per side of a plane, from this many front "
                  "vertices (the same mesh either way); 0: every push one by one")
      ->capture_default_str()
      ->group(stages);
  cmd->add_flag("--no-refine", args.no_refine, "Skip refinement/coarsening by metric edge length")->group(stages);
  cmd->add_flag("--no-optimize", args.no_optimize, "Skip CVT smoothing, flips and sliver removal")->group(stages);
  cmd->add_option("--anisotropic-cycles", args.anisotropic_cycles,
                  "With an anisotropic metric (--metric tensors, --bl-sizing): at most this many more rounds "
                  "of refinement then optimization after the first, which even the metric lengths and shapes "
                  "further; a round runs only after an optimization that raised the share of edges in range by 4.5 "
                  "points or more, and they stop after a round that raised it by less than 1 point")
      ->check(in_range(0, 10))
      ->capture_default_str()
      ->group(stages);

  const char* sizing = "Sizing";
  cmd->add_option("--size", args.size,
                  "A factor on every target edge length (of --metric's field, or of the default grid from "
                  "the surface's triangle sizes), after --hmin/--hmax/--hgrad: 0.5 = twice as fine, 2 = "
                  "twice as coarse")
      ->capture_default_str()
      ->check(positive())
      ->group(sizing);
  cmd->add_option("--max-tets", args.max_tets,
                  "Refuse to refine when the sizing field asks for more tets than this (estimated before "
                  "refinement); default: what free memory holds at about 200 bytes a tet; 0: no limit")
      ->check(non_negative())
      ->group(sizing);
  add_metric_options(*cmd, args.metric);

  const char* bl_group = "Boundary layer";
  cmd->add_option("--bl-patches", args.bl_patches,
                  "The input's patch labels (comma-separated) that are walls: n thin "
                  "prism layers grow there first, then the front layers on the whole front. BL tets keep "
                  "their heights (frozen for refinement and optimization) and get region bodies + body "
                  "(1 for one body)")
      ->delimiter(',')
      ->group(bl_group);
  CLI::Option* first_height_opt =
      cmd->add_option("--bl-first-height", args.bl_first_height,
                      "First layer height h0 (a length; needed with --bl-patches unless --bl-yplus gives it)")
          ->check(positive())
          ->group(bl_group);
  CLI::Option* reynolds_opt =
      cmd->add_option("--bl-reynolds", args.bl_reynolds, "Reynolds number Re = U L / nu, for --bl-yplus")
          ->check(positive())
          ->group(bl_group);
  CLI::Option* ref_length_opt =
      cmd->add_option("--bl-ref-length", args.bl_ref_length,
                      "Reference length L of --bl-reynolds (a length), for --bl-yplus")
          ->check(positive())
          ->group(bl_group);
  cmd->add_option("--bl-yplus", args.bl_yplus,
                  "Target y+ of the first layer: h0 from the flat-plate estimate Cf = 0.026 Re^(-1/7), "
                  "h0 = y+ L / (Re sqrt(Cf/2)); needs --bl-reynolds and --bl-ref-length, excludes "
                  "--bl-first-height; the h0 used is printed")
      ->check(positive())
      ->needs(reynolds_opt)
      ->needs(ref_length_opt)
      ->excludes(first_height_opt)
      ->group(bl_group);
  cmd->add_option("--bl-growth", args.bl_growth, "Growth ratio r: layer i has height h0 r^i")
      ->capture_default_str()
      ->check(in_range(1.0, 10.0))
      ->group(bl_group);
  cmd->add_option("--bl-layers", args.bl_layers, "Number of boundary layers n")
      ->capture_default_str()
      ->check(in_range(1, 1000))
      ->group(bl_group);
  cmd->add_option("--bl-slide-patches", args.bl_slide_patches,
                  "Patch labels (comma-separated) that the walls may meet (inlet, outlet, symmetry plane, a "
                  "channel's sides): the layers' columns slide along them and they are triangulated again "
                  "inside the band the layers cover; planar where the layers slide. Without it a wall "
                  "meeting another patch is refused. The rest of the surface stays exactly as given")
      ->delimiter(',')
      ->group(bl_group);
  cmd->add_option("--bl-cells", args.bl_cells,
                  "How the boundary layer's prisms are written: tets (each split into the 3 tets the "
                  "pipeline keeps, every format) or prisms (one prism cell each, and a pyramid where "
                  "a column stopped, for finite-volume solvers; .vtu and OpenFOAM polyMesh only, "
                  "other outputs are refused, as is anitet-mpi's .pvtu, whose ranks write their own tets)")
      ->capture_default_str()
      ->check(CLI::IsMember({"tets", "prisms"}))
      ->group(bl_group);
  cmd->add_option("--bl-columns", args.bl_columns,
                  "Write the boundary layer's columns to this CSV file: per wall vertex its point, the "
                  "layers its column reaches, its first and total height, its normal share (the least cosine "
                  "between the column and its wall triangles' normals) and its patch labels (to see "
                  "the columns at a trailing edge, a wing's tip or root)")
      ->group(bl_group);
  cmd->add_flag("--bl-mitre", args.bl_mitre,
                "At the walls' edges and corners (a trailing edge, a wing's tip, its root on a wall) "
                "lengthen each column by 1/cos of its angle to the farthest wall normal there (at most "
                "2), so that the layers keep their thickness across every wall; without it a "
                "right-angled edge's layers are 0.71 as thick across each wall as along the column")
      ->group(bl_group);
  cmd->add_flag("--bl-sizing", args.bl_sizing,
                "Refine the interior to continue the boundary layer's heights (normal size h0 + (r - 1) d "
                "at distance d from the walls) instead of jumping to the surface's sizes; anisotropic near "
                "the walls, so refinement is slower. Needs --bl-patches and --bl-growth above 1")
      ->group(bl_group);
  cmd->add_option("--bl-sizing-growth", args.bl_sizing_growth,
                  "With --bl-sizing: above the layers' top the normal size grows at this rate (at least "
                  "--bl-growth) instead of the layers' growth: the first tets there still get the next "
                  "layer's height, and the interior reaches its own sizes in fewer, cheaper tets")
      ->group(bl_group);
  cmd->footer(
      "Examples:\n"
      "  anitet mesh part.stl -o part.mesh                    # the defaults: sizes from the surface\n"
      "  anitet mesh part.stl -o fine.vtu --size 0.5          # every size halved\n"
      "  anitet mesh case.mesh -o case.su2 --also-write case.cgns --patch-names 1=wall,2=farfield \\\n"
      "      --bl-patches 1 --bl-first-height 1e-3 --bl-layers 10   # boundary layers on patch 1");
  return cmd;
}

int run_mesh(const CLI::App& cmd, MeshArgs& args) {
  if (const int code = check_mesh_option_combinations(cmd, args); code != kExitOk) return code;
  if (args.deprecated_layers > 0) {
    if (cmd.count("--front-layers") > 0) {
      std::cerr << "anitet mesh: --layers is the old name of --front-layers: give --front-layers only\n";
      return kExitUsage;
    }
    std::cerr << "anitet mesh: --layers is deprecated: it is --front-layers (stage 1's advancing-front "
                 "layers; boundary layers are --bl-layers)\n";
    args.layers = args.deprecated_layers;
  }
  if (args.bl_yplus > 0.0) {
    Result<double> h0 = first_height_from_yplus(args.bl_yplus, args.bl_reynolds, args.bl_ref_length);
    if (!h0.ok()) {
      std::cerr << "anitet mesh: --bl-yplus: " << h0.status().message() << "\n";
      return kExitUsage;
    }
    args.bl_first_height = h0.value();
    if (!args.quiet && !args.json)
      std::cout << "anitet mesh: --bl-yplus " << args.bl_yplus << " at Re " << args.bl_reynolds << ", L "
                << args.bl_ref_length << ": first height h0 = " << args.bl_first_height
                << " (flat plate: Cf = 0.026 Re^(-1/7), h0 = y+ L / (Re sqrt(Cf/2)))\n";
  }
  if (args.bl_cells == "prisms")
    for (const std::string& path : output_paths(args)) {
      Result<VolumeFormat> format = volume_format_from_path(path);
      if (format.ok() && !volume_format_writes_prisms(format.value())) {
        std::cerr << "anitet mesh: --bl-cells prisms: '" << path << "' is a format written with tets only; prism "
                  << "and pyramid cells are written to " << kPrismFormats << " (or give --bl-cells tets)\n";
        return kExitUsage;
      }
    }
  if (args.stop_after == "layers" &&
      (wants_sizing_field(args.metric) || args.metric.geodetic || !args.metric.background.empty())) {
    std::cerr << "anitet mesh: the sizing and geographic options (--metric, --background, --hmin, "
                 "--hmax, --hgrad, --write-metric, --write-sizing, --geodetic) apply to the whole "
                 "pipeline, not to --stop-after layers\n";
    return kExitUsage;
  }
  if (args.stop_after == "layers" && !args.report_html.empty()) {
    std::cerr << "anitet mesh: --report applies to the whole pipeline; for stage 1 alone, run "
                 "`anitet report OUT` on its output\n";
    return kExitUsage;
  }
  return args.stop_after == "layers" ? run_mesh_layers(args) : run_mesh_pipeline(args);
}

namespace {
const DistributedRun* g_distributed = nullptr;
}  // namespace

void set_distributed_run(const DistributedRun* run) { g_distributed = run; }
const DistributedRun* distributed_run() { return g_distributed; }

bool is_pvtu_path(const std::string& path) {
  return path.size() > 5 && (path.compare(path.size() - 5, 5, ".pvtu") == 0 || path.compare(path.size() - 5, 5, ".PVTU") == 0);
}

}  // namespace anitet::cli
