// Quality-driven flips (internal to optimize/): 2-3 on a facet, and edge removal (3-2, 4-4, and
// up to a ring of 7 tets) with the triangulation of the edge's ring that maximizes the worst
// radius ratio (dynamic programming over the ring polygon). A flip is applied only when it raises
// the worst radius ratio of the tets it replaces by more than `gain`.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/tet_mesh.hpp"
#include "refine/mesh_ops.hpp"

namespace anitet::optimize_detail {

// The shape measure the flips and moves maximize: meshops::shape_quality, or, when vertex_metric
// is filled (an anisotropic metric; 6 per vertex), the same measured in the metric: each tet in
// the mean of its four vertices' metrics, so that its figure does not depend on which ball or
// flip measures it. Euclidean when empty, bit for bit meshops::shape_quality.
struct Quality {
  std::vector<double> vertex_metric;
  bool anisotropic() const { return !vertex_metric.empty(); }
  double of(const TetMesh& m, const uint32_t v[4]) const;
  double tet(const TetMesh& m, uint32_t t) const { return of(m, &m.tet_v[4 * size_t(t)]); }
  // The metric a tet on v[4] is measured in (the mean of its vertices' metrics; the identity when
  // Euclidean), and the quality in a given one: a caller that measures the same tets again and
  // again while only their points move (a vertex's trial positions) factors it once.
  meshops::MetricMap map(const uint32_t v[4]) const;
  double of(const TetMesh& m, const uint32_t v[4], const meshops::MetricMap& map) const {
    return meshops::metric_shape_quality(map, m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3]));
  }
  static const Quality& euclidean();  // the empty one
};

// Which tets flip_sweep() need not try again: a tet for which it found no flip fails again as long
// as nothing within reach changed, and everything its attempts look at (the rings of its edges,
// the tets across its facets, their qualities) lies in the balls of its four vertices. So events
// are numbered in order: each vertex keeps the number of the last change in its ball (a tet made
// or removed there, a vertex of it moved, its metric measured again), each tet the number of the
// last failure on it, and a tet is skipped while its failure is newer than the changes of all
// four. The skips change no result, only the time: the sweeps after the CVT iterations meet the
// same tets below the flip threshold each time, nearly all failing again.
//
// The same numbers date each tet's quality as last measured by tets_below(): a tet's quality
// depends only on its four vertices (their points and metrics), and any change to them, or a new
// tet in the slot, touches them. So a measure newer than the changes of all four still holds, and
// the scans before each sweep (every tet of the mesh otherwise, each time) measure only the tets
// changed since the last one.
struct FlipMemo {
  uint32_t clock = 0;                  // the last event's number
  uint32_t everything = 0;             // the last change anywhere (touch_all)
  std::vector<uint32_t> changed;       // per vertex: its ball's last change (0: none)
  std::vector<uint32_t> failed;        // per tet slot: its last failure (0: none)
  double quality = -1.0, gain = -1.0;  // the sweep parameters the failures hold for
  std::vector<double> quality_of;      // per tet slot: its quality when `measured`
  std::vector<uint32_t> measured;      // per tet slot: the measure's number (0: none)
  void touch(uint32_t v) {
    if (v >= changed.size()) changed.resize(size_t(v) + 1, 0);
    changed[v] = tick();
  }
  void touch_all() { everything = tick(); }
  void fail(uint32_t t) {
    if (t >= failed.size()) failed.resize(size_t(t) + 1, 0);
    failed[t] = tick();
  }
  // t's vertices v[4]: its last failure is newer than any change in reach.
  bool still_fails(uint32_t t, const uint32_t v[4]) const;
  // quality_of[t] is t's quality still (t's vertices v[4]).
  bool knows_quality(uint32_t t, const uint32_t v[4]) const { return t < measured.size() && newer_than_changes(measured[t], v); }
  // The number for the measures of a scan over `slots` tet slots (sized for them): one event, so
  // that every change after the scan is newer.
  uint32_t start_measures(size_t slots) {
    if (quality_of.size() < slots) {
      quality_of.resize(slots, 0.0);
      measured.resize(slots, 0);
    }
    return tick();
  }

 private:
  // Event `when` (0: none) came after the last change anywhere and in the balls of v[4].
  bool newer_than_changes(uint32_t when, const uint32_t v[4]) const {
    if (when == 0 || when <= everything) return false;
    for (int i = 0; i < 4; ++i)
      if (v[i] < changed.size() && when <= changed[v[i]]) return false;  // (beyond: never changed)
    return true;
  }
  uint32_t tick() {
    if (clock == 0xffffffffu) {  // numbers run out: forget everything and start again
      std::fill(changed.begin(), changed.end(), 0);
      std::fill(failed.begin(), failed.end(), 0);
      std::fill(measured.begin(), measured.end(), 0);
      clock = everything = 0;
    }
    return ++clock;
  }
};

