#include "metric_options.hpp"
#include "cli_util.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <utility>

#include "io/volume_io.hpp"
#include "metric/combine.hpp"
#include "metric/lattice.hpp"
#include "metric/metric_field.hpp"
#include "metric/sol_field.hpp"
#include "metric/surface_sizing.hpp"

namespace anitet::cli {

namespace {

// A field together with the fields it refers to (BoundedField and BackgroundMeshField wrappers
// hold references), so the caller gets one owner.
class OwningField final : public SizingField {
 public:
  void metric(const double p[3], double m[6]) const override { top_->metric(p, m); }
  template <class F>
  F& keep(F&& field) {
    auto owned = std::make_unique<F>(std::move(field));
    F& ref = *owned;
    parts_.push_back(std::move(owned));
    top_ = &ref;
    return ref;
  }
  const SizingField& top() const { return *top_; }

 private:
  std::vector<std::unique_ptr<SizingField>> parts_;
  const SizingField* top_ = nullptr;
};

bool ends_with(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  std::string tail = s.substr(s.size() - suffix.size());
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return tail == suffix;
}

double mean_edge_length(const SurfaceMesh& s) {
  double sum = 0.0;
  size_t n = 0;
  for (size_t t = 0; t < s.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = s.tri[3 * t + k], b = s.tri[3 * t + (k + 1) % 3];
      if (a >= s.num_vertices() || b >= s.num_vertices()) continue;
      const double* p = s.point(a);
      const double* q = s.point(b);
      sum += std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                       (p[2] - q[2]) * (p[2] - q[2]));
      ++n;
    }
  return n ? sum / double(n) : 0.0;
}

// The field sampled as a voxel field over the surface's box (padded by two voxels), spacing the
// mean edge length grown until the box has at most 2^24 voxels.
Result<metric::MetricField> sample_on_surface_box(const SizingField& field, const SurfaceMesh& s) {
  if (s.num_vertices() == 0) return Status(Error::EmptyInput, "no surface to sample the field over");
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (size_t v = 0; v < s.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], s.point(v)[k]);
      hi[k] = std::max(hi[k], s.point(v)[k]);
    }
  double h = mean_edge_length(s);
  if (!(h > 0.0)) return Status(Error::InvalidArgument, "the surface has no edge");
  const double limit = double(size_t(1) << 24);
  for (;;) {
    double count = 1.0;
    for (int k = 0; k < 3; ++k) count *= std::ceil((hi[k] - lo[k]) / h) + 5.0;
    if (count <= limit) break;
    h *= 1.25;
  }
  for (int k = 0; k < 3; ++k) {
    lo[k] -= 2.0 * h;
    hi[k] += 2.0 * h;
  }
  return metric::MetricField::from_function(
      [&field](const double p[3], double m[6]) { field.metric(p, m); }, lo, hi, h);
}

Status check_bounds(const MetricCliOptions& o) {
  if (o.hmin < 0.0 || o.hmax < 0.0 || !std::isfinite(o.hmin) || !std::isfinite(o.hmax))
    return Status(Error::InvalidArgument, "--hmin and --hmax must be >= 0");
  if (o.hmin > 0.0 && o.hmax > 0.0 && o.hmin > o.hmax)
    return Status(Error::InvalidArgument, "--hmin must not exceed --hmax");
  if (o.hgrad != 0.0 && !(o.hgrad > 1.0))
    return Status(Error::InvalidArgument, "--hgrad must be > 1");
  return Status::success();
}

}  // namespace

