#include "optimize/optimize.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include "core/buckets.hpp"
#include "core/metric_measures.hpp"
#include "optimize/flips.hpp"
#include "predicates/predicates.hpp"
#include "refine/edges.hpp"
#include "refine/mesh_ops.hpp"
#include "refine/refine.hpp"

namespace anitet {

namespace {

using Clock = std::chrono::steady_clock;

class Optimizer {
 public:
  Optimizer(TetMesh& mesh, const SizingField& field, const OptimizeOptions& options)
      : mesh_(mesh), field_(field), options_(options), flips_{mesh, vt_, {}, {}, {}, {}, {}} {
    rng_ = options.seed | 1u;
    flips_.quality = &quality_;
  }
  Result<OptimizeStats> run();

 private:
  bool movable(uint32_t v) const {
    return !(mesh_.vflags[v] & (vflag::kOnInputSurface | vflag::kLocked)) && !vt_.removed(v);
  }
  // No vertex of t can move (a boundary-layer tet: its vertices locked): no move or collapse can
  // change it, so the sliver passes skip it before measuring it (over a million such tets in a
  // wing's 20 layers).
  bool fixed_tet(uint32_t t) const {
    for (int i = 0; i < 4; ++i)
      if (movable(mesh_.vertex(t, i))) return false;
    return true;
  }
  // After v moved: its size, and its metric when anisotropic, are measured again.
  void moved(uint32_t v) {
    if (v < sizes_.size()) sizes_[v] = -1.0;
    if (quality_.anisotropic()) metric_stale_[v] = 1;
  }
  // Anisotropic metric: measures the metric again at the vertices that moved since the last
  // call. Between calls the tets keep the metrics they had, so that a tet's quality does not
  // change while a pass compares it.
  void refresh_metrics();
  // Tells the flip memo of a change in the ball `ball` (the tets of a vertex that moved, or whose
  // metric changed).
  void touch_tets(const std::vector<uint32_t>& ball) {
    for (uint32_t s : ball)
      for (int i = 0; i < 4; ++i) flips_.memo.touch(mesh_.vertex(s, i));
  }
  // The same for v's ball, found from v.
  void touch_ball(uint32_t v) {
    const uint32_t t = vt_.tet_of(mesh_, v);
    if (t == TetMesh::kNone) return flips_.memo.touch_all();
    meshops::vertex_ball(mesh_, v, t, touch_scratch_);
    touch_tets(touch_scratch_);
  }
  // t's quality: the flip memo's measure when it still holds (the same figure), else measured.
  double known_quality(uint32_t t) const {
    const optimize_detail::FlipMemo& memo = flips_.memo;
    return memo.knows_quality(t, &mesh_.tet_v[4 * size_t(t)]) ? memo.quality_of[t] : quality_.tet(mesh_, t);
  }
  double size_at(uint32_t v) {
    if (sizes_.size() < mesh_.num_vertices()) sizes_.resize(mesh_.num_vertices(), -1.0);
    if (sizes_[v] < 0.0) {
      double m[6];
      field_.metric(mesh_.point(v), m);
      sizes_[v] = metric_size(m);
    }
    return sizes_[v];
  }
  // Scratch of one worker: the CVT pass runs two at once (see cvt_pass()).
  struct Work {
    std::vector<uint32_t> ball;
    std::vector<double> old_q, new_q;
    // Anisotropic: the metric each ball tet is measured in (Quality::map), which stays while v
    // tries positions (the vertices' metrics are measured again between passes only): the
    // trials then map and measure, without a mean and a Cholesky factor per tet and trial.
    // Empty when Euclidean.
    std::vector<meshops::MetricMap> maps;
    // And, with the metrics, each ball tet's points mapped by its map (12 per tet), of which only
    // the moving vertex's (at index moving_at[k]) is mapped again at each trial.
    std::vector<double> mapped;
    std::vector<uint8_t> moving_at;
    uint32_t moving = 0;  // the vertex whose ball this is
    // Anisotropic, with OptimizeOptions::keep_lengths_in_range: the moving vertex's neighbours
    // whose edge to it was in [1/sqrt2, sqrt2] in the metric when the ball was measured; a move
    // may not take one of these edges out of range.
    std::vector<uint32_t> in_range;
    std::vector<uint32_t> seen;  // per vertex: the last measure_ball() call that listed it
    uint32_t seen_mark = 0;
    // try_move(): the indices in in_range and in ball of the tests that last refused a trial.
    size_t range_first = 0, quality_first = 0;
    double old_min = 1.0;
    size_t target = SIZE_MAX;   // perturbation: the index in `ball` of the tet to open (SIZE_MAX: none)
    double target_floor = 0.0;  // and the floor of the other tets when only it gains
    // The rescue of an interior tet (rescue_pass()): the ball's qualities when the climb started,
    // its worst then, and which of its tets have a vertex on S.
    bool rescue = false;
    std::vector<double> start_q;
    std::vector<uint8_t> on_s;
    double start_min = 0.0;
    size_t moved = 0, rejected = 0;
  };
  // Qualities of w.ball's tets (the ball of v) before a move of v (w.old_q, w.old_min), and their
  // metrics (w.maps).
  void measure_ball(Work& w, uint32_t v);
  // Anisotropic: the edge uv's normalized length, in the metrics the vertices were last measured
  // in, is in [1/sqrt2, sqrt2] (refinement's range).
  bool edge_in_range(uint32_t v, uint32_t u) const {
    const std::vector<double>& m = quality_.vertex_metric;
    const double l = metric_edge_length(&m[6 * size_t(v)], mesh_.point(v), &m[6 * size_t(u)], mesh_.point(u));
    return in_unit_range(l);
  }
  double share_in_range() const {
    double mean = 0.0, share = 0.0;
    refine_detail::summarize_edge_lengths(mesh_, quality_.vertex_metric, kUnitRangeMin, kUnitRangeMax, mean, share);
    return share;
  }
  // The quality of w.ball[k] where its points are now (only w.moving moved since measure_ball()),
  // in the metric measure_ball() found: the same figure as quality_.of(mesh_, tet, w.maps[k]).
  double ball_tet_quality(const Work& w, size_t k) const {
    const uint32_t* tv = &mesh_.tet_v[4 * size_t(w.ball[k])];
    if (w.maps.empty()) return quality_.of(mesh_, tv);
    if (w.maps[k].identity) return quality_.of(mesh_, tv, w.maps[k]);
    double q[12];
    std::copy_n(&w.mapped[12 * k], 12, q);
    w.maps[k].apply(mesh_.point(w.moving), &q[3 * w.moving_at[k]]);
    return meshops::shape_quality(q, q + 3, q + 6, q + 9);
  }
  // Tries v at p: accepted when the ball stays positive (exact) and no tet falls below
  // min(its quality in w.old_q, floor); with quality_out, the worst one must also rise. Leaves v
  // where it was otherwise. The ball is w.ball; call measure_ball() first.
  bool try_move(Work& w, uint32_t v, const double p[3], double floor, double* quality_out);
  void cvt_target(const Work& w, uint32_t v, double target[3]);
  void cvt_move(Work& w, uint32_t v);
  size_t cvt_pass();
  // With `near` (1 per vertex): only the tets with a marked vertex.
  // With `bad_limit`: nothing is tried when more tets than that are below sliver_quality, and
  // `bad_count` gets how many are.
  size_t perturb_pass(const std::vector<uint8_t>* near = nullptr, size_t bad_limit = SIZE_MAX,
                      size_t* bad_count = nullptr);
  size_t polish_pass(const std::vector<uint8_t>* only_near, std::vector<uint8_t>& near);
  bool perturb_vertex(uint32_t t, int i, int trials, int levels, bool gradient = false, bool rescue = false);
  bool rescue_accepts(const Work& w) const;
  // With `near` (1 per vertex): only the tets with a marked vertex. Marks in `moved_near` the
  // vertices of the balls it changed.
  size_t rescue_pass(const std::vector<uint8_t>* near, std::vector<uint8_t>& moved_near);
  bool target_gradient(uint32_t v, uint32_t t, double scale, double grad[3]);
  // Collapses an edge of each tet below options_.collapse_quality (see OptimizeOptions).
  size_t collapse_pass();
  bool try_collapse(uint32_t v, uint32_t w, bool to_midpoint);
  std::vector<uint8_t> collapsed_near_;  // per vertex: in a tet changed by a collapse, the polish or the rescue
  void trial_offset(int trial, int levels, double top, const double* nrm, double d[3]);
  bool opening_direction(uint32_t t, int i, const meshops::MetricMap& map, double nrm[3]) const;
  double shortest_edge(uint32_t t) const;
  bool certified(uint32_t t) const;
  bool try_certify(uint32_t v, const double p[3], size_t flat);
  size_t certify_pass();
  void certify_round(const std::vector<uint32_t>& flat);
  double next_unit() {
    rng_ ^= rng_ << 13;
    rng_ ^= rng_ >> 7;
    rng_ ^= rng_ << 17;
    return double(rng_ >> 11) * (1.0 / 9007199254740992.0);
  }

