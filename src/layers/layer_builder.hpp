// Internal: the state of one build_layers run (see layers.hpp for the algorithm and its
// guarantees). layers.cpp holds the driver and the face step, push_step.cpp the push step.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/sizing.hpp"
#include "core/status.hpp"
#include "core/surface_mesh.hpp"
#include "layers/front.hpp"
#include "layers/layers.hpp"
#include "layers/tet_fit.hpp"

namespace anitet::layers {

std::string point_text(const double* p);

// body(i) for every i in [0, n), on the cores TBB gives: each i writes only its own data, so the
// result does not depend on the threads.
template <class Body>
void for_each_index(size_t n, Body&& body) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 512), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) body(i);
  });
}

class LayerBuilder {
 public:
  LayerBuilder(const SurfaceMesh& s, const SizingField& sizing, const LayersOptions& options,
               LayersOutput& out);

  Status run();

 private:
  // A push task of push_sides: a copy of `main`'s state (vertex coordinates, plans, the front
  // triangles on its side of the cut) into which it builds its own vertices and tets, numbered
  // after main's, for merge_side to append.
  LayerBuilder(const LayerBuilder& main, int axis, double cut, bool low_side);

  // ---- face step (layers.cpp) ----
  Status face_tet(uint32_t f, int layer);

  // ---- push step (push_step.cpp) ----
  Status push_step(const std::vector<uint32_t>& vertices);
  // The pushes of `order` (vertices with a valid plan) on two cores: the vertices whose push
  // reaches across a plane (layers.hpp: the one fewest reach across) are pushed first, one by
  // one; then those whose push (their star, their neighbours' stars and their apex's reach) stays
  // on one side of it are pushed by two tasks, one per side, each on a copy of its side of the
  // front. Returns the vertices left for the caller, in their order: those whose reach still
  // crosses the plane after four rounds of first pushes, and those whose planned push did not
  // fit. The result does not depend on the threads.
  Result<std::vector<uint32_t>> push_sides(const std::vector<uint32_t>& order);
  // Pushes v as the layer's loop does (push_vertex, and what a failure means).
  Status push_one(uint32_t v);
  // The planned push of a's whole star, while the plan still sees it (push_vertex's first try, a
  // task's only one): 1 pushed, 0 tried and did not fit (nothing changed but counters), -1 not
  // tried.
  int planned_push(uint32_t a, const std::vector<uint32_t>& star, int layer);
  // A task's push of a: its planned push only; false, with nothing changed but counters and a
  // still waiting, when it does not fit.
  bool push_planned(uint32_t a);
  // Appends task w's vertices, tets and front changes (w copied this builder when it had nv0
  // vertices).
  void merge_side(const LayerBuilder& w, uint32_t nv0);
  // Takes a off the front: one push of its whole star, or (when no direction sees the whole
  // star) several pushes of visible parts of it.
  Status push_vertex(uint32_t a, int layer);
  // Whether a, failing its whole-star push, stops instead of being pushed in parts, and the
  // status push_vertex returns then (push_one stops the vertex for the layer).
  bool stops_instead_of_partial(uint32_t a) const;
  Status whole_push_failed(uint32_t a, int layer) const;
  // Joins a new point near a to the star triangles `part` of a, halving until it fits.
  // Joins a new point a + s disp to the star triangles `part` of a, for s = 1, shrink, shrink^2,
  // ... until it fits.
  Status push_part(uint32_t a, const std::vector<uint32_t>& part, const double disp[3], int layer);
  // Scales disp to the fraction that makes the best tets: the cone's own, and those the waiting
  // neighbours will build on its outer faces from their planned points. When that is still poor
  // (an edge-on triangle), a pattern search in space gives `searched` and returns true. Both
  // still see every triangle of `part` (the cone's tets are positive in floating point).
  bool best_apex(uint32_t a, const std::vector<uint32_t>& part, double disp[3],
                 double searched[3]) const;
  // Opens a front transaction and joins `apex` to every triangle of `part`, tet by tet, each
  // accepted only when it fits exactly; false at the first that does not. The caller commits or
  // rolls back the transaction.
  bool join_to_front(const std::vector<uint32_t>& part, uint32_t apex);
  // Whether the cone of tets over `part` from a + scale d fits on the front now (all undone).
  bool cone_fits_near(uint32_t a, const std::vector<uint32_t>& part, const double d[3],
                      double scale);
  // Unit normals (into the region) and corner angles at a of the given star triangles, in a's
  // metric frame (see frame_of).
  void star_normals(uint32_t a, const std::vector<uint32_t>& star, std::vector<double>& normals,
                    std::vector<double>& weights) const;
  // The normals alone (the angles cost an atan2 each: skipped where only margins are asked).
  void star_normals(uint32_t a, const std::vector<uint32_t>& star, std::vector<double>& normals) const;
  void star_normals(uint32_t a, const std::vector<uint32_t>& star, std::vector<double>& normals,
                    std::vector<double>* weights) const;
  // Stage 1's directions and margins are measured in the metric at the vertex: the star is mapped
  // by U (M = U^T U) before its normals and angles are taken. A push that makes walls of
  // stretched neighbours in space (the sides of bench/aniso_cube: triangles 0.1 x 0.001) is a
  // fair one in the metric, and its margins say so. Visibility (the sign of d . n) does not
  // depend on the frame. Null when the metric at a is isotropic: then nothing is mapped, the
  // Euclidean figures bit for bit. Cached per vertex (measured where it first was asked); never
  // asked when the sizing says it is isotropic everywhere.
  const double* frame_of(uint32_t a) const;
  // A direction in space -> the unit direction in a's frame, and back (both unit).
  std::array<double, 3> into_frame(uint32_t a, const double d[3]) const;
  void out_of_frame(uint32_t a, double d[3]) const;
  // The unit normal of the triangle (p0 p1 p2) in a's frame.
  void frame_normal(uint32_t a, const double* p0, const double* p1, const double* p2, double n[3]) const;
  // The longest run of consecutive star triangles of a that a push along d can take off (see
  // push_step.cpp); scale: the local size. Empty when there is none.
  std::vector<uint32_t> visible_run(uint32_t a, const std::vector<uint32_t>& star, double scale,
                                    double d[3]);
  bool keeps_plans_visible(int halvings);
  // The push distance along d: the size, capped by the free distance to the front across.
  double target_height(uint32_t a, const double d[3]) const;
  // The push distance along d from the sizing alone (BL: h0 r^i).
  double sized_height(uint32_t a, const double d[3]) const;
  // Smooths the planned points tangentially (see Plan).
  void plan_targets(const std::vector<uint32_t>& vertices);
  // Lowers planned heights so that neighbours differ by at most the factor g, up to `rings`
  // edges away from a low vertex.
  void limit_gradation(const std::vector<std::pair<uint32_t, uint32_t>>& edges, double g,
                       int rings);
  // The layer's front edges between planned vertices (each once).
  std::vector<std::pair<uint32_t, uint32_t>> planned_edges(const std::vector<uint32_t>& vertices) const;

