#include "recovery/recovery.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "delaunay/delaunay.hpp"
#include "predicates/predicates.hpp"
#include "recovery/local_flips.hpp"
#include "recovery/recovery_util.hpp"
#include "recovery/split_recovery.hpp"

namespace anitet {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

constexpr uint32_t kNone = TetMesh::kNone;
constexpr uint32_t kGhost = TetMesh::kGhost;
constexpr uint32_t kNoNeighbour = TetMesh::kNoNeighbour;

using namespace recovery_detail;

// The recovery of one surface: state shared by the edge and face phases.
class Recoverer {
 public:
  Recoverer(const SurfaceMesh& s, const RecoveryOptions& o, RecoveryOutput& out)
      : S_(s), opt_(o), out_(out), mesh_(out.mesh), inserter_(out.mesh, o.seed) {}

  Status run();

 private:
  // Input edges: chain of vertices along each one (sorted by parameter from its first vertex).
  struct ChainPoint {
    double t;
    uint32_t v;
  };

  Status build_delaunay();
  void build_edges();
  bool has_edge(uint32_t u, uint32_t v);
  bool mark_edge(uint32_t u, uint32_t w, bool on);
  uint32_t tet_of(uint32_t v);
  void ball(uint32_t v, std::vector<uint32_t>& tets);
  void note_new_tets();
  bool insert(const double p[3], SteinerHost host, uint32_t host_id, uint32_t hint);
  size_t recover_edges_once(bool& failed_insert);
  bool split_segment(uint32_t e, size_t k);
  bool flip_edge(uint32_t u, uint32_t w);
  bool flip_face(uint32_t a, uint32_t b, uint32_t c);
  void note_tets(const std::vector<uint32_t>& tets);
  bool face_subfaces(uint32_t f, std::vector<Tri>& subfaces);
  bool insert_on_face(uint32_t f);
  void collect_face_vertices(uint32_t f, std::vector<uint32_t>& vs);
  bool on_input_edge(uint32_t v, uint32_t e) const;
  void protect(const std::vector<Tri>& tris);
  Status carve();
  std::string describe_face(uint32_t f) const;

  const SurfaceMesh& S_;
  const RecoveryOptions& opt_;
  RecoveryOutput& out_;
  TetMesh& mesh_;
  PointInserter inserter_;
  size_t n_in_ = 0;

  std::vector<uint32_t> edge_v_;            // 2 per input edge
  std::vector<uint32_t> face_edge_;         // 3 per face: edge of (v_k, v_k+1)
  std::vector<uint32_t> edge_faces_;        // 2 per input edge: its two faces
  std::vector<std::vector<ChainPoint>> chain_;
  std::vector<std::vector<uint32_t>> face_points_;  // interior Steiner points per face
  std::unordered_map<uint64_t, uint32_t> edge_id_;
  std::vector<int8_t> vhost_kind_;  // per vertex: -1 input vertex, 0 edge, 1 face
  std::vector<uint32_t> vhost_;     // per vertex: host edge / face

  std::vector<uint32_t> vert_tet_;  // per vertex: a live tet containing it (hint)
  std::vector<uint32_t> tet_stamp_;
  uint32_t stamp_ = 0;
  std::vector<uint32_t> vstamp_;
  uint32_t vstamp_value_ = 0;
  std::vector<uint32_t> scratch_;

  std::vector<uint8_t> face_done_;
  // Set by face_subfaces(): a subsegment of the face's boundary that no subface uses.
  uint32_t missing_edge_ = kNone;
  size_t missing_index_ = 0;
  bool repair_boundary_segment(uint32_t f);
  bool insert_face_point(uint32_t f, const double x[3], uint32_t hint);
  size_t steiner_cap_ = 0;
};

std::string Recoverer::describe_face(uint32_t f) const {
  return "input triangle " + std::to_string(f) + " (" + std::to_string(S_.tri[3 * f]) + " " +
         std::to_string(S_.tri[3 * f + 1]) + " " + std::to_string(S_.tri[3 * f + 2]) + ")";
}

Status Recoverer::build_delaunay() {
  if (Status s = delaunay_of_surface_points(mesh_, S_, opt_.remove_outside); !s.ok()) return s;
  vert_tet_.assign(mesh_.num_vertices(), kNone);
  for (uint32_t t = 0; t < mesh_.num_tet_slots(); ++t) {
    if (mesh_.is_deleted(t)) continue;
    for (int k = 0; k < 4; ++k) {
      const uint32_t v = mesh_.vertex(t, k);
      if (v != kGhost) vert_tet_[v] = t;
    }
  }
  vhost_kind_.assign(mesh_.num_vertices(), -1);  // the box corners too (kBoxCorners)
  vhost_.assign(mesh_.num_vertices(), kNone);
  return Status::success();
}

void Recoverer::build_edges() {
  const size_t nf = S_.num_triangles();
  face_edge_.resize(3 * nf);
  for (uint32_t f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = S_.tri[3 * f + k], b = S_.tri[3 * f + (k + 1) % 3];
      auto [it, fresh] = edge_id_.emplace(edge_key(a, b), uint32_t(edge_v_.size() / 2));
      if (fresh) {
        edge_v_.push_back(std::min(a, b));
        edge_v_.push_back(std::max(a, b));
        chain_.push_back({{0.0, std::min(a, b)}, {1.0, std::max(a, b)}});
      }
      face_edge_[3 * f + k] = it->second;
      if (edge_faces_.size() < edge_v_.size()) edge_faces_.resize(edge_v_.size(), kNone);
      (edge_faces_[2 * it->second] == kNone ? edge_faces_[2 * it->second] : edge_faces_[2 * it->second + 1]) = f;
    }
  }
  face_points_.assign(nf, {});
  face_done_.assign(nf, 0);
}

