#include "optimize/flips.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "core/bvh.hpp"
#include "core/metric_measures.hpp"
#include "core/sizing.hpp"
#include "predicates/predicates.hpp"

namespace anitet::optimize_detail {

const Quality& Quality::euclidean() {
  static const Quality empty;
  return empty;
}

double Quality::of(const TetMesh& m, const uint32_t v[4]) const {
  if (vertex_metric.empty()) return meshops::shape_quality(m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3]));
  return of(m, v, map(v));
}

meshops::MetricMap Quality::map(const uint32_t v[4]) const {
  if (vertex_metric.empty()) return {};
  double mean[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 6; ++k) mean[k] += 0.25 * vertex_metric[6 * size_t(v[i]) + k];
  return meshops::MetricMap::of(mean);
}

bool FlipMemo::still_fails(uint32_t t, const uint32_t v[4]) const {
  return t < failed.size() && newer_than_changes(failed[t], v);
}

namespace {

// Whether edge ab's normalized length, in its ends' metrics, is out of [1/sqrt2, sqrt2].
bool out_of_range(const FlipContext& c, uint32_t a, uint32_t b) {
  const std::vector<double>& m = c.quality->vertex_metric;
  const double l = metric_edge_length(&m[6 * size_t(a)], c.mesh.point(a), &m[6 * size_t(b)], c.mesh.point(b));
  return !in_unit_range(l);
}

bool guard_lengths(const FlipContext& c) { return c.keep_lengths_in_range && c.quality->anisotropic(); }

}  // namespace

bool try_flip23(FlipContext& c, uint32_t t, int i) {
  TetMesh& m = c.mesh;
  if (m.is_deleted(t) || m.facet_protected(t, i) || m.tet_adj[4 * size_t(t) + i] == TetMesh::kNoNeighbour)
    return false;
  const uint32_t n = m.neighbour(t, i);
  const int j = m.neighbour_facet(t, i);
  if (m.facet_protected(n, j)) return false;
  if (!c.owns(t) || !c.owns(n)) {
    c.foreign = true;
    return false;
  }
  const uint32_t d = m.vertex(t, i), e = m.vertex(n, j);
  if (guard_lengths(c) && out_of_range(c, d, e)) return false;
  const uint32_t f[3] = {m.vertex(t, kFacetVertex[i][0]), m.vertex(t, kFacetVertex[i][1]),
                         m.vertex(t, kFacetVertex[i][2])};
  const double before = std::min(c.known_tet(t), c.known_tet(n));
  double after = 1.0;
  c.fresh.clear();
  for (int k = 0; k < 3; ++k) {
    const meshops::TetVerts v = {f[k], f[(k + 1) % 3], e, d};
    after = std::min(after, c.of(v.data()));
    if (after <= before + c.gain) return false;
    c.fresh.push_back(v);
  }
  c.old = {t, n};
  if (!c.has_room(c.old.size(), c.fresh.size())) {
    c.foreign = true;
    return false;
  }
  if (!meshops::replace_tets(m, c.old, c.fresh, c.vt, c.scratch, c.rule)) return false;
  c.touch_tets(c.fresh);
  ++c.flips23;
  return true;
}