  // ---- after a layer (improve_step.cpp) ----
  // Moves the layer's new front vertices whose worst tet is below `below`, when valid (see the
  // file).
  void improve_layer(uint32_t first_new_vertex, double below);
  // A new front vertex's candidate moves, best first: those whose worst tet beats its present one
  // (below `below`) by 0.01. False when it needs none or has no candidate.
  struct Improvement {
    double edge = 0.0;  // the mean front edge at the vertex
    std::vector<std::pair<double, std::array<double, 3>>> ranked;
  };
  bool candidate_moves(uint32_t v, const std::vector<uint32_t>& tets, double below,
                       Improvement& out) const;
  // After the last layer: moves T1's interior vertices (off S, off the final front, in no BL
  // tet) to raise the worst tet around each, a move kept only when every tet around stays
  // positive (exact). Their link is fixed, so the tets still tile the same star.
  void smooth_interior(int passes);
  // The worst radius ratio of `tets` with v placed at `at` (-1 when one is not positive). Stops
  // at the first tet at or below `stop_at` and returns its value (its index in *stopped_at):
  // callers that only ask whether the worst beats a bar pass the bar and skip the rest of the tets.
  double worst_tet_with(uint32_t v, const double* at, const std::vector<uint32_t>& tets,
                        double stop_at = -2.0, size_t* stopped_at = nullptr) const;
  // Moves `best` (v's position) along the axes by `step`, halved when nothing improves until
  // below `stop`, keeping each move that raises worst_tet_with over `tets` (best_q).
  void compass_search(uint32_t v, const std::vector<uint32_t>& tets, double step, double stop,
                      std::array<double, 3>& best, double& best_q) const;
  bool relocate_if_valid(uint32_t v, const double to[3], const std::vector<uint32_t>& tets);
  // No front triangle outside v's ring comes within `gap` of `to`.
  bool keeps_clear(uint32_t v, const double to[3], double gap) const;
  // The distance from `at` to the front outside v's ring, looked for up to `within`; the search
  // stops as soon as a triangle closer than `stop_below` is found.
  double clear_distance(uint32_t v, const double at[3], double within, double stop_below = 0.0) const;

