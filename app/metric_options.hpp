// The metric and geographic options of `anitet mesh`, and the sizing field they describe.
//
// Order of use in a command (coordinates must be local before any field is built):
//   1. frame = prepare_geodetic(opts, surface)      --geodetic: surface -> local metres
//   2. field = build_sizing_field(opts, surface, frame ? &*frame : nullptr)
//   3. mesh with *field
//   4. write_metric_outputs(opts, *field, surface, mesh)   --write-metric / --write-sizing
//   5. restore_geodetic(opts, frame, mesh)          --geodetic-output: mesh -> lon, lat, h
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/sizing.hpp"
#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "core/volume_mesh.hpp"
#include "geo/geodetic.hpp"
#include "metric/surface_sizing.hpp"

namespace anitet::cli {

struct MetricCliOptions {
  std::string metric;      // --metric: a .vdb (size or log-metric grids) or a .sol
  std::string background;  // --background: the .sol's tetrahedral mesh (.mesh .msh .vtu ...)
  double hmin = 0.0;       // --hmin, --hmax: size bounds (0: none)
  double hmax = 0.0;
  double hgrad = 0.0;      // --hgrad: gradation (> 1; 0: none)
  bool geodetic = false;   // --geodetic: input x, y, z are longitude, latitude, height (WGS84)
  std::vector<double> origin;       // --origin lat,lon,h (empty: the data's centre)
  std::string geo_frame = "enu";    // --geo-frame enu|utm
  bool geodetic_output = false;     // --geodetic-output: write the mesh back in lon, lat, h
  std::string write_metric;  // --write-metric FILE.sol: the field at the mesh's vertices
  std::string write_sizing;  // --write-sizing FILE.vdb: the field as OpenVDB grids
};

// Registers the options above on a (sub)command, with their --help texts and checks.
void add_metric_options(CLI::App& cmd, MetricCliOptions& options);

// With --geodetic: the frame (--origin, or the centre of the surface's points) and the surface
// converted to it in place; without: std::nullopt and the surface untouched. Errors name the
// first bad point (Error::InvalidArgument).
Result<std::optional<geo::GeoFrame>> prepare_geodetic(const MetricCliOptions& options,
                                                      SurfaceMesh& surface);

// True when the options ask for a field other than the default one, or for its output (the
// command may then leave the mesher's own default sizing alone when false).
bool wants_sizing_field(const MetricCliOptions& options);

// The sizing field: the user's (--metric) or the default surface sizing grid (metric/
// surface_sizing with `default_sizing`, e.g. MesherOptions::surface_sizing), with
// --hmin/--hmax/--hgrad applied. `surface` is in local coordinates; with a
// geodetic frame the --background mesh is converted with it (a .vdb must already be in local
// metres). Voxel fields (.vdb, the default) are bounded and graded on their voxels; a .sol is
// bounded point-wise, and with --hgrad sampled on a lattice (spacing: the surface's mean edge,
// at most 2^24 voxels) first. The returned field owns everything it refers to.
Result<std::unique_ptr<SizingField>> build_sizing_field(const MetricCliOptions& options,
                                                        const SurfaceMesh& surface,
                                                        const geo::GeoFrame* frame = nullptr,
                                                        const metric::SurfaceSizingOptions&
                                                            default_sizing = {});

// --write-metric: the field sampled at the mesh's vertices as a .sol (sizes when every sample is
// isotropic, else tensors); --write-sizing: the field's grids as a .vdb (a field that is not a
// voxel field is sampled over the surface's box first). The mesh is still in local coordinates.
Status write_metric_outputs(const MetricCliOptions& options, const SizingField& field,
                            const SurfaceMesh& surface, VolumeMesh& mesh);

// --geodetic-output with a frame: the mesh's vertices back to longitude, latitude, height.
Status restore_geodetic(const MetricCliOptions& options,
                        const std::optional<geo::GeoFrame>& frame, VolumeMesh& mesh);

}  // namespace anitet::cli