uint32_t Recoverer::tet_of(uint32_t v) {
  uint32_t t = vert_tet_[v];
  auto holds = [&](uint32_t c) {
    if (c >= mesh_.num_tet_slots() || mesh_.is_deleted(c)) return false;
    for (int k = 0; k < 4; ++k)
      if (mesh_.vertex(c, k) == v) return true;
    return false;
  };
  if (holds(t)) return t;
  for (uint32_t c = 0; c < mesh_.num_tet_slots(); ++c)
    if (holds(c)) return vert_tet_[v] = c;
  return kNone;
}

// The tets around vertex v (ghosts included), by walking across the facets through v.
void Recoverer::ball(uint32_t v, std::vector<uint32_t>& tets) {
  tets.clear();
  const uint32_t t0 = tet_of(v);
  if (t0 == kNone) return;
  if (tet_stamp_.size() < mesh_.num_tet_slots()) tet_stamp_.resize(mesh_.num_tet_slots() * 2, 0);
  if (++stamp_ == 0) {
    std::fill(tet_stamp_.begin(), tet_stamp_.end(), 0);
    stamp_ = 1;
  }
  tets.push_back(t0);
  tet_stamp_[t0] = stamp_;
  for (size_t k = 0; k < tets.size(); ++k) {
    const uint32_t t = tets[k];
    for (int i = 0; i < 4; ++i) {
      if (mesh_.vertex(t, i) == v) continue;  // the facet opposite v does not contain it
      if (mesh_.tet_adj[4 * size_t(t) + i] == kNoNeighbour) continue;
      const uint32_t n = mesh_.neighbour(t, i);
      if (tet_stamp_[n] == stamp_) continue;
      tet_stamp_[n] = stamp_;
      tets.push_back(n);
    }
  }
}

// Sets (or clears) the constrained bit of edge (u v) in every tet around it; false when the edge
// is not in the mesh.
bool Recoverer::mark_edge(uint32_t u, uint32_t w, bool on) {
  ball(u, scratch_);
  return set_edge_constrained(mesh_, scratch_, u, w, on);
}

bool Recoverer::has_edge(uint32_t u, uint32_t v) {
  ball(u, scratch_);
  for (uint32_t t : scratch_)
    for (int k = 0; k < 4; ++k)
      if (mesh_.vertex(t, k) == v) return true;
  return false;
}

void Recoverer::note_new_tets() {
  for (uint32_t t : inserter_.new_tets())
    for (int k = 0; k < 4; ++k) {
      const uint32_t v = mesh_.vertex(t, k);
      if (v != kGhost) vert_tet_[v] = t;
    }
}

bool Recoverer::insert(const double p[3], SteinerHost host, uint32_t host_id, uint32_t hint) {
  InsertOptions io;
  io.vertex_flags = vflag::kOnInputSurface;
  const InsertResult r = inserter_.insert(p, hint, io);
  if (!r.ok()) {
    ++out_.stats.blocked_insertions;
    return false;
  }
  vert_tet_.push_back(kNone);
  vhost_kind_.push_back(static_cast<int8_t>(host));
  vhost_.push_back(host_id);
  note_new_tets();
  out_.steiner.push_back({r.vertex, host, host_id});
  if (host == SteinerHost::kEdge) ++out_.stats.steiner_on_edges;
  else ++out_.stats.steiner_on_faces;
  return true;
}

// Splits subsegment k (chain_[e][k] .. chain_[e][k+1]). Next to an input vertex the split is at a
// power-of-two distance from it (concentric shells, so that segments meeting at a small angle do
// not split each other forever); otherwise at the middle.
bool Recoverer::split_segment(uint32_t e, size_t k) {
  std::vector<ChainPoint>& ch = chain_[e];
  const ChainPoint u = ch[k], w = ch[k + 1];
  mark_edge(u.v, w.v, false);  // no longer a constraint once split
  const double* a = S_.point(edge_v_[2 * e]);
  const double* b = S_.point(edge_v_[2 * e + 1]);
  const double full = std::sqrt(dist2(a, b));
  const double len = (w.t - u.t) * full;
  double t = 0.5 * (u.t + w.t);
  const bool u_input = u.v < n_in_, w_input = w.v < n_in_;
  if (u_input != w_input && len > 0) {
    double d = std::exp2(std::floor(std::log2(len * 2.0 / 3.0)));
    if (d < len / 3.0) d *= 2.0;
    t = u_input ? u.t + d / full : w.t - d / full;
  }
  // Try the chosen parameter, then nearby ones when the kernel refuses the point.
  const double tries[4] = {t, 0.5 * (u.t + w.t), u.t + 0.4 * (w.t - u.t), u.t + 0.6 * (w.t - u.t)};
  for (double tt : tries) {
    if (!(tt > u.t && tt < w.t)) continue;
    double p[3];
    for (int d = 0; d < 3; ++d) p[d] = a[d] + tt * (b[d] - a[d]);
    if (tt >= 0.5) for (int d = 0; d < 3; ++d) p[d] = b[d] + (1.0 - tt) * (a[d] - b[d]);
    if (insert(p, SteinerHost::kEdge, e, vert_tet_[u.v])) {
      ch.insert(ch.begin() + static_cast<ptrdiff_t>(k + 1), ChainPoint{tt, uint32_t(mesh_.num_vertices() - 1)});
      return true;
    }
  }
  return false;
}

