#include "metric_options.hpp"
#include "cli_util.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <utility>

#include "io/volume_io.hpp"
#include "metric/bounded_sizing.hpp"
#include "metric/combine.hpp"
#include "metric/lattice.hpp"
#include "metric/metric_field.hpp"
#include "metric/sol_field.hpp"
#include "metric/surface_sizing.hpp"

namespace anitet::cli {

namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  std::string tail = s.substr(s.size() - suffix.size());
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return tail == suffix;
}

metric::SizeBounds bounds_of(const MetricCliOptions& o) { return {o.hmin, o.hmax, o.hgrad}; }

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
  if (Status st = metric::check_bounds(bounds_of(o)); !st.ok()) {
    std::string msg = st.message();  // named as the options are
    for (const char* name : {"hgrad", "hmax", "hmin"})
      for (size_t at = msg.find(name); at != std::string::npos; at = msg.find(name, at + 3)) msg.insert(at, "--");
    return Status(st.code(), msg);
  }
  if (o.metric.empty()) {
    if (!o.background.empty())
      return Status(Error::InvalidArgument, "--background needs a .sol or .solb --metric");
    return metric::bounded_sizing_field(surface, nullptr, bounds_of(o), default_sizing);
  }
  // The user's field, owned with what the bounds wrap it in.
  auto out = std::make_unique<metric::OwningField>();
  const SizingField* base = nullptr;
  if (ends_with(o.metric, ".vdb")) {
    if (!o.background.empty())
      return Status(Error::InvalidArgument, "--background is for a .sol or .solb --metric, not a .vdb");
    Result<metric::MetricField> f = metric::read_metric_vdb(o.metric);
    if (!f.ok()) return f.status();
    base = &out->keep(std::move(f.value()));
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
    base = &out->keep(std::move(f.value()));
  } else {
    return Status(Error::UnsupportedFormat, "--metric '" + o.metric + "': expected a .vdb, .sol or .solb file");
  }
  Result<std::unique_ptr<SizingField>> bounded = metric::bounded_sizing_field(surface, base, bounds_of(o), default_sizing);
  if (!bounded.ok()) return bounded.status();
  out->keep_owned(std::move(bounded).value());
  return std::unique_ptr<SizingField>(std::move(out));
}

Status write_metric_outputs(const MetricCliOptions& o, const SizingField& field,
                            const SurfaceMesh& surface, VolumeMesh& mesh) {
  if (!o.write_metric.empty()) {
    metric::sample_sizes_or_tensors(field, mesh);
    if (Status st = write_sol(mesh, o.write_metric); !st.ok()) return st;
  }
  if (!o.write_sizing.empty()) {
    const SizingField* f = &field;
    if (const auto* owner = dynamic_cast<const metric::OwningField*>(f)) f = &owner->top();
    if (const auto* grid = dynamic_cast<const metric::MetricField*>(f))
      return metric::write_metric_vdb(*grid, o.write_sizing);
    Result<metric::MetricField> sampled = metric::sample_on_surface_box(field, surface);
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