  TetMesh& mesh_;
  const SizingField& field_;
  const OptimizeOptions& options_;
  meshops::VertexTets vt_;
  optimize_detail::FlipContext flips_;
  std::vector<double> sizes_;  // lazily computed scalar size per vertex (-1: unknown)
  std::vector<uint32_t> touch_scratch_;  // touch_ball()'s ball
  optimize_detail::Quality quality_;  // Euclidean, or in the metric when it is anisotropic
  std::vector<uint8_t> metric_stale_;  // per vertex: moved since its metric was measured
  Work work_;                  // the sequential passes' scratch
  std::vector<meshops::TetVerts> collapse_fresh_;  // try_collapse()'s new tets
  std::vector<uint32_t> collapse_ball_w_;          // and its scratch
  static constexpr double kCollapseMaxLength = 1.5;  // longest new edge of a collapse, in sizes
  std::vector<uint8_t> side_;  // cvt_pass(): per vertex, its side of the split (2: seam bit)
  std::vector<double> tet_q_;  // per tet slot, during cvt_pass() only (the flip memo's; empty otherwise)
  // The tets of vertex v's ball are ball_tets_[ball_start_[v] .. ball_start_[v + 1]), during
  // cvt_pass() only (built at its start; released after the CVT iterations).
  std::vector<uint32_t> ball_start_, ball_tets_;
  OptimizeStats stats_;
  uint64_t rng_;
};

void Optimizer::refresh_metrics() {
  if (!quality_.anisotropic()) return;
  const auto nv = static_cast<uint32_t>(mesh_.num_vertices());
  // The tets of a vertex whose metric changes change quality: the flip memo must know.
  std::vector<uint32_t> stale;
  for (uint32_t v = 0; v < nv; ++v)
    if (metric_stale_[v]) stale.push_back(v);
  if (stale.size() > nv / 16) {
    flips_.memo.touch_all();
  } else {
    for (uint32_t v : stale) touch_ball(v);
  }
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, nv, 1024), [&](const tbb::blocked_range<uint32_t>& r) {
    for (uint32_t v = r.begin(); v < r.end(); ++v)
      if (metric_stale_[v]) {
        field_.metric(mesh_.point(v), &quality_.vertex_metric[6 * size_t(v)]);
        metric_stale_[v] = 0;
      }
  });
}

void Optimizer::measure_ball(Work& w, uint32_t v) {
  w.old_q.resize(w.ball.size());
  w.maps.clear();
  w.moving = v;
  if (quality_.anisotropic()) {
    w.mapped.resize(12 * w.ball.size());
    w.moving_at.resize(w.ball.size());
    for (size_t k = 0; k < w.ball.size(); ++k) {
      const uint32_t* tv = &mesh_.tet_v[4 * size_t(w.ball[k])];
      w.maps.push_back(quality_.map(tv));
      if (w.maps[k].identity) continue;  // (measured as it is: nothing mapped)
      for (int i = 0; i < 4; ++i) {
        if (tv[i] == v) w.moving_at[k] = static_cast<uint8_t>(i);
        else w.maps[k].apply(mesh_.point(tv[i]), &w.mapped[12 * k + 3 * size_t(i)]);
      }
    }
  }
  w.in_range.clear();
  if (quality_.anisotropic() && options_.keep_lengths_in_range) {
    // The neighbours once each (a neighbour is in several ball tets; marked by this call's
    // number, which a sort of the list took a tenth of the sliver stage to do), then the edges
    // measured.
    if (w.seen.size() < mesh_.num_vertices()) w.seen.resize(mesh_.num_vertices(), 0);
    if (++w.seen_mark == 0) {
      std::fill(w.seen.begin(), w.seen.end(), 0);
      w.seen_mark = 1;
    }
    w.seen[v] = w.seen_mark;
    for (uint32_t t : w.ball)
      for (int i = 0; i < 4; ++i) {
        const uint32_t u = mesh_.vertex(t, i);
        if (w.seen[u] == w.seen_mark) continue;
        w.seen[u] = w.seen_mark;
        if (edge_in_range(v, u)) w.in_range.push_back(u);
      }
  }
  w.range_first = w.quality_first = 0;
  w.old_min = 1.0;
  // (Outside the CVT pass, the flip memo's measures where they still hold: the same figures.)
  const optimize_detail::FlipMemo& memo = flips_.memo;
  for (size_t k = 0; k < w.ball.size(); ++k) {
    const uint32_t t = w.ball[k];
    if (!tet_q_.empty()) w.old_q[k] = tet_q_[t];
    else if (memo.knows_quality(t, &mesh_.tet_v[4 * size_t(t)])) w.old_q[k] = memo.quality_of[t];
    else w.old_q[k] = ball_tet_quality(w, k);
    w.old_min = std::min(w.old_min, w.old_q[k]);
  }
}