void Recoverer::note_tets(const std::vector<uint32_t>& tets) {
  for (uint32_t t : tets)
    for (int k = 0; k < 4; ++k) vert_tet_[mesh_.vertex(t, k)] = t;
}

// Makes (u w) an edge by one flip (local_flips.hpp's flip_in_edge).
bool Recoverer::flip_edge(uint32_t u, uint32_t w) {
  ball(u, scratch_);
  std::vector<uint32_t> created;
  if (!flip_in_edge(mesh_, u, w, scratch_, created)) return false;
  note_tets(created);
  ++out_.stats.flips;
  return true;
}

// Makes triangle (a b c), whose edges are present, a facet by one edge removal.
bool Recoverer::flip_face(uint32_t a, uint32_t b, uint32_t c) {
  ball(a, scratch_);
  std::vector<uint32_t> created;
  if (!flip_in_face(mesh_, a, b, c, scratch_, created)) return false;
  note_tets(created);
  ++out_.stats.flips;
  return true;
}

// One sweep over all subsegments; returns how many were missing.
size_t Recoverer::recover_edges_once(bool& failed_insert) {
  size_t missing = 0;
  for (uint32_t e = 0; e < chain_.size(); ++e) {
    for (size_t k = 0; k + 1 < chain_[e].size(); ++k) {
      // A present subsegment becomes a constrained edge: later insertions keep it.
      if (opt_.defend_edges ? mark_edge(chain_[e][k].v, chain_[e][k + 1].v, true)
                            : has_edge(chain_[e][k].v, chain_[e][k + 1].v))
        continue;
      if (opt_.use_flips && flip_edge(chain_[e][k].v, chain_[e][k + 1].v)) {
        if (opt_.defend_edges) mark_edge(chain_[e][k].v, chain_[e][k + 1].v, true);
        continue;
      }
      ++missing;
      if (split_segment(e, k)) ++k;  // the new right half is checked next sweep
      else failed_insert = true;
    }
  }
  return missing;
}

bool Recoverer::on_input_edge(uint32_t v, uint32_t e) const {
  if (v < n_in_) return v == edge_v_[2 * e] || v == edge_v_[2 * e + 1];
  return vhost_kind_[v] == 0 && vhost_[v] == e;
}

void Recoverer::collect_face_vertices(uint32_t f, std::vector<uint32_t>& vs) {
  vs.clear();
  for (int k = 0; k < 3; ++k)
    for (const ChainPoint& c : chain_[face_edge_[3 * f + k]]) vs.push_back(c.v);
  vs.insert(vs.end(), face_points_[f].begin(), face_points_[f].end());
  std::sort(vs.begin(), vs.end());
  vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
}

