#include "layers/planar_cdt.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <numeric>
#include <set>
#include <string>

#include "predicates/predicates.hpp"

namespace anitet::layers {

namespace {

constexpr uint32_t kNone = 0xffffffffu;

// Triangle t: corners v[0..2] counter-clockwise, n[k] the triangle across the edge opposite
// v[k] (from v[k+1] to v[k+2]).
struct Tri {
  std::array<uint32_t, 3> v;
  std::array<uint32_t, 3> n;
};

class Triangulation {
 public:
  explicit Triangulation(const std::vector<double>& xy) : np_(xy.size() / 2) {
    // The points, then three far corners of a triangle holding them all.
    double lo[2] = {HUGE_VAL, HUGE_VAL}, hi[2] = {-HUGE_VAL, -HUGE_VAL};
    for (size_t i = 0; i < np_; ++i)
      for (int k = 0; k < 2; ++k) {
        lo[k] = std::min(lo[k], xy[2 * i + k]);
        hi[k] = std::max(hi[k], xy[2 * i + k]);
      }
    const double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
    const double r = 100.0 * std::max({hi[0] - lo[0], hi[1] - lo[1], 1e-300});
    pts_.resize(3 * (np_ + 3));
    for (size_t i = 0; i < np_; ++i) set_point(uint32_t(i), xy[2 * i], xy[2 * i + 1]);
    set_point(uint32_t(np_), cx - 2 * r, cy - r);
    set_point(uint32_t(np_ + 1), cx + 2 * r, cy - r);
    set_point(uint32_t(np_ + 2), cx, cy + 2 * r);
    vtri_.assign(np_ + 3, kNone);
    tris_.push_back({{uint32_t(np_), uint32_t(np_ + 1), uint32_t(np_ + 2)}, {kNone, kNone, kNone}});
    for (int k = 0; k < 3; ++k) vtri_[np_ + size_t(k)] = 0;
  }

  Status insert_all() {
    std::vector<uint32_t> order(np_);
    std::iota(order.begin(), order.end(), 0u);
    // Walks stay short when each point is near the one before.
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      return pts_[3 * a] != pts_[3 * b] ? pts_[3 * a] < pts_[3 * b] : pts_[3 * a + 1] < pts_[3 * b + 1];
    });
    for (uint32_t p : order)
      if (Status st = insert(p); !st.ok()) return st;
    return Status::success();
  }

  Status constrain(uint32_t a, uint32_t b) {
    if (a == b || a >= np_ || b >= np_) return Status(Error::InvalidArgument, "planar triangulation: bad segment");
    constrained_.insert(key(a, b));
    if (find_edge(a, b).first != kNone) return Status::success();
    std::deque<std::pair<uint32_t, uint32_t>> crossing;
    if (Status st = crossing_edges(a, b, crossing); !st.ok()) return st;
    size_t stalls = 0;
    while (!crossing.empty()) {
      const auto [u, v] = crossing.front();
      crossing.pop_front();
      if (constrained_.count(key(u, v)))
        return Status(Error::InvalidArgument, "planar triangulation: two boundary segments cross");
      const auto [t, k] = find_edge(u, v);
      if (t == kNone) continue;
      const uint32_t p = tris_[t].v[k];
      const uint32_t o = tris_[t].n[k];
      const uint32_t q = opposite(o, t);
      if (!convex(t, k)) {
        crossing.emplace_back(u, v);
        if (++stalls > 4 * crossing.size() + 16)
          return Status(Error::InvalidArgument, "planar triangulation: a boundary segment cannot be recovered");
        continue;
      }
      stalls = 0;
      flip(t, k);
      if (p != a && p != b && q != a && q != b && side(a, b, p) * side(a, b, q) < 0) crossing.emplace_back(p, q);
    }
    if (find_edge(a, b).first == kNone)
      return Status(Error::InvalidArgument, "planar triangulation: a boundary segment was not recovered");
    return Status::success();
  }

