#include "optimize/flips.hpp"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "predicates/predicates.hpp"

namespace anitet::optimize_detail {

const Quality& Quality::euclidean() {
  static const Quality empty;
  return empty;
}

double Quality::of(const TetMesh& m, const uint32_t v[4]) const {
  const double* p[4] = {m.point(v[0]), m.point(v[1]), m.point(v[2]), m.point(v[3])};
  if (vertex_metric.empty()) return meshops::shape_quality(p[0], p[1], p[2], p[3]);
  double mean[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 6; ++k) mean[k] += 0.25 * vertex_metric[6 * size_t(v[i]) + k];
  return meshops::metric_shape_quality(meshops::MetricMap::of(mean), p[0], p[1], p[2], p[3]);
}

bool FlipMemo::still_fails(uint32_t t, const uint32_t v[4]) const {
  if (t >= failed.size() || failed[t] == 0 || failed[t] <= everything) return false;
  for (int i = 0; i < 4; ++i)
    if (v[i] < changed.size() && failed[t] <= changed[v[i]]) return false;  // (beyond: never changed)
  return true;
}

bool try_flip23(FlipContext& c, uint32_t t, int i) {
  TetMesh& m = c.mesh;
  if (m.is_deleted(t) || m.facet_protected(t, i) || m.tet_adj[4 * size_t(t) + i] == TetMesh::kNoNeighbour)
    return false;
  const uint32_t n = m.neighbour(t, i);
  const int j = m.neighbour_facet(t, i);
  if (m.facet_protected(n, j)) return false;
  const uint32_t d = m.vertex(t, i), e = m.vertex(n, j);
  const uint32_t f[3] = {m.vertex(t, kFacetVertex[i][0]), m.vertex(t, kFacetVertex[i][1]),
                         m.vertex(t, kFacetVertex[i][2])};
  const double before = std::min(c.tet(t), c.tet(n));
  double after = 1.0;
  c.fresh.clear();
  for (int k = 0; k < 3; ++k) {
    const meshops::TetVerts v = {f[k], f[(k + 1) % 3], e, d};
    after = std::min(after, c.of(v.data()));
    if (after <= before + c.gain) return false;
    c.fresh.push_back(v);
  }
  c.old = {t, n};
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
  double before = 1.0;
  for (uint32_t s : c.ring_tets) before = std::min(before, c.tet(s));
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
  c.old = c.ring_tets;
  if (!meshops::replace_tets(m, c.old, c.fresh, c.vt, c.scratch, c.rule)) return false;
  c.touch_tets(c.fresh);
  ++c.edge_removals;
  return true;
}

std::vector<uint32_t> tets_below(const TetMesh& m, double quality, const Quality& measure) {
  const uint32_t n = m.num_tet_slots();
  std::vector<uint8_t> below(n, 0);
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 1u << 14), [&](const tbb::blocked_range<uint32_t>& r) {
    for (uint32_t t = r.begin(); t < r.end(); ++t)
      below[t] = !m.is_deleted(t) && measure.tet(m, t) < quality;
  });
  std::vector<uint32_t> out;
  for (uint32_t t = 0; t < n; ++t)
    if (below[t]) out.push_back(t);
  return out;
}

size_t flip_sweep(FlipContext& c, double quality, int rounds) {
  TetMesh& m = c.mesh;
  size_t total = 0;
  FlipMemo& memo = c.memo;
  if (memo.quality != quality || memo.gain != c.gain) {
    memo.touch_all();  // failures under other parameters say nothing
    memo.quality = quality;
    memo.gain = c.gain;
  }
  // The first round scans the mesh; later ones only revisit the tets the flips created.
  std::vector<uint32_t> bad = tets_below(m, quality, *c.quality), fresh_bad;
  for (int round = 0; round < rounds && !bad.empty(); ++round) {
    fresh_bad.clear();
    size_t flips = 0;
    auto note_created = [&] {
      for (uint32_t s : c.scratch.created)
        if (c.tet(s) < quality) fresh_bad.push_back(s);
    };
    for (uint32_t t : bad) {
      // t is measured once: a flip that fails leaves it as it was, one that succeeds ends its turn.
      if (m.is_deleted(t) || memo.still_fails(t, &m.tet_v[4 * size_t(t)]) || c.tet(t) >= quality) continue;
      bool done = false;
      for (int k = 0; k < 6 && !done && !m.is_deleted(t); ++k) done = try_remove_edge(c, t, k);
      for (int i = 0; i < 4 && !done && !m.is_deleted(t); ++i) done = try_flip23(c, t, i);
      if (done) {
        ++flips;
        note_created();
      } else {
        memo.fail(t);
      }
    }
    total += flips;
    if (flips == 0) break;
    bad.swap(fresh_bad);
  }
  return total;
}

}  // namespace anitet::optimize_detail
