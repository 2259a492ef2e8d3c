#include "sol_field.hpp"

#include <algorithm>
#include <cmath>
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
  out.dimension = f.dimension;
  out.components = field_components(f.kinds[0], f.dimension);
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

void sample_sizes_or_tensors(const SizingField& field, VolumeMesh& mesh) {
  sample_at_vertices(field, mesh, false);
  const size_t nv = mesh.num_vertices();
  for (size_t v = 0; v < nv; ++v) {
    const double* m = &mesh.vertex_metric[6 * v];
    if (m[1] != 0.0 || m[3] != 0.0 || m[4] != 0.0 || m[0] != m[2] || m[0] != m[5]) return;
  }
  for (size_t v = 0; v < nv; ++v) mesh.vertex_metric[v] = 1.0 / std::sqrt(mesh.vertex_metric[6 * v]);
  mesh.vertex_metric.resize(nv);
}

Result<BackgroundMeshField> BackgroundMeshField::create(const VolumeMesh& mesh,
                                                        const SolField& field) {
  const size_t nv = mesh.num_vertices();
  if (mesh.num_tets() == 0) return Status(Error::EmptyInput, "the background mesh has no tetrahedron");
  if (field.dimension != 3)
    return Status(Error::InvalidArgument, "the .sol is two-dimensional (Dimension 2): it is for `anitet mesh2d`");
  if ((field.components != 1 && field.components != 6) || field.num_vertices() != nv ||
      field.values.size() != nv * size_t(field.components))
    return Status(Error::InvalidArgument,
                  "the .sol has " + std::to_string(field.num_vertices()) +
                      " values for a mesh of " + std::to_string(nv) + " vertices");
  Result<TetLocator> locator = TetLocator::create(mesh);
  if (!locator.ok()) return locator.status();
  BackgroundMeshField f(std::move(locator).value());
  f.components_ = field.components;
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
  return f;
}

void BackgroundMeshField::metric(const double p[3], double m[6]) const {
  const TetLocator::Location where = locator_.locate(p);
  const uint32_t* v = locator_.tet(where.tet);
  const double* w = where.weight;
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
