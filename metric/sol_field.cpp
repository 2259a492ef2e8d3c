#include "sol_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "io/file_bytes.hpp"
#include "io/gmf_format.hpp"
#include "io/sol_io.hpp"
#include "spd.hpp"

namespace anitet {
namespace metric {
namespace {

// A metric is one field: sizes (scalar) or tensors.
Result<SolField> metric_sol(Result<VertexFields> read, const std::string& name) {
  if (!read.ok()) return read.status();
  const VertexFields& f = read.value();
  if (f.kinds.size() != 1 || f.kinds[0] == FieldKind::Vector) {
    std::string kinds;
    for (const FieldKind k : f.kinds) kinds += (kinds.empty() ? "" : ", ") + std::string(field_kind_name(k));
    return Status(Error::UnsupportedFormat, name + ": a metric is one field of sizes (type 1) or symmetric tensors "
                                                   "(type 3); this file has " + kinds);
  }
  SolField out;
  out.components = field_components(f.kinds[0]);
  out.values = std::move(read.value().values);
  return out;
}

}  // namespace

Result<SolField> parse_sol(std::string_view data, const std::string& name) {
  return metric_sol(read_medit_sol(data, name), name);
}

Result<SolField> read_sol(const std::string& path) {
  Result<std::string> bytes = read_file_bytes(path);
  if (!bytes.ok()) return bytes.status();
  if (lower_extension(path) == "solb") return metric_sol(read_solb(bytes.value(), path), path);
  return parse_sol(bytes.value(), path);
}

void sample_at_vertices(const SizingField& field, VolumeMesh& mesh, bool as_size) {
  const size_t nv = mesh.num_vertices();
  mesh.vertex_metric.assign(nv * (as_size ? 1 : 6), 0.0);
  for (size_t v = 0; v < nv; ++v) {
    double m[6];
    field.metric(mesh.point(v), m);
    if (as_size) mesh.vertex_metric[v] = 1.0 / std::sqrt(m[0]);
    else std::copy(m, m + 6, &mesh.vertex_metric[6 * v]);
  }
}

Result<BackgroundMeshField> BackgroundMeshField::create(const VolumeMesh& mesh,
                                                        const SolField& field) {
  const size_t nv = mesh.num_vertices(), nt = mesh.num_tets();
  if (nt == 0) return Status(Error::EmptyInput, "the background mesh has no tetrahedron");
  if ((field.components != 1 && field.components != 6) || field.num_vertices() != nv ||
      field.values.size() != nv * size_t(field.components))
    return Status(Error::InvalidArgument,
                  "the .sol has " + std::to_string(field.num_vertices()) +
                      " values for a mesh of " + std::to_string(nv) + " vertices");
  BackgroundMeshField f;
  f.components_ = field.components;
  f.xyz_ = mesh.xyz;
  f.tet_ = mesh.tet;
  for (uint32_t v : f.tet_)
    if (v >= nv) return Status(Error::BadIndex, "a tet refers to a missing vertex");
  if (field.components == 1) {
    f.value_ = field.values;
    for (size_t v = 0; v < nv; ++v)
      if (!(f.value_[v] > 0.0) || !std::isfinite(f.value_[v]))
        return Status(Error::InvalidArgument, "size <= 0 at vertex " + std::to_string(v));
  } else {
    f.value_.resize(6 * nv);
    for (size_t v = 0; v < nv; ++v)
      if (!sym_log(&field.values[6 * v], &f.value_[6 * v]))
        return Status(Error::InvalidArgument, "metric not SPD at vertex " + std::to_string(v));
  }
  // Bucket grid: about one tet per cell.
  double hi[3];
  for (int k = 0; k < 3; ++k) {
    f.lo_[k] = HUGE_VAL;
    hi[k] = -HUGE_VAL;
  }
  for (size_t v = 0; v < nv; ++v)
    for (int k = 0; k < 3; ++k) {
      f.lo_[k] = std::min(f.lo_[k], f.xyz_[3 * v + k]);
      hi[k] = std::max(hi[k], f.xyz_[3 * v + k]);
    }
  const double ext = std::max({hi[0] - f.lo_[0], hi[1] - f.lo_[1], hi[2] - f.lo_[2], 1e-300});
  const double vol = std::max((hi[0] - f.lo_[0]) * (hi[1] - f.lo_[1]) * (hi[2] - f.lo_[2]),
                              ext * ext * ext * 1e-9);
  f.cell_ = std::cbrt(vol / double(nt)) * 1.5;
  // Grow the cells until there are at most ~4 per tet (a flat mesh would otherwise ask for many).
  for (;;) {
    double cells = 1.0;
    for (int k = 0; k < 3; ++k) {
      f.dims_[k] = std::max(1, std::min(1024, int((hi[k] - f.lo_[k]) / f.cell_) + 1));
      cells *= f.dims_[k];
    }
    if (cells <= 4.0 * double(nt) + 64.0) break;
    f.cell_ *= 1.25;
  }
  const size_t ncell = size_t(f.dims_[0]) * f.dims_[1] * f.dims_[2];
  auto cell_range = [&](size_t t, int c0[3], int c1[3]) {
    for (int k = 0; k < 3; ++k) {
      double mn = HUGE_VAL, mx = -HUGE_VAL;
      for (int i = 0; i < 4; ++i) {
        const double x = f.xyz_[3 * f.tet_[4 * t + i] + k];
        mn = std::min(mn, x);
        mx = std::max(mx, x);
      }
      c0[k] = std::min(f.dims_[k] - 1, std::max(0, int((mn - f.lo_[k]) / f.cell_)));
      c1[k] = std::min(f.dims_[k] - 1, std::max(0, int((mx - f.lo_[k]) / f.cell_)));
    }
  };
  f.cell_start_.assign(ncell + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<uint32_t> fill;
    if (pass == 1) {
      for (size_t c = 0; c < ncell; ++c) f.cell_start_[c + 1] += f.cell_start_[c];
      f.cell_tets_.resize(f.cell_start_[ncell]);
      fill.assign(f.cell_start_.begin(), f.cell_start_.end() - 1);
    }
    for (size_t t = 0; t < nt; ++t) {
      int c0[3], c1[3];
      cell_range(t, c0, c1);
      for (int z = c0[2]; z <= c1[2]; ++z)
        for (int y = c0[1]; y <= c1[1]; ++y)
          for (int x = c0[0]; x <= c1[0]; ++x) {
            const size_t c = (size_t(z) * f.dims_[1] + y) * f.dims_[0] + x;
            if (pass == 0) ++f.cell_start_[c + 1];
            else f.cell_tets_[fill[c]++] = uint32_t(t);
          }
    }
  }
  return f;
}

int64_t BackgroundMeshField::locate(const double p[3], double w[4]) const {
  int c[3];
  for (int k = 0; k < 3; ++k) {
    const double x = (p[k] - lo_[k]) / cell_;
    c[k] = x >= 0 ? std::min(dims_[k] - 1, int(x)) : 0;
  }
  const size_t cell = (size_t(c[2]) * dims_[1] + c[1]) * dims_[0] + c[0];
  int64_t best = -1;
  double best_min = -HUGE_VAL;
  for (uint32_t i = cell_start_[cell]; i < cell_start_[cell + 1]; ++i) {
    const uint32_t t = cell_tets_[i];
    const double* a = &xyz_[3 * tet_[4 * t]];
    const double* b = &xyz_[3 * tet_[4 * t + 1]];
    const double* cc = &xyz_[3 * tet_[4 * t + 2]];
    const double* d = &xyz_[3 * tet_[4 * t + 3]];
    // Barycentrics by Cramer's rule on (b-a, c-a, d-a).
    const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double e2[3] = {cc[0] - a[0], cc[1] - a[1], cc[2] - a[2]};
    const double e3[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    const double q[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    auto det = [](const double* u, const double* v, const double* s) {
      return u[0] * (v[1] * s[2] - v[2] * s[1]) - u[1] * (v[0] * s[2] - v[2] * s[0]) +
             u[2] * (v[0] * s[1] - v[1] * s[0]);
    };
    const double vol = det(e1, e2, e3);
    if (vol == 0.0) continue;
    double l[4];
    l[1] = det(q, e2, e3) / vol;
    l[2] = det(e1, q, e3) / vol;
    l[3] = det(e1, e2, q) / vol;
    l[0] = 1.0 - l[1] - l[2] - l[3];
    const double mn = std::min({l[0], l[1], l[2], l[3]});
    if (mn > best_min) {
      best_min = mn;
      best = t;
      std::copy(l, l + 4, w);
      if (mn >= 0.0) break;
    }
  }
  if (best >= 0 && best_min < 0.0) {
    // Outside every candidate: clamp the weights onto the best tet.
    double s = 0.0;
    for (int i = 0; i < 4; ++i) s += (w[i] = std::max(w[i], 0.0));
    for (int i = 0; i < 4; ++i) w[i] /= s;
  }
  return best;
}

void BackgroundMeshField::metric(const double p[3], double m[6]) const {
  double w[4];
  const int64_t t = locate(p, w);
  uint32_t v[4];
  if (t >= 0) {
    for (int i = 0; i < 4; ++i) v[i] = tet_[4 * size_t(t) + i];
  } else {
    // No tet near p: the nearest vertex.
    size_t best = 0;
    double bd = HUGE_VAL;
    for (size_t i = 0; i < xyz_.size() / 3; ++i) {
      const double d = (xyz_[3 * i] - p[0]) * (xyz_[3 * i] - p[0]) +
                       (xyz_[3 * i + 1] - p[1]) * (xyz_[3 * i + 1] - p[1]) +
                       (xyz_[3 * i + 2] - p[2]) * (xyz_[3 * i + 2] - p[2]);
      if (d < bd) bd = d, best = i;
    }
    v[0] = v[1] = v[2] = v[3] = uint32_t(best);
    w[0] = 1.0;
    w[1] = w[2] = w[3] = 0.0;
  }
  if (components_ == 1) {
    double h = 0.0;
    for (int i = 0; i < 4; ++i) h += w[i] * value_[v[i]];
    isotropic_metric(h, m);
    return;
  }
  double l[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 6; ++c) l[c] += w[i] * value_[6 * size_t(v[i]) + c];
  sym_exp(l, m);
}

}  // namespace metric
}  // namespace anitet
