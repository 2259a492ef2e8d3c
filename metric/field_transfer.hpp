// Per-vertex fields carried from one tetrahedral mesh to new points (an adapted mesh's
// vertices): each point is located in the old mesh (TetLocator), then every field is
// interpolated with the point's barycentric weights: linearly for scalars and vectors (linear
// fields are carried exactly, smooth ones with an O(h^2) error), in log space for metric tensors
// (log-Euclidean: log M interpolated, mapped back with exp, so the result stays SPD and a
// constant metric stays itself). A point outside the old mesh (a boundary that moved, e.g. onto
// the curved geometry) takes the value at the closest point of the old mesh's boundary; such
// points are counted. On every core (TBB); the result does not depend on the threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/status.hpp"
#include "core/vertex_fields.hpp"
#include "core/volume_mesh.hpp"
#include "tet_locator.hpp"

namespace anitet {
namespace metric {

// How symmetric tensor fields are interpolated.
enum class TensorInterpolation {
  Auto,          // log-Euclidean when every tensor of the field is SPD, else linear
  LogEuclidean,  // metrics: Error::InvalidArgument naming the vertex of a tensor that is not SPD
  Linear,        // component by component (stresses and other tensors that need not be SPD)
};

// Where the points lie in the old mesh.
struct PointLocations {
  std::vector<uint32_t> tet;     // 1 per point
  std::vector<double> weight;    // 4 per point: of the tet's vertices, >= 0, sum 1
  size_t outside = 0;            // points outside the old mesh (beyond rounding)
  double max_outside_distance = 0.0;
  size_t num_points() const { return tet.size(); }
};

struct TransferReport {
  size_t outside = 0;                 // as PointLocations
  double max_outside_distance = 0.0;
  std::vector<bool> log_euclidean;    // per field: interpolated in log space
};

// Locates num_points points (xyz: 3 each) on every core. Error::InvalidArgument for a point that
// is not finite (naming it).
Result<PointLocations> locate_points(const TetLocator& old_mesh, const double* xyz, size_t num_points);

// Every field of `fields` (values at the old mesh's vertices) at the located points, in the same
// field order and kinds. Error::InvalidArgument when the fields do not have one record per old
// vertex ("a field on another mesh"), or for a non-SPD tensor with LogEuclidean.
Result<VertexFields> interpolate_fields(const TetLocator& old_mesh, const VertexFields& fields,
                                        const PointLocations& where,
                                        TensorInterpolation tensors = TensorInterpolation::Auto,
                                        TransferReport* report = nullptr);

// Both at once: `fields` given at old_mesh's vertices, interpolated at new_xyz (3 per point).
// The errors of TetLocator::create, locate_points and interpolate_fields.
Result<VertexFields> transfer_fields(const VolumeMesh& old_mesh, const VertexFields& fields,
                                     const std::vector<double>& new_xyz,
                                     TensorInterpolation tensors = TensorInterpolation::Auto,
                                     TransferReport* report = nullptr);

}  // namespace metric
}  // namespace anitet