void add_metric_options(CLI::App& cmd, MetricCliOptions& o) {
  const char* group = "Sizing";
  cmd.add_option("--metric", o.metric,
                 "Sizing field: a .vdb (grid 'size', or the six 'log_metric_xx' .. "
                 "'log_metric_zz' or 'metric_xx' .. 'metric_zz' grids) or a Medit .sol or .solb "
                 "(with --background). Default: the surface's own sizing grid")
      ->group(group)
      ->check(CLI::ExistingFile);
  cmd.add_option("--background", o.background,
                 "Background tetrahedral mesh of a .sol/.solb --metric (.mesh .meshb .msh .vtu .node)")
      ->group(group)
      ->check(CLI::ExistingFile);
  cmd.add_option("--hmin", o.hmin,
                 "Smallest target edge length: an absolute length in the input's units, applied to the "
                 "field before --size (0: no bound)")
      ->group(group)
      ->check(non_negative());
  cmd.add_option("--hmax", o.hmax,
                 "Largest target edge length: an absolute length in the input's units, applied to the "
                 "field before --size (0: no bound)")
      ->group(group)
      ->check(non_negative());
  cmd.add_option("--hgrad", o.hgrad,
                 "Gradation: largest size ratio between neighbours per unit metric length, "
                 "applied to the whole tensor (> 1; 0: none)")
      ->group(group);
  cmd.add_option("--write-metric", o.write_metric,
                 "Write the sizing field (before --size) at the output mesh's vertices as a "
                 "Medit .sol, or binary .solb by its extension (sizes when isotropic, else tensors)")
      ->group(group);
  cmd.add_option("--write-sizing", o.write_sizing,
                 "Write the sizing field (before --size) as OpenVDB grids (.vdb), for any "
                 "OpenVDB viewer; readable again with --metric")
      ->group(group);
  const char* geo = "Geographic";
  cmd.add_flag("--geodetic", o.geodetic,
               "Input x, y, z are longitude, latitude (degrees) and height (m) on WGS84; meshing "
               "happens in a local frame in metres (sizes in metres)")
      ->group(geo);
  cmd.add_option("--origin", o.origin,
                 "Origin of the local frame as lat,lon,h (default: the centre of the data)")
      ->group(geo)
      ->delimiter(',')
      ->expected(3);
  cmd.add_option("--geo-frame", o.geo_frame,
                 "Local frame of --geodetic: enu (east-north-up at the origin) or utm (the "
                 "origin's zone)")
      ->group(geo)
      ->check(CLI::IsMember({"enu", "utm"}));
  cmd.add_flag("--geodetic-output", o.geodetic_output,
               "Write the mesh back in longitude, latitude, height, the input's vertices exactly "
               "as read (default: the mesh in the local frame)")
      ->group(geo);
}

bool wants_sizing_field(const MetricCliOptions& o) {
  return !o.metric.empty() || o.hmin > 0.0 || o.hmax > 0.0 || o.hgrad > 0.0 ||
         !o.write_metric.empty() || !o.write_sizing.empty();
}

Result<std::optional<geo::GeoFrame>> prepare_geodetic(const MetricCliOptions& o,
                                                      SurfaceMesh& surface) {
  if (!o.geodetic) {
    if (!o.origin.empty() || o.geodetic_output)
      return Status(Error::InvalidArgument, "--origin and --geodetic-output need --geodetic");
    return std::optional<geo::GeoFrame>();
  }
  const geo::FrameKind kind = o.geo_frame == "utm" ? geo::FrameKind::Utm : geo::FrameKind::Enu;
  Result<geo::GeoFrame> frame =
      o.origin.empty() ? geo::centred_frame(kind, surface.xyz)
      : o.origin.size() == 3
          ? geo::make_frame(kind, o.origin[0], o.origin[1], o.origin[2])
          : Result<geo::GeoFrame>(Error::InvalidArgument, "--origin takes lat,lon,h");
  if (!frame.ok()) return frame.status();
  if (Status st = geo::to_local(frame.value(), surface); !st.ok()) return st;
  return std::optional<geo::GeoFrame>(frame.value());
}

