// Point location in a tetrahedral mesh: the tet holding a point and the point's barycentric
// weights in it, for interpolating per-vertex values (background-mesh metrics, field transfer).
//
// A visibility walk (to the neighbour across the face of the most negative barycentric) from a
// start tet: the caller's, or the one a coarse grid keeps for the point's cell (about two tets
// across, so a walk takes a few steps). When the walk leaves the mesh or does not end, the point
// is found from the closest point q of the mesh's boundary (a BVH of its boundary faces): the ball
// around the point through q holds no boundary, so a point inside the mesh is reached by a walk
// from q's tet; when that walk leaves too, the point is outside and takes q's weights in q's tet
// (clamped). Immutable after create(): locate() may be called from any number of threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/bvh.hpp"
#include "core/status.hpp"
#include "core/volume_mesh.hpp"

namespace anitet {
namespace metric {

class TetLocator {
 public:
  static constexpr uint32_t kNoTet = 0xffffffffu;
  // A point within this relative barycentric tolerance of a tet counts as inside it (rounding).
  static constexpr double kInsideTolerance = 1e-10;

  struct Location {
    uint32_t tet = kNoTet;
    double weight[4] = {1.0, 0.0, 0.0, 0.0};  // of the tet's vertices: >= 0, sum 1
    bool outside = false;                     // beyond rounding: the weights are q's
    double distance = 0.0;                    // outside: from the point to q
  };

  // Copies the mesh's points and tets. Error::EmptyInput without tets, Error::BadIndex for a tet
  // referring to a missing vertex, Error::InvalidMesh for a face shared by three tets.
  static Result<TetLocator> create(const VolumeMesh& mesh);

  // Where p is; the walk starts at `start` when it is a tet (e.g. a neighbouring point's), else
  // at the grid's tet for p. The answer depends on `start` only for points on a face or an edge
  // (to rounding, the same weights).
  Location locate(const double p[3], uint32_t start = kNoTet) const;

  size_t num_vertices() const { return xyz_.size() / 3; }
  size_t num_tets() const { return tet_.size() / 4; }
  const uint32_t* tet(size_t t) const { return &tet_[4 * t]; }

 private:
  TetLocator() = default;
  void build_start_grid();
  void build_boundary();
  // The walk from `t`: true with `out` filled when p is inside a tet; else false with
  // `exit_face` (4 t + i) the boundary face it left through, or kNoTet (no end, or a flat tet).
  bool walk(const double p[3], uint32_t t, Location& out, uint32_t& exit_face) const;
  // Barycentric weights of p in tet t (unnormalised sum test: false for a flat tet).
  bool weights(const double p[3], uint32_t t, double w[4]) const;
  // The boundary face closest to p (ties: the lowest index) and its point q; `bound` is an upper
  // bound of the distance (HUGE_VAL: none known).
  uint32_t closest_boundary_face(const double p[3], double bound, double q[3]) const;
  uint32_t start_tet(const double p[3]) const;

  std::vector<double> xyz_;
  std::vector<uint32_t> tet_;
  std::vector<uint32_t> neighbour_;  // 4 per tet: across the face opposite vertex i, or kNoTet
  // Start grid: one tet per cell (the lowest-numbered tet whose centroid is in it, else a nearby
  // cell's).
  Box3 box_ = {{0, 0, 0}, {0, 0, 0}};  // of the vertices
  double lo_[3] = {0, 0, 0}, cell_ = 1.0;
  int dims_[3] = {1, 1, 1};
  std::vector<uint32_t> cell_tet_;
  // Boundary faces (4 t + i), their triangles (3 vertices each) and BVH.
  std::vector<uint32_t> boundary_face_;
  std::vector<uint32_t> boundary_tri_;
  TriangleBVH boundary_bvh_;
};

}  // namespace metric
}  // namespace anitet
