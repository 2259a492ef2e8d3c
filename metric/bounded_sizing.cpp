#include "metric/bounded_sizing.hpp"

#include <cmath>

#include "metric/combine.hpp"
#include "metric/lattice.hpp"

namespace anitet {
namespace metric {

namespace {

double mean_edge_length(const SurfaceMesh& s) {
  double sum = 0.0;
  size_t n = 0;
  for (size_t t = 0; t < s.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = s.tri[3 * t + k], b = s.tri[3 * t + (k + 1) % 3];
      if (a >= s.num_vertices() || b >= s.num_vertices()) continue;
      const double* p = s.point(a);
      const double* q = s.point(b);
      sum += std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
      ++n;
    }
  return n ? sum / double(n) : 0.0;
}

}  // namespace

Status check_bounds(const SizeBounds& b) {
  if (b.hmin < 0.0 || b.hmax < 0.0 || !std::isfinite(b.hmin) || !std::isfinite(b.hmax))
    return Status(Error::InvalidArgument, "hmin and hmax must be >= 0");
  if (b.hmin > 0.0 && b.hmax > 0.0 && b.hmin > b.hmax) return Status(Error::InvalidArgument, "hmin must not exceed hmax");
  if (b.hgrad != 0.0 && !(b.hgrad > 1.0)) return Status(Error::InvalidArgument, "hgrad must be > 1");
  return Status::success();
}

Result<MetricField> sample_on_surface_box(const SizingField& field, const SurfaceMesh& s) {
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
  return MetricField::from_function([&field](const double p[3], double m[6]) { field.metric(p, m); }, lo, hi, h);
}

Result<std::unique_ptr<SizingField>> bounded_sizing_field(const SurfaceMesh& surface, const SizingField* base,
                                                          const SizeBounds& b,
                                                          const SurfaceSizingOptions& default_sizing) {
  if (Status st = check_bounds(b); !st.ok()) return st;
  const bool bound = b.hmin > 0.0 || b.hmax > 0.0;
  auto out = std::make_unique<OwningField>();
  if (!base) {
    Result<Lattice> lat = surface_sizing(surface, default_sizing);
    if (!lat.ok()) return lat.status();
    if (bound)
      if (Status st = bound_sizes(lat.value(), b.hmin, b.hmax); !st.ok()) return st;
    if (b.hgrad > 0.0) {
      Result<GradationStats> g = grade(lat.value(), b.hgrad);
      if (!g.ok()) return g.status();
    }
    Result<MetricField> f = MetricField::from_lattice(lat.value(), default_sizing.prune_tolerance);
    if (!f.ok()) return f.status();
    out->keep(std::move(f.value()));
  } else if (const auto* voxels = dynamic_cast<const MetricField*>(base)) {
    if (!b.any()) {
      out->refer(*voxels);
    } else {
      Result<MetricField> f = bound_and_grade(*voxels, b.hmin, b.hmax, b.hgrad);
      if (!f.ok()) return f.status();
      out->keep(std::move(f.value()));
    }
  } else if (b.hgrad > 0.0) {
    Result<MetricField> grid = sample_on_surface_box(*base, surface);
    if (!grid.ok()) return grid.status();
    grid = bound_and_grade(grid.value(), b.hmin, b.hmax, b.hgrad);
    if (!grid.ok()) return grid.status();
    out->keep(std::move(grid.value()));
  } else if (bound) {
    out->keep(BoundedField(*base, b.hmin, b.hmax));
  } else {
    out->refer(*base);
  }
  return std::unique_ptr<SizingField>(std::move(out));
}

}  // namespace metric
}  // namespace anitet
