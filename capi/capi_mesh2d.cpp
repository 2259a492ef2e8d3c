// The 2D mesher's entry points: PSLGs from caller arrays or files, anitet_mesh2d_options ->
// mesh2d::Mesh2dOptions (with the caller's metric and progress callback), the triangle mesh and
// its accessors.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "caller_sizing.hpp"
#include "handles.hpp"
#include "mesh2d/geodetic2.hpp"
#include "mesh2d/mesh2d_io.hpp"
#include "mesh2d/pslg_io.hpp"
#include "shim.hpp"

using namespace anitet::capi;

static_assert(sizeof(anitet_mesh2d_options) == 8 * 4 + 8 * 5 + 2 * sizeof(void*),
              "anitet_mesh2d_options has an unexpected layout");

namespace {

int bad_option(const char* function, const std::string& what) {
  return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(function) + ": options: " + what);
}

int read_mesh2d_options(const char* function, const anitet_mesh2d_options* given, anitet_mesh2d_options& out) {
  out = ANITET_MESH2D_OPTIONS_INIT;
  if (given == nullptr) return ANITET_OK;
  if (given->version < 1 || given->version > ANITET_MESH2D_OPTIONS_VERSION)
    return bad_option(function, "version is " + std::to_string(given->version) + ", not 1.." +
                                    std::to_string(ANITET_MESH2D_OPTIONS_VERSION) +
                                    "; initialise with ANITET_MESH2D_OPTIONS_INIT or anitet_mesh2d_options_init");
  std::memcpy(&out, given, sizeof(anitet_mesh2d_options));  // version 1 is the whole struct
  return ANITET_OK;
}

int to_options(const char* function, const anitet_mesh2d_options& o, anitet::mesh2d::Mesh2dOptions& out) {
  if (o.layers < 1 || o.layers > 20) return bad_option(function, "layers is " + std::to_string(o.layers) + ", not 1..20");
  if (o.geo_frame != ANITET_GEO_ENU && o.geo_frame != ANITET_GEO_UTM)
    return bad_option(function, "geo_frame is " + std::to_string(o.geo_frame) + ", not ANITET_GEO_ENU or ANITET_GEO_UTM");
  auto finite_nonneg = [](double x) { return std::isfinite(x) && x >= 0.0; };
  if (!finite_nonneg(o.hsize) || !finite_nonneg(o.hmin) || !finite_nonneg(o.hmax) || !finite_nonneg(o.hgrad))
    return bad_option(function, "hsize, hmin, hmax and hgrad must be finite and >= 0");
  if (!(std::isfinite(o.size_scale) && o.size_scale > 0.0)) return bad_option(function, "size_scale must be finite and > 0");
  if (o.hgrad != 0.0 && !(o.hgrad > 1.0)) return bad_option(function, "hgrad must be > 1 (or 0: none)");
  if (o.hmin > 0 && o.hmax > 0 && o.hmin > o.hmax) return bad_option(function, "hmin exceeds hmax");
  out.split_segments = o.split_segments != 0;
  out.layers = o.layers;
  out.refine = o.refine != 0;
  out.optimize = o.optimize != 0;
  out.sizing.hsize = o.hsize;
  out.sizing.scale = o.size_scale;
  out.sizing.hmin = o.hmin;
  out.sizing.hmax = o.hmax;
  out.sizing.hgrad = o.hgrad;
  return ANITET_OK;
}

}  // namespace

