#include "mesh2d/optimize2.hpp"

#include <algorithm>
#include <cmath>

#include "mesh2d/corners.hpp"
#include "predicates/predicates.hpp"

namespace anitet::mesh2d {

using predicates::orient2d;

namespace {

class Smoother {
 public:
  Smoother(Triangulation& m, std::vector<uint8_t>& fixed, VertexMetrics& vm) : m_(m), fixed_(fixed), vm_(vm) {}

  // A point that may move: free, interior, on no constrained edge.
  bool movable(uint32_t v) {
    if (v >= fixed_.size() || fixed_[v] || m_.vtri[v] == kNone) return false;
    if (!m_.star(v, fan_)) return false;
    for (uint32_t t : fan_)
      for (int k = 0; k < 3; ++k)  // edge k is opposite vertex k: v's edges are the other two
        if (m_.v(t, k) != v && m_.constrained(t, k)) return false;
    return true;
  }

  // The worst quality of v's triangles with v at p (-1 when one is not positive).
  double star_quality(uint32_t v, const double* p) const {
    double worst = 1e300;
    for (uint32_t t : fan_) {
      const double* q[3];
      uint32_t id[3];
      for (int k = 0; k < 3; ++k) {
        id[k] = m_.v(t, k);
        q[k] = id[k] == v ? p : m_.point(id[k]);
      }
      if (orient2d(q[0], q[1], q[2]) <= 0) return -1.0;
      worst = std::min(worst, vm_.quality_at(q[0], q[1], q[2], id[0], id[1], id[2]));
    }
    return worst;
  }

  // The ODT/CVT target of v (fan_ must be v's star): circumcentres in v's metric, weighted by
  // area (in that metric) times the density det(M) of each triangle relative to v's.
  bool odt_target(uint32_t v, double out[2]) const {
    const Metric2& mv = vm_.at[v];
    const MetricFrame frame(vm_.anisotropic ? mv : Metric2{}, m_.point(v));
    double sx = 0, sy = 0, sw = 0;
    for (uint32_t t : fan_) {
      const uint32_t a = m_.v(t, 0), b = m_.v(t, 1), c = m_.v(t, 2);
      double pa[2], pb[2], pc[2], cc[2];
      frame.to(m_.point(a), pa);
      frame.to(m_.point(b), pb);
      frame.to(m_.point(c), pc);
      const double ar = area(pa, pb, pc);
      if (!(ar > 0)) return false;
      circumcenter(pa, pb, pc, cc);
      const double w = ar * (det(mean_metric(vm_.at[a], vm_.at[b], vm_.at[c])) / det(mv));
      sx += w * cc[0], sy += w * cc[1], sw += w;
    }
    if (!(sw > 0)) return false;
    const double target[2] = {sx / sw, sy / sw};
    frame.from(target, out);
    return std::isfinite(out[0]) && std::isfinite(out[1]);
  }

  // The length-based target of v (anisotropic fields): the mean over its neighbours x of the
  // point at unit metric length from x toward v (fan_ must be v's star).
  bool length_target(uint32_t v, double out[2]) {
    m_.neighbours(v, ring_);
    const double* p = m_.point(v);
    double sx = 0, sy = 0;
    for (uint32_t x : ring_) {
      const double* q = m_.point(x);
      const double l = vm_.length(m_, x, v);
      if (!(l > 0)) return false;
      sx += q[0] + (p[0] - q[0]) / l;
      sy += q[1] + (p[1] - q[1]) / l;
    }
    if (ring_.empty()) return false;
    out[0] = sx / double(ring_.size());
    out[1] = sy / double(ring_.size());
    return true;
  }

  // Sum over v's edges of log(length)^2 with v at p (anisotropic fields).
  double length_energy(uint32_t v, const double* p) {
    m_.neighbours(v, ring_);
    const Metric2 mp = metric_at(vm_.field, p[0], p[1]);
    double e = 0;
    for (uint32_t x : ring_) {
      const double l = std::log(edge_length(mp, p, vm_.at[x], m_.point(x)));
      e += l * l;
    }
    return e;
  }

