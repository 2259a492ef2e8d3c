// Stage 3c (paper, section 5.3, and what the best meshers add): mesh optimization that never
// touches S.
//   - CVT/Lloyd: every vertex not on S (layer vertices included) moves towards the centroid of
//     its cell with density rho = 1/h^5 (h = det(M)^(-1/6) for a metric M). The cell is
//     approximated by the vertex's ball: the target is the rho-weighted centroid of the ball's
//     tets (CentroidKind::kBall), or the ODT variant (the default), the rho- and volume-weighted
//     mean of their circumcentres (kOdt). With an anisotropic metric the ball is mapped by the
//     vertex's metric first, so circumcentres are taken in the metric. A move is accepted only
//     when every tet of the ball stays positive by the exact orient3d and no tet of the ball ends
//     below min(its old quality, accept_floor)
//     (a per-tet test: a max-min test on the ball would let all but its worst tet decay);
//     otherwise half and quarter steps are tried. Quality here is meshops::shape_quality, or,
//     when the metric is anisotropic at some vertex, the same measured in the metric (each tet
//     in the mean of its vertices' metrics, measured again after the vertex moves at the end
//     of each pass): every test below then uses it, flips included. Each
//     sweep runs on two cores (TBB): the vertices on either side of the median plane across the
//     longest extent move in two tasks, those of tets across the plane after them; the result
//     does not depend on the threads.
//   - Topology: quality-driven flips (2-3 on facets, 3-2 / 4-4 / n-2(n-2) edge removal with the
//     best triangulation of the edge's ring, n <= 7) around tets whose radius ratio is below
//     flip_quality; a flip is applied only when it raises the worst radius ratio of the tets it
//     replaces. Protected facets (S) are never flipped and edges of S never removed.
//   - Slivers: each free vertex of a tet below sliver_quality is perturbed (a hill climb over
//     trial positions: away from the opposite facet, then pseudo-random directions) to raise the
//     worst quality of its ball (no tet ending below min(its old quality, the midpoint of the
//     ball's old worst quality and sliver_quality)), or that tet's alone (no other tet ending
//     below min(its old quality, sliver_quality): the ball of a vertex of S1 holds tets on S's
//     sliver triangles, which no move lifts and which would block the rule above), interleaved
//     with flips, for sliver_rounds rounds, ending after a round that moved fewer vertices than 2%
//     of the tets it tried (with an anisotropic metric, also when the tets below sliver_quality
//     no longer fall by 2% a round: there the rounds made 2000 moves each and left as many).
//   - Collapses: a tet that no vertex move lifts (four nearly collinear points, each held by its
//     other tets, as at sharp creases) gets an edge collapse, its edges shortest first: the removed
//     end is free, the other stays (or, when free too, first tries the midpoint). Applied when
//     the worst tet of the changed region rises, every new tet is positive (exact) and no new
//     edge is longer than both 1.5 sizes and every edge of the two ends before (a local repair,
//     not a coarsening). Vertices of S, locked vertices and protected facets are never touched.
//     Removed vertices stay in the arrays, in no tet. Then flips and a perturbation round, again
//     while collapses happen (collapse_rounds).
//   - Polish: the free vertices of the tets left below 0.1 get a longer hill climb (8 times
//     perturb_trials, finer steps, half of them along the gradient of the tet's quality), then
//     the tets it lowered a perturbation round; three times at most (with sliver_rounds > 0), the
//     second and third on the tets near the balls the round before changed.
//   - Rescue: a tet with no vertex on S still below 0.06 after the polish (its vertices held by
//     tets on S's sliver triangles, which may not drop at all above) gets the polish's climb
//     again, judged by a looser rule: it must rise, tets off S may not fall below min(their
//     quality, accept_floor), tets on S may lose up to half their quality of the climb's start
//     but not fall below the ball's worst then; three rounds at most, each followed by flips,
//     the second and third on the tets near the moves of the round before.
//   - Flat tets: a tet positive for the exact orient3d but flat to rounding (a double evaluation
//     could find it zero or inverted: predicates::orient3d_certified) has its free vertices moved
//     (steps from twice its shortest edge down) until it is certified: a move is accepted when
//     fewer tets of the ball are uncertified and its worst quality does not drop (no per-tet
//     floor there); then the ones left get any flip that raises the worst quality of the tets it
//     replaces, and the moves again. Last, so that nothing after it flattens a tet again.
// Deterministic: same mesh and options, same result.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

#include "core/sizing.hpp"
#include "core/status.hpp"
#include "core/tet_mesh.hpp"