extern "C" {

int anitet_pslg_create(const double* xy, int64_t num_points, const int32_t* segments, int64_t num_segments,
                       const int32_t* labels, const double* holes, int64_t num_holes, int32_t index_base,
                       anitet_pslg** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    if (num_points < 0 || num_segments < 0 || num_holes < 0)
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": a count is negative");
    if (num_segments < 3) return set_error(ANITET_ERR_EMPTY_INPUT, std::string(fn) + ": fewer than 3 segments");
    if (xy == nullptr) return null_argument(fn, "xy");
    if (segments == nullptr) return null_argument(fn, "segments");
    if (num_holes > 0 && holes == nullptr) return null_argument(fn, "holes");
    auto p = std::make_unique<anitet_pslg>();
    anitet::mesh2d::Pslg& g = p->pslg;
    g.first_index = index_base;
    g.xy.assign(xy, xy + 2 * num_points);
    if (const int code = convert_indices(fn, "segment", segments, num_segments, 2, num_points, index_base, g.seg);
        code != ANITET_OK)
      return code;
    g.label.assign(size_t(num_segments), 0);
    if (labels) g.label.assign(labels, labels + num_segments);
    if (num_holes > 0) g.holes.assign(holes, holes + 2 * num_holes);
    *out = p.release();
    return ok();
  });
}

int anitet_pslg_read(const char* path, anitet_pslg** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (path == nullptr) return null_argument(fn, "path");
    anitet::Result<anitet::mesh2d::Pslg> read = anitet::mesh2d::read_pslg(path);
    if (!read.ok()) return set_status(fn, read.status());
    auto p = std::make_unique<anitet_pslg>();
    p->pslg = std::move(read.value());
    *out = p.release();
    return ok();
  });
}

void anitet_pslg_destroy(anitet_pslg* pslg) { delete pslg; }

int anitet_pslg_get_counts(const anitet_pslg* pslg, int64_t* num_points, int64_t* num_segments, int64_t* num_holes) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (pslg == nullptr) return null_argument(fn, "pslg");
    if (num_points) *num_points = int64_t(pslg->pslg.num_points());
    if (num_segments) *num_segments = int64_t(pslg->pslg.num_segments());
    if (num_holes) *num_holes = int64_t(pslg->pslg.num_holes());
    return ok();
  });
}

int anitet_mesh2d_options_init(anitet_mesh2d_options* options, int32_t version) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (options == nullptr) return null_argument(fn, "options");
    if (version < 1 || version > ANITET_MESH2D_OPTIONS_VERSION)
      return bad_option(fn, "version is " + std::to_string(version) + ", not 1.." + std::to_string(ANITET_MESH2D_OPTIONS_VERSION));
    anitet_mesh2d_options defaults = ANITET_MESH2D_OPTIONS_INIT;
    defaults.version = version;
    std::memcpy(options, &defaults, sizeof(anitet_mesh2d_options));
    return ok();
  });
}

int anitet_mesh2d_run(const anitet_pslg* pslg, const anitet_metric* metric, const anitet_mesh2d_options* options,
                      anitet_mesh2d** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (pslg == nullptr) return null_argument(fn, "pslg");
    anitet_mesh2d_options opt;
    if (const int code = read_mesh2d_options(fn, options, opt); code != ANITET_OK) return code;
    anitet::mesh2d::Mesh2dOptions mo;
    if (const int code = to_options(fn, opt, mo); code != ANITET_OK) return code;
    anitet::mesh2d::Pslg input = pslg->pslg;
    const std::vector<double> input_xy = input.xy;
    std::optional<anitet::geo::GeoFrame> frame;
    if (opt.geodetic) {
      anitet::Result<anitet::geo::GeoFrame> f =
          anitet::mesh2d::pslg_to_local(input, opt.geo_frame == ANITET_GEO_UTM ? anitet::geo::FrameKind::Utm : anitet::geo::FrameKind::Enu);
      if (!f.ok()) return set_status(fn, f.status());
      frame = f.value();
    }
    std::unique_ptr<CallerSizing> sizing;
    if (metric != nullptr) {
      double span = 1.0;
      if (!input.xy.empty()) {
        const auto [lo, hi] = std::minmax_element(input.xy.begin(), input.xy.end());
        span = std::max(*hi - *lo, 1e-300);
      }
      sizing = std::make_unique<CallerSizing>(*metric, span);
      mo.sizing.metric = sizing.get();
    }
    if (opt.progress || sizing) {
      mo.progress = [&opt, &sizing](double fraction, const char* stage) {
        if (sizing && sizing->failed()) return false;
        return !opt.progress || opt.progress(fraction, stage, opt.progress_user_data) == 0;
      };
    }
    anitet::mesh2d::Mesh2dStats stats;
    anitet::Result<anitet::mesh2d::TriMesh2> run = anitet::mesh2d::mesh_pslg(input, mo, &stats);
    if (sizing && sizing->failed()) return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": " + sizing->failure());
    if (!run.ok()) return set_status(fn, run.status());
    auto mesh = std::make_unique<anitet_mesh2d>();
    mesh->quality = anitet::mesh2d::measure_quality(run.value());
    mesh->mesh = std::move(run.value());
    if (frame)
      if (anitet::Status s = anitet::mesh2d::mesh_to_geodetic(*frame, mesh->mesh, input_xy); !s.ok()) return set_status(fn, s);
    *out = mesh.release();
    return ok();
  });
}