// The mesh triangles on face f. True when they triangulate f: a disk whose boundary is the chain
// of f's subsegments and that uses all of f's vertices.
bool Recoverer::face_subfaces(uint32_t f, std::vector<Tri>& subfaces) {
  subfaces.clear();
  missing_edge_ = kNone;
  std::vector<uint32_t> vs;
  collect_face_vertices(f, vs);
  if (vstamp_.size() < mesh_.num_vertices()) vstamp_.resize(2 * mesh_.num_vertices(), 0);
  ++vstamp_value_;
  for (uint32_t v : vs) vstamp_[v] = vstamp_value_;
  auto in_face = [&](uint32_t v) { return v != kGhost && vstamp_[v] == vstamp_value_; };
  double nf[3];
  {
    double ab[3], ac[3];
    const double* A = S_.point(S_.tri[3 * f]);
    sub(S_.point(S_.tri[3 * f + 1]), A, ab);
    sub(S_.point(S_.tri[3 * f + 2]), A, ac);
    cross(ab, ac, nf);
  }
  std::vector<uint32_t> tets;
  for (uint32_t v : vs) {
    ball(v, tets);
    for (uint32_t t : tets) {
      for (int i = 0; i < 4; ++i) {
        const Tri tr = {mesh_.vertex(t, kFacetVertex[i][0]), mesh_.vertex(t, kFacetVertex[i][1]),
                        mesh_.vertex(t, kFacetVertex[i][2])};
        if (!in_face(tr[0]) || !in_face(tr[1]) || !in_face(tr[2])) continue;
        // Only count a facet from the ball of its smallest vertex, once per facet side pair.
        if (std::min({tr[0], tr[1], tr[2]}) != v) continue;
        bool on_one_edge = false;
        for (int k = 0; k < 3 && !on_one_edge; ++k) {
          const uint32_t e = face_edge_[3 * f + k];
          on_one_edge = on_input_edge(tr[0], e) && on_input_edge(tr[1], e) && on_input_edge(tr[2], e);
        }
        if (on_one_edge) continue;
        // A nearly flat tet with all four vertices on f has facets on f on both sides: keep, of
        // each facet, only the one seen from above (the side f's normal points to), and only if
        // the tet above is not such a flat tet, so a stack of flat tets contributes its top.
        double xy[3], xz[3], m[3];
        sub(mesh_.point(tr[1]), mesh_.point(tr[0]), xy);
        sub(mesh_.point(tr[2]), mesh_.point(tr[0]), xz);
        cross(xy, xz, m);
        if (!(dot(m, nf) > 0)) continue;  // t is below this facet
        const uint32_t opp = mesh_.vertex(t, i);
        if (in_face(opp)) continue;  // t is flat on f
        subfaces.push_back(sorted(tr));
      }
    }
  }
  std::sort(subfaces.begin(), subfaces.end());
  subfaces.erase(std::unique(subfaces.begin(), subfaces.end()), subfaces.end());
  if (subfaces.empty()) return false;
  std::unordered_map<uint64_t, int> count;
  for (const Tri& t : subfaces)
    for (int k = 0; k < 3; ++k) ++count[edge_key(t[k], t[(k + 1) % 3])];
  size_t boundary = 0;
  for (int k = 0; k < 3; ++k) {
    const std::vector<ChainPoint>& ch = chain_[face_edge_[3 * f + k]];
    for (size_t j = 0; j + 1 < ch.size(); ++j) {
      auto it = count.find(edge_key(ch[j].v, ch[j + 1].v));
      if (it == count.end() || it->second != 1) {
        missing_edge_ = face_edge_[3 * f + k];
        missing_index_ = j;
        return false;
      }
      it->second = -1;  // seen as boundary
      ++boundary;
    }
  }
  size_t interior = 0;
  for (const auto& kv : count) {
    if (kv.second == -1) continue;
    if (kv.second != 2) {
      return false;
    }
    ++interior;
  }
  // Euler characteristic of a disk: V - E + F = 1 over the vertices the subfaces use. Every chain
  // vertex is used (the boundary check above); a Steiner point of f's interior may be left out:
  // the modified kernel can leave it in a flat tet just under the disk (inside the material),
  // where it stays an interior vertex within rounding of f.
  std::vector<char> used(vs.size(), 0);
  for (const Tri& t : subfaces)
    for (uint32_t v : t) used[size_t(std::lower_bound(vs.begin(), vs.end(), v) - vs.begin())] = 1;
  long long V = 0;
  for (size_t k = 0; k < vs.size(); ++k) {
    if (used[k]) ++V;
    else if (!(vs[k] >= n_in_ && vhost_kind_[vs[k]] == static_cast<int8_t>(SteinerHost::kFace) && vhost_[vs[k]] == f))
      return false;
  }
  const long long E = static_cast<long long>(boundary + interior);
  const long long F = static_cast<long long>(subfaces.size());
  return V - E + F == 1 && 3 * F == 2 * static_cast<long long>(interior) + static_cast<long long>(boundary);
}

// Inserts one Steiner point on face f: where a mesh edge crosses f's interior (the crossing
// farthest from f's vertices), else the sample of f farthest from its vertices.
bool Recoverer::insert_on_face(uint32_t f) {
  const double* A = S_.point(S_.tri[3 * f]);
  const double* B = S_.point(S_.tri[3 * f + 1]);
  const double* C = S_.point(S_.tri[3 * f + 2]);
  std::vector<uint32_t> vs;
  collect_face_vertices(f, vs);
  auto clearance = [&](const double* p) {
    double best = INFINITY;
    for (uint32_t v : vs) best = std::min(best, dist2(p, mesh_.point(v)));
    return best;
  };
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    lo[d] = std::min({A[d], B[d], C[d]});
    hi[d] = std::max({A[d], B[d], C[d]});
  }
  // Tets near f: breadth-first from the balls of f's corners, through tets meeting f's plane and
  // bounding box.
  if (tet_stamp_.size() < mesh_.num_tet_slots()) tet_stamp_.resize(mesh_.num_tet_slots() * 2, 0);
  std::vector<uint32_t> front, tets;
  for (int k = 0; k < 3; ++k) {
    ball(S_.tri[3 * f + k], tets);
    front.insert(front.end(), tets.begin(), tets.end());
  }
  if (++stamp_ == 0) {
    std::fill(tet_stamp_.begin(), tet_stamp_.end(), 0);
    stamp_ = 1;
  }
  for (uint32_t t : front) tet_stamp_[t] = stamp_;
  std::unordered_map<uint64_t, char> seen_edges;
  double best_p[3] = {0, 0, 0};
  double best_clear = -1;
  const size_t limit = 20000;
  for (size_t k = 0; k < front.size() && k < limit; ++k) {
    const uint32_t t = front[k];
    if (mesh_.is_ghost(t)) continue;
    int side[4];
    bool pos = false, neg = false;
    bool box = true;
    for (int i = 0; i < 4; ++i) {
      const double* p = mesh_.point(mesh_.vertex(t, i));
      side[i] = predicates::orient3d(A, B, C, p);
      pos |= side[i] > 0;
      neg |= side[i] < 0;
    }
    double tl[3] = {INFINITY, INFINITY, INFINITY}, th[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < 4; ++i) {
      const double* p = mesh_.point(mesh_.vertex(t, i));
      for (int d = 0; d < 3; ++d) {
        tl[d] = std::min(tl[d], p[d]);
        th[d] = std::max(th[d], p[d]);
      }
    }
    for (int d = 0; d < 3; ++d) box = box && tl[d] <= hi[d] && th[d] >= lo[d];
    if (!box || (pos && !neg && side[0] && side[1] && side[2] && side[3]) ||
        (neg && !pos && side[0] && side[1] && side[2] && side[3]))
      continue;
    // Edges of t crossing f's interior strictly.
    for (const auto& ev : kEdgeVertex) {
      const int i = ev[0], j = ev[1];
      if (side[i] * side[j] >= 0) continue;
      const uint32_t p = mesh_.vertex(t, i), q = mesh_.vertex(t, j);
      if (!seen_edges.emplace(edge_key(p, q), 1).second) continue;
      double x[3];
      if (!line_crosses_triangle(mesh_.point(p), mesh_.point(q), A, B, C, x)) continue;
      const double c = clearance(x);
      if (c > best_clear) {
        best_clear = c;
        std::copy(x, x + 3, best_p);
      }
    }
    for (int i = 0; i < 4; ++i) {
      const uint32_t n = mesh_.neighbour(t, i);
      if (mesh_.tet_adj[4 * size_t(t) + i] == kNoNeighbour || tet_stamp_[n] == stamp_) continue;
      tet_stamp_[n] = stamp_;
      front.push_back(n);
    }
  }
  if (best_clear > 0 && insert_face_point(f, best_p, vert_tet_[S_.tri[3 * f]])) {
    face_points_[f].push_back(uint32_t(mesh_.num_vertices() - 1));
    return true;
  }
  // No crossing edge (or the kernel refused it): the barycentric sample farthest from f's vertices.
  std::vector<std::pair<double, std::array<double, 3>>> samples;
  const int N = 12;
  for (int i = 1; i < N; ++i)
    for (int j = 1; i + j < N; ++j) {
      const double u = double(i) / N, v = double(j) / N, w = 1.0 - u - v;
      std::array<double, 3> x;
      for (int d = 0; d < 3; ++d) x[d] = w * A[d] + u * B[d] + v * C[d];
      samples.push_back({clearance(x.data()), x});
    }
  std::sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (size_t k = 0; k < samples.size() && k < 4; ++k) {
    if (insert_face_point(f, samples[k].second.data(), vert_tet_[S_.tri[3 * f]])) {
      face_points_[f].push_back(uint32_t(mesh_.num_vertices() - 1));
      return true;
    }
  }
  return false;
}