  // Pattern search on the length energy: the length target, then steps of 0.3, 0.1 and 0.03
  // along the metric's axes (in units of its sizes); true when v moved.
  bool energy_move(uint32_t v, double floor) {
    const double old[2] = {m_.point(v)[0], m_.point(v)[1]};
    const double q0 = star_quality(v, old);
    double best[2] = {old[0], old[1]}, best_e = length_energy(v, old);
    double cand[2];
    auto consider = [&](const double* p) {
      const double q = star_quality(v, p);
      if (q <= 0 || q < std::min(q0, floor)) return;
      const double e = length_energy(v, p);
      if (e < best_e - 1e-12) best_e = e, best[0] = p[0], best[1] = p[1];
    };
    if (length_target(v, cand)) consider(cand);
    const Metric2& mv = vm_.at[v];
    // The metric's axes scaled to its sizes.
    const double mean = 0.5 * (mv.xx + mv.yy), half = 0.5 * (mv.xx - mv.yy);
    const double dev = std::sqrt(half * half + mv.xy * mv.xy);
    const double th = 0.5 * std::atan2(2 * mv.xy, mv.xx - mv.yy);
    const double h1 = 1 / std::sqrt(mean + dev), h2 = 1 / std::sqrt(std::max(mean - dev, 1e-300));
    const double ax[2][2] = {{std::cos(th) * h1, std::sin(th) * h1}, {-std::sin(th) * h2, std::cos(th) * h2}};
    const int dirs = 4;
    for (double step : {0.3, 0.1, 0.03})
      for (int it = 0; it < 3; ++it) {
        const double from[2] = {best[0], best[1]};
        for (int d = 0; d < dirs; ++d) {
          const double ang = 2 * M_PI * d / dirs;
          const double c = std::cos(ang), sn = std::sin(ang);
          const double p[2] = {from[0] + step * (c * ax[0][0] + sn * ax[1][0]), from[1] + step * (c * ax[0][1] + sn * ax[1][1])};
          consider(p);
        }
        if (best[0] == from[0] && best[1] == from[1]) break;
      }
    if (best[0] == old[0] && best[1] == old[1]) return false;
    m_.xy[2 * size_t(v)] = best[0];
    m_.xy[2 * size_t(v) + 1] = best[1];
    vm_.at[v] = metric_at(vm_.field, best[0], best[1]);
    return true;
  }

  // Moves v toward target (full, half, quarter step) when its worst triangle stays above
  // min(old worst, floor); true when moved.
  bool try_move(uint32_t v, const double target[2], double floor) {
    const double old[2] = {m_.point(v)[0], m_.point(v)[1]};
    const double before = star_quality(v, old);
    for (double step : {1.0, 0.5, 0.25}) {
      const double p[2] = {old[0] + step * (target[0] - old[0]), old[1] + step * (target[1] - old[1])};
      const double after = star_quality(v, p);
      if (after > 0 && after >= std::min(before, floor)) {
        m_.xy[2 * size_t(v)] = p[0];
        m_.xy[2 * size_t(v) + 1] = p[1];
        vm_.at[v] = metric_at(vm_.field, p[0], p[1]);
        return true;
      }
    }
    return false;
  }

  const std::vector<uint32_t>& fan() const { return fan_; }