bool try_remove_edge(FlipContext& c, uint32_t t, int k) {
  TetMesh& m = c.mesh;
  if (m.is_deleted(t)) return false;
  const uint32_t a = m.vertex(t, kEdgeVertex[k][0]), b = m.vertex(t, kEdgeVertex[k][1]);
  if (!meshops::edge_ring(m, a, b, t, c.ring_tets, c.ring)) return false;
  const int n = static_cast<int>(c.ring.size());
  if (n < 3 || n > 7) return false;
  for (uint32_t s : c.ring_tets)
    if (!c.owns(s)) {
      c.foreign = true;
      return false;
    }
  double before = 1.0;
  for (uint32_t s : c.ring_tets) before = std::min(before, c.known_tet(s));
  // Orient the ring so that (r_i r_j r_k a) and (r_j r_i r_k b) are positive for i < j < k.
  if (predicates::orient3d(m.point(a), m.point(b), m.point(c.ring[0]), m.point(c.ring[1])) > 0)
    std::reverse(c.ring.begin(), c.ring.end());
  const uint32_t* r = c.ring.data();
  // best[i][j]: the best worst quality of a triangulation of the sub-polygon r_i .. r_j, exact
  // where it beats `bar` (only such a triangulation can replace the ring); a candidate that
  // cannot beat both bar and the best so far is not measured (its value would not change the
  // decision or the triangulation chosen), nor its second tet once the first fails.
  const double bar = before + c.gain;
  double best[7][7];
  int split[7][7];
  for (int len = 1; len < n; ++len)
    for (int i = 0; i + len < n; ++i) {
      const int j = i + len;
      if (len == 1) {
        best[i][j] = 2.0;
        split[i][j] = -1;
        continue;
      }
      best[i][j] = -2.0;
      split[i][j] = -1;
      for (int l = i + 1; l < j; ++l) {
        const double need = std::max(best[i][j], bar);
        const double sub = std::min(best[i][l], best[l][j]);
        if (!(sub > need)) continue;
        const uint32_t ta[4] = {r[i], r[l], r[j], a}, tb[4] = {r[l], r[i], r[j], b};
        const double qa = c.of(ta);
        if (!(qa > need)) continue;
        const double q = std::min({sub, qa, c.of(tb)});
        if (q > best[i][j]) {
          best[i][j] = q;
          split[i][j] = l;
        }
      }
    }
  if (best[0][n - 1] <= bar) return false;
  c.fresh.clear();
  int stack[16][2], top = 0;
  stack[top][0] = 0;
  stack[top][1] = n - 1;
  ++top;
  while (top > 0) {
    --top;
    const int i = stack[top][0], j = stack[top][1];
    const int l = split[i][j];
    if (l < 0) continue;
    c.fresh.push_back({r[i], r[l], r[j], a});
    c.fresh.push_back({r[l], r[i], r[j], b});
    stack[top][0] = i;
    stack[top][1] = l;
    ++top;
    stack[top][0] = l;
    stack[top][1] = j;
    ++top;
  }
  if (guard_lengths(c)) {
    // The new edges are the diagonals of the ring polygon's triangulation (c.fresh holds its
    // triangles, each as (r_i, r_l, r_j, a)); each diagonal is a side of two triangles.
    auto at = [&](uint32_t v) { return std::find(c.ring.begin(), c.ring.end(), v) - c.ring.begin(); };
    int out_twice = 0;
    for (size_t f = 0; f < c.fresh.size(); f += 2)
      for (int e = 0; e < 3; ++e) {
        const uint32_t p = c.fresh[f][e], q = c.fresh[f][(e + 1) % 3];
        const auto gap = std::abs(at(p) - at(q));
        if (gap != 1 && gap != n - 1) out_twice += out_of_range(c, p, q) ? 1 : 0;
      }
    if (out_twice > (out_of_range(c, a, b) ? 2 : 0)) return false;
  }
  c.old = c.ring_tets;
  if (!c.has_room(c.old.size(), c.fresh.size())) {
    c.foreign = true;
    return false;
  }
  if (!meshops::replace_tets(m, c.old, c.fresh, c.vt, c.scratch, c.rule)) return false;
  c.touch_tets(c.fresh);
  ++c.edge_removals;
  return true;
}

std::vector<uint32_t> tets_below(const TetMesh& m, double quality, const Quality& measure, FlipMemo* memo) {
  if (!memo) return live_tets_where(m, [&](uint32_t t) { return measure.tet(m, t) < quality; });
  const uint32_t now = memo->start_measures(m.num_tet_slots());
  return live_tets_where(m, [&](uint32_t t) {
    if (!memo->knows_quality(t, &m.tet_v[4 * size_t(t)])) {  // (each task writes its own slots)
      memo->quality_of[t] = measure.tet(m, t);
      memo->measured[t] = now;
    }
    return memo->quality_of[t] < quality;
  });
}