namespace anitet {

enum class CentroidKind { kBall, kOdt };

struct OptimizeOptions {
  // Lloyd iterations, each followed by a flip sweep. 3 rather than 4: nearly the same quality in
  // less time (4 was the quality of 6 in two thirds of the time).
  int cvt_iterations = 3;
  // kOdt: interior tets as good as with kBall or clearly better (with an anisotropic metric both
  // are taken in the metric, see the top).
  CentroidKind centroid = CentroidKind::kOdt;
  double accept_floor = 0.3;      // a move may lower a ball's worst quality down to this
  // Flips are tried around tets below this radius ratio, and perturbation targets tets below
  // sliver_quality. At 0.4 and 0.3 the tets between 0.3 and 0.4 had flips only, and were most of
  // those below 0.4 near a surface with poor triangles.
  double flip_quality = 0.5;
  double sliver_quality = 0.4;
  int sliver_rounds = 6;
  // After the perturbation rounds, each tet still below collapse_quality gets the collapse of its
  // shortest edge that raises the worst tet around it, then flips and a perturbation round, for
  // at most collapse_rounds rounds (see the top); 0: off.
  double collapse_quality = 0.3;
  int collapse_rounds = 4;
  int perturb_trials = 24;        // trial positions per vertex and round (8x in the polish of
                                  // the tets below 0.1 after the collapses, see the top)
  int num_threads = 0;            // 0: TBB's default; n: an arena of n threads (same result)
  // Called as the optimization goes with the share of it done (after each CVT iteration, after the
  // sliver rounds, at the end). For progress display only (it cannot stop the stage).
  std::function<void(double fraction)> progress;
  uint64_t seed = 0x5eed;
  // Anisotropic metric only: a vertex move (CVT, perturbation) is refused when it takes an edge
  // of the vertex out of [1/sqrt2, sqrt2] in the metric that was in it, and a flip when it adds
  // more edges out of that range than it removes (optimize_detail::FlipContext). Unguarded, the
  // flips after each CVT step took ~3 points of the share in range, which later moves and
  // collapses gave back (the UGAWG cube to its .sol).
  bool keep_lengths_in_range = true;
};

struct QualitySummary {
  size_t tets = 0;
  double mean = 0.0, min = 0.0;
  size_t below_01 = 0, below_04 = 0;  // radius ratio < 0.1, < 0.4
};

struct OptimizeStats {
  size_t moves = 0, moves_rejected = 0;
  size_t flips23 = 0, edge_removals = 0;
  size_t perturbations = 0;
  size_t collapses = 0;  // collapse_quality's edge collapses (vertices removed)
  // Tets flat to rounding (predicates::orient3d_certified not positive) found by the last pass,
  // and how many of them no vertex move could open.
  size_t flat_found = 0, flat_left = 0;
  QualitySummary before, after;  // Euclidean radius ratios
  bool anisotropic = false;       // the measures were taken in the metric (see the top)
  // Anisotropic only: the share of edges not on S whose normalized length is in [1/sqrt2, sqrt2]
  // (refinement's measure, RefineStats::length_in_range) before and after the optimization.
  double length_in_range_before = 0.0, length_in_range_after = 0.0;
  double seconds = 0.0;
  // Where the time went: the quality summaries and metric queries before and after, the CVT
  // passes, every flip sweep, sliver removal (perturbations, collapses, the polish) and the
  // final certification of tets flat to rounding.
  double seconds_setup = 0.0, seconds_cvt = 0.0, seconds_flips = 0.0, seconds_slivers = 0.0,
         seconds_certify = 0.0;
};

// Radius ratio statistics of the live non-ghost tets.
QualitySummary summarize_quality(const TetMesh& mesh);
// The same in the metric of `field`: each tet's radius ratio after the map of the metric at its
// centroid (M = L L^T, x -> L^T x), so a tet stretched as the metric asks counts as regular.
// Measured on every core; the sums run in tet order (the same figures whatever the threads).
QualitySummary summarize_metric_quality(const TetMesh& mesh, const SizingField& field);

struct FlatTetFlips {
  size_t found = 0;  // tets flat to rounding (predicates::orient3d_certified not positive) before
  size_t flips = 0;  // flips applied
  size_t left = 0;   // flat tets after
};

// Flips only, for a mesh whose vertices may not move (every vertex on S, as in a conforming
// recovery): each tet flat to rounding gets the first edge removal (its six edges in turn, the
// best triangulation of the ring) or else 2-3 flip that raises the worst quality of the tets it
// replaces, in rounds while the count of flat tets drops.
// Protected facets and constrained edges are kept; no ghosts allowed (a ghost tet is skipped).
FlatTetFlips flip_flat_tets(TetMesh& mesh);

// Optimizes `mesh` (no ghosts, adjacency built, S = protected facets, vflag::kOnInputSurface and
// kLocked vertices fixed). Regions and protected facets are kept.
Result<OptimizeStats> optimize_mesh(TetMesh& mesh, const SizingField& field, const OptimizeOptions& options = {});

}  // namespace anitet
