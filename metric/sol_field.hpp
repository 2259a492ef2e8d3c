// Medit .sol per-vertex fields and their interpolation on a background tetrahedral mesh.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/sizing.hpp"
#include "core/status.hpp"
#include "core/volume_mesh.hpp"
#include "tet_locator.hpp"

namespace anitet {
namespace metric {

struct SolField {
  int dimension = 3;           // Medit's Dimension: 3, or 2 (the 2D mesher's fields)
  // 1 (size h, Medit type 1) or, for type 3, the tensor: 6 in 3D (xx xy yy xz yz zz), 3 in 2D
  // (xx xy yy).
  int components = 0;
  std::vector<double> values;  // components per vertex
  size_t num_vertices() const { return components ? values.size() / size_t(components) : 0; }
};

// A metric as a Medit .sol (ASCII, read_medit_sol; Dimension 3, or 2 for the 2D mesher) or, for
// a path ending in .solb, a binary GMF .solb (read_solb, 3D): one SolAtVertices field of type 1
// or 3. Error::Parse naming the line or byte offset for malformed or truncated input,
// Error::UnsupportedFormat for other fields (vectors, several fields).
Result<SolField> parse_sol(std::string_view data, const std::string& name);
Result<SolField> read_sol(const std::string& path);

// Samples a field at the mesh's vertices into mesh.vertex_metric (6 values per vertex, or the
// size 1/sqrt(m_xx) per vertex when `as_size`, for isotropic fields), ready for write_sol.
void sample_at_vertices(const SizingField& field, VolumeMesh& mesh, bool as_size = false);
// The same, choosing: sizes when every tensor sampled is isotropic (a multiple of I), else
// tensors (what --write-metric and anitet_mesh_sample_metric write).
void sample_sizes_or_tensors(const SizingField& field, VolumeMesh& mesh);

// The field of a .sol on its background mesh: inside a tet, barycentric interpolation of h
// (isotropic: linear fields are exact) or of log(M) (tensors, log-Euclidean). Points outside the
// mesh take the value at the closest point of its boundary. Point location: TetLocator.
// Immutable, thread-safe.
class BackgroundMeshField final : public SizingField {
 public:
  // Error::InvalidArgument unless there is one value set per mesh vertex, sizes > 0 and metrics
  // SPD, and the field is three-dimensional; the errors of TetLocator::create (Error::EmptyInput
  // without tets, Error::BadIndex, Error::InvalidMesh for a face of three tets).
  static Result<BackgroundMeshField> create(const VolumeMesh& mesh, const SolField& field);

  void metric(const double p[3], double m[6]) const override;
  int components() const { return components_; }

 private:
  explicit BackgroundMeshField(TetLocator locator) : locator_(std::move(locator)) {}

  TetLocator locator_;
  int components_ = 1;
  std::vector<double> value_;  // h, or log(M) (6 per vertex)
};

}  // namespace metric
}  // namespace anitet