std::vector<uint8_t> median_sides(const TetMesh& m) {
  const auto nv = static_cast<uint32_t>(m.num_vertices());
  if (nv == 0) return {};
  const Box3 box = bounding_box(m.xyz.data(), nv);
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (box.hi[k] - box.lo[k] > box.hi[axis] - box.lo[axis]) axis = k;
  std::vector<double> coords(nv);
  for (uint32_t v = 0; v < nv; ++v) coords[v] = m.point(v)[axis];
  std::nth_element(coords.begin(), coords.begin() + nv / 2, coords.end());
  const double cut = coords[nv / 2];
  std::vector<uint8_t> side(nv);
  for (uint32_t v = 0; v < nv; ++v) side[v] = m.point(v)[axis] < cut ? 0 : 1;
  return side;
}

namespace {

// One round over `bad` (slot order): each live tet still below `quality` and not known to fail
// gets the first edge removal or 2-3 flip that raises its worst tet. The new tets still below
// go to fresh_bad; with c.log (a task of the parallel round), a tet whose attempts needed what
// the task may not touch goes to `deferred`. Returns the number of flips.
size_t flip_round(FlipContext& c, double quality, const std::vector<uint32_t>& bad, std::vector<uint32_t>& fresh_bad,
                  std::vector<uint32_t>* deferred) {
  TetMesh& m = c.mesh;
  const FlipMemo& memo = c.memo_source ? *c.memo_source : c.memo;
  auto touched_now = [&](const uint32_t* v) {
    return c.phase_touched && (c.phase_touched[v[0]] | c.phase_touched[v[1]] | c.phase_touched[v[2]] | c.phase_touched[v[3]]);
  };
  size_t flips = 0;
  for (uint32_t t : bad) {
    // t is measured once: a flip that fails leaves it as it was, one that succeeds ends its turn.
    if (m.is_deleted(t)) continue;
    const uint32_t* v = &m.tet_v[4 * size_t(t)];
    if ((memo.still_fails(t, v) && !touched_now(v)) || c.known_tet(t) >= quality) continue;
    c.foreign = false;
    bool done = false;
    for (int k = 0; k < 6 && !done && !m.is_deleted(t); ++k) done = try_remove_edge(c, t, k);
    for (int i = 0; i < 4 && !done && !m.is_deleted(t); ++i) done = try_flip23(c, t, i);
    if (done) {
      ++flips;
      for (uint32_t s : c.scratch.created)
        if (c.tet(s) < quality) fresh_bad.push_back(s);
    } else if (c.foreign && deferred) {
      deferred->push_back(t);
    } else {
      c.record(2 * uint64_t(t) + 1);
    }
  }
  return flips;
}

// A round on two tasks (see flip_sweep): returns its flips; fresh_bad gets the new tets
// still below `quality`, `rest` the tets left to the sequential round, in slot order.
size_t parallel_round(FlipContext& c, double quality, const std::vector<uint32_t>& bad, std::vector<uint32_t>& fresh_bad,
                      std::vector<uint32_t>& rest) {
  TetMesh& m = c.mesh;
  const auto nv = static_cast<uint32_t>(m.num_vertices());
  const std::vector<uint8_t> side = median_sides(m);
  std::vector<uint8_t> touched(nv, 0);

  struct Task {
    std::vector<uint32_t> mine, fresh, deferred;
    std::vector<uint64_t> log;
    size_t flips = 0, flips23 = 0, edge_removals = 0;
    meshops::ReplaceScratch scratch;
  };
  Task tasks[2];
  for (uint32_t t : bad) {
    const uint32_t* v = &m.tet_v[4 * size_t(t)];
    const uint8_t s = side[v[0]];
    if (side[v[1]] == s && side[v[2]] == s && side[v[3]] == s) tasks[s].mine.push_back(t);
    else rest.push_back(t);
  }
  // Pools of an eighth of the task's tets (flips mostly keep the count; a task that runs out
  // leaves the rest to the sequential round): the mesh's free slots dealt out in turn, then
  // fresh ones.
  size_t want[2];
  for (int k = 0; k < 2; ++k) {
    want[k] = tasks[k].mine.size() / 8 + 1024;
    tasks[k].scratch.use_pool = true;
  }
  size_t kept = 0;
  for (size_t i = 0; i < m.free_tets.size(); ++i) {
    std::vector<uint32_t>& free = tasks[i % 2].scratch.pool.free;
    if (free.size() < want[i % 2]) free.push_back(m.free_tets[i]);
    else m.free_tets[kept++] = m.free_tets[i];
  }
  m.free_tets.resize(kept);
  size_t total = 0;
  for (int k = 0; k < 2; ++k) total += want[k] - tasks[k].scratch.pool.free.size();
  uint32_t next = meshops::append_pool_slots(m, total);
  for (int k = 0; k < 2; ++k) {
    meshops::ReplaceScratch::SlotPool& pool = tasks[k].scratch.pool;
    pool.next = next;
    pool.end = next + static_cast<uint32_t>(want[k] - pool.free.size());
    next = pool.end;
  }
  c.vt.reserve(m);
  // Each task reads the memo (through memo_source) and logs its own events.
  auto task_body = [&](int k) {
    Task& task = tasks[k];
    FlipContext sub{m, c.vt, std::move(task.scratch), {}, {}, {}, {}};
    sub.gain = c.gain;
    sub.rule = c.rule;
    sub.quality = c.quality;
    sub.keep_lengths_in_range = c.keep_lengths_in_range;
    sub.side = side.data();
    sub.me = static_cast<uint8_t>(k);
    sub.log = &task.log;
    sub.phase_touched = touched.data();
    sub.memo_source = &c.memo;
    task.flips = flip_round(sub, quality, task.mine, task.fresh, &task.deferred);
    task.flips23 = sub.flips23;
    task.edge_removals = sub.edge_removals;
    task.scratch = std::move(sub.scratch);
  };
  tbb::parallel_invoke([&] { task_body(0); }, [&] { task_body(1); });
  size_t flips = 0;
  for (Task& task : tasks) {
    meshops::return_pool_slots(m, task.scratch.pool);
    for (uint64_t e : task.log) c.record(e);  // (c has no log: into the memo)
    fresh_bad.insert(fresh_bad.end(), task.fresh.begin(), task.fresh.end());
    rest.insert(rest.end(), task.deferred.begin(), task.deferred.end());
    flips += task.flips;
    c.flips23 += task.flips23;
    c.edge_removals += task.edge_removals;
  }
  std::sort(rest.begin(), rest.end());
  return flips;
}

}  // namespace

size_t flip_sweep(FlipContext& c, double quality, int rounds) {
  TetMesh& m = c.mesh;
  size_t total = 0;
  FlipMemo& memo = c.memo;
  if (memo.quality != quality || memo.gain != c.gain) {
    memo.touch_all();  // failures under other parameters say nothing
    memo.quality = quality;
    memo.gain = c.gain;
  }
  // The first round scans the mesh; later ones only revisit the tets the flips created. Every
  // round with parallel_min tets or more runs on two tasks (on a large mesh the later rounds
  // still revisit tens of thousands).
  std::vector<uint32_t> bad = tets_below(m, quality, *c.quality, &memo), fresh_bad, rest;
  for (int round = 0; round < rounds && !bad.empty(); ++round) {
    fresh_bad.clear();
    size_t flips = 0;
    if (bad.size() >= c.parallel_min) {
      rest.clear();
      flips += parallel_round(c, quality, bad, fresh_bad, rest);
      flips += flip_round(c, quality, rest, fresh_bad, nullptr);
    } else {
      flips += flip_round(c, quality, bad, fresh_bad, nullptr);
    }
    total += flips;
    if (flips == 0) break;
    bad.swap(fresh_bad);
  }
  return total;
}

}  // namespace anitet::optimize_detail