Result<std::unique_ptr<SizingField>> build_sizing_field(const MetricCliOptions& o,
                                                        const SurfaceMesh& surface,
                                                        const geo::GeoFrame* frame,
                                                        const metric::SurfaceSizingOptions&
                                                            default_sizing) {
  if (Status st = check_bounds(o); !st.ok()) return st;
  const bool bound = o.hmin > 0.0 || o.hmax > 0.0;
  auto out = std::make_unique<OwningField>();
  if (o.metric.empty()) {
    if (!o.background.empty())
      return Status(Error::InvalidArgument, "--background needs a .sol or .solb --metric");
    // Bounded and graded on the dense lattice, before the sparse storage prunes it.
    const metric::SurfaceSizingOptions& so = default_sizing;
    Result<metric::Lattice> lat = metric::surface_sizing(surface, so);
    if (!lat.ok()) return lat.status();
    if (bound)
      if (Status st = metric::bound_sizes(lat.value(), o.hmin, o.hmax); !st.ok()) return st;
    if (o.hgrad > 0.0) {
      Result<metric::GradationStats> g = metric::grade(lat.value(), o.hgrad);
      if (!g.ok()) return g.status();
    }
    Result<metric::MetricField> f = metric::MetricField::from_lattice(lat.value(), so.prune_tolerance);
    if (!f.ok()) return f.status();
    out->keep(std::move(f.value()));
  } else if (ends_with(o.metric, ".vdb")) {
    if (!o.background.empty())
      return Status(Error::InvalidArgument, "--background is for a .sol or .solb --metric, not a .vdb");
    Result<metric::MetricField> f = metric::read_metric_vdb(o.metric);
    if (!f.ok()) return f.status();
    if (bound || o.hgrad > 0.0) {
      f = metric::bound_and_grade(f.value(), o.hmin, o.hmax, o.hgrad);
      if (!f.ok()) return f.status();
    }
    out->keep(std::move(f.value()));
  } else if (ends_with(o.metric, ".sol") || ends_with(o.metric, ".solb")) {
    if (o.background.empty())
      return Status(Error::InvalidArgument, "a .sol or .solb --metric needs --background MESH");
    Result<metric::SolField> sol = metric::read_sol(o.metric);
    if (!sol.ok()) return sol.status();
    Result<VolumeMesh> bg = read_volume_mesh(o.background);
    if (!bg.ok()) return bg.status();
    if (frame)
      if (Status st = geo::to_local(*frame, bg.value().xyz); !st.ok()) return st;
    Result<metric::BackgroundMeshField> f = metric::BackgroundMeshField::create(bg.value(), sol.value());
    if (!f.ok()) return f.status();
    const SizingField& base = out->keep(std::move(f.value()));
    if (o.hgrad > 0.0) {
      // Gradation needs neighbours: on the voxels of a lattice over the surface.
      Result<metric::MetricField> grid = sample_on_surface_box(base, surface);
      if (!grid.ok()) return grid.status();
      grid = metric::bound_and_grade(grid.value(), o.hmin, o.hmax, o.hgrad);
      if (!grid.ok()) return grid.status();
      out->keep(std::move(grid.value()));
    } else if (bound) {
      out->keep(metric::BoundedField(base, o.hmin, o.hmax));
    }
  } else {
    return Status(Error::UnsupportedFormat,
                  "--metric '" + o.metric + "': expected a .vdb, .sol or .solb file");
  }
  return std::unique_ptr<SizingField>(std::move(out));
}

Status write_metric_outputs(const MetricCliOptions& o, const SizingField& field,
                            const SurfaceMesh& surface, VolumeMesh& mesh) {
  if (!o.write_metric.empty()) {
    metric::sample_at_vertices(field, mesh, false);
    bool isotropic = true;
    for (size_t v = 0; v < mesh.num_vertices() && isotropic; ++v) {
      const double* m = &mesh.vertex_metric[6 * v];
      isotropic = m[1] == 0.0 && m[3] == 0.0 && m[4] == 0.0 && m[0] == m[2] && m[0] == m[5];
    }
    if (isotropic) metric::sample_at_vertices(field, mesh, true);
    if (Status st = write_sol(mesh, o.write_metric); !st.ok()) return st;
  }
  if (!o.write_sizing.empty()) {
    const SizingField* f = &field;
    if (const auto* owner = dynamic_cast<const OwningField*>(f)) f = &owner->top();
    if (const auto* grid = dynamic_cast<const metric::MetricField*>(f))
      return metric::write_metric_vdb(*grid, o.write_sizing);
    Result<metric::MetricField> sampled = sample_on_surface_box(field, surface);
    if (!sampled.ok()) return sampled.status();
    return metric::write_metric_vdb(sampled.value(), o.write_sizing);
  }
  return Status::success();
}

Status restore_geodetic(const MetricCliOptions& o, const std::optional<geo::GeoFrame>& frame,
                        VolumeMesh& mesh) {
  if (!o.geodetic_output) return Status::success();
  if (!frame) return Status(Error::InvalidArgument, "--geodetic-output needs --geodetic");
  return geo::to_geodetic(*frame, mesh.xyz);
}

}  // namespace anitet::cli