  // Lawson flips of the edges that are not segments, until locally regular (or a cap).
  void make_regular() {
    for (int pass = 0; pass < 50; ++pass) {
      bool any = false;
      for (uint32_t t = 0; t < tris_.size(); ++t)
        for (int k = 0; k < 3; ++k) {
          const uint32_t o = tris_[t].n[k];
          if (o == kNone || o < t) continue;
          const uint32_t u = tris_[t].v[(k + 1) % 3], v = tris_[t].v[(k + 2) % 3];
          if (constrained_.count(key(u, v)) || !should_flip(t, k)) continue;
          flip(t, k);
          any = true;
        }
      if (!any) return;
    }
  }

  Result<std::vector<uint32_t>> region(const std::vector<std::pair<uint32_t, uint32_t>>& segments) const {
    std::vector<int8_t> mark(tris_.size(), 0);  // 1 inside, -1 outside seed
    std::vector<uint32_t> stack;
    for (const auto& [a, b] : segments) {
      const auto [t, k] = find_edge(a, b);
      if (t == kNone) return Status(Error::InvalidArgument, "planar triangulation: a segment is missing");
      // Edge opposite v[k] runs v[k+1] -> v[k+2] in t; the other triangle has it reversed.
      const bool t_left = tris_[t].v[(k + 1) % 3] == a;
      const uint32_t inside = t_left ? t : tris_[t].n[k], outside = t_left ? tris_[t].n[k] : t;
      if (inside == kNone || mark[inside] == -1 || (outside != kNone && mark[outside] == 1))
        return Status(Error::InvalidArgument, "planar triangulation: the segments do not bound a region consistently");
      if (outside != kNone) mark[outside] = -1;
      if (mark[inside] == 0) {
        mark[inside] = 1;
        stack.push_back(inside);
      }
    }
    while (!stack.empty()) {
      const uint32_t t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        if (tris_[t].v[k] >= np_)
          return Status(Error::InvalidArgument, "planar triangulation: the segments do not close the region");
        const uint32_t o = tris_[t].n[k];
        const uint32_t u = tris_[t].v[(k + 1) % 3], v = tris_[t].v[(k + 2) % 3];
        if (o == kNone || constrained_.count(key(u, v))) continue;
        if (mark[o] == -1)
          return Status(Error::InvalidArgument, "planar triangulation: the segments do not close the region");
        if (mark[o] == 0) {
          mark[o] = 1;
          stack.push_back(o);
        }
      }
    }
    std::vector<uint32_t> out;
    for (uint32_t t = 0; t < tris_.size(); ++t)
      if (mark[t] == 1) out.insert(out.end(), tris_[t].v.begin(), tris_[t].v.end());
    return out;
  }

 private:
  void set_point(uint32_t i, double x, double y) {
    pts_[3 * i] = x;
    pts_[3 * i + 1] = y;
    pts_[3 * i + 2] = x * x + y * y;  // the lift (rounded; see the header)
  }
  const double* pt(uint32_t i) const { return &pts_[3 * size_t(i)]; }
  int orient(uint32_t a, uint32_t b, uint32_t c) const {
    const double pa[2] = {pts_[3 * a], pts_[3 * a + 1]}, pb[2] = {pts_[3 * b], pts_[3 * b + 1]},
                 pc[2] = {pts_[3 * c], pts_[3 * c + 1]};
    return predicates::orient2d(pa, pb, pc);
  }
  int side(uint32_t a, uint32_t b, uint32_t c) const { return orient(a, b, c); }
  static uint64_t key(uint32_t a, uint32_t b) {
    return a < b ? (uint64_t(a) << 32) | b : (uint64_t(b) << 32) | a;
  }
  uint32_t opposite(uint32_t o, uint32_t t) const {
    for (int j = 0; j < 3; ++j)
      if (tris_[o].n[j] == t) return tris_[o].v[j];
    return kNone;
  }
  // (triangle, k) whose edge opposite v[k] is {a, b}, or (kNone, 0).
  std::pair<uint32_t, int> find_edge(uint32_t a, uint32_t b) const {
    // Turning around a one way (across the edge (a, v[i+2])), then, for a far corner on the
    // hull, the other way (across (a, v[i+1])).
    const uint32_t start = vtri_[a];
    for (int way = 1; way <= 2; ++way) {
      uint32_t t = start;
      for (size_t guard = 0; guard < tris_.size() + 1; ++guard) {
        int i = 0;
        while (tris_[t].v[i] != a) ++i;
        if (tris_[t].v[(i + 1) % 3] == b) return {t, (i + 2) % 3};
        if (tris_[t].v[(i + 2) % 3] == b) return {t, (i + 1) % 3};
        t = tris_[t].n[(i + way) % 3];
        if (t == kNone) break;
        if (t == start) return {kNone, 0};
      }
    }
    return {kNone, 0};
  }
  // The quad of t and its neighbour across the edge opposite v[k] is strictly convex.
  bool convex(uint32_t t, int k) const {
    const uint32_t o = tris_[t].n[k];
    if (o == kNone) return false;
    const uint32_t p = tris_[t].v[k], u = tris_[t].v[(k + 1) % 3], v = tris_[t].v[(k + 2) % 3];
    const uint32_t q = opposite(o, t);
    return orient(p, u, q) > 0 && orient(q, v, p) > 0;
  }
  bool should_flip(uint32_t t, int k) const {
    if (!convex(t, k)) return false;
    const uint32_t q = opposite(tris_[t].n[k], t);
    const std::array<uint32_t, 3>& v = tris_[t].v;
    if (v[0] >= np_ || v[1] >= np_ || v[2] >= np_ || q >= np_) return false;  // (far corners)
    // q strictly inside the circle of t: its lift below t's plane.
    return predicates::orient3d(pt(v[0]), pt(v[1]), pt(v[2]), pt(q)) < 0;
  }
  // Replaces t = (p, u, v) and o = (q, v, u) by (p, u, q) and (q, v, p).
  void flip(uint32_t t, int k) {
    const uint32_t o = tris_[t].n[k];
    const uint32_t p = tris_[t].v[k], u = tris_[t].v[(k + 1) % 3], v = tris_[t].v[(k + 2) % 3];
    int j = 0;
    while (tris_[o].n[j] != t) ++j;
    const uint32_t q = tris_[o].v[j];
    // Outer neighbours: t across (p,u) [opposite v] and (v,p) [opposite u]; o across (q,v)
    // [opposite u] and (u,q) [opposite v].
    const uint32_t t_pu = tris_[t].n[(k + 2) % 3], t_vp = tris_[t].n[(k + 1) % 3];
    uint32_t o_qv = kNone, o_uq = kNone;
    for (int i = 0; i < 3; ++i) {
      if (tris_[o].v[i] == u) o_qv = tris_[o].n[i];
      if (tris_[o].v[i] == v) o_uq = tris_[o].n[i];
    }
    tris_[t] = {{p, u, q}, {o_uq, o, t_pu}};
    tris_[o] = {{q, v, p}, {t_vp, t, o_qv}};
    relink(o_uq, o, t);
    relink(t_vp, t, o);
    for (uint32_t w : {p, u}) vtri_[w] = t;
    for (uint32_t w : {q, v}) vtri_[w] = o;
  }
  // Neighbour x, which was next to `from`, is next to `to` now.
  void relink(uint32_t x, uint32_t from, uint32_t to) {
    if (x == kNone) return;
    for (int j = 0; j < 3; ++j)
      if (tris_[x].n[j] == from) tris_[x].n[j] = to;
  }

  Status insert(uint32_t p) {
    // Walk from the last triangle touched (a few random edges first, then a scan).
    uint32_t t = last_ < tris_.size() ? last_ : 0;
    bool found = false;
    for (size_t steps = 0; steps < 4 * tris_.size() + 64 && !found; ++steps) {
      found = true;
      const int first = int(steps % 3);
      for (int r = 0; r < 3; ++r) {
        const int k = (first + r) % 3;
        if (orient(tris_[t].v[(k + 1) % 3], tris_[t].v[(k + 2) % 3], p) < 0) {
          t = tris_[t].n[k];
          found = false;
          break;
        }
      }
      if (t == kNone) return Status(Error::Internal, "planar triangulation: a point is outside the far triangle");
    }
    if (!found)
      for (t = 0; t < tris_.size(); ++t) {
        bool in = true;
        for (int k = 0; k < 3 && in; ++k) in = orient(tris_[t].v[(k + 1) % 3], tris_[t].v[(k + 2) % 3], p) >= 0;
        if (in) break;
      }
    if (t >= tris_.size()) return Status(Error::Internal, "planar triangulation: a point was not located");
    int zero = -1, zeros = 0;
    for (int k = 0; k < 3; ++k)
      if (orient(tris_[t].v[(k + 1) % 3], tris_[t].v[(k + 2) % 3], p) == 0) {
        zero = k;
        ++zeros;
      }
    if (zeros >= 2) return Status(Error::InvalidArgument, "planar triangulation: a point is given twice");
    std::vector<std::pair<uint32_t, int>> check;
    if (zeros == 0) {
      split_triangle(t, p, check);
    } else {
      split_edge(t, zero, p, check);
    }
    // Legalize the edges opposite p.
    while (!check.empty()) {
      auto [s, k] = check.back();
      check.pop_back();
      if (tris_[s].v[k] != p) continue;  // changed since
      const uint32_t o = tris_[s].n[k];
      if (o == kNone || !should_flip(s, k)) continue;
      flip(s, k);  // s = (p, u, q), o = (q, v, p): the new edges opposite p are (u,q) and (q,v)
      check.emplace_back(s, 0);
      check.emplace_back(o, 2);
    }
    last_ = vtri_[p];
    return Status::success();
  }

  void split_triangle(uint32_t t, uint32_t p, std::vector<std::pair<uint32_t, int>>& check) {
    const Tri old = tris_[t];
    const uint32_t t1 = uint32_t(tris_.size()), t2 = t1 + 1;
    const uint32_t a = old.v[0], b = old.v[1], c = old.v[2];
    // t = (p, b, c), t1 = (p, c, a), t2 = (p, a, b).
    tris_[t] = {{p, b, c}, {old.n[0], t1, t2}};
    tris_.push_back({{p, c, a}, {old.n[1], t2, t}});
    tris_.push_back({{p, a, b}, {old.n[2], t, t1}});
    relink(old.n[1], t, t1);
    relink(old.n[2], t, t2);
    vtri_[p] = t;
    vtri_[a] = t1;
    vtri_[b] = t;
    vtri_[c] = t;
    check.insert(check.end(), {{t, 0}, {t1, 0}, {t2, 0}});
  }

  // p on the edge opposite v[k] of t (strictly inside it: not a corner).
  void split_edge(uint32_t t, int k, uint32_t p, std::vector<std::pair<uint32_t, int>>& check) {
    const uint32_t o = tris_[t].n[k];
    const uint32_t a = tris_[t].v[k], u = tris_[t].v[(k + 1) % 3], v = tris_[t].v[(k + 2) % 3];
    const uint32_t t_au = tris_[t].n[(k + 2) % 3], t_va = tris_[t].n[(k + 1) % 3];
    const uint32_t t1 = uint32_t(tris_.size());
    // t = (a, u, p), t1 = (a, p, v).
    tris_[t] = {{a, u, p}, {kNone, t1, t_au}};
    tris_.push_back({{a, p, v}, {kNone, t_va, t}});
    relink(t_va, t, t1);
    vtri_[a] = t;
    vtri_[u] = t;
    vtri_[v] = t1;
    vtri_[p] = t;
    check.insert(check.end(), {{t, 2}, {t1, 1}});
    if (o == kNone) return;
    int j = 0;
    while (tris_[o].n[j] != t) ++j;
    const uint32_t b = tris_[o].v[j];  // o = (b, v, u)
    uint32_t o_bv = kNone, o_ub = kNone;
    for (int i = 0; i < 3; ++i) {
      if (tris_[o].v[i] == u) o_bv = tris_[o].n[i];
      if (tris_[o].v[i] == v) o_ub = tris_[o].n[i];
    }
    const uint32_t o1 = uint32_t(tris_.size());
    // o = (b, v, p), o1 = (b, p, u).
    tris_[o] = {{b, v, p}, {t1, o1, o_bv}};
    tris_.push_back({{b, p, u}, {t, o_ub, o}});
    relink(o_ub, o, o1);
    tris_[t].n[0] = o1;   // t's edge (u, p) faces o1
    tris_[t1].n[0] = o;   // t1's edge (p, v) faces o
    vtri_[b] = o;
    check.insert(check.end(), {{o, 2}, {o1, 1}});
  }

  // The edges crossed by the open segment a -> b, in order from a.
  Status crossing_edges(uint32_t a, uint32_t b, std::deque<std::pair<uint32_t, uint32_t>>& out) const {
    // The triangle at a whose wedge holds the direction to b.
    uint32_t t = vtri_[a];
    const uint32_t start = t;
    uint32_t x = kNone, y = kNone;
    for (size_t guard = 0; guard < tris_.size() + 1; ++guard) {
      int i = 0;
      while (tris_[t].v[i] != a) ++i;
      const uint32_t p = tris_[t].v[(i + 1) % 3], q = tris_[t].v[(i + 2) % 3];
      const int sp = orient(a, p, b), sq = orient(a, q, b);
      if ((sp == 0 && dot_along(a, b, p) > 0) ||
          (sq == 0 && dot_along(a, b, q) > 0))
        return Status(Error::InvalidArgument, "planar triangulation: a point lies on a boundary segment");
      if (sp > 0 && sq < 0) {
        x = p;
        y = q;
        break;
      }
      t = tris_[t].n[(i + 1) % 3];
      if (t == kNone || t == start) break;
    }
    if (x == kNone) return Status(Error::Internal, "planar triangulation: no triangle at a segment's start");
    // Walk across (x, y) towards b.
    for (size_t guard = 0; guard < tris_.size() + 1; ++guard) {
      out.emplace_back(x, y);
      const auto [s, k] = find_edge(x, y);
      // The triangle beyond (x, y), seen from a: the one not holding the previous apex.
      const uint32_t beyond = orient(x, y, tris_[s].v[k]) * orient(x, y, a) > 0 ? tris_[s].n[k] : s;
      if (beyond == kNone) return Status(Error::Internal, "planar triangulation: a segment leaves the triangulation");
      uint32_t z = kNone;
      for (int j = 0; j < 3; ++j)
        if (tris_[beyond].v[j] != x && tris_[beyond].v[j] != y) z = tris_[beyond].v[j];
      if (z == b) return Status::success();
      const int sz = orient(a, b, z);
      if (sz == 0) return Status(Error::InvalidArgument, "planar triangulation: a point lies on a boundary segment");
      // x is right of a->b, y left: z replaces the one on its side.
      if (sz > 0) y = z;
      else x = z;
    }
    return Status(Error::Internal, "planar triangulation: a segment's walk did not end");
  }
  double dot_along(uint32_t a, uint32_t b, uint32_t p) const {
    return (pts_[3 * b] - pts_[3 * a]) * (pts_[3 * p] - pts_[3 * a]) +
           (pts_[3 * b + 1] - pts_[3 * a + 1]) * (pts_[3 * p + 1] - pts_[3 * a + 1]);
  }

  size_t np_;
  std::vector<double> pts_;  // 3 per point: x, y, lift
  std::vector<Tri> tris_;
  std::vector<uint32_t> vtri_;
  std::set<uint64_t> constrained_;
  uint32_t last_ = 0;
};

}  // namespace

Result<std::vector<uint32_t>> triangulate_region(const std::vector<double>& xy,
                                                 const std::vector<std::pair<uint32_t, uint32_t>>& segments) {
  if (xy.size() % 2 != 0 || xy.size() < 6 || segments.size() < 3)
    return Status(Error::InvalidArgument, "planar triangulation: fewer than 3 points or segments");
  for (double x : xy)
    if (!std::isfinite(x)) return Status(Error::InvalidArgument, "planar triangulation: a point is not finite");
  Triangulation tri(xy);
  if (Status st = tri.insert_all(); !st.ok()) return st;
  for (const auto& [a, b] : segments)
    if (Status st = tri.constrain(a, b); !st.ok()) return st;
  tri.make_regular();
  return tri.region(segments);
}

}  // namespace anitet::layers
