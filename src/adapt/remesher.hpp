// The local operations of adaptation and their sweeps over the mesh (internal to src/adapt):
//   split.cpp    edges longer than split_length cut at their metric midpoint (on the surface
//                curve for a surface edge, on the ridge curve for a ridge);
//   collapse.cpp edges shorter than collapse_length removed by merging one end into the other;
//   swap.cpp     edge removal (the shell of an edge re-triangulated, 3-2, 4-4, 5-6 ... flips),
//                2-3 face flips, and surface edge swaps, each when it raises the worst quality;
//   smooth.cpp   vertex moves towards the mean of the points that would make each tet of the
//                ball regular in the metric (surface points along the surface, ridge points
//                along the ridge).
// Every operation checks that the tets it makes are positive (exact orient3d) before it changes
// anything, so a refused operation leaves the mesh as it was.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "adapt/adapt.hpp"
#include "adapt/adapt_mesh.hpp"
#include "core/metric_measures.hpp"
#include "adapt/metric_source.hpp"

namespace anitet::adapt {

using TetVerts = std::array<uint32_t, 4>;

class Remesher {
 public:
  Remesher(AdaptMesh& mesh, const MetricSource& metric, const AdaptOptions& options, AdaptStats& stats)
      : mesh_(mesh), metric_(metric), opt_(options), stats_(stats) {}

  // ---- measures ----
  double length(uint32_t a, uint32_t b) const {
    return ugawg_edge_length(mesh_.p(a), mesh_.p(b), mesh_.m(a), mesh_.m(b));
  }
  // The quality of the tet (a b c d) with point `moved` (when not kNone) at pos with metric
  // met/det: the worst of its mean ratios in its four corners' metrics (at most the UGAWG mean
  // ratio, which takes the corner of largest det).
  double quality(const uint32_t v[4], uint32_t moved = kNone, const double* pos = nullptr,
                 const double* met = nullptr, double det = 0.0) const;
  double quality(uint32_t t) const { return quality(mesh_.verts(t)); }
  void update_quality(uint32_t t) { mesh_.qual[t] = quality(t); }

  // ---- operations (true when made) ----
  bool split_edge(uint32_t a, uint32_t b, uint32_t t0);
  // The point pos (metric met) inserted on the inner edge of shell s by the metric Delaunay
  // kernel (cavity.cpp).
  bool insert_on_inner_edge(const Shell& s, const double pos[3], const double met[6], uint32_t hint);
  // p removed, merged into q (q moved to the metric midpoint with to_midpoint: inner points only).
  bool collapse_edge(uint32_t p, uint32_t q, uint32_t t_pq, bool to_midpoint = false);
  bool swap_edge(uint32_t a, uint32_t b, uint32_t t0);        // removes edge ab if better
  bool swap_face(uint32_t t, int i);                          // 2-3 flip of face i of t if better
  bool move_point(uint32_t v);

  // ---- sweeps (counts of operations made) ----
  // Split and collapse sweeps look at the edges of active points (AdaptMesh::active); the
  // smoothing sweep at active points, or all with all_points.
  size_t split_sweep();
  size_t collapse_sweep();
  size_t swap_sweep(double below);  // around tets of quality below `below`
  size_t smooth_sweep(bool all_points);

  // Replaces `old` tets by `fresh` (positive, same region), matching faces; the old boundary's
  // faces carry their neighbours and boundary flags over. With surface_label set, faces of the new
  // tets that match nothing become hull boundary faces with that label and old hull faces may
  // vanish (a surface swap). False, the mesh unchanged, when the faces do not match.
  bool replace(const std::vector<uint32_t>& old, const std::vector<TetVerts>& fresh, bool surface_change = false,
               int32_t surface_label = 0);

  // The edges of the active points with a tet each and their lengths, longer than `above` or
  // shorter than `below`.
  struct EdgeRec {
    double length;
    uint32_t a, b, t;
  };
  void collect_edges(double below, double above, std::vector<EdgeRec>& out);

  // The surface normal of boundary point v on the side of a face of normal `face_n`.
  const double* side_normal(uint32_t v, const double face_n[3]) const;
  // A point an operation is about to move or make, for surface_fit: its id (a new point: any id
  // not yet used), tag and normals.
  struct PointGeometry {
    uint32_t id;
    uint8_t tag;
    const double* nrm;
    const double* nrm2;  // a ridge point's second side (may be null)
  };
  // How well a boundary face lies on the smooth surface: the smallest cosine between its unit
  // normal n (out of the mesh when `oriented`: a hull face; an interface's normals have no side)
  // and the surface normals at its points v[0..2] (`moved`'s taken from it). 1: tangent to the
  // surface everywhere; near or below 0: folded. Operations keep it at least
  // min(what it was, kSurfaceFit).
  double surface_fit(const uint32_t v[3], const double n[3], bool oriented, const PointGeometry* moved = nullptr) const;
  static constexpr double kSurfaceFit = 0.9396926207859084;  // 20 degrees