bool Optimizer::try_move(Work& w, uint32_t v, const double p[3], double floor, double* quality_out) {
  // Per tet: no tet may end below min(its old quality, floor). A max-min test on the ball alone
  // would let every tet but the worst one decay down to the worst one's level.
  double* x = &mesh_.xyz[3 * size_t(v)];
  const double saved[3] = {x[0], x[1], x[2]};
  std::copy_n(p, 3, x);
  double q_min = 1.0;
  bool ok = true;
  // Every test must pass, so their order changes no verdict, only how soon a trial is refused:
  // the edge lengths first (far cheaper than a tet's quality, and they refuse most trials whose
  // qualities pass), and in both lists the test that refused the trial before first (the next
  // trial of a climb is most often refused by it again).
  if (!w.in_range.empty()) {
    ok = edge_in_range(v, w.in_range[w.range_first]);
    for (size_t k = 0; k < w.in_range.size() && ok; ++k)
      if (k != w.range_first && !edge_in_range(v, w.in_range[k])) {
        ok = false;
        w.range_first = k;
      }
  }
  w.new_q.resize(w.ball.size());
  auto passes = [&](size_t k) {
    const double q = ball_tet_quality(w, k);
    w.new_q[k] = q;
    q_min = std::min(q_min, q);
    return q > 0.0 && q >= std::min(w.old_q[k], floor);
  };
  if (ok) ok = passes(w.quality_first);
  for (size_t k = 0; k < w.ball.size() && ok; ++k)
    if (k != w.quality_first && !passes(k)) {
      ok = false;
      w.quality_first = k;
    }
  // quality_out asks for a strict gain (perturbation): of the ball's worst tet, or of the target
  // while no tet falls below min(its quality, target_floor). The worst alone would not do: a
  // vertex of S1 holds tets on S's sliver triangles, whose quality no move raises much, and the
  // sliver beside them could never be opened.
  if (ok && quality_out && w.rescue) {
    ok = rescue_accepts(w);
  } else if (ok && quality_out) {
    bool gain = q_min > w.old_min + 1e-9;
    if (!gain && w.target < w.ball.size() && w.new_q[w.target] > w.old_q[w.target] + 1e-9) {
      gain = true;
      for (size_t k = 0; k < w.ball.size() && gain; ++k) gain = w.new_q[k] >= std::min(w.old_q[k], w.target_floor);
    }
    ok = gain;
  }
  if (ok && meshops::all_positive(mesh_, w.ball)) {
    if (!tet_q_.empty())
      for (size_t k = 0; k < w.ball.size(); ++k) tet_q_[w.ball[k]] = w.new_q[k];
    if (quality_out) {
      // The new position is the next trial's reference: its qualities are new_q (every tet
      // measured, since all passed), the ball and its metrics unchanged.
      *quality_out = q_min;
      w.old_q.swap(w.new_q);
      w.old_min = q_min;
    }
    return true;
  }
  std::copy_n(saved, 3, x);
  return false;
}

void Optimizer::cvt_target(const Work& w, uint32_t v, double target[3]) {
  // With an anisotropic metric the ball is measured in v's metric (points mapped by L^T about v)
  // and the target mapped back: Euclidean circumcentres of tets stretched as the metric asks lie
  // far outside them, and the edges there come out of range.
  meshops::MetricMap map;
  if (quality_.anisotropic()) map = meshops::MetricMap::of(&quality_.vertex_metric[6 * size_t(v)]);
  const double* pv = mesh_.point(v);
  double mapped[4][3];
  double sum_w = 0.0, acc[3] = {0.0, 0.0, 0.0};
  for (uint32_t t : w.ball) {
    const double* P[4];
    double h = 0.0;
    for (int i = 0; i < 4; ++i) {
      P[i] = mesh_.point(mesh_.vertex(t, i));
      h += 0.25 * size_at(mesh_.vertex(t, i));
      if (!map.identity) {
        const double rel[3] = {P[i][0] - pv[0], P[i][1] - pv[1], P[i][2] - pv[2]};
        map.apply(rel, mapped[i]);
        P[i] = mapped[i];
      }
    }
    const double ab[3] = {P[1][0] - P[0][0], P[1][1] - P[0][1], P[1][2] - P[0][2]};
    const double ac[3] = {P[2][0] - P[0][0], P[2][1] - P[0][1], P[2][2] - P[0][2]};
    const double ad[3] = {P[3][0] - P[0][0], P[3][1] - P[0][1], P[3][2] - P[0][2]};
    const double cx = ac[1] * ad[2] - ac[2] * ad[1], cy = ac[2] * ad[0] - ac[0] * ad[2],
                 cz = ac[0] * ad[1] - ac[1] * ad[0];
    const double v6 = ab[0] * cx + ab[1] * cy + ab[2] * cz;
    if (!(v6 > 0.0)) continue;
    const double rho = 1.0 / (h * h * h * h * h);
    const double weight = rho * v6;
    double c[3];
    if (options_.centroid == CentroidKind::kOdt) {
      // Circumcentre: a + (|ab|^2 (ac x ad) + |ac|^2 (ad x ab) + |ad|^2 (ab x ac)) / (2 v6).
      const double lab = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
      const double lac = ac[0] * ac[0] + ac[1] * ac[1] + ac[2] * ac[2];
      const double lad = ad[0] * ad[0] + ad[1] * ad[1] + ad[2] * ad[2];
      const double db[3] = {ad[1] * ab[2] - ad[2] * ab[1], ad[2] * ab[0] - ad[0] * ab[2], ad[0] * ab[1] - ad[1] * ab[0]};
      const double bc[3] = {ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0]};
      const double cd[3] = {cx, cy, cz};
      for (int k = 0; k < 3; ++k) c[k] = P[0][k] + (lab * cd[k] + lac * db[k] + lad * bc[k]) / (2.0 * v6);
    } else {
      for (int k = 0; k < 3; ++k) c[k] = 0.25 * (P[0][k] + P[1][k] + P[2][k] + P[3][k]);
    }
    for (int k = 0; k < 3; ++k) acc[k] += weight * c[k];
    sum_w += weight;
  }
  if (!(sum_w > 0.0)) {
    std::copy_n(pv, 3, target);
  } else if (map.identity) {
    for (int k = 0; k < 3; ++k) target[k] = acc[k] / sum_w;
  } else {
    const double mean[3] = {acc[0] / sum_w, acc[1] / sum_w, acc[2] / sum_w};
    map.unapply(mean, target);
    for (int k = 0; k < 3; ++k) target[k] += pv[k];
  }
}

void Optimizer::cvt_move(Work& w, uint32_t v) {
  w.ball.assign(ball_tets_.begin() + ball_start_[v], ball_tets_.begin() + ball_start_[v + 1]);
  if (w.ball.empty()) return;
  double target[3];
  cvt_target(w, v, target);
  measure_ball(w, v);
  const double p[3] = {mesh_.point(v)[0], mesh_.point(v)[1], mesh_.point(v)[2]};
  bool ok = false;
  for (double step = 1.0; step > 0.2 && !ok; step *= 0.5) {
    const double q[3] = {p[0] + step * (target[0] - p[0]), p[1] + step * (target[1] - p[1]),
                         p[2] + step * (target[2] - p[2])};
    ok = try_move(w, v, q, options_.accept_floor, nullptr);
  }
  if (ok) {
    ++w.moved;
    moved(v);
  } else {
    ++w.rejected;
  }
}