// A boundary subsegment (u w) of face f that no subface uses: a tet around it has an edge crossing
// f near it. Insert that crossing when it is inside f, else split the subsegment (the chain then
// follows the straight input edge more closely).
bool Recoverer::repair_boundary_segment(uint32_t f) {
  const uint32_t e = missing_edge_;
  const size_t j = missing_index_;
  const uint32_t u = chain_[e][j].v, w = chain_[e][j + 1].v;
  const double* A = S_.point(S_.tri[3 * f]);
  const double* B = S_.point(S_.tri[3 * f + 1]);
  const double* C = S_.point(S_.tri[3 * f + 2]);
  std::vector<uint32_t> vs;
  collect_face_vertices(f, vs);
  ball(u, scratch_);
  std::vector<uint32_t> ring;
  for (uint32_t t : scratch_) {
    if (mesh_.is_ghost(t)) continue;
    for (int k = 0; k < 4; ++k)
      if (mesh_.vertex(t, k) == w) ring.push_back(t);
  }
  for (uint32_t t : ring) {
    uint32_t xy[2], n = 0;
    for (int k = 0; k < 4; ++k) {
      const uint32_t v = mesh_.vertex(t, k);
      if (v != u && v != w) xy[n++] = v;
    }
    if (std::binary_search(vs.begin(), vs.end(), xy[0]) || std::binary_search(vs.begin(), vs.end(), xy[1]))
      continue;
    const double *P = mesh_.point(xy[0]), *Q = mesh_.point(xy[1]);
    if (predicates::orient3d(A, B, C, P) * predicates::orient3d(A, B, C, Q) >= 0) continue;
    double x[3];
    if (!line_crosses_triangle(P, Q, A, B, C, x)) continue;
    if (insert_face_point(f, x, t)) {
      face_points_[f].push_back(uint32_t(mesh_.num_vertices() - 1));
      return true;
    }
  }
  // A ring vertex on f's plane but not f's: the triangulation of that flat region ignores f's
  // boundary there. A point of f just inside (u w) makes (u w x) a subface candidate.
  bool coplanar = false;
  for (uint32_t t : ring)
    for (int k = 0; k < 4; ++k) {
      const uint32_t y = mesh_.vertex(t, k);
      if (!std::binary_search(vs.begin(), vs.end(), y) && predicates::orient3d(A, B, C, mesh_.point(y)) == 0)
        coplanar = true;
    }
  if (coplanar || opt_.apex_always) {
    const double *U = mesh_.point(u), *W = mesh_.point(w);
    double nrm[3], ab[3], ac[3], uw[3], dir[3], m[3];
    sub(B, A, ab);
    sub(C, A, ac);
    cross(ab, ac, nrm);
    sub(W, U, uw);
    cross(nrm, uw, dir);
    for (int d = 0; d < 3; ++d) m[d] = 0.5 * (U[d] + W[d]);
    const double* corners[3] = {A, B, C};
    const double* far = A;
    for (const double* c : corners)
      if (!on_input_edge(uint32_t(S_.tri[3 * f + (c == A ? 0 : c == B ? 1 : 2)]), e)) far = c;
    double mf[3];
    sub(far, m, mf);
    const double sign = dot(dir, mf) >= 0 ? 1.0 : -1.0;
    const double dl = std::sqrt(dot(dir, dir));
    double h = 0.3 * std::sqrt(dot(uw, uw));
    for (int attempt = 0; attempt < 6; ++attempt, h *= 0.5) {
      double x[3];
      for (int d = 0; d < 3; ++d) x[d] = m[d] + sign * h * dir[d] / dl;
      // Inside f: on the inner side of each edge, seen along f's normal.
      bool inside = true;
      for (int k = 0; k < 3 && inside; ++k) {
        double ed[3], ex[3], c[3];
        sub(corners[(k + 1) % 3], corners[k], ed);
        sub(x, corners[k], ex);
        cross(ed, ex, c);
        inside = dot(c, nrm) > 0;
      }
      if (inside && insert_face_point(f, x, ring.empty() ? kNone : ring[0])) {
        face_points_[f].push_back(uint32_t(mesh_.num_vertices() - 1));
        return true;
      }
    }
  }
  // A subsegment of a face already recovered stays whole: splitting it would open a gap
  // between that face's protected subfaces and this one's.
  for (int k = 0; k < 2; ++k)
    if (edge_faces_[2 * e + k] != kNone && face_done_[edge_faces_[2 * e + k]]) return false;
  return split_segment(e, j);
}

