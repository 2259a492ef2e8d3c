#include "mesh2d/triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "mesh2d/metric2.hpp"
#include "predicates/predicates.hpp"

namespace anitet::mesh2d {

using predicates::incircle;
using predicates::orient2d;

uint32_t Triangulation::add_vertex(double x, double y) {
  xy.push_back(x);
  xy.push_back(y);
  vtri.push_back(kNone);
  return uint32_t(vtri.size() - 1);
}

uint32_t Triangulation::add_triangle(uint32_t a, uint32_t b, uint32_t c) {
  uint32_t t;
  if (!free_slots.empty()) {
    t = free_slots.back();
    free_slots.pop_back();
  } else {
    t = uint32_t(num_slots());
    tri.resize(tri.size() + 3);
    nbr.resize(nbr.size() + 3);
    tag.resize(tag.size() + 3);
  }
  const size_t i = 3 * size_t(t);
  tri[i] = a;
  tri[i + 1] = b;
  tri[i + 2] = c;
  nbr[i] = nbr[i + 1] = nbr[i + 2] = kNone;
  tag[i] = tag[i + 1] = tag[i + 2] = kFree;
  vtri[a] = vtri[b] = vtri[c] = t;
  return t;
}

void Triangulation::free_triangle(uint32_t t) {
  tri[3 * size_t(t)] = kNone;
  free_slots.push_back(t);
}

int Triangulation::index_of(uint32_t t, uint32_t vertex) const {
  for (int k = 0; k < 3; ++k)
    if (tri[3 * size_t(t) + size_t(k)] == vertex) return k;
  return -1;
}

int Triangulation::mirror(uint32_t t, int k) const {
  const uint32_t n = across(t, k);
  if (n == kNone) return -1;
  for (int j = 0; j < 3; ++j)
    if (nbr[3 * size_t(n) + size_t(j)] == t) return j;
  return -1;
}

void Triangulation::link(uint32_t t, int k, uint32_t n, int kn) {
  nbr[3 * size_t(t) + size_t(k)] = n;
  if (n != kNone) nbr[3 * size_t(n) + size_t(kn)] = t;
}

void Triangulation::set_edge_tag(uint32_t t, int k, int32_t value) {
  tag[3 * size_t(t) + size_t(k)] = value;
  const int j = mirror(t, k);
  if (j >= 0) tag[3 * size_t(across(t, k)) + size_t(j)] = value;
}

bool Triangulation::star(uint32_t vertex, std::vector<uint32_t>& out) const {
  out.clear();
  const uint32_t start = vtri[vertex];
  if (start == kNone) return false;
  uint32_t t = start;
  // Counter-clockwise: across the edge (v, next-but-one vertex), i.e. opposite the next vertex.
  for (;;) {
    out.push_back(t);
    const int i = index_of(t, vertex);
    const uint32_t n = across(t, (i + 1) % 3);
    if (n == start) return true;
    if (n == kNone) break;
    t = n;
    if (out.size() > num_slots()) return true;  // corrupt mesh: do not loop forever
  }
  // On the boundary: the rest clockwise from the start, then reordered counter-clockwise.
  std::vector<uint32_t> cw;
  t = start;
  for (;;) {
    const int i = index_of(t, vertex);
    const uint32_t n = across(t, (i + 2) % 3);
    if (n == kNone) break;
    cw.push_back(n);
    t = n;
    if (cw.size() > num_slots()) break;
  }
  std::reverse(cw.begin(), cw.end());
  cw.insert(cw.end(), out.begin(), out.end());
  out.swap(cw);
  return false;
}

void Triangulation::neighbours(uint32_t vertex, std::vector<uint32_t>& out) const {
  std::vector<uint32_t> fan;
  const bool closed = star(vertex, fan);
  out.clear();
  for (uint32_t t : fan) out.push_back(tri[3 * size_t(t) + size_t((index_of(t, vertex) + 1) % 3)]);
  if (!closed && !fan.empty()) out.push_back(tri[3 * size_t(fan.back()) + size_t((index_of(fan.back(), vertex) + 2) % 3)]);
}

bool Triangulation::find_edge(uint32_t a, uint32_t b, uint32_t& t, int& k) const {
  std::vector<uint32_t> fan;
  star(a, fan);
  for (uint32_t f : fan) {
    const int i = index_of(f, a);
    if (tri[3 * size_t(f) + size_t((i + 1) % 3)] == b) {
      t = f;
      k = (i + 2) % 3;  // edge opposite the third vertex goes a -> b
      return true;
    }
  }
  return false;
}

void Triangulation::rebuild_vertex_triangles() {
  vtri.assign(num_vertices(), kNone);
  for (uint32_t t = 0; t < num_slots(); ++t)
    if (alive(t))
      for (int k = 0; k < 3; ++k) vtri[v(t, k)] = t;
}

namespace {

// Gives each fan of triangles around a vertex after its first a copy of the vertex (m.copies).
void split_pinched_vertices(Triangulation& m) {
  std::vector<uint8_t> seen(m.tri.size(), 0);  // per corner (3 t + i)
  std::vector<uint8_t> claimed(m.num_vertices(), 0);
  std::vector<uint32_t> fan;
  for (uint32_t t0 = 0; t0 < m.num_slots(); ++t0)
    for (int i0 = 0; i0 < 3; ++i0) {
      if (seen[3 * size_t(t0) + size_t(i0)]) continue;
      const uint32_t v = m.v(t0, i0);
      // The fan through corner (t0, i0): counter-clockwise, then clockwise from t0.
      fan.assign(1, t0);
      bool closed = false;
      for (int dir : {1, 2}) {
        uint32_t t = m.across(t0, (i0 + dir) % 3);
        for (; t != kNone && t != t0 && !closed; t = m.across(t, (m.index_of(t, v) + dir) % 3)) fan.push_back(t);
        closed = closed || t == t0;
      }
      uint32_t id = v;
      if (claimed[v]) {
        id = uint32_t(m.num_vertices());
        m.xy.insert(m.xy.end(), {m.xy[2 * size_t(v)], m.xy[2 * size_t(v) + 1]});
        m.copies.emplace_back(id, v);
      }
      claimed[v] = 1;
      for (uint32_t t : fan) {
        const int i = m.index_of(t, v);
        seen[3 * size_t(t) + size_t(i)] = 1;
        m.tri[3 * size_t(t) + size_t(i)] = id;
      }
    }
}

}  // namespace

Result<Triangulation> build_triangulation(std::vector<double> xy, std::vector<uint32_t> tri,
                                          const std::vector<uint32_t>& edges,
                                          const std::vector<int32_t>& edge_tags) {
  Triangulation m;
  m.xy = std::move(xy);
  m.tri = std::move(tri);
  const size_t nt = m.tri.size() / 3, nv = m.num_vertices();
  for (uint32_t v : m.tri)
    if (v >= nv) return Status(Error::BadIndex, "triangle refers to vertex " + std::to_string(v) + " of " + std::to_string(nv));
  m.nbr.assign(m.tri.size(), kNone);
  m.tag.assign(m.tri.size(), kFree);
  // Directed half-edges (a, b) -> (t, k), sorted by the undirected key.
  struct Half {
    uint64_t key;
    uint32_t t;
    int k;
    bool forward;
  };
  std::vector<Half> half;
  half.reserve(m.tri.size());
  for (uint32_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.edge_a(t, k), b = m.edge_b(t, k);
      half.push_back({(uint64_t(std::min(a, b)) << 32) | std::max(a, b), t, k, a < b});
    }
  std::sort(half.begin(), half.end(), [](const Half& x, const Half& y) { return x.key < y.key; });
  for (size_t i = 0; i < half.size();) {
    size_t j = i + 1;
    while (j < half.size() && half[j].key == half[i].key) ++j;
    const std::string edge = "edge " + std::to_string(half[i].key >> 32) + "-" + std::to_string(half[i].key & 0xffffffffu);
    if (j - i > 2) return Status(Error::InvalidMesh, edge + " belongs to " + std::to_string(j - i) + " triangles");
    if (j - i == 2) {
      if (half[i].forward == half[i + 1].forward)
        return Status(Error::InvalidMesh, edge + ": its two triangles have opposite orientations");
      m.link(half[i].t, half[i].k, half[i + 1].t, half[i + 1].k);
    }
    i = j;
  }
  // Tags from the sorted half-edges (not find_edge: a pinched vertex's star is not yet one fan).
  for (size_t e = 0; e < edges.size() / 2; ++e) {
    const uint32_t a = edges[2 * e], b = edges[2 * e + 1];
    const uint64_t key = (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
    auto it = std::lower_bound(half.begin(), half.end(), key, [](const Half& h, uint64_t k) { return h.key < k; });
    if (it == half.end() || it->key != key)
      return Status(Error::InvalidMesh, "edge " + std::to_string(a) + "-" + std::to_string(b) + " is no triangle's");
    m.set_edge_tag(it->t, it->k, e < edge_tags.size() ? edge_tags[e] : int32_t(e));
  }
  split_pinched_vertices(m);
  m.rebuild_vertex_triangles();
  return m;
}

bool find_edge_of_points(const Triangulation& m, uint32_t a, uint32_t b, uint32_t& t, int& k) {
  std::vector<uint32_t> as{a}, bs{b};
  for (const auto& [copy, original] : m.copies) {
    if (original == a) as.push_back(copy);
    if (original == b) bs.push_back(copy);
  }
  for (uint32_t x : as)
    for (uint32_t y : bs)
      if (m.find_edge(x, y, t, k) || m.find_edge(y, x, t, k)) return true;
  return false;
}

Status check_triangulation(const Triangulation& m) {
  auto fail = [](const std::string& what) { return Status(Error::InvalidMesh, what); };
  for (uint32_t t = 0; t < m.num_slots(); ++t) {
    if (!m.alive(t)) continue;
    const std::string name = "triangle " + std::to_string(t);
    for (int k = 0; k < 3; ++k)
      if (m.v(t, k) >= m.num_vertices()) return fail(name + " has a bad vertex");
    if (orient2d(m.point(m.v(t, 0)), m.point(m.v(t, 1)), m.point(m.v(t, 2))) <= 0)
      return fail(name + " is not counter-clockwise");
    for (int k = 0; k < 3; ++k) {
      const uint32_t n = m.across(t, k);
      if (n == kNone) continue;
      if (n >= m.num_slots() || !m.alive(n)) return fail(name + " has a dead neighbour");
      const int j = m.mirror(t, k);
      if (j < 0) return fail(name + ": its neighbour does not see it");
      if (m.edge_a(n, j) != m.edge_b(t, k) || m.edge_b(n, j) != m.edge_a(t, k))
        return fail(name + ": its neighbour's shared edge differs");
      if (m.edge_tag(n, j) != m.edge_tag(t, k)) return fail(name + ": an edge has different tags on its sides");
    }
  }
  for (uint32_t v = 0; v < m.num_vertices(); ++v) {
    const uint32_t t = m.vtri[v];
    if (t == kNone) continue;
    if (t >= m.num_slots() || !m.alive(t) || m.index_of(t, v) < 0)
      return fail("vertex " + std::to_string(v) + " points to a triangle without it");
  }
  return Status::success();
}

// ---- Kernel -------------------------------------------------------------------------------

uint32_t Kernel::next_stamp(std::vector<uint32_t>& marks, uint32_t& stamp, size_t size) {
  if (marks.size() < size) marks.resize(size + size / 2 + 16, 0u);
  if (++stamp == 0xffffffffu) {
    std::fill(marks.begin(), marks.end(), 0u);
    stamp = 1;
  }
  return stamp;
}

Location Kernel::locate(const double p[2], uint32_t t) {
  Location loc;
  for (size_t steps = 0; steps < 4 * m_.num_slots() + 64; ++steps) {
    rng_ ^= rng_ << 13;
    rng_ ^= rng_ >> 7;
    rng_ ^= rng_ << 17;
    const int r = int(rng_ % 3);
    int zero[3], nzero = 0;
    bool moved = false;
    for (int i = 0; i < 3; ++i) {
      const int k = (r + i) % 3;
      const int o = orient2d(m_.point(m_.edge_a(t, k)), m_.point(m_.edge_b(t, k)), p);
      if (o < 0) {
        const uint32_t n = m_.across(t, k);
        if (n == kNone) {
          loc.t = t;
          loc.kind = Location::Outside;
          loc.k = k;
          return loc;
        }
        t = n;
        moved = true;
        break;
      }
      if (o == 0) zero[nzero++] = k;
    }
    if (moved) continue;
    loc.t = t;
    if (nzero == 0) {
      loc.kind = Location::Inside;
    } else if (nzero == 1) {
      loc.kind = Location::OnEdge;
      loc.k = zero[0];
    } else {
      loc.kind = Location::OnVertex;
      loc.k = 3 - zero[0] - zero[1];
    }
    return loc;
  }
  loc.t = kNone;  // a corrupt mesh: the walk cycled
  return loc;
}

bool Kernel::conflict(uint32_t t, const double p[2], const Metric2* metric) const {
  const double* a = m_.point(m_.v(t, 0));
  const double* b = m_.point(m_.v(t, 1));
  const double* c = m_.point(m_.v(t, 2));
  if (!metric) return incircle(a, b, c, p) > 0;
  // In the metric's frame (mesh2d/metric2.hpp), where its unit circle is a circle.
  const MetricFrame frame(*metric, p);
  double ta[2], tb[2], tc[2];
  frame.to(a, ta);
  frame.to(b, tb);
  frame.to(c, tc);
  const double origin[2] = {0.0, 0.0};
  return incircle(ta, tb, tc, origin) > 0;
}

// One round of the cavity's repair: the triangle to drop (kNone when the cavity is fine, or
// `refuse` when a seed would have to go).
uint32_t Kernel::cavity_defect(const double p[2], const CavitySeeds& s) {
  const uint32_t vs = next_stamp(vmark_, vstamp_, m_.num_vertices());
  auto is_seed = [&](uint32_t t) { return t == s.seed[0] || t == s.seed[1]; };
  for (uint32_t t : cavity_)
    for (int k = 0; k < 3; ++k) {
      const uint32_t n = m_.across(t, k);
      if (n != kNone && in_cavity(n)) {
        if (m_.constrained(t, k) && !s.is_split_edge(m_, t, k)) return is_seed(t) ? n : t;
        continue;
      }
      vmark_[m_.edge_a(t, k)] = vs;
      vmark_[m_.edge_b(t, k)] = vs;
      if (s.on_boundary && t == s.seed[0] && k == s.k) continue;  // p lies on it
      if (orient2d(m_.point(m_.edge_a(t, k)), m_.point(m_.edge_b(t, k)), p) <= 0) return t;
    }
  // A vertex with all its triangles in the cavity would vanish: drop one of them (no seed).
  for (uint32_t t : cavity_)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = m_.v(t, k);
      if (vmark_[v] == vs) continue;
      for (uint32_t u : cavity_)
        if (!is_seed(u) && m_.index_of(u, v) >= 0) return u;
      return s.seed[0];
    }
  return kNone;
}

bool Kernel::CavitySeeds::is_split_edge(const Triangulation& m, uint32_t t, int edge) const {
  if (a == kNone) return false;
  const uint32_t x = m.edge_a(t, edge), y = m.edge_b(t, edge);
  return (x == a && y == b) || (x == b && y == a);
}

uint32_t Kernel::insert(const double p[2], const Location& loc, const Metric2* metric, bool split_constraints) {
  return insert_impl(p, loc, metric, split_constraints, kNone);
}

uint32_t Kernel::insert_vertex(uint32_t v, const Location& loc) {
  if (v >= m_.num_vertices() || m_.vtri[v] != kNone) return kNone;
  return insert_impl(m_.point(v), loc, nullptr, false, v);
}

uint32_t Kernel::insert_impl(const double* p_in, const Location& loc, const Metric2* metric, bool split_constraints,
                             uint32_t existing) {
  const double p[2] = {p_in[0], p_in[1]};  // p_in may point into xy, which may grow
  if (loc.t == kNone || (loc.kind != Location::Inside && loc.kind != Location::OnEdge)) return kNone;
  CavitySeeds s;
  s.seed[0] = loc.t;
  int32_t split_tag = kFree;
  if (loc.kind == Location::OnEdge) {
    if (m_.constrained(loc.t, loc.k)) {
      if (!split_constraints) return kNone;
      split_tag = m_.edge_tag(loc.t, loc.k);
    }
    s.a = m_.edge_a(loc.t, loc.k);
    s.b = m_.edge_b(loc.t, loc.k);
    s.k = loc.k;
    s.seed[1] = m_.across(loc.t, loc.k);
    s.on_boundary = s.seed[1] == kNone;
  }
  // Grow through unconstrained edges to the triangles in conflict.
  uint32_t stamp = next_stamp(in_, cstamp_, m_.num_slots());
  cavity_.clear();
  for (uint32_t t : s.seed)
    if (t != kNone) {
      in_[t] = stamp;
      cavity_.push_back(t);
    }
  for (size_t i = 0; i < cavity_.size(); ++i) {
    const uint32_t t = cavity_[i];
    for (int k = 0; k < 3; ++k) {
      if (m_.constrained(t, k)) continue;
      const uint32_t n = m_.across(t, k);
      if (n == kNone || in_[n] == stamp) continue;
      if (conflict(n, p, metric)) {
        in_[n] = stamp;
        cavity_.push_back(n);
      }
    }
  }
  // Shrink: drop a defect, keep the part still connected to the seeds, until none is left.
  for (;;) {
    const uint32_t drop = cavity_defect(p, s);
    if (drop == kNone) break;
    if (drop == s.seed[0] || drop == s.seed[1]) return kNone;
    in_[drop] = 0;
    const uint32_t old = stamp;
    stamp = next_stamp(in_, cstamp_, m_.num_slots());
    stack_.swap(cavity_);
    cavity_.clear();
    for (uint32_t t : s.seed)
      if (t != kNone) {
        in_[t] = stamp;
        cavity_.push_back(t);
      }
    for (size_t i = 0; i < cavity_.size(); ++i) {
      const uint32_t t = cavity_[i];
      for (int k = 0; k < 3; ++k) {
        const uint32_t n = m_.across(t, k);
        if (n == kNone || in_[n] != old) continue;
        if (m_.constrained(t, k) && !s.is_split_edge(m_, t, k)) continue;
        in_[n] = stamp;
        cavity_.push_back(n);
      }
    }
  }
  // The cavity's boundary, counter-clockwise edges (a, b) with the cavity on their left.
  boundary_.clear();
  for (uint32_t t : cavity_)
    for (int k = 0; k < 3; ++k) {
      const uint32_t n = m_.across(t, k);
      if (n != kNone && in_cavity(n)) continue;
      if (s.on_boundary && t == s.seed[0] && k == s.k) continue;
      boundary_.push_back({m_.edge_a(t, k), m_.edge_b(t, k), n, n == kNone ? -1 : m_.mirror(t, k), m_.edge_tag(t, k)});
    }
  for (uint32_t t : cavity_) {
    in_[t] = 0;
    m_.free_triangle(t);
  }
  const uint32_t pv = existing != kNone ? existing : m_.add_vertex(p[0], p[1]);
  if (vslot_.size() < m_.num_vertices()) vslot_.resize(m_.num_vertices() + m_.num_vertices() / 2 + 16, kNone);
  created_.clear();
  for (const BoundaryEdge& e : boundary_) {
    const uint32_t nt = m_.add_triangle(pv, e.a, e.b);
    m_.tag[3 * size_t(nt)] = e.tag;
    m_.link(nt, 0, e.out, e.out_k);
    vslot_[e.a] = nt;
    created_.push_back(nt);
  }
  for (size_t i = 0; i < boundary_.size(); ++i) {
    const uint32_t nt = created_[i];
    const BoundaryEdge& e = boundary_[i];
    // Edge 1 of (p, a, b) is (b, p): the new triangle starting at b has it as its edge 2. On a
    // boundary split the fan is open: nothing starts at the split edge's first vertex.
    if (!(s.on_boundary && e.b == s.a)) m_.link(nt, 1, vslot_[e.b], 2);
    if (s.a != kNone && (split_tag != kFree || s.on_boundary)) {
      if (e.a == s.a || e.a == s.b) m_.tag[3 * size_t(nt) + 2] = split_tag;
      if (e.b == s.a || e.b == s.b) m_.tag[3 * size_t(nt) + 1] = split_tag;
    }
  }
  return pv;
}

bool Kernel::flip(uint32_t t, int k) {
  if (m_.constrained(t, k)) return false;
  const uint32_t n = m_.across(t, k);
  if (n == kNone) return false;
  const int j = m_.mirror(t, k);
  const uint32_t x = m_.v(t, k), a = m_.edge_a(t, k), b = m_.edge_b(t, k), y = m_.v(n, j);
  // t = (x, a, b), n = (y, b, a); new: t = (x, a, y), n = (y, b, x).
  if (orient2d(m_.point(x), m_.point(a), m_.point(y)) <= 0 || orient2d(m_.point(y), m_.point(b), m_.point(x)) <= 0)
    return false;
  // Outer neighbours and tags: of t, edge (a, b)'s neighbours (x, a) [opposite b] and (b, x)
  // [opposite a]; of n, (y, b) [opposite a] and (a, y) [opposite b].
  const int t_opp_a = (k + 1) % 3, t_opp_b = (k + 2) % 3;
  const int n_opp_b = (j + 1) % 3, n_opp_a = (j + 2) % 3;
  const uint32_t t_xa = m_.across(t, t_opp_b), t_bx = m_.across(t, t_opp_a);
  const uint32_t n_yb = m_.across(n, n_opp_a), n_ay = m_.across(n, n_opp_b);
  const int t_xa_k = m_.mirror(t, t_opp_b), t_bx_k = m_.mirror(t, t_opp_a);
  const int n_yb_k = m_.mirror(n, n_opp_a), n_ay_k = m_.mirror(n, n_opp_b);
  const int32_t g_xa = m_.edge_tag(t, t_opp_b), g_bx = m_.edge_tag(t, t_opp_a);
  const int32_t g_yb = m_.edge_tag(n, n_opp_a), g_ay = m_.edge_tag(n, n_opp_b);
  // t = (x, a, y): edge 0 (a, y), edge 1 (y, x) shared with n, edge 2 (x, a).
  // n = (y, b, x): edge 0 (b, x), edge 1 (x, y) shared with t, edge 2 (y, b).
  const size_t ti = 3 * size_t(t), ni = 3 * size_t(n);
  m_.tri[ti] = x, m_.tri[ti + 1] = a, m_.tri[ti + 2] = y;
  m_.tri[ni] = y, m_.tri[ni + 1] = b, m_.tri[ni + 2] = x;
  m_.tag[ti] = g_ay, m_.tag[ti + 1] = kFree, m_.tag[ti + 2] = g_xa;
  m_.tag[ni] = g_bx, m_.tag[ni + 1] = kFree, m_.tag[ni + 2] = g_yb;
  m_.link(t, 0, n_ay, n_ay_k);
  m_.link(t, 2, t_xa, t_xa_k);
  m_.link(n, 0, t_bx, t_bx_k);
  m_.link(n, 2, n_yb, n_yb_k);
  m_.link(t, 1, n, 1);
  m_.vtri[x] = t, m_.vtri[a] = t, m_.vtri[y] = t, m_.vtri[b] = n;
  return true;
}

bool Kernel::can_collapse(uint32_t v, uint32_t w) {
  const bool closed = m_.star(v, fan_);
  if (fan_.empty()) return false;
  int constrained = 0, along = 0;
  int32_t tag = kFree;
  size_t shared = 0;
  // Neighbours of v; those of w; the edge's opposite vertices.
  m_.neighbours(v, nv_);
  m_.neighbours(w, nw_);
  if (std::find(nv_.begin(), nv_.end(), w) == nv_.end()) return false;
  for (uint32_t t : fan_) {
    const int i = m_.index_of(t, v);
    // The edge (v, next) is edge (i + 2) % 3 of t; count each of v's edges once (the one
    // leaving v counter-clockwise in t), plus the last edge of an open fan.
    const int e = (i + 2) % 3;
    if (m_.constrained(t, e)) {
      ++constrained;
      if (tag != kFree && tag != m_.edge_tag(t, e)) return false;
      tag = m_.edge_tag(t, e);
      if (m_.edge_b(t, e) == w) ++along;
    }
    if (m_.index_of(t, w) >= 0) ++shared;
  }
  if (!closed) {
    const uint32_t last = fan_.back();
    const int i = m_.index_of(last, v), e = (i + 1) % 3;  // the edge (prev, v) on the boundary
    if (m_.constrained(last, e)) {
      ++constrained;
      if (tag != kFree && tag != m_.edge_tag(last, e)) return false;
      tag = m_.edge_tag(last, e);
      if (m_.edge_a(last, e) == w) ++along;
    }
  }
  if (constrained == 0 && !closed) return false;
  if (constrained != 0 && (constrained != 2 || along != 1)) return false;
  // Link condition: the common neighbours are the opposite vertices of the shared triangles.
  size_t common = 0;
  for (uint32_t x : nv_)
    if (x != w && std::find(nw_.begin(), nw_.end(), x) != nw_.end()) ++common;
  if (common != shared) return false;
  for (uint32_t t : fan_) {
    if (m_.index_of(t, w) >= 0) continue;
    const int i = m_.index_of(t, v);
    const double* p[3] = {m_.point(m_.v(t, 0)), m_.point(m_.v(t, 1)), m_.point(m_.v(t, 2))};
    p[i] = m_.point(w);
    if (orient2d(p[0], p[1], p[2]) <= 0) return false;
  }
  return true;
}

void Kernel::collapse(uint32_t v, uint32_t w) {
  m_.star(v, fan_);
  struct Join {
    uint32_t n1;
    int k1;
    uint32_t n2;
    int k2;
    int32_t tag;
  };
  std::vector<Join> joins;
  for (uint32_t t : fan_) {
    const int iv = m_.index_of(t, v), iw = m_.index_of(t, w);
    if (iw < 0) continue;
    // t = (v, w, x) in some rotation: its edges opposite v (w, x) and opposite w (x, v).
    const uint32_t n1 = m_.across(t, iv), n2 = m_.across(t, iw);
    const int32_t g1 = m_.edge_tag(t, iv), g2 = m_.edge_tag(t, iw);
    joins.push_back({n1, m_.mirror(t, iv), n2, m_.mirror(t, iw), g1 != kFree ? g1 : g2});
  }
  for (uint32_t t : fan_) {
    const int iv = m_.index_of(t, v);
    if (m_.index_of(t, w) >= 0) {
      m_.free_triangle(t);
      continue;
    }
    m_.tri[3 * size_t(t) + size_t(iv)] = w;
    for (int k = 0; k < 3; ++k) m_.vtri[m_.v(t, k)] = t;
  }
  for (const Join& j : joins) {
    if (j.n1 != kNone) {
      m_.nbr[3 * size_t(j.n1) + size_t(j.k1)] = j.n2;
      m_.tag[3 * size_t(j.n1) + size_t(j.k1)] = j.tag;
      for (int k = 0; k < 3; ++k) m_.vtri[m_.v(j.n1, k)] = j.n1;
    }
    if (j.n2 != kNone) {
      m_.nbr[3 * size_t(j.n2) + size_t(j.k2)] = j.n1;
      m_.tag[3 * size_t(j.n2) + size_t(j.k2)] = j.tag;
      for (int k = 0; k < 3; ++k) m_.vtri[m_.v(j.n2, k)] = j.n2;
    }
  }
  m_.vtri[v] = kNone;
}

void circumcenter(const double* a, const double* b, const double* c, double out[2]) {
  const double bx = b[0] - a[0], by = b[1] - a[1], cx = c[0] - a[0], cy = c[1] - a[1];
  const double d = 2.0 * (bx * cy - by * cx);
  const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  out[0] = a[0] + (cy * b2 - by * c2) / d;
  out[1] = a[1] + (bx * c2 - cx * b2) / d;
}

}  // namespace anitet::mesh2d
