// Per-vertex solution fields, as a Medit/GMF SolAtVertices block holds them (.sol, .solb): any
// number of fields, each a scalar, a vector or a symmetric tensor, stored vertex by vertex (one
// record per vertex: every field's components in field order). 3D unless `dimension` is 2 (an
// ASCII .sol of the 2D mesher).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace anitet {

// The GMF type codes (libMeshb's GmfSca, GmfVec, GmfSymMat).
enum class FieldKind : int32_t { Scalar = 1, Vector = 2, SymTensor = 3 };

// Components of one field in 3D: 1, 3 (x y z) or 6 (xx xy yy xz yz zz, Medit's order and
// VolumeMesh::vertex_metric's).
constexpr int field_components(FieldKind kind) {
  return kind == FieldKind::Scalar ? 1 : kind == FieldKind::Vector ? 3 : 6;
}
// In 2D: 1, 2 (x y) or 3 (xx xy yy).
constexpr int field_components(FieldKind kind, int dimension) {
  return dimension == 2 ? (kind == FieldKind::Scalar ? 1 : kind == FieldKind::Vector ? 2 : 3) : field_components(kind);
}

constexpr const char* field_kind_name(FieldKind kind) {
  return kind == FieldKind::Scalar ? "scalar" : kind == FieldKind::Vector ? "vector" : "symmetric tensor";
}

struct VertexFields {
  std::vector<FieldKind> kinds;  // one per field, in file order
  std::vector<double> values;    // record_size() per vertex
  int dimension = 3;             // 3, or 2 for a 2D .sol

  // Components per vertex: the sum over the fields.
  size_t record_size() const {
    size_t n = 0;
    for (FieldKind k : kinds) n += size_t(field_components(k, dimension));
    return n;
  }
  size_t num_vertices() const {
    const size_t r = record_size();
    return r ? values.size() / r : 0;
  }
  // Where field f starts in a vertex's record.
  size_t offset(size_t field) const {
    size_t n = 0;
    for (size_t f = 0; f < field; ++f) n += size_t(field_components(kinds[f], dimension));
    return n;
  }
  // One field of `kind` with `values` (field_components(kind) per vertex).
  static VertexFields single(FieldKind kind, std::vector<double> values) {
    VertexFields out;
    out.kinds = {kind};
    out.values = std::move(values);
    return out;
  }
};

}  // namespace anitet