// A point of face f. (Splitting an encroached subsegment instead, as conforming Delaunay
// refinement does, can cascade into far more points: not done.)
bool Recoverer::insert_face_point(uint32_t f, const double x[3], uint32_t hint) {
  return insert(x, SteinerHost::kFace, f, hint);
}

void Recoverer::protect(const std::vector<Tri>& tris) {
  for (const Tri& tr : tris) {
    ball(tr[0], scratch_);
    for (uint32_t t : scratch_)
      for (int i = 0; i < 4; ++i) {
        const Tri ft = sorted({mesh_.vertex(t, kFacetVertex[i][0]), mesh_.vertex(t, kFacetVertex[i][1]),
                               mesh_.vertex(t, kFacetVertex[i][2])});
        if (ft == tr) mesh_.set_facet_protected(t, i, true);
      }
  }
}

Status Recoverer::run() {
  n_in_ = S_.num_vertices();
  const auto t0 = Clock::now();
  if (Status s = build_delaunay(); !s.ok()) return s;
  out_.stats.seconds_delaunay = seconds_since(t0);
  const auto t1 = Clock::now();
  build_edges();
  const size_t nf = S_.num_triangles();
  steiner_cap_ = size_t(opt_.max_steiner_per_face * double(nf)) + 1000;

  std::vector<Tri> subfaces;
  std::vector<std::vector<Tri>> face_subs(nf);
  size_t pass = 0;
  for (;; ++pass) {
    if (pass >= opt_.max_passes || out_.steiner.size() > steiner_cap_ ||
        seconds_since(t1) > opt_.max_seconds)
      break;
    bool failed = false;  // a refused split is retried on the next pass
    const size_t missing_edges = recover_edges_once(failed);
    if (missing_edges > 0) continue;  // edges first: faces are looked at once all edges exist
    size_t missing_faces = 0;
    for (uint32_t f = 0; f < nf; ++f) {
      if (face_done_[f]) continue;
      if (face_subfaces(f, subfaces)) {
        protect(subfaces);
        face_subs[f] = subfaces;
        face_done_[f] = 1;
        continue;
      }
      if (opt_.use_flips && chain_[face_edge_[3 * f]].size() == 2 && chain_[face_edge_[3 * f + 1]].size() == 2 &&
          chain_[face_edge_[3 * f + 2]].size() == 2 && face_points_[f].empty() &&
          flip_face(S_.tri[3 * f], S_.tri[3 * f + 1], S_.tri[3 * f + 2]) && face_subfaces(f, subfaces)) {
        protect(subfaces);
        face_subs[f] = subfaces;
        face_done_[f] = 1;
        continue;
      }
      ++missing_faces;
      // Near the boundary subsegment no subface uses when there is one, else anywhere on f.
      if (!(missing_edge_ != kNone && repair_boundary_segment(f))) insert_on_face(f);
    }
    if (missing_faces == 0) break;
  }
  out_.stats.passes = pass;
  for (uint32_t f = 0; f < nf; ++f) {
    if (face_done_[f]) continue;
    // Name the first constraint still missing.
    for (int k = 0; k < 3; ++k) {
      const uint32_t e = face_edge_[3 * f + k];
      for (size_t j = 0; j + 1 < chain_[e].size(); ++j)
        if (!has_edge(chain_[e][j].v, chain_[e][j + 1].v))
          return Status(Error::RecoveryFailed,
                        "recover_boundary: input edge (" + std::to_string(edge_v_[2 * e]) + " " +
                            std::to_string(edge_v_[2 * e + 1]) + ") of " + describe_face(f) +
                            " not recovered after " + std::to_string(pass) + " passes, " +
                            std::to_string(out_.steiner.size()) + " Steiner points and " +
                            std::to_string(seconds_since(t1)) + " s");
    }
    return Status(Error::RecoveryFailed, "recover_boundary: " + describe_face(f) +
                                             " not recovered after " + std::to_string(pass) +
                                             " passes and " + std::to_string(out_.steiner.size()) +
                                             " Steiner points");
  }
  // S2, each subface oriented like its input face.
  for (uint32_t f = 0; f < nf; ++f) {
    const double* A = S_.point(S_.tri[3 * f]);
    double ab[3], ac[3], n[3];
    sub(S_.point(S_.tri[3 * f + 1]), A, ab);
    sub(S_.point(S_.tri[3 * f + 2]), A, ac);
    cross(ab, ac, n);
    for (const Tri& t : face_subs[f]) {
      double xy[3], xz[3], m[3];
      sub(mesh_.point(t[1]), mesh_.point(t[0]), xy);
      sub(mesh_.point(t[2]), mesh_.point(t[0]), xz);
      cross(xy, xz, m);
      const bool flip = dot(m, n) < 0;
      out_.s2_tri.push_back(t[0]);
      out_.s2_tri.push_back(flip ? t[2] : t[1]);
      out_.s2_tri.push_back(flip ? t[1] : t[2]);
      out_.s2_face.push_back(f);
      out_.s2_patch.push_back(f < S_.patch.size() ? S_.patch[f] : 0);
    }
  }
  // Constrained edge bits on every subsegment.
  for (uint32_t e = 0; e < chain_.size(); ++e)
    for (size_t j = 0; j + 1 < chain_[e].size(); ++j) mark_edge(chain_[e][j].v, chain_[e][j + 1].v, true);
  out_.input_edges = edge_v_;
  out_.stats.seconds_recovery = seconds_since(t1);
  const auto t2 = Clock::now();
  if (opt_.remove_outside)
    if (Status s = carve(); !s.ok()) return s;
  out_.stats.seconds_carve = seconds_since(t2);
  out_.stats.seconds_total = seconds_since(t0);
  out_.stats.tets = count_live_tets(mesh_);
  return Status::success();
}