// One Lloyd sweep over the free vertices, on two cores: the vertices are split by the median
// plane across the mesh's longest extent; a vertex all of whose tets lie on one side moves in
// that side's task (the two tasks then touch disjoint tets, read only their own side's points,
// and fill the lazy size cache only for their own side's vertices), in index order; the seam
// vertices (in a tet with points on both sides) move afterwards, in index order. The result does
// not depend on the threads' timing.
size_t Optimizer::cvt_pass() {
  const auto nv = static_cast<uint32_t>(mesh_.num_vertices());
  const uint32_t n_slots = mesh_.num_tet_slots();
  sizes_.resize(nv, -1.0);  // no resizing inside the parallel tasks
  // Every tet's quality once, kept up to date by the accepted moves: each tet is in four balls,
  // so measuring balls from scratch would compute it four times. In the flip memo's own array,
  // lent to tet_q_ for the sweep (no second 8 bytes per tet slot: issue 49); what it held for a
  // tet is kept where the memo still knows it, and at the end the memo knows every tet.
  optimize_detail::FlipMemo& memo = flips_.memo;
  if (memo.quality_of.size() < n_slots) {
    memo.quality_of.resize(n_slots, 0.0);
    memo.measured.resize(n_slots, 0);
  }
  // Every vertex's ball, in tet order (moves keep the topology, so one scan of the tets serves
  // the whole sweep instead of a traversal per vertex).
  {
    std::vector<uint32_t> fill;
    parallel_bucket_by_key(
        nv, n_slots,
        [&](size_t first, size_t last, auto&& emit) {
          for (auto t = uint32_t(first); t < last; ++t)
            if (!mesh_.is_deleted(t))
              for (int i = 0; i < 4; ++i) emit(mesh_.vertex(t, i), t);
        },
        ball_start_, ball_tets_, fill);
  }
  auto measure = [&](uint32_t begin, uint32_t end) {
    for (uint32_t t = begin; t < end; ++t)
      if (!mesh_.is_deleted(t) && !memo.knows_quality(t, &mesh_.tet_v[4 * size_t(t)]))
        memo.quality_of[t] = quality_.tet(mesh_, t);
  };
  // The split: side 0 or 1 per vertex, then kSeam for the vertices of tets across it.
  constexpr uint8_t kSeam = 2;
  side_ = optimize_detail::median_sides(mesh_);
  for (uint32_t t = 0; t < n_slots; ++t) {
    if (mesh_.is_deleted(t)) continue;
    const uint32_t* tv = &mesh_.tet_v[4 * size_t(t)];
    uint8_t seen = 0;
    for (int i = 0; i < 4; ++i) seen |= uint8_t(1u << (side_[tv[i]] & 1u));
    if (seen == 3)
      for (int i = 0; i < 4; ++i) side_[tv[i]] |= kSeam;
  }
  Work halves[2];
  auto sweep_side = [&](uint8_t which) {
    for (uint32_t v = 0; v < nv; ++v)
      if (side_[v] == which && movable(v)) cvt_move(halves[which], v);
  };
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n_slots, 4096),
                    [&](const tbb::blocked_range<uint32_t>& r) { measure(r.begin(), r.end()); });
  tet_q_.swap(memo.quality_of);
  tbb::parallel_invoke([&] { sweep_side(0); }, [&] { sweep_side(1); });
  Work& seam = work_;
  seam.moved = seam.rejected = 0;
  for (uint32_t v = 0; v < nv; ++v)
    if ((side_[v] & kSeam) && movable(v)) cvt_move(seam, v);
  // Nearly every vertex moved; tet_q_ holds every tet's quality now (the moves kept it).
  tet_q_.swap(memo.quality_of);
  memo.touch_all();
  const uint32_t now = memo.start_measures(n_slots);
  for (uint32_t t = 0; t < n_slots; ++t) memo.measured[t] = mesh_.is_deleted(t) ? 0 : now;
  stats_.moves_rejected += halves[0].rejected + halves[1].rejected + seam.rejected;
  return halves[0].moved + halves[1].moved + seam.moved;
}

size_t Optimizer::collapse_pass() {
  const double cq = options_.collapse_quality;
  const std::vector<uint32_t> bad = optimize_detail::tets_below(mesh_, cq, quality_, &flips_.memo);
  size_t done = 0;
  for (uint32_t t : bad) {
    if (mesh_.is_deleted(t) || fixed_tet(t) || known_quality(t) >= cq) continue;
    // Its edges, shortest first; the removed end must be free (a vertex of S never moves).
    std::array<std::pair<double, int>, 6> edges;
    for (int k = 0; k < 6; ++k) {
      const double* a = mesh_.point(mesh_.vertex(t, kEdgeVertex[k][0]));
      const double* b = mesh_.point(mesh_.vertex(t, kEdgeVertex[k][1]));
      edges[k] = {(a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]), k};
    }
    std::sort(edges.begin(), edges.end());
    for (const auto& e : edges) {
      const uint32_t a = mesh_.vertex(t, kEdgeVertex[e.second][0]);
      const uint32_t b = mesh_.vertex(t, kEdgeVertex[e.second][1]);
      const bool ok = (movable(a) && movable(b) && try_collapse(a, b, true)) ||
                      (movable(a) && try_collapse(a, b, false)) || (movable(b) && try_collapse(b, a, false));
      if (ok) {
        ++done;
        break;
      }
    }
  }
  return done;
}

bool Optimizer::try_collapse(uint32_t v, uint32_t w, bool to_midpoint) {
  // v goes, w stays (at the edge's midpoint when both are free). The tets of v's ball (and, when w
  // moves, those of w's) are replaced by the same without the edge's tets and with v renamed w.
  const uint32_t tv = vt_.tet_of(mesh_, v);
  if (tv == TetMesh::kNone) return false;
  std::vector<uint32_t>& old = work_.ball;
  if (!meshops::collapse_tets(mesh_, vt_, v, tv, w, to_midpoint, old, collapse_fresh_, collapse_ball_w_))
    return false;
  // (A bad tet's edges try up to three collapses each, on the same balls.)
  double old_min = 1.0;
  for (uint32_t t : old) old_min = std::min(old_min, known_quality(t));
  double* xw = &mesh_.xyz[3 * size_t(w)];
  const double saved[3] = {xw[0], xw[1], xw[2]};
  if (to_midpoint)
    for (int k = 0; k < 3; ++k) xw[k] = 0.5 * (xw[k] + mesh_.point(v)[k]);
  // The worst tet must rise, and no new edge from w may be longer than 1.5 sizes and than the
  // edges of v and w before (the collapse is a local repair, not a coarsening).
  double longest2 = 0.0;
  for (uint32_t t : old)
    for (const auto& e : kEdgeVertex) {
      const uint32_t a = mesh_.vertex(t, e[0]), b = mesh_.vertex(t, e[1]);
      if (a != v && a != w && b != v && b != w) continue;
      const double* pa = a == w ? saved : mesh_.point(a);  // (w may be at the midpoint now)
      const double* pb = b == w ? saved : mesh_.point(b);
      longest2 = std::max(longest2, (pa[0] - pb[0]) * (pa[0] - pb[0]) + (pa[1] - pb[1]) * (pa[1] - pb[1]) +
                                        (pa[2] - pb[2]) * (pa[2] - pb[2]));
    }
  // Both tests must pass for every new tet: the lengths (cheap) first, then the qualities.
  bool ok = true;
  const double hw = size_at(w);
  for (size_t i = 0; i < collapse_fresh_.size() && ok; ++i)
    for (uint32_t x : collapse_fresh_[i]) {
      if (x == w) continue;
      const double* px = mesh_.point(x);
      const double d2 = (px[0] - xw[0]) * (px[0] - xw[0]) + (px[1] - xw[1]) * (px[1] - xw[1]) +
                        (px[2] - xw[2]) * (px[2] - xw[2]);
      if (d2 > longest2 && d2 > kCollapseMaxLength * kCollapseMaxLength * hw * size_at(x)) ok = false;
    }
  double new_min = 1.0;
  for (size_t i = 0; i < collapse_fresh_.size() && ok; ++i) {
    new_min = std::min(new_min, quality_.of(mesh_, collapse_fresh_[i].data()));
    ok = new_min > old_min + 1e-9;
  }
  if (ok) ok = meshops::replace_tets(mesh_, old, collapse_fresh_, vt_, flips_.scratch);
  if (!ok) {
    std::copy_n(saved, 3, xw);
    return false;
  }
  vt_.forget(v);
  if (to_midpoint) moved(w);
  flips_.touch_tets(collapse_fresh_);  // w's whole new ball, v's neighbours among them
  for (const meshops::TetVerts& f : collapse_fresh_)
    for (uint32_t x : f) collapsed_near_[x] = 1;
  return true;
}

