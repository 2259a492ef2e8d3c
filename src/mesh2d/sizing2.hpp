// The 2D mesher's sizing fields (2D fields are SizingFields evaluated at z = 0): a 2D lattice of
// sizes or log-metrics (metric::Lattice with one layer; bounded and graded by metric/'s
// bound_sizes and grade), an ESRI ASCII grid for bathymetry, a .sol on a 2D background mesh,
// and the field the options describe:
//  - default: the paper's sizing grid in 2D: lattice nodes within half a cell of a segment take
//    its length and stay pinned, the domain's other nodes are smoothed (Laplacian, over-relaxed
//    Gauss-Seidel) from them;
//  - or the intersection (smallest sizes) of the sources given: a constant size, a user metric,
//    sizes growing with the distance to the input's segments (h0 + rate d), sizes from a depth
//    raster (a wavelength rule, h = T sqrt(g depth) / N), Triangle's regional area bounds;
// then scaled, clamped to [hmin, hmax] and graded (hgrad). A user metric or constant size alone,
// with no gradation, is used directly (no lattice).
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/sizing.hpp"
#include "core/status.hpp"
#include "mesh2d/domain.hpp"
#include "mesh2d/metric2.hpp"
#include "mesh2d/pslg.hpp"
#include "metric/lattice.hpp"

namespace anitet::mesh2d {

// Bilinear interpolation of a one-layer lattice: of h (components 1: linear sizes exact) or of
// log(M) (components 6, the 2D block used). Points outside take the nearest border value.
class LatticeField2 final : public SizingField {
 public:
  explicit LatticeField2(metric::Lattice lattice) : lattice_(std::move(lattice)) {}
  void metric(const double p[3], double m[6]) const override;
  bool isotropic() const override { return lattice_.components == 1; }
  const metric::Lattice& lattice() const { return lattice_; }

 private:
  metric::Lattice lattice_;
};

// An ESRI ASCII grid (.asc, GDAL's AAIGrid): ncols, nrows, xllcorner/xllcenter,
// yllcorner/yllcenter, cellsize (or dx and dy), optional NODATA_value, then nrows rows from the
// top. `value` interpolates bilinearly between cell centres; NaN outside the centres' box or
// next to a no-data cell.
struct Raster {
  int ncols = 0, nrows = 0;
  double x0 = 0, y0 = 0;  // centre of the lower left cell
  double dx = 1, dy = 1;
  std::vector<double> values;  // row-major from the bottom row; NaN for no data
  double value(double x, double y) const;
};
Result<Raster> parse_ascii_grid(std::string_view data, const std::string& name);
Result<Raster> read_ascii_grid(const std::string& path);

// A field given at the vertices of a 2D background triangle mesh (a 2D .mesh with a Dimension 2
// .sol of sizes or xx xy yy tensors): linear in h, or in log(M), inside its triangles; outside,
// the nearest triangle's value (clamped barycentric weights).
class Background2Field final : public SizingField {
 public:
  // Error::InvalidArgument unless one value set per vertex, sizes > 0 and tensors SPD;
  // EmptyInput without triangles.
  static Result<std::unique_ptr<Background2Field>> create(std::vector<double> xy, std::vector<uint32_t> tri,
                                                          const std::vector<double>& values, int components);
  void metric(const double p[3], double m[6]) const override;
  bool isotropic() const override { return components_ == 1; }

 private:
  Background2Field() = default;
  int components_ = 1;
  std::vector<double> xy_;
  std::vector<uint32_t> tri_;
  std::vector<Metric2> log_;  // log(M) per vertex (tensors), or h in xx (sizes)
  double lo_[2] = {0, 0}, cell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<uint32_t> start_, items_;  // CSR: triangles whose boxes meet each cell
};
// Reads a Dimension 2 .sol on its 2D .mesh background.
Result<std::unique_ptr<SizingField>> read_background_field(const std::string& sol_path, const std::string& mesh_path);

struct SizingOptions2 {
  double hsize = 0;                       // a constant size (> 0), or 0
  const SizingField* metric = nullptr;    // a user field, or null
  double distance_h0 = 0, distance_rate = 0;  // h = h0 + rate d (h0 > 0 to use)
  const Raster* bathymetry = nullptr;     // depth (or elevation) raster
  double wave_period = 44712.0;           // T, seconds (the M2 tide's 12.42 h)
  double points_per_wavelength = 40.0;    // N
  double min_depth = 1.0;                 // depths below (and land, no data) count as this
  bool elevation = false;                 // raster values are elevations (negative under water)
  // The raster's frame from local coordinates, in place on (x, y) pairs (null: the same).
  std::function<Status(std::vector<double>& xy)> to_raster_frame;
  double scale = 1.0;                     // every size times this
  double hmin = 0, hmax = 0, hgrad = 0;   // bounds and gradation (0: none)
  double spacing = 0;                     // lattice spacing (0: from the sources)
  size_t max_nodes = size_t(1) << 22;
};

struct SizingStats2 {
  bool lattice = false;
  int nx = 0, ny = 0;
  double spacing = 0;
  int smoothing_iterations = 0;
  int gradation_passes = 0;
  std::string source;  // "boundary", "constant", "metric", ... joined by " + "
};

Result<std::unique_ptr<SizingField>> build_sizing2(const Pslg& pslg, const Domain& domain, const SizingOptions2& options,
                                                   SizingStats2* stats = nullptr);

}  // namespace anitet::mesh2d
