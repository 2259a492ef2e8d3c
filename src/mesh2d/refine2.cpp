#include "mesh2d/refine2.hpp"

#include "mesh2d/corners.hpp"
#include "mesh2d/optimize2.hpp"

#include <algorithm>
#include <cmath>

namespace anitet::mesh2d {

namespace {

struct EdgeRef {
  double length;
  uint32_t t;
  int k;
  uint32_t a, b;
};

// Each edge once (from its triangle with the smaller slot, or its only one).
template <class F>
void for_each_edge(const Triangulation& m, F&& f) {
  for (uint32_t t = 0; t < m.num_slots(); ++t) {
    if (!m.alive(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t n = m.across(t, k);
      if (n != kNone && n < t) continue;
      f(t, k);
    }
  }
}

bool too_close(const Triangulation& m, const VertexMetrics& vm, const double* p, const Metric2& mp, uint32_t t,
               double spacing) {
  if (spacing <= 0) return false;
  auto near = [&](uint32_t x) { return edge_length(mp, p, vm.at[x], m.point(x)) < spacing; };
  for (int k = 0; k < 3; ++k) {
    if (near(m.v(t, k))) return true;
    const uint32_t n = m.across(t, k);
    if (n != kNone && near(m.v(n, m.mirror(t, k)))) return true;
  }
  return false;
}

size_t split_pass(Triangulation& m, std::vector<uint8_t>& fixed, VertexMetrics& vm, const RefineOptions2& o,
                  std::vector<uint32_t>& touched, uint32_t stamp, RefineStats2& st) {
  std::vector<EdgeRef> edges;
  for_each_edge(m, [&](uint32_t t, int k) {
    if (m.constrained(t, k) && !o.split_segments) return;
    const uint32_t a = m.edge_a(t, k), b = m.edge_b(t, k);
    const double len = vm.length(m, a, b);
    if (len > o.split_length) edges.push_back({len, t, k, a, b});
  });
  std::sort(edges.begin(), edges.end(), [](const EdgeRef& x, const EdgeRef& y) { return x.length > y.length; });
  Kernel kernel(m);
  size_t done = 0;
  for (const EdgeRef& e : edges) {
    if (!m.alive(e.t) || m.edge_a(e.t, e.k) != e.a || m.edge_b(e.t, e.k) != e.b) continue;
    const uint32_t n = m.across(e.t, e.k);
    if (touched[e.t] == stamp || (n != kNone && touched[n] == stamp)) continue;
    // The metric midpoint: half the metric length on each side, the size varying geometrically
    // from a to b (h(t) = h_a r^t, r = h_b / h_a: the length to t is proportional to 1 - r^-t).
    const double* pa = m.point(e.a);
    const double* pb = m.point(e.b);
    const double la = norm(vm.at[e.a], pb[0] - pa[0], pb[1] - pa[1]), lb = norm(vm.at[e.b], pb[0] - pa[0], pb[1] - pa[1]);
    const double r = la / lb;
    const double f = std::fabs(r - 1.0) < 1e-6 ? 0.5 : std::clamp(-std::log(0.5 * (1.0 + 1.0 / r)) / std::log(r), 0.1, 0.9);
    const double mid[2] = {pa[0] + f * (pb[0] - pa[0]), pa[1] + f * (pb[1] - pa[1])};
    const bool segment = m.constrained(e.t, e.k);
    Location loc;
    if (segment) {
      loc.t = e.t, loc.kind = Location::OnEdge, loc.k = e.k;  // on the segment, to rounding
    } else {
      loc = kernel.locate(mid, e.t);
      if (loc.kind != Location::Inside && loc.kind != Location::OnEdge) continue;
    }
    if (segment) {  // at a shell when next to a sharp corner
      const size_t made = split_segment_piece(m, vm, fixed, e.t, e.k);
      if (touched.size() < m.num_slots()) touched.resize(m.num_slots() + m.num_slots() / 2, 0);
      // The pieces' new triangles are not known here: mark the two old ones' slots.
      touched[e.t] = stamp;
      if (n != kNone) touched[n] = stamp;
      done += made;
      st.segment_splits += made;
      continue;
    }
    const Metric2 mm = metric_at(vm.field, mid[0], mid[1]);
    // Not too close to the points around (a point of the triangle it falls in or of their
    // neighbours): such a split would only make short edges to collapse again.
    if (too_close(m, vm, mid, mm, loc.t, vm.anisotropic ? o.min_spacing_anisotropic : o.min_spacing)) continue;
    const uint32_t v = kernel.insert(mid, loc, vm.anisotropic ? &mm : nullptr, segment);
    if (v == kNone) continue;
    vm.at.push_back(mm);
    fixed.push_back(0);
    if (touched.size() < m.num_slots()) touched.resize(m.num_slots() + m.num_slots() / 2, 0);
    for (uint32_t t : kernel.created()) touched[t] = stamp;
    ++done;
  }
  st.splits += done;
  return done;
}

// Whether v may be removed: a free point (not the input's).
bool removable(const std::vector<uint8_t>& fixed, uint32_t v) { return !fixed[v]; }

size_t collapse_pass(Triangulation& m, std::vector<uint8_t>& fixed, VertexMetrics& vm, const RefineOptions2& o,
                     std::vector<uint32_t>& vtouched, uint32_t stamp, RefineStats2& st) {
  std::vector<EdgeRef> edges;
  for_each_edge(m, [&](uint32_t t, int k) {
    const uint32_t a = m.edge_a(t, k), b = m.edge_b(t, k);
    if (!removable(fixed, a) && !removable(fixed, b)) return;
    const double len = vm.length(m, a, b);
    if (len < o.collapse_length) edges.push_back({len, t, k, a, b});
  });
  std::sort(edges.begin(), edges.end(), [](const EdgeRef& x, const EdgeRef& y) { return x.length < y.length; });
  Kernel kernel(m);
  std::vector<uint32_t> fan, ring;
  size_t done = 0;
  for (const EdgeRef& e : edges) {
    if (m.vtri[e.a] == kNone || m.vtri[e.b] == kNone || vtouched[e.a] == stamp || vtouched[e.b] == stamp) continue;
    for (const auto& [v, w] : {std::pair{e.a, e.b}, std::pair{e.b, e.a}}) {
      if (!removable(fixed, v) || !kernel.can_collapse(v, w)) continue;
      // No new edge longer than the split bound, the worst triangle around no worse.
      m.star(v, fan);
      double before = 1e300, after = 1e300;
      bool ok = true;
      for (uint32_t t : fan) {
        const uint32_t a = m.v(t, 0), b = m.v(t, 1), c = m.v(t, 2);
        before = std::min(before, vm.quality(m, a, b, c));
        if (m.index_of(t, w) >= 0) continue;
        const int i = m.index_of(t, v);
        uint32_t x[3] = {a, b, c};
        x[i] = w;
        after = std::min(after, vm.quality(m, x[0], x[1], x[2]));
        for (int k = 1; k < 3; ++k)
          if (vm.length(m, w, x[(i + k) % 3]) > o.split_length) ok = false;
      }
      if (!ok || after < std::min(before, o.collapse_quality)) continue;
      m.neighbours(v, ring);
      kernel.collapse(v, w);
      vtouched[w] = stamp;
      for (uint32_t x : ring) vtouched[x] = stamp;
      ++done;
      break;
    }
  }
  st.collapses += done;
  return done;
}

}  // namespace

Status refine2(Triangulation& m, std::vector<uint8_t>& fixed, VertexMetrics& vm, const RefineOptions2& o,
               RefineStats2* stats) {
  RefineStats2 local;
  RefineStats2& st = stats ? *stats : local;
  vm.update(m);
  fixed.resize(m.num_vertices(), 0);
  std::vector<uint32_t> touched(m.num_slots(), 0), vtouched;
  uint32_t stamp = 0;
  int quiet = 0;
  for (int pass = 0; pass < o.max_passes; ++pass) {
    ++stamp;
    const size_t splits = split_pass(m, fixed, vm, o, touched, stamp, st);
    // In an anisotropic field the new points first settle (a point splitting a chord near a
    // curved layer lands next to the layer inside it), then short edges are collapsed.
    if (vm.anisotropic && splits)
      for (int i = 0; i < o.anisotropic_smoothing; ++i) length_smoothing(m, fixed, vm, 0.0);
    vtouched.resize(m.num_vertices(), 0);
    const size_t collapses = collapse_pass(m, fixed, vm, o, vtouched, stamp, st);
    // Flips between passes, around what the pass changed: a long edge of a flat triangle is
    // often better flipped than split.
    size_t flips = 0;
    if (o.flips) {
      std::vector<uint32_t> seeds;
      for (uint32_t t = 0; t < m.num_slots(); ++t) {
        if (!m.alive(t)) continue;
        bool changed = t < touched.size() && touched[t] == stamp;
        for (int k = 0; k < 3 && !changed; ++k) changed = vtouched[m.v(t, k)] == stamp;
        if (changed) seeds.push_back(t);
      }
      flips = quality_flips(m, vm, 4, &seeds);
    }
    st.flips += flips;
    ++st.passes;
    if (splits == 0 && collapses == 0) break;
    // Near the end a few edges may cycle (split, then collapsed again, where fixed segments
    // force sizes): stop after two passes that changed fewer than 1% of the points.
    quiet = double(splits + collapses) < 0.01 * double(m.num_vertices()) ? quiet + 1 : 0;
    if (quiet >= 2) break;
  }
  return Status::success();
}

double share_in_range(const Triangulation& m, const VertexMetrics& vm) {
  size_t in = 0, all = 0;
  for_each_edge(m, [&](uint32_t t, int k) {
    const double len = vm.length(m, m.edge_a(t, k), m.edge_b(t, k));
    ++all;
    if (in_unit_range(len)) ++in;
  });
  return all ? double(in) / double(all) : 1.0;
}

}  // namespace anitet::mesh2d