 private:
  Triangulation& m_;
  std::vector<uint8_t>& fixed_;
  VertexMetrics& vm_;
  std::vector<uint32_t> fan_, ring_;
};

// A walk from t toward p that stops at constrained edges: the triangle holding p (k = -1), or
// the triangle and edge where a constraint blocks the way.
std::pair<uint32_t, int> walk_to(const Triangulation& m, uint32_t t, const double* p) {
  for (size_t steps = 0; steps < m.num_slots(); ++steps) {
    int exit = -1;
    for (int k = 0; k < 3 && exit < 0; ++k)
      if (orient2d(m.point(m.edge_a(t, k)), m.point(m.edge_b(t, k)), p) < 0) exit = k;
    if (exit < 0) return {t, -1};
    if (m.constrained(t, exit) || m.across(t, exit) == kNone) return {t, exit};
    t = m.across(t, exit);
  }
  return {kNone, -1};
}

// Whether p lies inside the circle on the edge (a, b) as diameter.
bool encroaches(const double* a, const double* b, const double* p) {
  return (a[0] - p[0]) * (b[0] - p[0]) + (a[1] - p[1]) * (b[1] - p[1]) < 0;
}

// Shewchuk's rule against endless refinement at small input angles: a triangle whose shortest
// edge joins two points on the segments of one sharp corner, at one distance from it (a
// "seditious" edge), or that has the corner itself, is left as it is.
bool near_sharp_corner(const Triangulation& m, uint32_t t, const std::vector<uint32_t>& corners) {
  int shortest = 0;
  double len = 1e300;
  for (int k = 0; k < 3; ++k) {
    const double l = std::hypot(m.point(m.edge_b(t, k))[0] - m.point(m.edge_a(t, k))[0],
                                m.point(m.edge_b(t, k))[1] - m.point(m.edge_a(t, k))[1]);
    if (l < len) len = l, shortest = k;
  }
  const double* a = m.point(m.edge_a(t, shortest));
  const double* b = m.point(m.edge_b(t, shortest));
  for (uint32_t v : corners) {
    if (m.index_of(t, v) >= 0) return true;
    const double* o = m.point(v);
    const double da = std::hypot(a[0] - o[0], a[1] - o[1]), db = std::hypot(b[0] - o[0], b[1] - o[1]);
    if (std::fabs(da - db) > 1e-6 * std::max(da, db)) continue;
    const double cosine = ((a[0] - o[0]) * (b[0] - o[0]) + (a[1] - o[1]) * (b[1] - o[1])) / (da * db);
    if (cosine > 0.5) return true;  // under 60 degrees apart, seen from the corner
  }
  return false;
}

bool bad(const Triangulation& m, const VertexMetrics& vm, uint32_t t, const OptimizeOptions2& o) {
  if (vm.anisotropic) return vm.quality(m, m.v(t, 0), m.v(t, 1), m.v(t, 2)) < o.target_quality;
  return min_angle(m.point(m.v(t, 0)), m.point(m.v(t, 1)), m.point(m.v(t, 2))) < o.target_angle_deg * M_PI / 180.0;
}


// The clean-up's actions on a bad triangle t, tried in this order.
// 1. Moves a point of t to the best of its ODT target and its neighbours' centroid (full or
// half step) when its star gets better.
bool move_a_point(Triangulation& m, VertexMetrics& vm, Smoother& s, uint32_t t, std::vector<uint32_t>& ring) {
  for (int k = 0; k < 3; ++k) {
    const uint32_t v = m.v(t, k);
    if (!s.movable(v)) continue;
    const double before = s.star_quality(v, m.point(v));
    double best_q = before, best[2] = {0, 0};
    double cand[2][2];
    const bool has_odt = s.odt_target(v, cand[0]);
    m.neighbours(v, ring);
    cand[1][0] = cand[1][1] = 0;
    for (uint32_t x : ring) cand[1][0] += m.point(x)[0] / double(ring.size()), cand[1][1] += m.point(x)[1] / double(ring.size());
    for (int c = has_odt ? 0 : 1; c < 2; ++c)
      for (double step : {1.0, 0.5}) {
        const double p[2] = {m.point(v)[0] + step * (cand[c][0] - m.point(v)[0]), m.point(v)[1] + step * (cand[c][1] - m.point(v)[1])};
        const double q = s.star_quality(v, p);
        if (q > best_q + 1e-9) best_q = q, best[0] = p[0], best[1] = p[1];
      }
    if (best_q > before + 1e-9) {
      m.xy[2 * size_t(v)] = best[0];
      m.xy[2 * size_t(v) + 1] = best[1];
      vm.at[v] = metric_at(vm.field, best[0], best[1]);
      return true;
    }
  }
  return false;
}

// 2. Collapses t's shortest edge (a free end onto the other) when the worst triangle around
// gets better and no edge grows past 1.6.
bool collapse_shortest_edge(Triangulation& m, const VertexMetrics& vm, const std::vector<uint8_t>& fixed,
                            Kernel& kernel, uint32_t t) {
  int shortest = 0;
  double len = 1e300;
  for (int k = 0; k < 3; ++k) {
    const double l = vm.length(m, m.edge_a(t, k), m.edge_b(t, k));
    if (l < len) len = l, shortest = k;
  }
  const uint32_t ea = m.edge_a(t, shortest), eb = m.edge_b(t, shortest);
  std::vector<uint32_t> fan;
  for (const auto& [v, w] : {std::pair{ea, eb}, std::pair{eb, ea}}) {
    if (fixed[v] || !kernel.can_collapse(v, w)) continue;
    m.star(v, fan);
    double before = 1e300, after = 1e300;
    bool too_long = false;
    for (uint32_t f : fan) {
      uint32_t x[3] = {m.v(f, 0), m.v(f, 1), m.v(f, 2)};
      before = std::min(before, vm.quality(m, x[0], x[1], x[2]));
      if (m.index_of(f, w) >= 0) continue;
      const int i = m.index_of(f, v);
      x[i] = w;
      after = std::min(after, vm.quality(m, x[0], x[1], x[2]));
      for (int k = 1; k < 3; ++k) too_long |= vm.length(m, w, x[(i + k) % 3]) > 1.6;
    }
    if (too_long || after <= before + 1e-9) continue;
    kernel.collapse(v, w);
    return true;
  }
  return false;
}

// 3. Inserts t's circumcentre (in its metric) when it lies in the mesh, not too close to a
// vertex, and the cavity does not reach past a constraint to it. Returns the points inserted.
size_t insert_circumcenter(Triangulation& m, VertexMetrics& vm, std::vector<uint8_t>& fixed, Kernel& kernel,
                           uint32_t t, bool split_segments) {
  const uint32_t a = m.v(t, 0), b = m.v(t, 1), c = m.v(t, 2);
  double cc[2];
  if (vm.anisotropic) metric_circumcenter(m.point(a), m.point(b), m.point(c), mean_metric(vm.at[a], vm.at[b], vm.at[c]), cc);
  else circumcenter(m.point(a), m.point(b), m.point(c), cc);
  if (!std::isfinite(cc[0]) || !std::isfinite(cc[1])) return 0;
  Location loc;
  if (split_segments) {
    // Ruppert's rule: a circumcentre beyond a segment, or inside the diametral circle of a
    // segment piece next to where it falls, splits that piece instead.
    const auto [ct, ck] = walk_to(m, t, cc);
    if (ct == kNone) return 0;
    uint32_t st_t = kNone;
    int st_k = -1;
    if (ck >= 0) {
      if (m.constrained(ct, ck)) st_t = ct, st_k = ck;
    } else {
      for (int k = 0; k < 3 && st_t == kNone; ++k) {
        const uint32_t cand[2] = {ct, m.across(ct, k)};
        for (uint32_t x : cand) {
          if (x == kNone) continue;
          for (int j = 0; j < 3 && st_t == kNone; ++j)
            if (m.constrained(x, j) && encroaches(m.point(m.edge_a(x, j)), m.point(m.edge_b(x, j)), cc)) st_t = x, st_k = j;
        }
      }
    }
    if (st_t != kNone) return split_segment_piece(m, vm, fixed, st_t, st_k);
    if (ck >= 0) return 0;  // left the mesh
    loc = kernel.locate(cc, ct);
  } else {
    loc = kernel.locate(cc, t);
  }
  const Metric2 mc = metric_at(vm.field, cc[0], cc[1]);
  for (int k = 0; k < 3; ++k)
    if (edge_length(mc, cc, vm.at[m.v(loc.t, k)], m.point(m.v(loc.t, k))) < 0.5) return 0;
  const uint32_t nv = kernel.insert(cc, loc, vm.anisotropic ? &mc : nullptr, false);
  if (nv == kNone) return 0;
  vm.at.push_back(mc);
  fixed.push_back(0);
  return 1;
}

}  // namespace

size_t length_smoothing(Triangulation& m, std::vector<uint8_t>& fixed, VertexMetrics& vm, double floor) {
  Smoother s(m, fixed, vm);
  size_t moves = 0;
  for (uint32_t v = 0; v < m.num_vertices(); ++v)
    if (s.movable(v) && s.energy_move(v, floor)) ++moves;
  return moves;
}

size_t quality_flips(Triangulation& m, const VertexMetrics& vm, int rounds, const std::vector<uint32_t>* seeds) {
  // A work list: the seed triangles (or all), and both triangles of every flip made.
  Kernel kernel(m);
  std::vector<uint32_t> work;
  if (seeds) {
    for (uint32_t t : *seeds)
      if (t < m.num_slots() && m.alive(t)) work.push_back(t);
  } else {
    for (uint32_t t = 0; t < m.num_slots(); ++t)
      if (m.alive(t)) work.push_back(t);
  }
  const size_t budget = size_t(std::max(rounds, 1)) * (work.size() + 16);
  size_t total = 0, visits = 0;
  while (!work.empty() && visits++ < budget) {
    const uint32_t t = work.back();
    work.pop_back();
    if (!m.alive(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t n = m.across(t, k);
      if (n == kNone || m.constrained(t, k)) continue;
      const int j = m.mirror(t, k);
      const uint32_t x = m.v(t, k), a = m.edge_a(t, k), b = m.edge_b(t, k), y = m.v(n, j);
      // Isotropic: the Delaunay flip (the triangulation of the four points with the larger
      // smallest angle; exact). Anisotropic: the worse quality in the metric must rise.
      bool better;
      if (!vm.anisotropic) {
        better = predicates::incircle(m.point(x), m.point(a), m.point(b), m.point(y)) > 0;
      } else {
        if (orient2d(m.point(x), m.point(a), m.point(y)) <= 0 || orient2d(m.point(y), m.point(b), m.point(x)) <= 0) continue;
        const double before = std::min(vm.quality(m, x, a, b), vm.quality(m, y, b, a));
        const double after = std::min(vm.quality(m, x, a, y), vm.quality(m, y, b, x));
        better = after > before + 1e-9;
      }
      if (better && kernel.flip(t, k)) {
        ++total;
        work.push_back(n);
        work.push_back(t);
        break;  // t changed: its edges again from the list
      }
    }
  }
  return total;
}

Status optimize2(Triangulation& m, std::vector<uint8_t>& fixed, VertexMetrics& vm, const OptimizeOptions2& o,
                 OptimizeStats2* stats) {
  OptimizeStats2 local;
  OptimizeStats2& st = stats ? *stats : local;
  vm.update(m);
  fixed.resize(m.num_vertices(), 0);
  Smoother s(m, fixed, vm);
  st.flips += quality_flips(m, vm);
  std::vector<uint32_t> moved, mark;
  for (int sweep = 0; sweep < o.sweeps; ++sweep) {
    moved.clear();
    mark.assign(m.num_slots(), 0);
    for (uint32_t v = 0; v < m.num_vertices(); ++v) {
      if (!s.movable(v)) continue;  // (leaves v's star in s.fan())
      double target[2];
      const bool move = vm.anisotropic ? s.energy_move(v, o.anisotropic_floor)
                                       : s.odt_target(v, target) && s.try_move(v, target, 0.5);
      if (!move) continue;
      ++st.moves;
      for (uint32_t t : s.fan())
        if (!mark[t]) mark[t] = 1, moved.push_back(t);
    }
    st.flips += quality_flips(m, vm, 20, &moved);  // around the points that moved
  }
  if (!o.cleanup) return Status::success();
  // Clean-up of the bad triangles with a free point.
  Kernel kernel(m);
  std::vector<uint32_t> ring, corners, ends;
  if (o.split_segments)
    for (uint32_t v = 0; v < m.num_vertices(); ++v) {
      double shortest;
      if (fixed[v] && sharp_corner(m, v, ends, shortest)) corners.push_back(v);
    }
  for (int round = 0; round < o.cleanup_rounds; ++round) {
    size_t changed = 0;
    for (uint32_t t = 0; t < m.num_slots(); ++t) {
      if (!m.alive(t) || !bad(m, vm, t, o)) continue;
      if (o.split_segments && near_sharp_corner(m, t, corners)) continue;
      if (move_a_point(m, vm, s, t, ring)) {
        ++st.cleanup_moves, ++changed;
      } else if (collapse_shortest_edge(m, vm, fixed, kernel, t)) {
        ++st.cleanup_collapses, ++changed;
      } else if (o.insert) {
        const size_t made = insert_circumcenter(m, vm, fixed, kernel, t, o.split_segments);
        st.cleanup_inserts += made;
        changed += made > 0;
      }
    }
    st.flips += quality_flips(m, vm);
    if (changed == 0) break;
  }
  st.bad_left = 0;
  for (uint32_t t = 0; t < m.num_slots(); ++t) {
    if (!m.alive(t) || !bad(m, vm, t, o)) continue;
    bool free_point = false;
    for (int k = 0; k < 3; ++k) free_point |= !fixed[m.v(t, k)];
    if (free_point) ++st.bad_left;
  }
  return Status::success();
}

}  // namespace anitet::mesh2d