 private:
  // Whether p may go onto q by its tags and the edge's shell.
  bool collapse_allowed(uint32_t p, uint32_t q, const Shell& s) const;
  // The surface checks of a collapse of boundary point p (ball: p's) onto q.
  bool surface_collapse_fits(uint32_t p, uint32_t q, const Shell& s, const std::vector<uint32_t>& ball);
  // Makes the collapse of p onto q (ball: p's): faces glued across the edge's tets, p renamed.
  void apply_collapse(uint32_t p, uint32_t q, const std::vector<uint32_t>& ball);
  bool move_interior(uint32_t v, const std::vector<uint32_t>& ball);
  bool move_surface(uint32_t v, const std::vector<uint32_t>& ball);
  // v tried all, half and a quarter of the way to target (a surface point in its tangent plane,
  // landing on the smooth surface), each try by try_move.
  bool move_interior_towards(uint32_t v, const std::vector<uint32_t>& ball, const double target[3], bool balance);
  bool move_surface_towards(uint32_t v, const std::vector<uint32_t>& ball, const double target[3], bool balance);
  bool move_ridge(uint32_t v, const std::vector<uint32_t>& ball);
  // Tries v at pos (metric evaluated there) with the geometry `nrm`/`nrm2`/`tng` (null: kept):
  // made when every tet of the ball stays positive and its qualities improve; with `balance`,
  // when the length energy of v's edges to nb_ falls and no quality falls below a floor
  // (smooth.cpp).
  bool try_move(uint32_t v, const std::vector<uint32_t>& ball, const double pos[3], const double* nrm,
                const double* nrm2, const double* tng, bool surface, bool balance = false);
  // v's neighbours, each once, from its ball.
  void neighbours(uint32_t v, const std::vector<uint32_t>& ball, std::vector<uint32_t>& out);
  // The sum of the squared logs of the metric lengths from pos (metric met) to the points nb.
  double length_energy(const std::vector<uint32_t>& nb, const double pos[3], const double met[6]) const;
  // Where v's edges come nearest unit length: the mean over its neighbours y of the point at unit
  // metric length from y on the line y v. Leaves the neighbours in nb_ and the length energy of v
  // where it is in nb_energy_, which the balancing tries of try_move compare with.
  bool balance_target(uint32_t v, const std::vector<uint32_t>& ball, double out[3]);
  // Where the edge ab (lengths la, lb in a's and b's metric) is cut: its parameter, the point
  // there (place(t, x, false) puts the point of parameter t in x), its metric and hint
  // (split.cpp).
  template <class Place>
  double split_parameter(uint32_t a, uint32_t b, double la, double lb, Place&& place, double pos[3], double met[6],
                         uint32_t& hint);
  // The ideal point of v over face i of t (the apex making it regular in the metric m).
  bool ideal_point(uint32_t t, int i, const double m[6], double out[3]) const;

  AdaptMesh& mesh_;
  const MetricSource& metric_;
  const AdaptOptions& opt_;
  AdaptStats& stats_;
  // Scratch.
  Shell shell_;
  std::vector<uint32_t> ball_, ball2_, moved_ball_, created_, cavity_, nb_;
  double nb_energy_ = 0.0;  // balance_target(): the length energy of v's edges to nb_ before a move
  std::vector<uint8_t> incav_;  // per tet: 1 in the cavity, 2 a seed (zero between insertions)
  std::vector<TetVerts> fresh_;
  std::vector<uint32_t> fresh_tets_;  // the tets a swap replaces
  std::vector<double> newq_;
  std::vector<EdgeRec> edges_;
  FlatKeyMap tried_;  // edges a swap sweep tried
  uint32_t first_new_ = 0;  // the first point the running split sweep made
  struct FaceMatch {
    std::array<uint32_t, 3> key;
    uint32_t src;  // new: 4 n + i; old: index into outer_
    bool is_new;
  };
  struct OuterFace {
    uint32_t adj;  // neighbour half-face or kNone
    bool bnd;
    int32_t label;
  };
  std::vector<FaceMatch> match_;
  std::vector<OuterFace> outer_;
};

}  // namespace anitet::adapt