void anitet_mesh2d_destroy(anitet_mesh2d* mesh) { delete mesh; }

int anitet_mesh2d_get_counts(const anitet_mesh2d* mesh, int64_t* num_points, int64_t* num_triangles, int64_t* num_edges) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (num_points) *num_points = int64_t(mesh->mesh.num_vertices());
    if (num_triangles) *num_triangles = int64_t(mesh->mesh.num_triangles());
    if (num_edges) *num_edges = int64_t(mesh->mesh.edge_label.size());
    return ok();
  });
}

int anitet_mesh2d_get_points(const anitet_mesh2d* mesh, double* xy, int64_t xy_len) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    return fill(fn, "xy", mesh->mesh.xy, xy, xy_len, [](double v) { return v; });
  });
}

int anitet_mesh2d_get_triangles(const anitet_mesh2d* mesh, int32_t* tri, int64_t tri_len, int32_t index_base) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    return fill(fn, "tri", mesh->mesh.tri, tri, tri_len, [&](uint32_t v) { return int32_t(v) + index_base; });
  });
}

int anitet_mesh2d_get_attributes(const anitet_mesh2d* mesh, double* attributes, int64_t attributes_len) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    return fill(fn, "attributes", mesh->mesh.attribute, attributes, attributes_len, [](double v) { return v; });
  });
}

int anitet_mesh2d_get_edges(const anitet_mesh2d* mesh, int32_t* edges, int64_t edges_len, int32_t index_base) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    return fill(fn, "edges", mesh->mesh.edges, edges, edges_len, [&](uint32_t v) { return int32_t(v) + index_base; });
  });
}

int anitet_mesh2d_get_edge_labels(const anitet_mesh2d* mesh, int32_t* labels, int64_t labels_len) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    return fill(fn, "labels", mesh->mesh.edge_label, labels, labels_len, [](int32_t v) { return v; });
  });
}

int anitet_mesh2d_write(const anitet_mesh2d* mesh, const char* path) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    if (path == nullptr) return null_argument(fn, "path");
    return set_status(fn, anitet::mesh2d::write_mesh2d(path, mesh->mesh));
  });
}

int anitet_mesh2d_quality(const anitet_mesh2d* mesh, double* min_angle_deg, double* min_angle_off_input_deg,
                          double* mean_radius_ratio, double* edges_in_range) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (mesh == nullptr) return null_argument(fn, "mesh");
    const anitet::mesh2d::Quality2& q = mesh->quality;
    if (min_angle_deg) *min_angle_deg = q.min_angle_deg;
    if (min_angle_off_input_deg) *min_angle_off_input_deg = q.min_angle_free_deg;
    if (mean_radius_ratio) *mean_radius_ratio = q.mean_radius_ratio;
    if (edges_in_range) *edges_in_range = q.in_range;
    return ok();
  });
}

}  // extern "C"