struct FlipContext {
  TetMesh& mesh;
  meshops::VertexTets& vt;
  meshops::ReplaceScratch scratch;
  std::vector<uint32_t> ring_tets, ring;
  std::vector<uint32_t> old;
  std::vector<meshops::TetVerts> fresh;
  double gain = 1e-6;
  // kRefuse in the optimizer (S's edges never move); kKeep on a recovered surface, whose
  // constrained edges are subsegments of S that no flip here can remove anyway.
  meshops::ConstrainedEdges rule = meshops::ConstrainedEdges::kRefuse;
  size_t flips23 = 0, edge_removals = 0;
  const Quality* quality = &Quality::euclidean();
  // Anisotropic quality: a flip may not add edges out of [1/sqrt2, sqrt2] in the vertices'
  // metrics beyond those it removes (a 2-3 flip's new edge must be in range; an edge removal
  // may make no more out-of-range edges than the one it removes).
  bool keep_lengths_in_range = false;
  FlipMemo memo{};
  // flip_sweep() runs a round on two tasks when it has at least this many tets to try.
  size_t parallel_min = 4096;
  // Inside one of those tasks (set by flip_sweep): the task may read and change only the tets
  // whose four vertices have side[v] == me; an attempt that needs another tet (or more slots
  // than the task's pool has) sets `foreign` and fails, for the sequential round after. The
  // memo's events go to `log` (replayed after the tasks) and mark `phase_touched`.
  const uint8_t* side = nullptr;
  uint8_t me = 0;
  bool foreign = false;
  std::vector<uint64_t>* log = nullptr;  // 2 v: touch(v); 2 t + 1: fail(t)
  uint8_t* phase_touched = nullptr;
  const FlipMemo* memo_source = nullptr;  // the memo a task reads (its own `memo` unused)
  bool owns(uint32_t t) const {
    if (!side) return true;
    const uint32_t* v = &mesh.tet_v[4 * size_t(t)];
    return side[v[0]] == me && side[v[1]] == me && side[v[2]] == me && side[v[3]] == me;
  }
  // Room in the task's pool for replacing `old_count` tets by `new_count`.
  bool has_room(size_t old_count, size_t new_count) const {
    const meshops::ReplaceScratch::SlotPool& p = scratch.pool;
    return !scratch.use_pool || p.free.size() + old_count + (p.end - p.next) >= new_count;
  }
  // A memo event, 2 v (a change in v's ball) or 2 t + 1 (a failure on t): to the memo, or, in a
  // task of the parallel round, to its log (replayed into the memo after the tasks).
  void record(uint64_t event) {
    const auto id = static_cast<uint32_t>(event >> 1);
    if (log) {
      log->push_back(event);
      if ((event & 1u) == 0) phase_touched[id] = 1;
    } else if (event & 1u) {
      memo.fail(id);
    } else {
      memo.touch(id);
    }
  }
  void touch_tets(const std::vector<meshops::TetVerts>& tets) {
    for (const meshops::TetVerts& f : tets)
      for (uint32_t x : f) record(2 * uint64_t(x));
  }
  double tet(uint32_t t) const { return quality->tet(mesh, t); }
  // The same, from the memo's measure when it still holds (the flips' tets are mostly ones
  // tets_below() measured, and each measure in the metric takes a mean and a Cholesky factor).
  double known_tet(uint32_t t) const {
    const FlipMemo& m = memo_source ? *memo_source : memo;
    const uint32_t* v = &mesh.tet_v[4 * size_t(t)];
    const bool touched =
        phase_touched && (phase_touched[v[0]] | phase_touched[v[1]] | phase_touched[v[2]] | phase_touched[v[3]]);
    return m.knows_quality(t, v) && !touched ? m.quality_of[t] : tet(t);
  }
  double of(const uint32_t v[4]) const { return quality->of(mesh, v); }
};

// Per vertex, 0 or 1: below or above the median of the coordinates along the vertices' longest
// extent (the split of the optimizer's two-task passes).
std::vector<uint8_t> median_sides(const TetMesh& m);

// 2-3 flip of facet i of tet t (not protected, with a neighbour).
bool try_flip23(FlipContext& c, uint32_t t, int i);
// Removes edge k (kEdgeVertex order) of tet t.
bool try_remove_edge(FlipContext& c, uint32_t t, int k);
// The live tets t with pred(t), in slot order; pred is evaluated on every core (it must only
// read the mesh).
template <class Pred>
std::vector<uint32_t> live_tets_where(const TetMesh& m, Pred&& pred) {
  const uint32_t n = m.num_tet_slots();
  std::vector<uint8_t> hit(n, 0);
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 1u << 14), [&](const tbb::blocked_range<uint32_t>& r) {
    for (uint32_t t = r.begin(); t < r.end(); ++t) hit[t] = !m.is_deleted(t) && pred(t);
  });
  std::vector<uint32_t> out;
  for (uint32_t t = 0; t < n; ++t)
    if (hit[t]) out.push_back(t);
  return out;
}
// The live tets whose shape quality is below `quality`, in slot order (measured on every core).
// With a memo, only the tets changed since its last measure are measured again (the memo must
// always be given measures by the same `measure`, and told of every change, as flip_sweep() asks).
std::vector<uint32_t> tets_below(const TetMesh& m, double quality, const Quality& measure = Quality::euclidean(),
                                 FlipMemo* memo = nullptr);
// Tries edge removals then 2-3 flips on every live tet below `quality`, then for at most
// `rounds` - 1 more rounds on the new tets still below it. Returns the number of flips. With at
// least c.parallel_min tets to try, a round runs on two tasks, one per side of the median
// plane across the vertices' longest extent, each on the tets all of whose vertices lie on its
// side (they read and change disjoint tets; slots from pools of their own), then the tets left
// (across the plane, or whose flip needed a tet across it) in slot order. The result depends on
// parallel_min, never on the thread count. Skips the tets c.memo knows to fail: whoever moves a
// vertex or changes a metric between sweeps must touch the vertices of its ball (or touch_all);
// the flips touch their own.
size_t flip_sweep(FlipContext& c, double quality, int rounds);

}  // namespace anitet::optimize_detail