size_t Optimizer::perturb_pass(const std::vector<uint8_t>* near, size_t bad_limit, size_t* bad_count) {
  const std::vector<uint32_t> bad = optimize_detail::tets_below(mesh_, options_.sliver_quality, quality_, &flips_.memo);
  if (bad_count) *bad_count = bad.size();
  if (bad.size() > bad_limit) return 0;
  size_t moved = 0;
  for (uint32_t t : bad) {
    if (!mesh_.is_deleted(t) && fixed_tet(t)) continue;
    if (near && !mesh_.is_deleted(t)) {
      bool close = false;
      for (int i = 0; i < 4; ++i) close |= (*near)[mesh_.vertex(t, i)] != 0;
      if (!close) continue;
    }
    for (int i = 0; i < 4; ++i) {
      if (mesh_.is_deleted(t) || known_quality(t) >= options_.sliver_quality) break;
      moved += perturb_vertex(t, i, options_.perturb_trials, 4);
    }
  }
  return moved;
}

// The worst tets decide the minimum users see; they are few, so each free vertex of those below
// kPolishQuality gets a longer hill climb with finer steps (8 times the trials, steps down to 1/512
// of the ball's size instead of 1/8, every other cycle along the gradient of the tet's quality).
// Marks in `near` the vertices of the balls it changed.
size_t Optimizer::polish_pass(const std::vector<uint8_t>* only_near, std::vector<uint8_t>& near) {
  constexpr double kPolishQuality = 0.1;
  size_t moved = 0;
  for (uint32_t t : optimize_detail::tets_below(mesh_, kPolishQuality, quality_, &flips_.memo)) {
    if (mesh_.is_deleted(t) || fixed_tet(t)) continue;
    if (only_near) {
      bool close = false;
      for (int i = 0; i < 4; ++i) close |= (*only_near)[mesh_.vertex(t, i)] != 0;
      if (!close) continue;
    }
    for (int i = 0; i < 4 && !mesh_.is_deleted(t); ++i) {
      const bool mv = perturb_vertex(t, i, 8 * options_.perturb_trials, 10, !quality_.anisotropic());
      moved += mv;
      if (mv)
        for (uint32_t b : work_.ball)
          for (int k = 0; k < 4; ++k) near[mesh_.vertex(b, k)] = 1;
    }
  }
  return moved;
}

// The rescue's test of a trial position: the target rises; every other tet ends at least at
// min(its quality before the trial, accept_floor), or, when it has a vertex on S, at half its
// quality when the climb started and no lower than the ball's worst then.
bool Optimizer::rescue_accepts(const Work& w) const {
  if (!(w.new_q[w.target] > w.old_q[w.target] + 1e-9)) return false;
  for (size_t k = 0; k < w.ball.size(); ++k) {
    if (k == w.target) continue;
    const double q = w.new_q[k];
    if (q >= std::min(w.old_q[k], options_.accept_floor)) continue;
    if (!(w.on_s[k] && q >= 0.5 * w.start_q[k] && q >= w.start_min)) return false;
  }
  return true;
}

// Tets off S below kRescueQuality after the polish: their vertices are held by tets on S's
// sliver triangles, which no move lifts and which the climbs above may not lower at all, so the
// tet off S stays a sliver (tray_bottom, turbine: interior radius ratio 0.049, 0.022). Each free
// vertex of such a tet gets the polish's climb with rescue_accepts() instead, which trades some
// of the quality of the tets on S (at most half, never below the ball's worst) for it.
size_t Optimizer::rescue_pass(const std::vector<uint8_t>* near, std::vector<uint8_t>& moved_near) {
  constexpr double kRescueQuality = 0.06;  // radius ratio >= shape_quality: the 0.05 bar, and a margin
  size_t moved = 0;
  for (uint32_t t : optimize_detail::tets_below(mesh_, kRescueQuality, quality_, &flips_.memo)) {
    bool interior = true, close = near == nullptr;
    for (int i = 0; i < 4; ++i) {
      interior &= !(mesh_.vflags[mesh_.vertex(t, i)] & vflag::kOnInputSurface);
      close |= near && (*near)[mesh_.vertex(t, i)] != 0;
    }
    for (int i = 0; interior && close && i < 4 && !mesh_.is_deleted(t) && known_quality(t) < kRescueQuality;
         ++i) {
      const bool mv = perturb_vertex(t, i, 8 * options_.perturb_trials, 10, !quality_.anisotropic(), true);
      moved += mv;
      if (mv)
        for (uint32_t b : work_.ball)
          for (int k = 0; k < 4; ++k) moved_near[mesh_.vertex(b, k)] = 1;
    }
  }
  return moved;
}