  // ---- boundary-layer mode (bl_step.cpp) ----
  // Wall flags, the number of BL layers; NotImplemented for a wall shell that is not whole.
  Status setup_boundary_layer();
  // Smoothed normals and BL heights (h0 r^i, reduced where needed) for the wall vertices.
  void plan_boundary_layer(const std::vector<uint32_t>& vertices);
  // h0 r^i along d, capped by the share of the free distance across (fronts colliding).
  double bl_height(uint32_t a, const double d[3]) const;
  void record_bl_push(uint32_t a, uint32_t moved);
  // The junction vertices among `vertices` (BoundaryLayerOptions::column_next) pushed to their
  // columns' next points, in increasing id order, and taken out of the list.
  void push_junctions(std::vector<uint32_t>& vertices);
  // One of them: the cone from `next` over a's star closes the band triangles holding `next`;
  // when it does not fit, a waits (counted as reduced).
  void push_junction(uint32_t a, uint32_t next);
  // The wall vertex below v (its column) had a reduced or stopped BL layer.
  void mark_bl_reduced(uint32_t v);
  double bl_nominal() const;
  // The free distance from p along the unit direction d to the front (triangles with a corner
  // in `skip` ignored), looked for up to max_dist; +inf when free.
  double clearance(const double p[3], const double d[3], double max_dist,
                   const std::vector<uint32_t>& skip) const;

  // ---- shared (layers.cpp) ----
  void commit_tet(const uint32_t v[4], const uint32_t closing[4]);
  // The input triangle below front triangle f (input triangles occupy slots 0..n-1 at the start).
  uint32_t column_of(uint32_t f) const;
  void truncate_tets(size_t n);
  Status finish();

  LayersOutput own_out_;  // a push task's output (out_ refers to it); unused by the main builder
  const SurfaceMesh& s_;
  const SizingField& sizing_;
  const LayersOptions& opt_;
  LayersOutput& out_;
  TetMesh& mesh_;
  Front front_;
  FitCounters fit_;

  // The push step's plan for each vertex of the layer's starting front: a direction that sees
  // its star, and the margin (min d . n over the star) that pushes of its neighbours must leave
  // it. A push whose new triangles would leave a waiting neighbour without a direction that sees
  // its star with that margin is shortened (halved) like one that does not fit: as the push
  // distance tends to 0 the new triangles tend to the ones they replace, which respect the
  // margin, so this terminates too. Vertices whose star no single direction sees get no plan and
  // are pushed last, when their neighbours' pushes have often turned their star into a cup seen
  // from the region; if not, their star is taken off in visible parts.
  //
  // Planned points a + height d are chosen for all the layer's vertices before the first push:
  // heights from the sizing, capped by a share of the free distance to the front across, then the
  // points smoothed tangentially, so that the next front is even.
  struct Plan {
    double d[3] = {0, 0, 0};
    double height = 0.0;
    double size = 0.0;  // the height from the sizing alone, before any cap
    double keep = 0.0;  // the margin to keep
    bool valid = false;
    bool waiting = false;
  };
  std::vector<Plan> plan_;
  struct Replan {
    uint32_t v;
    double d[3];
  };
  std::vector<Replan> replans_;  // new plans the push being tried needs (applied on success)
  std::vector<uint32_t> added_;  // front triangles added by the push being tried
  std::vector<uint32_t> near_;   // join_to_front: the front triangles near the cone being joined
  std::vector<uint32_t> touched_plans_;  // vertices whose plan a push changed (merge_side)
  int remaining_layers_ = 1;     // layers still to build, the current one included
  int layer_ = 0;                // the layer being built (1-based)
  int bl_index_ = -1;            // the BL layer being built (0-based), -1: an ordinary layer
  int bl_layers_ = 0;
  std::vector<uint8_t> wall_;    // 1 per vertex: on a wall shell (or pushed from one)
  std::vector<uint8_t> wall_triangle_;    // 1 per input triangle: a wall patch's
  std::vector<uint8_t> bl_reduced_root_;  // 1 per input vertex: some BL layer was reduced
  std::vector<uint8_t> column_halved_;    // 1 per input triangle, for the current layer
  // frame_of()'s cache: per vertex 0 unknown, 1 isotropic, 2 anisotropic (U in frame_).
  mutable std::vector<uint8_t> frame_state_;
  mutable std::vector<std::array<double, 9>> frame_;
  // A push task's: the cut its pushes stay on one side of (axis -1: the main builder), the number
  // of main's tets (the task's own tets are numbered from it on the front) and main's columns of
  // those tets, and the front slots it copied.
  int cut_axis_ = -1;
  double cut_ = 0.0;
  bool low_side_ = true;
  uint32_t tet_base_ = 0;
  const std::vector<uint32_t>* base_tet_column_ = nullptr;
  std::vector<uint32_t> copied_slots_;
  size_t base_slots_ = 0;
};

}  // namespace anitet::layers
