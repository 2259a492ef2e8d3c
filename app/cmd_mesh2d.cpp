// `anitet mesh2d IN -o OUT`: read a PSLG (.poly, 2D .mesh, GeoJSON), optionally from longitude
// and latitude into a local frame in metres, build its sizing field, mesh it (src/mesh2d), write
// the mesh (and back in longitude and latitude on request, the input's points exactly as given),
// print the quality figures.
#include "cmd_mesh2d.hpp"

#include <cmath>
#include <iostream>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_util.hpp"
#include "exit_codes.hpp"
#include "geo/geodetic.hpp"
#include "io/file_bytes.hpp"
#include "mesh2d/geodetic2.hpp"
#include "mesh2d/mesh2d_io.hpp"
#include "mesh2d/mesher2.hpp"
#include "mesh2d/pslg_io.hpp"
#include "mesh2d/quality2.hpp"
#include "mesh2d/sizing2.hpp"
#include "metric/metric_field.hpp"

namespace anitet::cli {

struct Mesh2dCommand::Args {
  std::string input, output;
  std::vector<std::string> also_write;
  std::vector<std::vector<double>> holes;
  bool quiet = false, json = false;
  // method
  bool split_segments = false, no_refine = false, no_optimize = false;
  int layers = 1, anisotropic_cycles = 2;
  double min_angle = 30.0;
  // sizing
  double hsize = 0, size = 1, hmin = 0, hmax = 0, hgrad = 0;
  std::string metric, background, write_metric;
  std::vector<double> distance_size;
  std::string bathymetry;
  double wave_period = 44712.0, points_per_wavelength = 40.0, min_depth = 1.0;
  bool elevation = false;
  // geography
  bool geodetic = false, planar = false, geodetic_output = false;
  std::string geo_frame = "enu";
  std::vector<double> origin;
  // ADCIRC
  std::vector<int32_t> open_labels;
  std::string title = "anitet mesh2d";
};

namespace {

constexpr const char* kCmd = "anitet mesh2d";

bool is_geojson(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == "geojson" || ext == "json";
}

// The exit code of a library error raised in `stage`.
int exit_code_of(const Status& s, const std::string& stage) {
  switch (s.code()) {
    case Error::FileNotFound: return kExitReadError;
    case Error::Parse:  // read but malformed, or a variant not read: invalid input
    case Error::UnsupportedFormat:
    case Error::BadIndex: return kExitInvalidInput;
    case Error::NotImplemented: return kExitNotImplemented;
    case Error::OutOfMemory:
    case Error::Internal:
    case Error::Cancelled: return kExitInternal;
    default: break;
  }
  // A file read but not a valid PSLG (a ring of 2 points, no edges), refused by the checks, or
  // too thin beside a segment for stage 1 in doubles.
  if (stage == "read" || stage == "validate" || stage == "front") return kExitInvalidInput;
  return s.code() == Error::InvalidArgument ? kExitUsage : kExitInternal;
}

int fail(const Status& s, int code) {
  std::cerr << kCmd << ": " << s.message() << "\n";
  return code;
}

// The user's metric: a Dimension 2 .sol on its --background, or a .vdb (read at z = 0).
Result<std::unique_ptr<SizingField>> read_user_metric(const Mesh2dCommand::Args& a) {
  const std::string ext = lower_extension(a.metric);
  if (ext == "sol") {
    if (a.background.empty())
      return Status(Error::InvalidArgument, "--metric " + a.metric + ": a .sol needs --background (its 2D .mesh)");
    return mesh2d::read_background_field(a.metric, a.background);
  }
  if (ext == "vdb") {
    if (!a.background.empty()) return Status(Error::InvalidArgument, "--background goes with a .sol, not a .vdb");
    Result<metric::MetricField> f = metric::read_metric_vdb(a.metric);
    if (!f.ok()) return f.status();
    return std::unique_ptr<SizingField>(new metric::MetricField(std::move(f.value())));
  }
  return Status(Error::UnsupportedFormat, "--metric " + a.metric + ": a .sol (with --background) or a .vdb");
}

nlohmann::ordered_json report_json(const mesh2d::TriMesh2& mesh, const mesh2d::Mesh2dStats& st,
                                   const mesh2d::Quality2& q, const std::vector<std::string>& outputs) {
  nlohmann::ordered_json j;
  j["command"] = "mesh2d";
  j["outputs"] = outputs;
  j["vertices"] = q.vertices;
  j["triangles"] = q.triangles;
  j["edges"] = q.edges;
  j["boundary_edges"] = mesh.edge_label.size();
  j["input_points"] = mesh.input_points;
  j["seconds"] = st.seconds;
  nlohmann::ordered_json stages = nlohmann::ordered_json::object();
  for (const auto& [name, sec] : st.stage_seconds)
    if (name != "done") stages[name] = sec;
  j["stage_seconds"] = stages;
  j["sizing"] = {{"source", st.sizing.source}, {"lattice", st.sizing.lattice}, {"nx", st.sizing.nx},
                 {"ny", st.sizing.ny}, {"spacing", st.sizing.spacing}};
  j["front"] = {{"t1_triangles", st.stages.t1_triangles}, {"closed_corners", st.stages.closed},
                {"epsilon_halvings", st.stages.halvings}, {"s1_edges", st.stages.s1_edges}};
  j["recovery"] = {{"t2_triangles", st.stages.t2_triangles}, {"steiner_points_on_s1", st.stages.steiner_on_s1},
                   {"coupled_triangles", st.stages.coupled}};
  j["refine"] = {{"splits", st.refine.splits}, {"segment_splits", st.refine.segment_splits},
                 {"collapses", st.refine.collapses}, {"passes", st.refine.passes}};
  j["optimize"] = {{"moves", st.optimize.moves}, {"flips", st.optimize.flips + st.refine.flips},
                   {"cleanup_moves", st.optimize.cleanup_moves}, {"cleanup_collapses", st.optimize.cleanup_collapses},
                   {"cleanup_inserts", st.optimize.cleanup_inserts}};
  j["quality"] = {{"min_angle_deg", q.min_angle_deg}, {"max_angle_deg", q.max_angle_deg},
                  {"min_angle_off_input_points_deg", q.min_angle_free_deg},
                  {"triangles_off_input_points", q.free_triangles}, {"mean_radius_ratio", q.mean_radius_ratio},
                  {"min_radius_ratio", q.min_radius_ratio}, {"edges_in_range", q.in_range},
                  {"length_min", q.length_min}, {"length_max", q.length_max}};
  return j;
}

int run(Mesh2dCommand::Args& a) {
  std::vector<std::string> outputs{a.output};
  outputs.insert(outputs.end(), a.also_write.begin(), a.also_write.end());
  for (const std::string& o : outputs)
    if (mesh2d::mesh2d_format(o).empty()) {
      std::cerr << kCmd << ": " << o << ": unknown output format (.mesh .msh .vtu, .14 or fort.14)\n";
      return kExitUsage;
    }
  if (a.geodetic && a.planar) {
    std::cerr << kCmd << ": --geodetic and --planar exclude each other\n";
    return kExitUsage;
  }
  Result<mesh2d::Pslg> read = mesh2d::read_pslg(a.input);
  if (!read.ok()) return fail(read.status(), exit_code_of(read.status(), "read"));
  mesh2d::Pslg& pslg = read.value();
  // --hole points: named "hole N" after the file's own (no line).
  for (const std::vector<double>& h : a.holes) pslg.holes.insert(pslg.holes.end(), {h[0], h[1]});
  if (!pslg.hole_origin.empty()) pslg.hole_origin.resize(pslg.num_holes());

  // Longitude and latitude: mesh in a local frame in metres.
  const bool geodetic = a.geodetic || (is_geojson(a.input) && !a.planar);
  const std::vector<double> input_xy = pslg.xy;
  std::optional<geo::GeoFrame> frame;
  if (geodetic) {
    Result<geo::GeoFrame> f = mesh2d::pslg_to_local(pslg, a.geo_frame == "utm" ? geo::FrameKind::Utm : geo::FrameKind::Enu, a.origin);
    if (!f.ok()) return fail(Status(f.status().code(), a.input + ": " + f.status().message()), kExitInvalidInput);
    frame = f.value();
    if (!a.quiet && !a.json)
      std::cout << kCmd << ": longitude/latitude input, meshed in the " << (a.geo_frame == "utm" ? "UTM" : "ENU")
                << " frame at lat " << frame->origin_lat << ", lon " << frame->origin_lon << " (metres)\n";
  } else if (a.geodetic_output) {
    std::cerr << kCmd << ": --geodetic-output needs longitude/latitude input (--geodetic, or GeoJSON)\n";
    return kExitUsage;
  }

  // Sizing sources.
  std::unique_ptr<SizingField> user;
  if (!a.metric.empty()) {
    Result<std::unique_ptr<SizingField>> f = read_user_metric(a);
    if (!f.ok()) return fail(f.status(), f.status().code() == Error::InvalidArgument ? kExitUsage : exit_code_of(f.status(), "read"));
    user = std::move(f.value());
  } else if (!a.background.empty()) {
    std::cerr << kCmd << ": --background needs --metric (a .sol)\n";
    return kExitUsage;
  }
  std::optional<mesh2d::Raster> raster;
  if (!a.bathymetry.empty()) {
    Result<mesh2d::Raster> r = mesh2d::read_ascii_grid(a.bathymetry);
    if (!r.ok()) return fail(r.status(), exit_code_of(r.status(), "read"));
    raster = std::move(r.value());
  }
  mesh2d::Mesh2dOptions o;
  o.layers = a.layers;
  o.split_segments = a.split_segments;
  o.refine = !a.no_refine;
  o.optimize = !a.no_optimize;
  o.anisotropic_cycles = a.anisotropic_cycles;
  o.optimize_options.target_angle_deg = a.min_angle;
  mesh2d::SizingOptions2& so = o.sizing;
  so.hsize = a.hsize;
  so.metric = user.get();
  so.scale = a.size;
  so.hmin = a.hmin, so.hmax = a.hmax, so.hgrad = a.hgrad;
  if (a.distance_size.size() == 2) so.distance_h0 = a.distance_size[0], so.distance_rate = a.distance_size[1];
  if (raster) {
    so.bathymetry = &*raster;
    so.wave_period = a.wave_period, so.points_per_wavelength = a.points_per_wavelength, so.min_depth = a.min_depth;
    so.elevation = a.elevation;
    if (frame) so.to_raster_frame = [&](std::vector<double>& xy) { return mesh2d::convert_pairs(*frame, xy, false); };
  }
  ProgressLine bar(!a.quiet && !a.json);
  o.progress = [&](double fraction, const char* stage) { return bar.update(stage, fraction); };
  mesh2d::Mesh2dStats st;
  Result<mesh2d::TriMesh2> result = mesh2d::mesh_pslg(pslg, o, &st);
  if (!result.ok()) {
    bar.update("failed", 1.0);
    return fail(result.status(), exit_code_of(result.status(), st.failed_stage));
  }
  mesh2d::TriMesh2& mesh = result.value();
  const mesh2d::Quality2 q = mesh2d::measure_quality(mesh);

  if (!a.write_metric.empty())
    if (Status s = mesh2d::write_sol2d(a.write_metric, mesh); !s.ok()) return fail(s, kExitReadError);
  mesh2d::Fort14Options fort;
  fort.title = a.title;
  fort.open_labels.insert(a.open_labels.begin(), a.open_labels.end());
  if (raster) {
    std::vector<double> at = mesh.xy;
    if (frame)
      if (Status s = mesh2d::convert_pairs(*frame, at, false); !s.ok()) return fail(s, kExitInternal);
    for (size_t v = 0; v < mesh.num_vertices(); ++v) {
      const double value = raster->value(at[2 * v], at[2 * v + 1]);
      fort.depth.push_back(std::isfinite(value) ? (a.elevation ? -value : value) : 0.0);
    }
  }
  if (a.geodetic_output)
    if (Status s = mesh2d::mesh_to_geodetic(*frame, mesh, input_xy); !s.ok()) return fail(s, kExitInternal);
  for (const std::string& path : outputs)
    if (Status s = mesh2d::write_mesh2d(path, mesh, fort); !s.ok()) return fail(s, kExitReadError);

  if (a.json) {
    std::cout << report_json(mesh, st, q, outputs).dump(2) << "\n";
  } else if (!a.quiet) {
    std::printf("%s: %zu triangles, %zu vertices (%zu of the input's) in %.3f s -> %s\n", kCmd, q.triangles, q.vertices,
                mesh.input_points, st.seconds, a.output.c_str());
    std::printf("  stage 1: %zu triangles on the input's segments (%zu corners closed, %zu epsilon halvings)\n",
                st.stages.t1_triangles, st.stages.closed, st.stages.halvings);
    std::printf("  stage 2: %zu Steiner points on S1's %zu edges; coupling split %zu T1 triangles\n", st.stages.steiner_on_s1,
                st.stages.s1_edges, st.stages.coupled);
    std::printf("  sizing: %s; refinement: %zu splits, %zu collapses; %zu CVT moves, %zu flips\n", st.sizing.source.c_str(),
                st.refine.splits, st.refine.collapses, st.optimize.moves, st.optimize.flips + st.refine.flips);
    char off_input[64] = "no triangle off the input's points";
    if (q.free_triangles > 0) std::snprintf(off_input, sizeof off_input, "%.2f deg off the input's points", q.min_angle_free_deg);
    std::printf("  quality: min angle %.2f deg (%s), mean radius ratio %.4f (min %.4f)\n", q.min_angle_deg, off_input,
                q.mean_radius_ratio, q.min_radius_ratio);
    std::printf("  edges of metric length in [1/sqrt2, sqrt2]: %.2f%%\n", 100.0 * q.in_range);
  }
  return kExitOk;
}

}  // namespace

Mesh2dCommand::~Mesh2dCommand() = default;

Mesh2dCommand::Mesh2dCommand(CLI::App& app) : args_(std::make_unique<Args>()) {
  Args& a = *args_;
  cmd_ = app.add_subcommand("mesh2d", "Triangle mesh of a planar straight-line graph or a coastline, keeping its segments");
  CLI::App* c = cmd_;
  c->footer(
      "Every input segment stays a union of mesh edges with no point added on it (the paper's\n"
      "method in 2D: a front layer, conforming Delaunay recovery of the new front, coupling,\n"
      "metric refinement, CVT and flips), unless --split-segments. docs/mesh2d.md has more.\n\n"
      "Examples:\n"
      "  anitet mesh2d lake.poly -o lake.mesh\n"
      "  anitet mesh2d lake.poly -o lake.msh --hsize 0.01 --hgrad 1.3\n"
      "  anitet mesh2d coast.geojson -o coast.14 --hsize 5000 --open-labels 3 --geodetic-output\n"
      "  anitet mesh2d coast.geojson -o coast.vtu --bathymetry depth.asc --hmin 500 --hmax 20000\n"
      "  anitet mesh2d ring.poly -o ring.mesh --metric m.sol --background bg.mesh");
  const char* io = "Input and output";
  c->add_option("IN", a.input, "Triangle .poly, 2D Medit .mesh (Edges), or GeoJSON polygons (lon/lat)")
      ->required()
      ->group(io);
  c->add_option("-o,--output", a.output, ".mesh .msh .vtu, or .14 / fort.14 (ADCIRC)")->required()->group(io);
  c->add_option("--also-write", a.also_write, "Also write the mesh here (repeatable)")->group(io);
  c->add_option("--hole", a.holes, "A hole point X,Y (repeatable; in the input's coordinates)")
      ->delimiter(',')
      ->expected(1, 1000)
      ->group(io);
  c->add_option("--write-metric", a.write_metric, "Write the sizing field at the mesh's vertices as a 2D .sol")
      ->group(io);
  c->add_flag("--json", a.json, "Print the report as JSON")->group(io);
  c->add_flag("-q,--quiet", a.quiet, "Print nothing but errors")->group(io);

  const char* method = "Method";
  c->add_flag("--split-segments", a.split_segments,
              "Allow points on the input's segments (better triangles at small input angles)")
      ->group(method);
  c->add_option("--layers", a.layers, "Front layers of stage 1")->capture_default_str()->check(CLI::Range(1, 20))->group(method);
  c->add_option("--min-angle", a.min_angle, "Clean-up target angle in degrees (isotropic)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 40.0))
      ->group(method);
  c->add_option("--anisotropic-cycles", a.anisotropic_cycles, "More refine + optimize rounds on an anisotropic field")
      ->capture_default_str()
      ->check(CLI::Range(0, 10))
      ->group(method);
  c->add_flag("--no-refine", a.no_refine, "Skip refinement/coarsening to the sizes")->group(method);
  c->add_flag("--no-optimize", a.no_optimize, "Skip CVT smoothing, flips and clean-up")->group(method);

  const char* sizing = "Sizing (default: the input's segment lengths, smoothed inside)";
  c->add_option("--hsize", a.hsize, "A constant target edge length")->check(CLI::PositiveNumber)->group(sizing);
  c->add_option("--size", a.size, "Scale every target length (2: twice as coarse)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber)
      ->group(sizing);
  c->add_option("--hmin", a.hmin, "Smallest target length")->check(CLI::PositiveNumber)->group(sizing);
  c->add_option("--hmax", a.hmax, "Largest target length")->check(CLI::PositiveNumber)->group(sizing);
  c->add_option("--hgrad", a.hgrad, "Gradation: sizes grow at most this factor per edge length (> 1)")
      ->check(CLI::Range(1.0, 100.0))
      ->group(sizing);
  c->add_option("--metric", a.metric, "A metric: a Dimension 2 .sol (with --background) or a .vdb (read at z = 0)")
      ->group(sizing);
  c->add_option("--background", a.background, "The 2D .mesh the --metric .sol is given on")->group(sizing);
  c->add_option("--distance-size", a.distance_size, "H0,RATE: sizes H0 + RATE d at distance d from the segments")
      ->delimiter(',')
      ->expected(2)
      ->group(sizing);
  const char* ocean = "Bathymetry (sizes from depth: T sqrt(9.81 depth) / N)";
  c->add_option("--bathymetry", a.bathymetry, "An ESRI ASCII grid (.asc) of depths (in lon/lat for geographic input)")
      ->group(ocean);
  c->add_option("--wave-period", a.wave_period, "T in seconds (the M2 tide's)")->capture_default_str()->check(CLI::PositiveNumber)->group(ocean);
  c->add_option("--points-per-wavelength", a.points_per_wavelength, "N")->capture_default_str()->check(CLI::PositiveNumber)->group(ocean);
  c->add_option("--min-depth", a.min_depth, "Shallower depths (and land) count as this")
      ->capture_default_str()
      ->check(CLI::PositiveNumber)
      ->group(ocean);
  c->add_flag("--elevation", a.elevation, "The grid holds elevations (negative under water)")->group(ocean);

  const char* geography = "Geographic input (longitude, latitude in degrees on WGS84)";
  c->add_flag("--geodetic", a.geodetic, "IN's x, y are longitude, latitude (GeoJSON's are unless --planar)")
      ->group(geography);
  c->add_flag("--planar", a.planar, "GeoJSON coordinates are planar, not lon/lat")->group(geography);
  c->add_option("--geo-frame", a.geo_frame, "The local frame: enu (tangent plane) or utm")
      ->capture_default_str()
      ->check(CLI::IsMember({"enu", "utm"}))
      ->group(geography);
  c->add_option("--origin", a.origin, "LAT,LON of the frame (default: the input's centre)")
      ->delimiter(',')
      ->expected(2)
      ->group(geography);
  c->add_flag("--geodetic-output", a.geodetic_output, "Write the mesh in lon/lat (the input's points exactly as given)")
      ->group(geography);
  const char* adcirc = "ADCIRC fort.14 output";
  c->add_option("--open-labels", a.open_labels, "Labels of open (ocean) boundaries; all other segments are land")
      ->delimiter(',')
      ->group(adcirc);
  c->add_option("--title", a.title, "The grid's title line")->capture_default_str()->group(adcirc);
}

int Mesh2dCommand::run_if_parsed() {
  if (!cmd_->parsed()) return -1;
  for (const std::vector<double>& h : args_->holes)
    if (h.size() != 2) {
      std::cerr << kCmd << ": --hole takes X,Y\n";
      return kExitUsage;
    }
  return run(*args_);
}

}  // namespace anitet::cli