// Hill climb of vertex i of t (when free) to open t: `trials` trial offsets whose lengths halve
// over `levels` steps from a fifth of the ball's size and start again; with `gradient`, every
// other run of `levels` along the gradient of t's quality; with `rescue`, rescue_accepts() judges
// the trials. True when it moved.
bool Optimizer::perturb_vertex(uint32_t t, int i, int trials, int levels, bool gradient, bool rescue) {
  const uint32_t v = mesh_.vertex(t, i);
  if (!movable(v)) return false;
  meshops::vertex_ball(mesh_, v, t, work_.ball);
  measure_ball(work_, v);
  work_.target = size_t(std::find(work_.ball.begin(), work_.ball.end(), t) - work_.ball.begin());
  work_.target_floor = options_.sliver_quality;
  work_.rescue = rescue;
  if (rescue) {
    work_.start_q = work_.old_q;
    work_.start_min = work_.old_min;
    work_.on_s.assign(work_.ball.size(), 0);
    for (size_t k = 0; k < work_.ball.size(); ++k)
      for (int j = 0; j < 4; ++j)
        work_.on_s[k] |= (mesh_.vflags[mesh_.vertex(work_.ball[k], j)] & vflag::kOnInputSurface) != 0;
  }
  const double* x = mesh_.point(v);
  const double start[3] = {x[0], x[1], x[2]};
  double best[3] = {x[0], x[1], x[2]};
  // Away from the opposite facet (the direction that opens the tet), then random ones. With
  // an anisotropic metric, all of it in the metric of v: Euclidean steps of the ball's size
  // would cross the thin direction many times over.
  meshops::MetricMap map;
  if (quality_.anisotropic()) map = meshops::MetricMap::of(&quality_.vertex_metric[6 * size_t(v)]);
  double nrm[3], grad[3];
  opening_direction(t, i, map, nrm);  // zero when the facet is degenerate
  double scale = 0.0;
  for (uint32_t s : work_.ball)
    for (int k = 0; k < 4; ++k) {
      const double* y = mesh_.point(mesh_.vertex(s, k));
      const double step[3] = {y[0] - start[0], y[1] - start[1], y[2] - start[2]};
      double e[3] = {step[0], step[1], step[2]};
      if (!map.identity) map.apply(step, e);
      scale = std::max(scale, std::fabs(e[0]) + std::fabs(e[1]) + std::fabs(e[2]));
    }
  scale *= 0.2;
  bool along_gradient = false;
  for (int trial = 0; trial < trials; ++trial) {
    double d[3];
    // Each odd run starts from the gradient where the climb stands (a flat one: a random run).
    if (trial % levels == 0) along_gradient = gradient && (trial / levels) % 2 == 1 && target_gradient(v, t, scale, grad);
    if (along_gradient) {
      const double r = scale * std::ldexp(1.0, -(trial % levels));
      for (int k = 0; k < 3; ++k) d[k] = r * grad[k];
    } else {
      trial_offset(trial, levels, scale, nrm, d);
    }
    if (!map.identity) {
      const double dm[3] = {d[0], d[1], d[2]};
      map.unapply(dm, d);
    }
    const double q[3] = {best[0] + d[0], best[1] + d[1], best[2] + d[2]};
    double got = 0.0;
    const double floor = rescue ? 0.0 : 0.5 * (work_.old_min + options_.sliver_quality);  // (rescue: its own)
    if (try_move(work_, v, q, floor, &got)) std::copy_n(q, 3, best);
  }
  work_.target = SIZE_MAX;
  work_.rescue = false;
  if (best[0] == start[0] && best[1] == start[1] && best[2] == start[2]) return false;
  this->moved(v);
  touch_tets(work_.ball);  // v's ball (moves keep the tets)
  return true;
}

// The unit direction in which t's quality rises fastest when its vertex v moves (central
// differences, steps of scale * 1e-6); false when flat. Euclidean: for the polish only.
bool Optimizer::target_gradient(uint32_t v, uint32_t t, double scale, double grad[3]) {
  double* x = &mesh_.xyz[3 * size_t(v)];
  const double h = scale * 1e-6;
  double len2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double saved = x[k];
    x[k] = saved + h;
    const double up = quality_.tet(mesh_, t);
    x[k] = saved - h;
    const double down = quality_.tet(mesh_, t);
    x[k] = saved;
    grad[k] = up - down;
    len2 += grad[k] * grad[k];
  }
  if (!(len2 > 0.0)) return false;
  const double len = std::sqrt(len2);
  for (int k = 0; k < 3; ++k) grad[k] /= len;
  return true;
}

// The offset of trial `trial` of a vertex move: lengths halve from `top` over `levels` trials
// and start again; the first `levels` go along nrm (when given), the others in pseudo-random
// directions.
void Optimizer::trial_offset(int trial, int levels, double top, const double* nrm, double d[3]) {
  const double r = top * std::ldexp(1.0, -(trial % levels));
  if (nrm && trial < levels) {
    for (int k = 0; k < 3; ++k) d[k] = r * nrm[k];
  } else {
    for (int k = 0; k < 3; ++k) d[k] = r * (2.0 * next_unit() - 1.0);
  }
}

// The unit normal of facet i of t pointing into t: the direction that opens t when its vertex i
// moves along it; in the coordinates of `map` (the metric's space) when it is not the identity.
// False (nrm zero) when the facet is degenerate.
bool Optimizer::opening_direction(uint32_t t, int i, const meshops::MetricMap& map, double nrm[3]) const {
  const int* f = kFacetVertex[i];
  const double* A = mesh_.point(mesh_.vertex(t, f[0]));
  const double* B = mesh_.point(mesh_.vertex(t, f[1]));
  const double* C = mesh_.point(mesh_.vertex(t, f[2]));
  double u[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]};
  double w[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
  if (!map.identity) {
    const double u0[3] = {u[0], u[1], u[2]}, w0[3] = {w[0], w[1], w[2]};
    map.apply(u0, u);
    map.apply(w0, w);
  }
  nrm[0] = u[1] * w[2] - u[2] * w[1];
  nrm[1] = u[2] * w[0] - u[0] * w[2];
  nrm[2] = u[0] * w[1] - u[1] * w[0];
  const double len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
  if (!(len > 0.0)) {
    nrm[0] = nrm[1] = nrm[2] = 0.0;
    return false;
  }
  for (int k = 0; k < 3; ++k) nrm[k] /= len;
  return true;
}

double Optimizer::shortest_edge(uint32_t t) const {
  double shortest = INFINITY;
  for (const auto& e : kEdgeVertex) {
    const double* p = mesh_.point(mesh_.vertex(t, e[0]));
    const double* q = mesh_.point(mesh_.vertex(t, e[1]));
    double d2 = 0.0;
    for (int k = 0; k < 3; ++k) d2 += (p[k] - q[k]) * (p[k] - q[k]);
    shortest = std::min(shortest, std::sqrt(d2));
  }
  return shortest;
}

bool Optimizer::certified(uint32_t t) const {
  return predicates::orient3d_certified(mesh_.point(mesh_.vertex(t, 0)), mesh_.point(mesh_.vertex(t, 1)),
                                        mesh_.point(mesh_.vertex(t, 2)), mesh_.point(mesh_.vertex(t, 3))) > 0;
}

// Tries v at p for certify_pass(): accepted when the ball stays positive (exact), fewer of its
// tets are uncertified than the `flat` it had, and its worst quality does not drop (no per-tet
// floor: the ball's other tets may give a little so that a flat one opens). Leaves v where it
// was otherwise.
bool Optimizer::try_certify(uint32_t v, const double p[3], size_t flat) {
  double* x = &mesh_.xyz[3 * size_t(v)];
  const double saved[3] = {x[0], x[1], x[2]};
  std::copy_n(p, 3, x);
  double q_min = 1.0;
  size_t still_flat = 0;
  for (size_t k = 0; k < work_.ball.size() && still_flat < flat; ++k) {
    q_min = std::min(q_min, ball_tet_quality(work_, k));
    still_flat += !certified(work_.ball[k]);
  }
  if (still_flat < flat && q_min >= work_.old_min && meshops::all_positive(mesh_, work_.ball)) return true;
  std::copy_n(saved, 3, x);
  return false;
}