// Components of tets connected through unprotected facets. The ghosts' components are outside;
// any other component is inside when it lies behind the input face of a subface bounding it
// (faces point away from the material). Outside tets are deleted.
Status Recoverer::carve() {
  const size_t nslots = mesh_.num_tet_slots();
  std::unordered_map<Tri, uint32_t, TriHash> face_of;
  for (size_t k = 0; k < out_.s2_face.size(); ++k)
    face_of.emplace(sorted({out_.s2_tri[3 * k], out_.s2_tri[3 * k + 1], out_.s2_tri[3 * k + 2]}),
                    out_.s2_face[k]);
  std::vector<int32_t> comp(nslots, -1);
  struct Comp {
    int inside = -1;  // -1 unknown, 0 outside (ghosts), 1 inside
    double vote = 0;  // sum over bounding subfaces of (area) x (+1 if behind the input face)
    uint32_t min_face = kNone;
  };
  std::vector<Comp> comps;
  std::vector<uint32_t> stack;
  for (uint32_t s = 0; s < nslots; ++s) {
    if (mesh_.is_deleted(s) || comp[s] >= 0) continue;
    const int32_t c = static_cast<int32_t>(comps.size());
    comps.push_back({});
    comp[s] = c;
    stack.assign(1, s);
    while (!stack.empty()) {
      const uint32_t t = stack.back();
      stack.pop_back();
      if (mesh_.is_ghost(t)) comps[c].inside = 0;
      for (int i = 0; i < 4; ++i) {
        if (mesh_.tet_adj[4 * size_t(t) + i] == kNoNeighbour) continue;
        if (mesh_.facet_protected(t, i)) {
          if (mesh_.is_ghost(t)) continue;
          const Tri tr = {mesh_.vertex(t, kFacetVertex[i][0]), mesh_.vertex(t, kFacetVertex[i][1]),
                          mesh_.vertex(t, kFacetVertex[i][2])};
          auto it = face_of.find(sorted(tr));
          if (it == face_of.end()) continue;
          const uint32_t f = it->second;
          comps[c].min_face = std::min(comps[c].min_face, f);
          if (comps[c].inside == 0) continue;  // touches the ghosts: outside whatever the vote
          // The facet's normal points into t; t is inside when that is against f's normal.
          double ab[3], ac[3], n[3], xy[3], xz[3], m[3];
          const double* A = S_.point(S_.tri[3 * f]);
          sub(S_.point(S_.tri[3 * f + 1]), A, ab);
          sub(S_.point(S_.tri[3 * f + 2]), A, ac);
          cross(ab, ac, n);
          sub(mesh_.point(tr[1]), mesh_.point(tr[0]), xy);
          sub(mesh_.point(tr[2]), mesh_.point(tr[0]), xz);
          cross(xy, xz, m);
          // Weighted by the facet's area: a sliver subface's normal is not to be trusted alone.
          comps[c].vote += dot(m, n) / std::sqrt(dot(n, n));
          continue;
        }
        const uint32_t n = mesh_.neighbour(t, i);
        if (comp[n] >= 0) continue;
        comp[n] = c;
        stack.push_back(n);
      }
    }
  }
  for (Comp& c : comps)
    if (c.inside < 0) c.inside = c.vote < 0 ? 1 : 0;
  // Inside components numbered by the smallest input face bounding them.
  std::vector<int32_t> order;
  for (int32_t c = 0; c < int32_t(comps.size()); ++c)
    if (comps[c].inside == 1) order.push_back(c);
  std::sort(order.begin(), order.end(), [&](int32_t a, int32_t b) { return comps[a].min_face < comps[b].min_face; });
  std::vector<int32_t> region(comps.size(), -1);
  for (size_t k = 0; k < order.size(); ++k) region[order[k]] = int32_t(k);
  out_.stats.regions = order.size();
  keep_regions(mesh_, comp, region);
  return Status::success();
}

}  // namespace

