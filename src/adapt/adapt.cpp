#include "adapt/adapt.hpp"

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "adapt/adapt_mesh.hpp"
#include "adapt/metric_source.hpp"
#include "adapt/remesher.hpp"
#include "adapt/setup.hpp"

namespace anitet {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Swaps are tried around tets below this quality while the mesh is refined and coarsened, and
// below kSwapOptimize in the sweeps after.
constexpr double kSwapCycle = 0.6;
constexpr double kSwapOptimize = 0.9;
constexpr double kStagnation = 0.9;

class Run {
 public:
  Run(const adapt::MetricSource& source, const AdaptOptions& options) : source_(source), opt_(options) {}

  Result<AdaptResult> go(const VolumeMesh& in, const adapt::VertexMetricSource* at_vertices) {
    const auto t0 = Clock::now();
    AdaptResult out;
    AdaptStats& st = out.stats;
    st.vertices_in = in.num_vertices();
    st.tets_in = in.num_tets();
    st.boundary_triangles_in = in.num_boundary_triangles();
    if (Status s = adapt::build_adapt_mesh(in, mesh_); !s.ok()) return s;
    for (uint32_t v = 0; v < mesh_.num_points(); ++v) {
      if (mesh_.tag[v] & adapt::ptag::kRemoved) continue;
      double m[6];
      uint32_t hint = mesh_.ptet[v];
      if (at_vertices) at_vertices->at_vertex(v, m);
      else source_.eval(mesh_.p(v), hint, m);
      mesh_.set_metric(v, m);
      mesh_.hint[v] = mesh_.ptet[v];
    }
    const adapt::SurfaceFeatures f = adapt::analyse_surface(mesh_, opt_.ridge_angle_deg, opt_.keep_surface);
    st.ridge_edges = f.ridge_edges;
    st.corners = f.corners;
    adapt::Remesher r(mesh_, source_, opt_, st);
    for (uint32_t t = 0; t < mesh_.num_slots(); ++t) r.update_quality(t);
    st.seconds_setup = since(t0);
    if (Status s = check("setup"); !s.ok()) return s;

    const int total = opt_.max_cycles + opt_.optimize_cycles;
    std::vector<size_t> changes;  // splits and collapses of each cycle
    for (int c = 0; c < opt_.max_cycles; ++c) {
      if (!progress("adapt, cycle " + std::to_string(c + 1), double(c) / total)) return cancelled();
      const size_t before = mesh_.num_tets();
      mesh_.epoch = uint32_t(c + 1);
      const size_t splits = timed(st.seconds_split, [&] { return r.split_sweep(); });
      if (Status s = check("split"); !s.ok()) return s;
      const size_t collapses = timed(st.seconds_collapse, [&] { return r.collapse_sweep(); });
      if (Status s = check("collapse"); !s.ok()) return s;
      const size_t swaps = timed(st.seconds_swap, [&] { return r.swap_sweep(kSwapCycle); });
      if (Status s = check("swap"); !s.ok()) return s;
      const size_t moves = timed(st.seconds_smooth, [&] { return r.smooth_sweep(false); });
      if (Status s = check("smooth"); !s.ok()) return s;
      log("cycle " + std::to_string(c + 1) + ": " + std::to_string(splits) + " splits, " + std::to_string(collapses) +
          " collapses, " + std::to_string(swaps) + " swaps, " + std::to_string(moves) + " moves, " +
          std::to_string(mesh_.num_tets()) + " tets, " + std::to_string(since(t0)) + " s");
      st.cycles = c + 1;
      // Done when a cycle changes next to nothing, or when the changes stop falling (under a
      // tenth fewer than five cycles before): the splits and collapses then undo each other
      // (on the sphere case, 165 of each per cycle for 20 cycles, nothing gained).
      changes.push_back(splits + collapses);
      if (double(splits + collapses) < 1e-3 * double(before)) break;
      if (c >= 5 && double(changes[size_t(c)]) > kStagnation * double(changes[size_t(c) - 5])) break;
    }
    for (int c = 0; c < opt_.optimize_cycles; ++c) {
      if (!progress("optimize, sweep " + std::to_string(c + 1), double(opt_.max_cycles + c) / total))
        return cancelled();
      const size_t swaps = timed(st.seconds_swap, [&] { return r.swap_sweep(kSwapOptimize); });
      const size_t moves = timed(st.seconds_smooth, [&] { return r.smooth_sweep(true); });
      if (Status s = check("optimize"); !s.ok()) return s;
      log("optimize " + std::to_string(c + 1) + ": " + std::to_string(swaps) + " swaps, " + std::to_string(moves) +
          " moves, " + std::to_string(since(t0)) + " s");
    }
    const auto t1 = Clock::now();
    out.mesh = adapt::export_mesh(mesh_);
    st.vertices_out = out.mesh.num_vertices();
    st.tets_out = out.mesh.num_tets();
    st.boundary_triangles_out = out.mesh.num_boundary_triangles();
    st.seconds_output = since(t1);
    st.seconds_total = since(t0);
    return out;
  }

 private:
  template <class F>
  size_t timed(double& seconds, F&& f) {
    const auto t0 = Clock::now();
    const size_t n = f();
    seconds += since(t0);
    return n;
  }
  bool progress(const std::string& stage, double fraction) const {
    return !opt_.progress || opt_.progress(stage, fraction);
  }
  void log(const std::string& line) const {
    if (opt_.log) opt_.log(line);
  }
  static Status cancelled() { return Status(Error::Cancelled, "adaptation cancelled"); }
  Status check(const char* after) const {
    if (!opt_.check_each_sweep) return Status::success();
    const std::string problem = mesh_.check();
    if (problem.empty()) return Status::success();
    return Status(Error::Internal, std::string("adaptation broke the mesh (after ") + after + "): " + problem);
  }

  const adapt::MetricSource& source_;
  const AdaptOptions& opt_;
  adapt::AdaptMesh mesh_;
};

}  // namespace

Result<AdaptResult> adapt_mesh(const VolumeMesh& in, const std::vector<double>& vertex_metric,
                               const AdaptOptions& options) {
  Result<std::unique_ptr<adapt::VertexMetricSource>> source = adapt::VertexMetricSource::create(in, vertex_metric);
  if (!source.ok()) return source.status();
  Run run(*source.value(), options);
  return run.go(in, source.value().get());
}

Result<AdaptResult> adapt_mesh(const VolumeMesh& in, const SizingField& field, const AdaptOptions& options) {
  adapt::FieldMetricSource source(field);
  Run run(source, options);
  return run.go(in, nullptr);
}

}  // namespace anitet