// Tets flat to rounding (positive for the exact orient3d, but not certified for a double
// evaluation: a solver or checker computing volumes in doubles may find them zero or inverted)
// that the sliver pass could not open: each free vertex is tried at steps from twice the tet's
// shortest edge down, away from its opposite facet and in pseudo-random directions, until the
// tet is certified; rounds repeat while they open some (a neighbour's move can free a stuck
// one). Then flips on the ones left, and the moves again. Returns how many such tets are left.
size_t Optimizer::certify_pass() {
  auto uncertified = [&] { return optimize_detail::live_tets_where(mesh_, [&](uint32_t t) { return !certified(t); }); };
  auto move_rounds = [&](std::vector<uint32_t>& flat) {
    constexpr int kRounds = 4;
    for (int round = 0; round < kRounds && !flat.empty(); ++round) {
      const size_t before = flat.size();
      certify_round(flat);
      flat.erase(std::remove_if(flat.begin(), flat.end(), [&](uint32_t t) { return mesh_.is_deleted(t) || certified(t); }),
                 flat.end());
      if (flat.size() == before) break;
    }
  };
  std::vector<uint32_t> flat = uncertified();
  stats_.flat_found = flat.size();
  move_rounds(flat);
  if (flat.empty()) return 0;
  // The ones no move opens (every move of their vertices inverts a neighbour): a flip that raises
  // the worst quality of the tets it replaces at all (the sweeps ask for a gain of 1e-6, which a
  // tet among nearly flat ones may not reach), then the moves again on what is still flat.
  const double gain = flips_.gain;
  flips_.gain = 0.0;
  for (uint32_t t : flat) {
    for (int k = 0; k < 6 && !mesh_.is_deleted(t); ++k) optimize_detail::try_remove_edge(flips_, t, k);
    for (int i = 0; i < 4 && !mesh_.is_deleted(t); ++i) optimize_detail::try_flip23(flips_, t, i);
  }
  flips_.gain = gain;
  flat = uncertified();
  move_rounds(flat);
  return flat.size();
}

void Optimizer::certify_round(const std::vector<uint32_t>& flat) {
  constexpr int kLevels = 20, kTrials = 80;
  for (uint32_t t : flat) {
    for (int i = 0; i < 4 && !mesh_.is_deleted(t) && !certified(t); ++i) {
      const uint32_t v = mesh_.vertex(t, i);
      if (!movable(v)) continue;
      meshops::vertex_ball(mesh_, v, t, work_.ball);
      measure_ball(work_, v);
      const double shortest = shortest_edge(t);
      double nrm[3];
      const bool has_normal = opening_direction(t, i, meshops::MetricMap{}, nrm);
      const double start[3] = {mesh_.point(v)[0], mesh_.point(v)[1], mesh_.point(v)[2]};
      auto flat_in_ball = [&] {
        size_t n = 0;
        for (uint32_t b : work_.ball) n += !certified(b);
        return n;
      };
      size_t flat_now = flat_in_ball();
      for (int trial = 0; trial < kTrials && !certified(t); ++trial) {
        double d[3];
        trial_offset(trial, kLevels, 2.0 * shortest, has_normal ? nrm : nullptr, d);
        const double q[3] = {start[0] + d[0], start[1] + d[1], start[2] + d[2]};
        if (try_certify(v, q, flat_now)) {
          measure_ball(work_, v);  // the new position is the next trial's reference
          flat_now = flat_in_ball();
          moved(v);
          touch_tets(work_.ball);  // v's ball (moves keep the tets)
        }
      }
    }
  }
}

Result<OptimizeStats> Optimizer::run() {
  const auto start = Clock::now();
  auto lap = Clock::now();
  // Adds the time since the last call to `into`.
  auto take_lap = [&lap](double& into) {
    const auto now = Clock::now();
    into += std::chrono::duration<double>(now - lap).count();
    lap = now;
  };
  for (uint32_t t = 0; t < mesh_.num_tet_slots(); ++t)
    if (!mesh_.is_deleted(t) && mesh_.is_ghost(t))
      return Status(Error::InvalidArgument, "optimize: the mesh has ghost tets");
  stats_.before = summarize_quality(mesh_);
  vt_.build(mesh_);
  const auto nv = static_cast<uint32_t>(mesh_.num_vertices());
  sizes_.assign(nv, -1.0);
  // An anisotropic metric at some vertex: every measure is taken in the metric (see Quality).
  // The same queries fill the size cache, which CVT would otherwise fill with them again.
  {
    std::vector<double> metrics(6 * size_t(nv));
    std::vector<uint8_t> aniso(nv, 0);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, nv, 1024), [&](const tbb::blocked_range<uint32_t>& r) {
      for (uint32_t v = r.begin(); v < r.end(); ++v) {
        const double* m = &metrics[6 * size_t(v)];
        field_.metric(mesh_.point(v), &metrics[6 * size_t(v)]);
        aniso[v] = !meshops::MetricMap::of(m).identity;
        sizes_[v] = metric_size(m);
      }
    });
    if (std::find(aniso.begin(), aniso.end(), 1) != aniso.end()) {
      quality_.vertex_metric = std::move(metrics);
      metric_stale_.assign(nv, 0);
    }
  }
  stats_.anisotropic = quality_.anisotropic();
  flips_.keep_lengths_in_range = options_.keep_lengths_in_range;
  if (stats_.anisotropic) stats_.length_in_range_before = share_in_range();
  take_lap(stats_.seconds_setup);
  for (int it = 0; it < options_.cvt_iterations; ++it) {
    refresh_metrics();
    stats_.moves += cvt_pass();
    refresh_metrics();
    take_lap(stats_.seconds_cvt);
    optimize_detail::flip_sweep(flips_, options_.flip_quality, 3);
    take_lap(stats_.seconds_flips);
    // The CVT iterations are about two thirds of the stage's time.
    if (options_.progress) options_.progress(0.65 * double(it + 1) / double(options_.cvt_iterations));
  }
  std::vector<uint32_t>().swap(ball_start_);
  std::vector<uint32_t>().swap(ball_tets_);
  // Anisotropic: the rounds stop when the tets below sliver_quality no longer fall by 2% a
  // round (the UGAWG cube to its .sol: 4652, 4726, 4821, 4819, 4781, 4801 in six rounds of
  // 2000 moves each, a third of the run's time).
  size_t bad_before = SIZE_MAX;
  for (int round = 0; round < options_.sliver_rounds; ++round) {
    optimize_detail::flip_sweep(flips_, options_.flip_quality, 3);
    take_lap(stats_.seconds_flips);
    size_t bad_now = 0;
    const size_t bad_limit = quality_.anisotropic() && round > 0 ? size_t(0.98 * double(bad_before)) : SIZE_MAX;
    const size_t moved = perturb_pass(nullptr, bad_limit, &bad_now);
    bad_before = bad_now;
    refresh_metrics();
    stats_.perturbations += moved;
    take_lap(stats_.seconds_slivers);
    // A round that lifts under 2% of the tets it tries is followed by no other: the rest are held
    // by S's own slivers (adis16480: 451 moves of 69k tried, 4 s a round) and go to the collapses.
    if (moved == 0 || moved < bad_now / 50) break;
  }
  if (options_.progress) options_.progress(0.85);
  // Tets that no move lifted, such as four nearly collinear points whose every vertex is held by
  // its other tets, get an edge collapse, then the flips and one more perturbation round.
  // The perturbation round after collapses looks only at the tets near them: the others were
  // tried by every round before.
  for (int round = 0; round < options_.collapse_rounds && options_.collapse_quality > 0.0; ++round) {
    collapsed_near_.assign(mesh_.num_vertices(), 0);
    const size_t collapsed = collapse_pass();
    stats_.collapses += collapsed;
    take_lap(stats_.seconds_slivers);
    if (collapsed == 0) break;
    optimize_detail::flip_sweep(flips_, options_.flip_quality, 3);
    take_lap(stats_.seconds_flips);
    stats_.perturbations += perturb_pass(&collapsed_near_);
    refresh_metrics();
    take_lap(stats_.seconds_slivers);
  }
  // The polish, then the perturbation of the tets it lowered (the worst one's neighbours bound
  // it), twice more, then only near the balls the round before changed (the tets it could not
  // lift elsewhere would be tried again in vain: adis16480, 8000 tets below 0.1 on its needle
  // fans, 1.7 s a round for 15 moves); part of sliver removal (none with sliver_rounds 0).
  std::vector<uint8_t> polished_near;
  for (int round = 0; round < 3 && options_.sliver_rounds > 0; ++round) {
    collapsed_near_.assign(mesh_.num_vertices(), 0);
    const size_t polished = polish_pass(round == 0 ? nullptr : &polished_near, collapsed_near_);
    stats_.perturbations += polished;
    refresh_metrics();
    if (polished == 0) break;
    stats_.perturbations += perturb_pass(&collapsed_near_);
    refresh_metrics();
    polished_near.swap(collapsed_near_);
  }
  // The rescue (see the top); after its first round, only the tets near its moves: the others
  // were tried already.
  std::vector<uint8_t> rescued_near;
  for (int round = 0; round < 3 && options_.sliver_rounds > 0; ++round) {
    collapsed_near_.assign(mesh_.num_vertices(), 0);
    const size_t rescued = rescue_pass(round == 0 ? nullptr : &rescued_near, collapsed_near_);
    stats_.perturbations += rescued;
    refresh_metrics();
    if (rescued == 0) break;
    optimize_detail::flip_sweep(flips_, options_.flip_quality, 3);
    rescued_near.swap(collapsed_near_);
  }
  take_lap(stats_.seconds_slivers);
  optimize_detail::flip_sweep(flips_, options_.flip_quality, 3);
  take_lap(stats_.seconds_flips);
  stats_.flat_left = certify_pass();
  take_lap(stats_.seconds_certify);
  if (stats_.anisotropic) {
    refresh_metrics();
    stats_.length_in_range_after = share_in_range();
    take_lap(stats_.seconds_setup);
  }
  stats_.flips23 = flips_.flips23;
  stats_.edge_removals = flips_.edge_removals;
  stats_.after = summarize_quality(mesh_);
  take_lap(stats_.seconds_setup);
  stats_.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return stats_;
}

}  // namespace