namespace {

// The split strategy's retry removes a missing triangle's crossing edges this many times.
constexpr int kRetryCrossingFlips = 3;

// An empty result for one strategy's run on S.
RecoveryOutput fresh_output(const SurfaceMesh& S, size_t strategy) {
  RecoveryOutput out;
  out.stats.input_vertices = S.num_vertices();
  out.stats.input_triangles = S.num_triangles();
  out.stats.strategy = strategy;
  return out;
}

}  // namespace

const char* recovery_strategy_name(size_t strategy) {
  switch (strategy) {
    case 0: return "fuzzy faces";
    case 1: return "fuzzy faces with flips";
    case 2: return "fuzzy faces with defended edges";
    case 3: return "split constraints";
    case 4: return "split constraints, crossing edges removed 3 times, edge-crossing splits switched";
    case 5: return "split constraints, tets flat in exact geometry allowed";
    default: return "unknown";
  }
}

Result<RecoveryOutput> recover_boundary(const SurfaceMesh& S, const RecoveryOptions& options) {
  if (S.num_vertices() < 4 || S.num_triangles() < 4)
    return Status(Error::EmptyInput, "recover_boundary: a closed surface needs at least 4 vertices and 4 triangles");
  // The strategies, each from scratch: split constraints (split_recovery.hpp); then the fuzzy
  // faces as asked, then (when retry_strategies) with flips, then with defended subsegments. No
  // one of them recovers every shared surface; together they recover more (measurements in the
  // README's status table).
  std::vector<RecoveryOptions> attempts = {options};
  if (options.retry_strategies) {
    RecoveryOptions flips = options;
    flips.use_flips = true;
    flips.defend_edges = false;
    RecoveryOptions defend = options;
    defend.use_flips = false;
    defend.defend_edges = true;
    for (const RecoveryOptions& o : {flips, defend})
      if (o.use_flips != options.use_flips || o.defend_edges != options.defend_edges) attempts.push_back(o);
  }
  // A strategy's success, without the box corners its Delaunay mesh had.
  auto finished = [&](RecoveryOutput& out) -> Result<RecoveryOutput> {
    if (options.remove_outside)
      if (Status s = recovery_detail::drop_box_corners(out, S.num_vertices()); !s.ok()) return s;
    return std::move(out);
  };
  Status first;
  if (options.split_constraints) {
    RecoveryOutput out = fresh_output(S, 3);
    Status s = recovery_detail::recover_by_splitting(S, options, out);
    if (s.ok()) return finished(out);
    if (s.code() == Error::RecoveryFailed && options.retry_strategies && options.split_flips &&
        options.split_crossing_flips < kRetryCrossingFlips) {
      RecoveryOptions more = options;
      more.split_crossing_flips = kRetryCrossingFlips;
      // and the other way round for edge crossings: some fronts need them off, others on.
      more.split_edge_crossings = !options.split_edge_crossings;
      RecoveryOutput again = fresh_output(S, 4);
      const Status s2 = recovery_detail::recover_by_splitting(S, more, again);
      if (s2.ok()) return finished(again);
    }
    if (s.code() == Error::RecoveryFailed && options.retry_strategies && options.split_exact_degeneracies) {
      // Once more without the degeneracy oracle: refusing every tet flat in exact geometry can
      // leave a segment no point recovers (an S1 rounded far from the origin; without the oracle it
      // is recovered at once). The tets flat to double rounding this may make are opened later (the
      // optimizer's last pass; flip_flat_tets in `anitet recover`).
      RecoveryOptions plain = options;
      plain.split_exact_degeneracies = false;
      RecoveryOutput again = fresh_output(S, 5);
      const Status s3 = recovery_detail::recover_by_splitting(S, plain, again);
      if (s3.ok()) return finished(again);
    }
    if (s.code() != Error::RecoveryFailed || !options.fuzzy_faces) return s;
    first = s;
  }
  if (!options.fuzzy_faces)
    return Status(Error::InvalidArgument, "recover_boundary: no strategy enabled (split_constraints and fuzzy_faces are off)");
  for (size_t k = 0; k < attempts.size(); ++k) {
    // 0: as asked; a retry is named by what it changed (see RecoveryStats::strategy).
    RecoveryOutput out = fresh_output(S, k == 0 ? 0 : attempts[k].use_flips ? 1 : 2);
    Status s;
    {
      Recoverer r(S, attempts[k], out);
      s = r.run();
    }
    if (s.ok()) return finished(out);
    if (s.code() != Error::RecoveryFailed) return s;
    if (first.ok()) first = s;
  }
  if (attempts.size() == 1 && !options.split_constraints) return first;
  return Status(first.code(), first.message() + " (" + (options.split_constraints ? "the fuzzy-face strategies" : "the retries with flips and with defended subsegments") + " failed too)");
}

}  // namespace anitet