namespace {

// The summary of per-slot qualities q (-2: not a live tet), summed in slot order.
QualitySummary summarize(const std::vector<double>& q) {
  QualitySummary s;
  s.min = 1.0;
  double sum = 0.0;
  for (double x : q) {
    if (x == -2.0) continue;
    ++s.tets;
    sum += x;
    s.min = std::min(s.min, x);
    s.below_01 += x < 0.1 ? 1 : 0;
    s.below_04 += x < 0.4 ? 1 : 0;
  }
  s.mean = s.tets ? sum / double(s.tets) : 0.0;
  if (s.tets == 0) s.min = 0.0;
  return s;
}

}  // namespace

QualitySummary summarize_quality(const TetMesh& mesh) {
  const uint32_t n = mesh.num_tet_slots();
  std::vector<double> q(n, -2.0);  // -2: not a live tet
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 4096), [&](const tbb::blocked_range<uint32_t>& r) {
    for (uint32_t t = r.begin(); t < r.end(); ++t)
      if (!mesh.is_deleted(t) && !mesh.is_ghost(t)) q[t] = meshops::tet_radius_ratio(mesh, t);
  });
  return summarize(q);
}

QualitySummary summarize_metric_quality(const TetMesh& mesh, const SizingField& field) {
  const uint32_t n = mesh.num_tet_slots();
  std::vector<double> q(n, -2.0);  // -2: not a live tet
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 1024), [&](const tbb::blocked_range<uint32_t>& r) {
    for (uint32_t t = r.begin(); t < r.end(); ++t) {
      if (mesh.is_deleted(t) || mesh.is_ghost(t)) continue;
      const double* p[4];
      double c[3] = {0.0, 0.0, 0.0};
      for (int i = 0; i < 4; ++i) {
        p[i] = mesh.point(mesh.vertex(t, i));
        for (int k = 0; k < 3; ++k) c[k] += 0.25 * p[i][k];
      }
      double m[6];
      field.metric(c, m);
      const meshops::MetricMap map = meshops::MetricMap::of(m);
      double mapped[4][3];
      for (int i = 0; i < 4; ++i) map.apply(p[i], mapped[i]);
      q[t] = map.identity ? meshops::radius_ratio(p[0], p[1], p[2], p[3])
                          : meshops::radius_ratio(mapped[0], mapped[1], mapped[2], mapped[3]);
    }
  });
  return summarize(q);
}

FlatTetFlips flip_flat_tets(TetMesh& mesh) {
  auto certified = [&](uint32_t t) {
    return predicates::orient3d_certified(mesh.point(mesh.vertex(t, 0)), mesh.point(mesh.vertex(t, 1)),
                                          mesh.point(mesh.vertex(t, 2)), mesh.point(mesh.vertex(t, 3))) > 0;
  };
  auto flat_tets = [&] {
    return optimize_detail::live_tets_where(mesh, [&](uint32_t t) { return !mesh.is_ghost(t) && !certified(t); });
  };
  FlatTetFlips out;
  std::vector<uint32_t> flat = flat_tets();
  out.found = out.left = flat.size();
  if (flat.empty()) return out;
  meshops::VertexTets vt;
  vt.build(mesh);
  optimize_detail::FlipContext c{mesh, vt, {}, {}, {}, {}, {}};
  c.gain = 0.0;  // any gain: the worst tet is flat, the flip that makes it less so is wanted
  c.rule = meshops::ConstrainedEdges::kKeep;
  constexpr int kRounds = 4;
  for (int round = 0; round < kRounds; ++round) {
    for (uint32_t t : flat) {
      for (int k = 0; k < 6 && !mesh.is_deleted(t); ++k) optimize_detail::try_remove_edge(c, t, k);
      for (int i = 0; i < 4 && !mesh.is_deleted(t); ++i) optimize_detail::try_flip23(c, t, i);
    }
    flat = flat_tets();
    const bool dropped = flat.size() < out.left;
    out.left = flat.size();
    if (!dropped || flat.empty()) break;
  }
  out.flips = c.flips23 + c.edge_removals;
  return out;
}

Result<OptimizeStats> optimize_mesh(TetMesh& mesh, const SizingField& field, const OptimizeOptions& options) {
  if (options.cvt_iterations < 0 || options.sliver_rounds < 0 || options.perturb_trials < 0 ||
      options.collapse_rounds < 0)
    return Status(Error::InvalidArgument, "optimize: iteration counts must be >= 0");
  if (options.num_threads < 0) return Status(Error::InvalidArgument, "optimize: num_threads must be >= 0");
  Optimizer optimizer(mesh, field, options);
  if (options.num_threads == 0) return optimizer.run();
  // Every parallel loop inside runs in this arena (one thread: the same result, sequentially).
  tbb::task_arena arena(options.num_threads);
  return arena.execute([&] { return optimizer.run(); });
}

}  // namespace anitet
