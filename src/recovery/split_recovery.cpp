#include "recovery/split_recovery.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/buckets.hpp"
#include "core/tet_ops.hpp"
#include "delaunay/delaunay.hpp"
#include "predicates/predicates.hpp"
#include "recovery/local_flips.hpp"
#include "recovery/recovery_util.hpp"

namespace anitet::recovery_detail {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

constexpr uint32_t kNone = TetMesh::kNone;
constexpr uint32_t kNoNeighbour = TetMesh::kNoNeighbour;

class SplitRecoverer : public DegeneracyOracle {
 public:
  SplitRecoverer(const SurfaceMesh& s, const RecoveryOptions& o, RecoveryOutput& out)
      : S_(s), opt_(o), out_(out), mesh_(out.mesh), inserter_(out.mesh, o.seed) {}

  Status run();

  // Three vertices on one input segment, or four on one plane of exactly coplanar input faces:
  // flat in exact geometry (the Steiner points are on their hosts only to rounding).
  bool flat(uint32_t a, uint32_t b, uint32_t c, uint32_t d) const override;

 private:
  // A constraint edge: the (at most two) live constraint triangles on it, and the input edge it
  // lies on (kNone for an edge inside an input face, made by a triangle split).
  struct CEdge {
    uint32_t tri[2] = {kNone, kNone};
    uint32_t input_edge = kNone;
    // Present and marked constrained (defend()): neither the kernel nor a flip removes it, so
    // the sweeps need not look for it in the mesh again.
    bool defended = false;
  };
  enum : uint8_t { kMissing = 0, kRecovered = 1, kDead = 2 };
  // An edge of a recovered (protected) triangle stays in the mesh: no sweep needs to look at it.
  // Drops erased and settled edges from the sweep list (a settled edge stays settled: recovered
  // triangles are never split).
  void drop_settled_keys() {
    edge_keys_.erase(std::remove_if(edge_keys_.begin(), edge_keys_.end(),
                                    [&](uint64_t key) {
                                      auto it = edges_.find(key);
                                      return it == edges_.end() || settled(it->second);
                                    }),
                     edge_keys_.end());
  }
  // The constraint edge `key` when a sweep still has to look for it: alive, on an input edge
  // (on_input_edge) or inside a face (otherwise), neither settled nor defended; else null.
  CEdge* still_open(uint64_t key, bool on_input_edge) {
    auto it = edges_.find(key);
    if (it == edges_.end() || (it->second.input_edge != kNone) != on_input_edge || settled(it->second) ||
        it->second.defended)
      return nullptr;
    return &it->second;
  }
  bool settled(const CEdge& e) const {
    return (e.tri[0] != kNone && ct_state_[e.tri[0]] == kRecovered) ||
           (e.tri[1] != kNone && ct_state_[e.tri[1]] == kRecovered);
  }

  Status build_delaunay();
  void build_constraints();
  Status check_apexes();
  void add_tri(uint32_t a, uint32_t b, uint32_t c, uint32_t face);
  void remove_tri(uint32_t k);
  CEdge& edge_of(uint32_t a, uint32_t b, uint32_t input_edge);
  const std::vector<uint32_t>& ball(uint32_t v);
  bool has_edge(uint32_t a, uint32_t b);
  bool find_facet(const Tri& t, uint32_t& tet, int& facet);
  void protect(uint32_t k);
  void mark_edge_constrained(uint32_t a, uint32_t b);
  double param_on(uint32_t v, uint32_t e) const;
  uint32_t insert(const double p[3], SteinerHost host, uint32_t host_id, double param, uint32_t hint,
                  const uint32_t* keep = nullptr, size_t keep_count = 0, bool force_keep = false,
                  std::array<uint32_t, 2> crossed = {kNone, kNone});
  uint32_t split_edge(uint64_t key, double at = -1.0);
  void defend(uint32_t a, uint32_t b);
  void defend_present(CEdge& e, uint32_t a, uint32_t b);
  void defend_split(uint64_t key, uint32_t v);
  size_t flip_face_edges();
  void recover_face_edges(size_t cap);
  size_t walk_points(uint32_t a, uint32_t b);
  uint32_t crossed_edge_point(uint32_t u, uint32_t w, double& frac);
  void split_caps();
  bool flip_in(uint32_t a, uint32_t b);
  bool flip_in_tri(uint32_t k);
  bool flip_along(uint32_t a, uint32_t b);
  uint32_t entered_tet(uint32_t a, const double* B);
  uint32_t entered_facet(uint32_t a, const double* B, int& ia, uint32_t f[3]);
  bool sees_apex(const double* a, const double* b, const double* c, uint32_t face) const;
  bool flip_edge(uint64_t key, bool only_to_mesh);
  bool split_triangle(uint32_t k);
  Status carve();
  std::string describe_tri(uint32_t k) const;
  std::string shown_id(uint32_t v) const;

  const SurfaceMesh& S_;
  const RecoveryOptions& opt_;
  RecoveryOutput& out_;
  TetMesh& mesh_;
  PointInserter inserter_;
  meshops::VertexTets vt_;
  size_t n_in_ = 0;

  std::vector<uint32_t> edge_v_;                 // 2 per input edge (sorted ids)
  std::unordered_map<uint64_t, uint32_t> input_edge_id_;
  // Per vertex, where it lies; one record, since flat() reads all of it for the four vertices of
  // every facet of every cavity.
  struct VertexHost {
    int8_t kind = -1;      // -1 input vertex, else a SteinerHost: edge or face
    uint32_t host = kNone;  // host input edge / face
    // A point split where its segment crosses a mesh edge pq exactly coplanar with it stands for
    // that crossing (a point of both in exact geometry): tets with p, q and it are flat too (else a
    // flip makes pq again beside it, and the pieces from it cross pq within rounding of it). Not
    // for a crossing near pq: the two are then skew.
    std::array<uint32_t, 2> crossed = {kNone, kNone};  // that edge, or kNone twice
    std::array<uint32_t, 2> planes = {kNone, kNone};   // host_planes()
  };
  std::vector<VertexHost> vhost_;
  std::vector<double> vparam_;  // edge-hosted: parameter from edge_v_[2e]
  VertexHost pending_;           // the point being inserted
  const VertexHost& host_record(uint32_t v) const { return v < vhost_.size() ? vhost_[v] : pending_; }
  std::array<uint32_t, 2> crossed_of(uint32_t v) const { return host_record(v).crossed; }
  std::vector<uint32_t> edge_face_;              // 2 per input edge: its input triangles
  std::vector<uint32_t> face_plane_;             // per input triangle: its group of coplanar ones
  std::vector<uint32_t> vplane_begin_, vplane_;  // per input vertex: the groups of its triangles
  void build_planes();
  int8_t kind_of(uint32_t v) const { return host_record(v).kind; }
  uint32_t host_of(uint32_t v) const { return host_record(v).host; }
  bool on_plane(uint32_t v, uint32_t plane) const;
  std::array<uint32_t, 2> host_planes(int8_t kind, uint32_t host) const;
  std::array<uint32_t, 2> planes_of(uint32_t v) const { return host_record(v).planes; }
  const DegeneracyOracle* oracle() const { return opt_.split_exact_degeneracies ? this : nullptr; }

  std::vector<Tri> ct_;                          // constraint triangles, oriented like S
  std::vector<uint32_t> ct_face_;                // their input face
  std::vector<uint8_t> ct_state_;
  std::unordered_map<uint64_t, CEdge> edges_;
  std::vector<uint64_t> edge_keys_;              // sweep order (erased keys are skipped)

  int apex_sign_ = 0;  // the orient3d sign of the input triangles with their face_apex (0: no guard)
  std::vector<uint32_t> ball_, bfs_;
  // ball_ is the ball of this vertex until the mesh's tets change (changed()): one missing edge's
  // sweep asks for its end's ball up to a dozen times, and needle fans' ends have thousands.
  uint32_t ball_of_ = kNone;
  void changed() { ball_of_ = kNone; }
  // After an insertion or a flip made `tets`: the cached ball is stale, and each new real tet
  // becomes its vertices' entry in vt_.
  void tets_made(const std::vector<uint32_t>& tets) {
    changed();
    for (uint32_t t : tets) {
      if (!mesh_.is_ghost(t)) vt_.note(mesh_, t);
      for (int i = 0; i < 4; ++i)
        if (const uint32_t x = mesh_.vertex(t, i); x < snap_dirty_.size()) snap_dirty_[x] = 1;
    }
  }
  // A snapshot of every vertex's tets, built on every core before a sweep that asks about many
  // edges or triangles: a vertex none of whose tets changed since (every vertex of a changed tet
  // is one of a made tet: no vertex goes) reads its tets there instead of walking its ball. In
  // tet order, not ball order: only for the questions the order does not change (has_edge,
  // find_facet, mark_edge_constrained).
  std::vector<uint32_t> snap_start_, snap_tets_, snap_counts_;
  std::vector<uint8_t> snap_dirty_;  // per vertex of the snapshot: its tets changed since
  struct TetSpan {
    const uint32_t* first;
    size_t count;
    const uint32_t* begin() const { return first; }
    const uint32_t* end() const { return first + count; }
  };
  TetSpan tets_of(uint32_t v) {
    if (v < snap_dirty_.size() && !snap_dirty_[v])
      return {snap_tets_.data() + snap_start_[v], size_t(snap_start_[v + 1] - snap_start_[v])};
    const std::vector<uint32_t>& b = ball(v);
    return {b.data(), b.size()};
  }
  // Takes the snapshot when `questions` lookups are to come: worth a scan of every tet when they
  // are more than half the vertices (a ball walk each otherwise).
  void snapshot_tets(size_t questions);
  std::vector<uint32_t> tet_stamp_;
  uint32_t stamp_ = 0;
  std::vector<std::array<uint32_t, 3>> crossings_;  // split_triangle(): (tet, p, r) per crossing edge
  std::vector<uint8_t> ct_flipped_;  // per constraint triangle: how often its crossing edges were removed
  std::vector<double> walk_frac_;    // walk_points()
  std::vector<uint32_t> walk_chain_;
  EdgeRing crossed_ring_;            // crossed_edge_point()
  bool crossed_coplanar_ = false;    // and the segment and that edge are exactly coplanar
};

// A vertex id as the result would number it (without the box corners).
std::string SplitRecoverer::shown_id(uint32_t v) const {
  const bool box = opt_.remove_outside && v >= n_in_;
  return std::to_string(box && v >= n_in_ + kBoxCorners ? v - kBoxCorners : v);
}

std::string SplitRecoverer::describe_tri(uint32_t k) const {
  const uint32_t f = ct_face_[k];
  return "input triangle " + std::to_string(f) + " (" + std::to_string(S_.tri[3 * f]) + " " +
         std::to_string(S_.tri[3 * f + 1]) + " " + std::to_string(S_.tri[3 * f + 2]) + ")";
}

Status SplitRecoverer::build_delaunay() {
  if (Status s = delaunay_of_surface_points(mesh_, S_, opt_.remove_outside); !s.ok()) return s;
  vt_.build(mesh_);
  vhost_.assign(mesh_.num_vertices(), VertexHost{});
  vparam_.assign(mesh_.num_vertices(), 0.0);
  return Status::success();
}

SplitRecoverer::CEdge& SplitRecoverer::edge_of(uint32_t a, uint32_t b, uint32_t input_edge) {
  const uint64_t key = edge_key(a, b);
  auto [it, fresh] = edges_.try_emplace(key);
  if (fresh) {
    it->second.input_edge = input_edge;
    edge_keys_.push_back(key);
  }
  return it->second;
}

void SplitRecoverer::add_tri(uint32_t a, uint32_t b, uint32_t c, uint32_t face) {
  const auto k = static_cast<uint32_t>(ct_.size());
  ct_.push_back({a, b, c});
  ct_face_.push_back(face);
  ct_state_.push_back(kMissing);
  ct_flipped_.push_back(0);
  const uint32_t v[3] = {a, b, c};
  for (int i = 0; i < 3; ++i) {
    CEdge& e = edge_of(v[i], v[(i + 1) % 3], kNone);
    (e.tri[0] == kNone ? e.tri[0] : e.tri[1]) = k;
  }
}

void SplitRecoverer::remove_tri(uint32_t k) {
  ct_state_[k] = kDead;
  const Tri& t = ct_[k];
  for (int i = 0; i < 3; ++i) {
    auto it = edges_.find(edge_key(t[i], t[(i + 1) % 3]));
    if (it == edges_.end()) continue;
    for (uint32_t& s : it->second.tri)
      if (s == k) s = kNone;
    if (it->second.tri[0] == kNone && it->second.tri[1] == kNone) edges_.erase(it);
  }
}

void SplitRecoverer::build_constraints() {
  const size_t nf = S_.num_triangles();
  for (uint32_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = S_.tri[3 * f + k], b = S_.tri[3 * f + (k + 1) % 3];
      auto [it, fresh] = input_edge_id_.emplace(edge_key(a, b), uint32_t(edge_v_.size() / 2));
      if (fresh) {
        edge_v_.push_back(std::min(a, b));
        edge_v_.push_back(std::max(a, b));
      }
      edge_of(a, b, it->second);
    }
  for (uint32_t f = 0; f < nf; ++f) add_tri(S_.tri[3 * f], S_.tri[3 * f + 1], S_.tri[3 * f + 2], f);
}

// Groups of exactly coplanar input triangles (joined across edges where the opposite vertex is
// on the other triangle's plane by the exact orient3d), and the groups around each input vertex.
void SplitRecoverer::build_planes() {
  const size_t nf = S_.num_triangles();
  const size_t ne = edge_v_.size() / 2;
  edge_face_.assign(2 * ne, kNone);
  for (uint32_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t e = input_edge_id_.at(edge_key(S_.tri[3 * f + k], S_.tri[3 * f + (k + 1) % 3]));
      (edge_face_[2 * e] == kNone ? edge_face_[2 * e] : edge_face_[2 * e + 1]) = f;
    }
  face_plane_.resize(nf);
  for (uint32_t f = 0; f < nf; ++f) face_plane_[f] = f;
  auto root = [&](uint32_t f) {
    while (face_plane_[f] != f) f = face_plane_[f] = face_plane_[face_plane_[f]];
    return f;
  };
  for (uint32_t e = 0; e < ne; ++e) {
    const uint32_t f = edge_face_[2 * e], g = edge_face_[2 * e + 1];
    if (f == kNone || g == kNone) continue;
    uint32_t opposite = kNone;
    for (int k = 0; k < 3; ++k)
      if (S_.tri[3 * g + k] != edge_v_[2 * e] && S_.tri[3 * g + k] != edge_v_[2 * e + 1]) opposite = S_.tri[3 * g + k];
    if (predicates::orient3d(S_.point(S_.tri[3 * f]), S_.point(S_.tri[3 * f + 1]), S_.point(S_.tri[3 * f + 2]),
                             S_.point(opposite)) == 0)
      face_plane_[root(f)] = root(g);
  }
  // Faces of one axis-aligned plane (a coordinate shared exactly by their three corners) are one
  // group even when no chain of coplanar neighbours joins them: CAD parts have many.
  std::map<std::pair<int, double>, uint32_t> axis_plane;
  for (uint32_t f = 0; f < nf; ++f) {
    const double* A = S_.point(S_.tri[3 * f]);
    const double* B = S_.point(S_.tri[3 * f + 1]);
    const double* C = S_.point(S_.tri[3 * f + 2]);
    for (int d = 0; d < 3; ++d) {
      if (!(A[d] == B[d] && B[d] == C[d])) continue;
      auto [it, fresh] = axis_plane.emplace(std::make_pair(d, A[d] == 0 ? 0.0 : A[d]), f);
      if (!fresh) face_plane_[root(f)] = root(it->second);
    }
  }
  for (uint32_t f = 0; f < nf; ++f) face_plane_[f] = root(f);
  std::vector<std::vector<uint32_t>> around(n_in_);
  for (uint32_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      std::vector<uint32_t>& a = around[S_.tri[3 * f + k]];
      if (std::find(a.begin(), a.end(), face_plane_[f]) == a.end()) a.push_back(face_plane_[f]);
    }
  vplane_begin_.assign(n_in_ + 1, 0);
  for (uint32_t v = 0; v < n_in_; ++v) {
    vplane_begin_[v + 1] = vplane_begin_[v] + static_cast<uint32_t>(around[v].size());
    vplane_.insert(vplane_.end(), around[v].begin(), around[v].end());
  }
}

bool SplitRecoverer::on_plane(uint32_t v, uint32_t plane) const {
  if (v < n_in_) return std::find(vplane_.begin() + vplane_begin_[v], vplane_.begin() + vplane_begin_[v + 1], plane) !=
                        vplane_.begin() + vplane_begin_[v + 1];
  const std::array<uint32_t, 2> planes = planes_of(v);
  return plane != kNone && (planes[0] == plane || planes[1] == plane);
}

// The groups a point that is not an input vertex lies on: its face's, or its edge's two faces'
// (kNone for the rest, and twice for a box corner).
std::array<uint32_t, 2> SplitRecoverer::host_planes(int8_t kind, uint32_t h) const {
  if (kind == static_cast<int8_t>(SteinerHost::kFace)) return {face_plane_[h], kNone};
  if (kind != static_cast<int8_t>(SteinerHost::kEdge)) return {kNone, kNone};
  const uint32_t g = edge_face_[2 * h + 1];
  return {face_plane_[edge_face_[2 * h]], g != kNone ? face_plane_[g] : kNone};
}

bool SplitRecoverer::flat(uint32_t a, uint32_t b, uint32_t c, uint32_t d) const {
  const uint32_t v[4] = {a, b, c, d};
  const VertexHost* rec[4] = {};  // null for input vertices
  int steiner = -1;               // the first vertex that is not an input vertex
  for (int i = 0; i < 4; ++i)
    if (v[i] >= n_in_) {
      rec[i] = &host_record(v[i]);
      if (steiner < 0) steiner = i;
    }
  if (steiner < 0) return false;  // input vertices only: the exact orient3d decided
  auto on_edge = [&](int j, uint32_t e) {
    return rec[j] ? rec[j]->kind == static_cast<int8_t>(SteinerHost::kEdge) && rec[j]->host == e
                  : v[j] == edge_v_[2 * e] || v[j] == edge_v_[2 * e + 1];
  };
  for (int i = steiner; i < 4; ++i) {
    if (!rec[i]) continue;
    const std::array<uint32_t, 2>& pq = rec[i]->crossed;
    if (pq[0] != kNone) {
      int on = 0;
      for (int j = 0; j < 4; ++j) on += v[j] == pq[0] || v[j] == pq[1];
      if (on == 2) return true;
    }
    if (rec[i]->kind == static_cast<int8_t>(SteinerHost::kEdge)) {
      int on = 0;
      for (int j = 0; j < 4; ++j)
        if (j != i && on_edge(j, rec[i]->host)) ++on;
      if (on >= 2) return true;
    }
  }
  // Four points on one group: it is one of the groups of each of them, so of the first Steiner
  // point's.
  for (uint32_t plane : rec[steiner]->planes) {
    if (plane == kNone) continue;
    bool all = true;
    for (int j = 0; j < 4 && all; ++j)
      if (j != steiner) all = rec[j] ? rec[j]->planes[0] == plane || rec[j]->planes[1] == plane : on_plane(v[j], plane);
    if (all) return true;
  }
  return false;
}

Status SplitRecoverer::check_apexes() {
  if (opt_.face_apex.empty()) return Status::success();
  const size_t nf = S_.num_triangles();
  if (opt_.face_apex.size() != 3 * nf)
    return Status(Error::InvalidArgument, "recover_boundary: face_apex needs 3 coordinates per input triangle");
  // The side the input triangles see their apexes on; every input triangle must agree.
  for (uint32_t f = 0; f < nf; ++f) {
    const int s = predicates::orient3d(S_.point(S_.tri[3 * f]), S_.point(S_.tri[3 * f + 1]),
                                       S_.point(S_.tri[3 * f + 2]), &opt_.face_apex[3 * size_t(f)]);
    if (s == 0 || (apex_sign_ != 0 && s != apex_sign_))
      return Status(Error::InvalidArgument, "recover_boundary: input triangle " + std::to_string(f) +
                                                " does not see its face_apex on the side the others do");
    apex_sign_ = s;
  }
  return Status::success();
}

const std::vector<uint32_t>& SplitRecoverer::ball(uint32_t v) {
  if (v == ball_of_) return ball_;
  ball_of_ = kNone;
  const uint32_t t = vt_.tet_of(mesh_, v);
  if (t == kNone) {
    ball_.clear();
    return ball_;
  }
  meshops::vertex_ball(mesh_, v, t, ball_);
  ball_of_ = v;
  return ball_;
}

void SplitRecoverer::snapshot_tets(size_t questions) {
  const size_t nv = mesh_.num_vertices();
  if (2 * questions < nv) return;
  parallel_bucket_by_key(
      nv, mesh_.num_tet_slots(),
      [&](size_t first, size_t last, auto&& emit) {
        for (auto t = uint32_t(first); t < last; ++t)
          if (!mesh_.is_deleted(t))
            for (int i = 0; i < 4; ++i)
              if (const uint32_t x = mesh_.vertex(t, i); x < nv) emit(x, t);
      },
      snap_start_, snap_tets_, snap_counts_);
  snap_dirty_.assign(nv, 0);
}

bool SplitRecoverer::has_edge(uint32_t a, uint32_t b) {
  for (uint32_t t : tets_of(a))
    if (meshops::tet_has_vertex(mesh_, t, b)) return true;
  return false;
}

bool SplitRecoverer::find_facet(const Tri& tr, uint32_t& tet, int& facet) {
  for (uint32_t t : tets_of(tr[0])) {
    int missing = -1, found = 0;
    for (int i = 0; i < 4; ++i) {
      const uint32_t v = mesh_.vertex(t, i);
      if (v == tr[0] || v == tr[1] || v == tr[2]) ++found;
      else missing = i;
    }
    if (found == 3) {
      tet = t;
      facet = missing;
      return true;
    }
  }
  return false;
}

void SplitRecoverer::protect(uint32_t k) {
  uint32_t t;
  int i;
  if (!find_facet(ct_[k], t, i)) return;
  mesh_.set_facet_protected(t, i, true);
  const uint32_t adj = mesh_.tet_adj[4 * size_t(t) + i];
  if (adj != kNoNeighbour) mesh_.set_facet_protected(uint32_t(adj >> 2), int(adj & 3), true);
  ct_state_[k] = kRecovered;
}

void SplitRecoverer::mark_edge_constrained(uint32_t a, uint32_t b) {
  const TetSpan tets = tets_of(a);
  set_edge_constrained(mesh_, tets.first, tets.count, a, b, true);
}

// Marks edge (a b) constrained when it is in the mesh (RecoveryOptions::split_defend_edges).
void SplitRecoverer::defend(uint32_t a, uint32_t b) {
  if (opt_.split_defend_edges && has_edge(a, b)) defend_present(edges_.at(edge_key(a, b)), a, b);
}

// defend() of the constraint edge e = (a b), known to be in the mesh.
void SplitRecoverer::defend_present(CEdge& e, uint32_t a, uint32_t b) {
  if (!opt_.split_defend_edges) return;
  mark_edge_constrained(a, b);
  e.defended = true;
}

// After split_edge(key) made vertex v: defends the two pieces.
void SplitRecoverer::defend_split(uint64_t key, uint32_t v) {
  defend(uint32_t(key >> 32), v);
  defend(v, uint32_t(key & 0xffffffffu));
}

double SplitRecoverer::param_on(uint32_t v, uint32_t e) const {
  if (v == edge_v_[2 * e]) return 0.0;
  if (v == edge_v_[2 * e + 1]) return 1.0;
  return vparam_[v];
}

uint32_t SplitRecoverer::insert(const double p[3], SteinerHost host, uint32_t host_id, double param,
                                uint32_t hint, const uint32_t* keep, size_t keep_count, bool force_keep,
                                std::array<uint32_t, 2> crossed) {
  InsertOptions io;
  io.vertex_flags = vflag::kOnInputSurface;
  io.keep_tets = keep;
  io.keep_count = keep_count;
  io.force_keep = force_keep;
  io.degeneracy = oracle();
  pending_.kind = static_cast<int8_t>(host);
  pending_.host = host_id;
  pending_.crossed = crossed;
  pending_.planes = host_planes(pending_.kind, host_id);
  const InsertResult r = inserter_.insert(p, hint, io);
  if (!r.ok()) {
    ++out_.stats.blocked_insertions;
    return kNone;
  }
  tets_made(inserter_.new_tets());
  vhost_.push_back(pending_);
  vparam_.push_back(param);
  out_.steiner.push_back({r.vertex, host, host_id});
  if (host == SteinerHost::kEdge) ++out_.stats.steiner_on_edges;
  else ++out_.stats.steiner_on_faces;
  return r.vertex;
}

// Whether triangle (a b c), a piece of input triangle `face`, sees the face's apex on the side the
// input triangles do (RecoveryOptions::face_apex; always true without it).
bool SplitRecoverer::sees_apex(const double* a, const double* b, const double* c, uint32_t face) const {
  if (apex_sign_ == 0) return true;
  return predicates::orient3d(a, b, c, &opt_.face_apex[3 * size_t(face)]) == apex_sign_;
}

// Makes the missing edge (a b) by one flip (no Steiner point); the mesh is then no longer
// Delaunay, which the modified kernel accepts.
bool SplitRecoverer::flip_in(uint32_t a, uint32_t b) {
  std::vector<uint32_t> created;
  if (!flip_in_edge(mesh_, a, b, ball(a), created, oracle())) return false;
  tets_made(created);
  ++out_.stats.flips;
  return true;
}

// The tet of a's ball that segment a->B enters: B inside its closed cone at a (on the side of
// each facet through a that the facet's opposite vertex is on, or on its plane: on flat CAD faces
// ab often lies in a facet's plane). kNone when no live tet is entered.
uint32_t SplitRecoverer::entered_tet(uint32_t a, const double* B) {
  for (uint32_t c : ball(a)) {
    if (mesh_.is_ghost(c)) continue;
    int ia = 0;
    while (mesh_.vertex(c, ia) != a) ++ia;
    bool inside = true;
    for (int j = 0; j < 4 && inside; ++j) {
      if (j == ia) continue;
      const double* f[3];
      for (int k = 0; k < 3; ++k) f[k] = mesh_.point(mesh_.vertex(c, kFacetVertex[j][k]));
      const int sb = predicates::orient3d(f[0], f[1], f[2], B);
      const int so = predicates::orient3d(f[0], f[1], f[2], mesh_.point(mesh_.vertex(c, j)));
      if (sb != so && sb != 0) inside = false;
    }
    if (inside) return c;
  }
  return kNone;
}

// entered_tet(a, B), with a's index in it (ia) and the vertices of its facet opposite a (f, in
// kFacetVertex order).
uint32_t SplitRecoverer::entered_facet(uint32_t a, const double* B, int& ia, uint32_t f[3]) {
  const uint32_t t = entered_tet(a, B);
  if (t == kNone) return kNone;
  ia = 0;
  while (mesh_.vertex(t, ia) != a) ++ia;
  for (int k = 0; k < 3; ++k) f[k] = mesh_.vertex(t, kFacetVertex[ia][k]);
  return t;
}

// Makes the missing edge (a b) by flips along it, no Steiner point (thin plates: a long edge
// crosses a few tets spanning the plate, where splits would go down to the plate's thickness).
// The tet a->b enters first has a facet opposite a that the segment crosses: a 2-3 flip there
// (the segment then crosses one tet fewer), or, when the two tets are not convex or the segment
// passes through an edge of that facet, the removal of that facet's edge. Each flip is checked
// exactly; constraint edges and protected facets are never removed.
bool SplitRecoverer::flip_along(uint32_t a, uint32_t b) {
  constexpr int kMaxFlips = 24;
  std::vector<uint32_t> created;
  const double* A = mesh_.point(a);
  const double* B = mesh_.point(b);
  for (int flips = 0; flips < kMaxFlips; ++flips) {
    if (has_edge(a, b)) return true;
    int ia;
    uint32_t f[3];
    const uint32_t t = entered_facet(a, B, ia, f);
    if (t == kNone) return false;
    // Where the line ab meets facet f: the sign of orient3d(a, b, f_k, f_k+1) per edge (all
    // alike: the interior; a zero: through that edge).
    int side[3];
    for (int k = 0; k < 3; ++k) side[k] = predicates::orient3d(A, B, mesh_.point(f[k]), mesh_.point(f[(k + 1) % 3]));
    bool done = false;
    created.clear();
    if (side[0] != 0 && side[0] == side[1] && side[1] == side[2]) done = flip23(mesh_, t, ia, &created, oracle());
    for (int k = 0; k < 3 && !done; ++k) {
      // Only the edge the segment passes through, or, for an interior crossing, any of the three.
      const bool through = side[k] == 0;
      const bool interior = side[0] != 0 && side[0] == side[1] && side[1] == side[2];
      if (!through && !interior) continue;
      const uint32_t p = f[k], q = f[(k + 1) % 3];
      if (edges_.count(edge_key(p, q))) continue;  // a constraint edge stays
      EdgeRing ring;
      if (!edge_ring(mesh_, t, p, q, ring)) continue;
      created.clear();
      done = remove_edge(mesh_, ring, nullptr, 0, &created, oracle());
    }
    if (!done) return false;
    tets_made(created);
    ++out_.stats.flips;
  }
  return has_edge(a, b);
}

// When segment u->w, from u, first meets the facet opposite u of the tet it enters at (or near:
// a barycentric weight below kNearEdge) an edge pq of that facet, and pq is not a constraint
// edge: sets frac, the fraction of |uw| where it passes nearest to line pq (in (0.01, 0.99)), and
// crossed_ring_, pq's ring; returns the tet entered, kNone otherwise.
uint32_t SplitRecoverer::crossed_edge_point(uint32_t u, uint32_t w, double& frac) {
  const double* U = mesh_.point(u);
  const double* W = mesh_.point(w);
  int iu;
  uint32_t f[3];
  const uint32_t t = entered_facet(u, W, iu, f);
  if (t == kNone) return kNone;
  // Where line uw meets the facet's plane, as barycentric weights (floating point: the exact
  // zeros of orient3d(u, w, f_k, f_k+1) say "through the edge" on flat faces).
  double vol[3], total = 0;
  int zero = -1;
  for (int k = 0; k < 3; ++k) {
    const double* P = mesh_.point(f[k]);
    const double* Q = mesh_.point(f[(k + 1) % 3]);
    if (predicates::orient3d(U, W, P, Q) == 0) zero = k;
    double up[3], uq[3], uw[3], c[3];
    sub(P, U, up);
    sub(Q, U, uq);
    sub(W, U, uw);
    cross(up, uq, c);
    vol[k] = dot(c, uw);
    total += vol[k];
  }
  // Near an edge: on nearly flat fans the segment runs nearly in the facet's plane, and a crossing
  // this near an edge is where the walk's points would creep to (with 1e-9, needle fans flat only
  // to rounding stalled). The kernel still refuses the point when pq's ring is not star-shaped
  // from it.
  constexpr double kNearEdge = 1e-3;
  int k = zero;
  crossed_coplanar_ = zero >= 0;
  if (k < 0 && total != 0)
    for (int j = 0; j < 3; ++j)
      if (std::fabs(vol[j] / total) < kNearEdge && (k < 0 || std::fabs(vol[j]) < std::fabs(vol[k]))) k = j;
  if (k < 0) return kNone;
  const uint32_t p = f[k], q = f[(k + 1) % 3];
  if (edges_.count(edge_key(p, q))) return kNone;
  // Nearest points of lines u + s (w - u) and p + r (q - p).
  const double* P = mesh_.point(p);
  const double* Q = mesh_.point(q);
  double d1[3], d2[3], r0[3];
  sub(W, U, d1);
  sub(Q, P, d2);
  sub(U, P, r0);
  const double a11 = dot(d1, d1), a12 = dot(d1, d2), a22 = dot(d2, d2);
  const double b1 = dot(d1, r0), b2 = dot(d2, r0);
  const double den = a11 * a22 - a12 * a12;
  if (!(den > 0)) return kNone;
  const double sfrac = (a12 * b2 - a22 * b1) / den;
  if (!(sfrac > 0.01 && sfrac < 0.99)) return kNone;
  if (!edge_ring(mesh_, t, p, q, crossed_ring_, 64)) return kNone;
  frac = sfrac;
  return t;
}

// Points of segment a->b whose insertion would join it to a. The walk goes along the segment
// through the tets it crosses, t_1 (in a's ball), t_2, ...; the middle of the segment's piece in
// t_k, when it lies inside the circumspheres of t_1..t_k, has them all in its cavity, and the new
// vertex is joined to a when none of them leaves the cavity (InsertOptions::keep_tets makes the
// kernel refuse the point otherwise). walk_frac_[k-1] is that point's fraction of |ab|, the chain
// is walk_chain_; returns how many points were found. A split there recovers one piece of a
// missing segment without needing the piece to be Delaunay (the midpoint rule does, and on needle
// triangles splits an edge down to the needles' width). With split_forced_walk the empty-sphere
// condition is dropped: the chain is forced into the cavity, and only the kernel's star-shape
// shrinking refuses a point (split_edge() tries the farthest first).
size_t SplitRecoverer::walk_points(uint32_t a, uint32_t b) {
  walk_frac_.clear();
  walk_chain_.clear();
  const double* A = mesh_.point(a);
  const double* B = mesh_.point(b);
  uint32_t t = entered_tet(a, B);
  int entry = -1;  // facet of t the segment came in through (-1: t has a as a vertex)
  if (t == kNone) return 0;
  constexpr size_t kMaxSteps = 48;
  double last = 0.0;  // the fraction where the walk entered t
  while (walk_chain_.size() < kMaxSteps) {
    walk_chain_.push_back(t);
    // The exit facet: the smallest crossing fraction among the facets B is beyond (floating
    // point: the walk only proposes a point; the kernel's exact tests decide).
    int exit = -1;
    double best = INFINITY;
    bool reached_b = false;
    const bool has_a = meshops::tet_has_vertex(mesh_, t, a);
    for (int j = 0; j < 4; ++j) {
      if (j == entry) continue;
      if (mesh_.vertex(t, j) == b) reached_b = true;
      // A tet with a as a vertex: every facet but the one opposite a passes through a, and the
      // segment does not leave through it.
      if (has_a && mesh_.vertex(t, j) != a) continue;
      const double* f[3];
      for (int k = 0; k < 3; ++k) f[k] = mesh_.point(mesh_.vertex(t, kFacetVertex[j][k]));
      double nrm[3], u[3], w[3], da[3], db[3];
      sub(f[1], f[0], u);
      sub(f[2], f[0], w);
      cross(u, w, nrm);  // points into t (kFacetVertex orientation)
      sub(A, f[0], da);
      sub(B, f[0], db);
      // Signed distances times |nrm|, positive outside t: b must be outside.
      const double pa = -dot(nrm, da), pb = -dot(nrm, db);
      if (!(pb > 0) || !(pa < pb)) continue;
      const double x = -pa / (pb - pa);
      if (x < best) {
        best = x;
        exit = j;
      }
    }
    if (reached_b || exit < 0 || !(best > last) || !(best < 1)) break;
    // The middle of the segment's piece inside t (a point on a facet would make the cavity's
    // exact tests depend on rounding).
    const double mid = 0.5 * (last + best);
    double x[3];
    for (int d = 0; d < 3; ++d) x[d] = A[d] + mid * (B[d] - A[d]);
    bool all_in = true;
    for (size_t k = 0; k < walk_chain_.size() && all_in && !opt_.split_forced_walk; ++k) {
      const uint32_t c = walk_chain_[k];
      all_in = predicates::insphere(mesh_.point(mesh_.vertex(c, 0)), mesh_.point(mesh_.vertex(c, 1)),
                                    mesh_.point(mesh_.vertex(c, 2)), mesh_.point(mesh_.vertex(c, 3)), x) > 0;
    }
    if (!all_in) break;
    walk_frac_.push_back(mid);
    last = best;
    const uint32_t adj = mesh_.tet_adj[4 * size_t(t) + exit];
    if (adj == kNoNeighbour || mesh_.is_ghost(uint32_t(adj >> 2))) break;
    const uint32_t nt = uint32_t(adj >> 2);
    entry = int(adj & 3);
    t = nt;
  }
  walk_chain_.resize(walk_frac_.size());
  return walk_frac_.size();
}

// Makes the missing constraint triangle k (its edges present) a facet by one edge removal, and
// protects it: no Steiner point, where a split leaves three pieces that may be missing again.
bool SplitRecoverer::flip_in_tri(uint32_t k) {
  const Tri t = ct_[k];
  if (!sees_apex(mesh_.point(t[0]), mesh_.point(t[1]), mesh_.point(t[2]), ct_face_[k])) return false;
  std::vector<uint32_t> created;
  if (!flip_in_face(mesh_, t[0], t[1], t[2], ball(t[0]), created, oracle())) return false;
  tets_made(created);
  ++out_.stats.flips;
  protect(k);
  return ct_state_[k] == kRecovered;
}

// A cap (an input triangle with an angle above kCapAngle) has a huge circumsphere: the Delaunay
// mesh misses its long edge, and splitting that edge at the middle, then the pieces, cascades.
// Splitting the long edge once at the apex's projection leaves two right-angled pieces, each
// within the diametral sphere of its hypotenuse.
void SplitRecoverer::split_caps() {
  const double cos_cap = std::cos(opt_.split_cap_degrees * 3.14159265358979323846 / 180.0);
  const auto n0 = static_cast<uint32_t>(ct_.size());
  for (uint32_t k = 0; k < n0; ++k) {
    if (ct_state_[k] != kMissing) continue;
    const Tri t = ct_[k];
    for (int i = 0; i < 3; ++i) {
      const uint32_t c = t[i], a = t[(i + 1) % 3], b = t[(i + 2) % 3];
      const double *C = mesh_.point(c), *A = mesh_.point(a), *B = mesh_.point(b);
      double ca[3], cb[3];
      sub(A, C, ca);
      sub(B, C, cb);
      if (!(dot(ca, cb) < cos_cap * std::sqrt(dot(ca, ca) * dot(cb, cb)))) continue;
      auto it = edges_.find(edge_key(a, b));
      if (it == edges_.end() || it->second.input_edge == kNone) break;
      // The apex's projection on the input segment, as a parameter from its first vertex.
      const uint32_t e = it->second.input_edge;
      const double* P = S_.point(edge_v_[2 * e]);
      const double* Q = S_.point(edge_v_[2 * e + 1]);
      double pq[3], pc[3];
      sub(Q, P, pq);
      sub(C, P, pc);
      const double ta = param_on(a, e), tb = param_on(b, e);
      const double lo = std::min(ta, tb), hi = std::max(ta, tb);
      const double tp = std::min(std::max(dot(pc, pq) / dot(pq, pq), lo + 0.05 * (hi - lo)), hi - 0.05 * (hi - lo));
      if (split_edge(it->first, tp) != kNone) ++out_.stats.caps_split;
      break;
    }
  }
}

// Splits the missing constraint edge `key` and its two triangles at a new point. On an input
// edge the point is on the input segment (by its parameter), at a power-of-two distance from an
// input vertex when the edge ends at one (concentric shells: segments meeting at a small angle
// do not split each other forever), else at the middle; inside a face, at the middle. Returns
// the new vertex (kNone when every point tried was refused).
uint32_t SplitRecoverer::split_edge(uint64_t key, double at) {
  const CEdge ce = edges_.at(key);
  const auto a = uint32_t(key >> 32), b = uint32_t(key & 0xffffffffu);
  uint32_t v = kNone;
  const uint32_t hint = vt_.tet_of(mesh_, a);
  // The two pieces of each triangle on (a b), split at p, must see their face's apex.
  auto pieces_see_apex = [&](const double* p) {
    for (uint32_t k : ce.tri) {
      if (k == kNone) continue;
      const Tri& t = ct_[k];
      int i = 0;
      while (!((t[i] == a && t[(i + 1) % 3] == b) || (t[i] == b && t[(i + 1) % 3] == a))) ++i;
      const double* x = mesh_.point(t[i]);
      const double* y = mesh_.point(t[(i + 1) % 3]);
      const double* z = mesh_.point(t[(i + 2) % 3]);
      if (!sees_apex(x, p, z, ct_face_[k]) || !sees_apex(p, y, z, ct_face_[k])) return false;
    }
    return true;
  };
  // The point at fraction s of (a b): on an input edge, computed from the input segment by its
  // parameter (so that every point of that edge is rounded from the same two points).
  auto on_input_edge = [&](uint32_t e, double param, double p[3]) {
    const double* A = S_.point(edge_v_[2 * e]);
    const double* B = S_.point(edge_v_[2 * e + 1]);
    if (param < 0.5) for (int d = 0; d < 3; ++d) p[d] = A[d] + param * (B[d] - A[d]);
    else for (int d = 0; d < 3; ++d) p[d] = B[d] + (1.0 - param) * (A[d] - B[d]);
  };
  auto point_at = [&](double frac, double p[3], double& param) {
    if (ce.input_edge != kNone) {
      const uint32_t e = ce.input_edge;
      param = param_on(a, e) + frac * (param_on(b, e) - param_on(a, e));
      on_input_edge(e, param, p);
    } else {
      param = 0.0;
      for (int d = 0; d < 3; ++d) p[d] = mesh_.point(a)[d] + frac * (mesh_.point(b)[d] - mesh_.point(a)[d]);
    }
  };
  const uint32_t host = ce.input_edge != kNone ? ce.input_edge
                                               : (ce.tri[0] != kNone ? ct_face_[ce.tri[0]] : ct_face_[ce.tri[1]]);
  const SteinerHost kind = ce.input_edge != kNone ? SteinerHost::kEdge : SteinerHost::kFace;
  // A segment that runs through an edge pq of the first facet it meets (exactly, on flat faces,
  // or near it: a barycentric weight below kNearEdge) is split where it passes pq, with pq's
  // ring of tets forced into the cavity: the point is then joined to the segment's end and to
  // everything around pq. A walk's point short of pq is joined to the end too, but the rest of
  // the segment crosses pq again, and the splits creep towards pq without reaching it (down to
  // pieces at the scale of rounding).
  if (at < 0 && opt_.split_walk && opt_.split_edge_crossings)
    for (int from = 0; from < 2 && v == kNone; ++from) {
      const uint32_t u = from == 0 ? a : b, w = from == 0 ? b : a;
      double frac = 0;
      const uint32_t t = crossed_edge_point(u, w, frac);
      if (t == kNone) continue;
      double p[3], param;
      point_at(from == 0 ? frac : 1.0 - frac, p, param);
      if (!pieces_see_apex(p)) continue;
      v = insert(p, kind, host, param, t, crossed_ring_.tets.data(), crossed_ring_.tets.size(), true,
                 opt_.split_exact_degeneracies && crossed_coplanar_
                     ? std::array<uint32_t, 2>{crossed_ring_.p, crossed_ring_.q}
                                               : std::array<uint32_t, 2>{kNone, kNone});
      if (v != kNone) ++out_.stats.edge_crossing_splits;
    }
  // Then the walk's points, farthest first, each kept only when it is joined to a (or to b,
  // walking from b).
  if (at < 0 && opt_.split_walk)
    for (int from = 0; from < 2 && v == kNone; ++from) {
      const uint32_t u = from == 0 ? a : b, w = from == 0 ? b : a;
      for (size_t k = walk_points(u, w); k > 0 && v == kNone; --k) {
        const double frac = from == 0 ? walk_frac_[k - 1] : 1.0 - walk_frac_[k - 1];
        double p[3], param;
        point_at(frac, p, param);
        if (!pieces_see_apex(p)) continue;
        v = insert(p, kind, host, param, walk_chain_[0], walk_chain_.data(), k, opt_.split_forced_walk);
      }
    }
  if (v != kNone) {
    ++out_.stats.walk_splits;
  } else if (ce.input_edge != kNone) {
    const uint32_t e = ce.input_edge;
    const double* A = S_.point(edge_v_[2 * e]);
    const double* B = S_.point(edge_v_[2 * e + 1]);
    double ta = param_on(a, e), tb = param_on(b, e);
    const bool a_input = a < n_in_, b_input = b < n_in_;
    bool lo_input = a_input, hi_input = b_input;
    if (ta > tb) {
      std::swap(ta, tb);
      std::swap(lo_input, hi_input);
    }
    const double full = std::sqrt(dist2(A, B));
    const double len = (tb - ta) * full;
    double t = 0.5 * (ta + tb);
    if (at > ta && at < tb) {
      t = at;
    } else if (lo_input != hi_input && len > 0) {
      double d = std::exp2(std::floor(std::log2(len * 2.0 / 3.0)));
      if (d < len / 3.0) d *= 2.0;
      t = lo_input ? ta + d / full : tb - d / full;
    }
    const double tries[4] = {t, 0.5 * (ta + tb), ta + 0.4 * (tb - ta), ta + 0.6 * (tb - ta)};
    for (double tt : tries) {
      if (!(tt > ta && tt < tb)) continue;
      double p[3];
      on_input_edge(e, tt, p);
      if (!pieces_see_apex(p)) continue;
      v = insert(p, SteinerHost::kEdge, e, tt, hint);
      if (v != kNone) break;
    }
  } else {
    const uint32_t face = ce.tri[0] != kNone ? ct_face_[ce.tri[0]] : ct_face_[ce.tri[1]];
    const double* P = mesh_.point(a);
    const double* Q = mesh_.point(b);
    for (double s : {0.5, 0.4, 0.6}) {
      double p[3];
      for (int d = 0; d < 3; ++d) p[d] = P[d] + s * (Q[d] - P[d]);
      if (!pieces_see_apex(p)) continue;
      v = insert(p, SteinerHost::kFace, face, 0.0, hint);
      if (v != kNone) break;
    }
  }
  if (v == kNone) return kNone;
  // The triangles on (a b) become two each, on either side of v.
  uint32_t tris[2] = {ce.tri[0], ce.tri[1]};
  Tri old[2];
  uint32_t faces[2];
  for (int s = 0; s < 2; ++s) {
    if (tris[s] == kNone) continue;
    old[s] = ct_[tris[s]];
    faces[s] = ct_face_[tris[s]];
    remove_tri(tris[s]);
  }
  edge_of(a, v, ce.input_edge);
  edge_of(v, b, ce.input_edge);
  for (int s = 0; s < 2; ++s) {
    if (tris[s] == kNone) continue;
    const Tri& t = old[s];
    int i = 0;
    while (!((t[i] == a && t[(i + 1) % 3] == b) || (t[i] == b && t[(i + 1) % 3] == a))) ++i;
    const uint32_t x = t[i], y = t[(i + 1) % 3], z = t[(i + 2) % 3];
    add_tri(x, v, z, faces[s]);
    add_tri(v, y, z, faces[s]);
  }
  return v;
}

// Flips the constraint edge `key` inside its input face: its triangles (v z x) and (z v y) become
// (x v y) and (y z x) when the quadrilateral is convex in the face's plane, and the mesh has the
// edge (x y) (only_to_mesh), or else y is inside the circle of (v z x) (a 2D Delaunay flip).
bool SplitRecoverer::flip_edge(uint64_t key, bool only_to_mesh) {
  const CEdge ce = edges_.at(key);
  if (ce.input_edge != kNone || ce.tri[0] == kNone || ce.tri[1] == kNone) return false;
  const uint32_t k1 = ce.tri[0], k2 = ce.tri[1];
  if (ct_state_[k1] != kMissing || ct_state_[k2] != kMissing || ct_face_[k1] != ct_face_[k2]) return false;
  const auto a = uint32_t(key >> 32), b = uint32_t(key & 0xffffffffu);
  // k1 = (v z x) with v -> z along k1's orientation; then k2 = (z v y).
  const Tri& t1 = ct_[k1];
  int i = 0;
  while (!(t1[i] == a || t1[i] == b) || !(t1[(i + 1) % 3] == a || t1[(i + 1) % 3] == b)) ++i;
  const uint32_t v = t1[i], z = t1[(i + 1) % 3], x = t1[(i + 2) % 3];
  const Tri& t2 = ct_[k2];
  uint32_t y = kNone;
  for (uint32_t w : t2)
    if (w != v && w != z) y = w;
  if (y == kNone || y == x || edges_.count(edge_key(x, y))) return false;
  const uint32_t f = ct_face_[k1];
  double n[3];
  {
    const double* A = S_.point(S_.tri[3 * f]);
    double ab[3], ac[3];
    sub(S_.point(S_.tri[3 * f + 1]), A, ab);
    sub(S_.point(S_.tri[3 * f + 2]), A, ac);
    cross(ab, ac, n);
  }
  auto area = [&](uint32_t p, uint32_t q, uint32_t r) {
    double u[3], w[3], c[3];
    sub(mesh_.point(q), mesh_.point(p), u);
    sub(mesh_.point(r), mesh_.point(p), w);
    cross(u, w, c);
    return dot(c, n);
  };
  if (!(area(x, v, y) > 0 && area(y, z, x) > 0)) return false;
  if (!sees_apex(mesh_.point(x), mesh_.point(v), mesh_.point(y), f) ||
      !sees_apex(mesh_.point(y), mesh_.point(z), mesh_.point(x), f))
    return false;
  if (only_to_mesh) {
    if (!has_edge(x, y)) return false;
  } else {
    // y inside the circumcircle of (v z x), in the face's plane (floating point: a heuristic).
    double e1[3], e2[3], nn = std::sqrt(dot(n, n));
    sub(mesh_.point(z), mesh_.point(v), e1);
    const double l1 = std::sqrt(dot(e1, e1));
    for (double& c : e1) c /= l1;
    cross(n, e1, e2);
    for (double& c : e2) c /= nn;
    auto uv = [&](uint32_t p, double& pu, double& pv) {
      double d[3];
      sub(mesh_.point(p), mesh_.point(v), d);
      pu = dot(d, e1);
      pv = dot(d, e2);
    };
    double P[4][2];
    const uint32_t q[4] = {v, z, x, y};
    for (int k = 0; k < 4; ++k) uv(q[k], P[k][0], P[k][1]);
    double m[3][3];
    for (int k = 0; k < 3; ++k) {
      const double du = P[k][0] - P[3][0], dv = P[k][1] - P[3][1];
      m[k][0] = du;
      m[k][1] = dv;
      m[k][2] = du * du + dv * dv;
    }
    const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                       m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                       m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    if (!(det > 0)) return false;  // (v z x) counter-clockwise: det > 0 means y inside
  }
  remove_tri(k1);
  remove_tri(k2);
  add_tri(x, v, y, f);
  add_tri(y, z, x, f);
  return true;
}

// An edge inside an input face is free: flips a missing one to the mesh's edge, or to the face's
// 2D Delaunay edge, until none flips, so each face's pieces reach its 2D Delaunay triangulation:
// short rungs across a needle instead of the fans its edge splits made. A work list: a flip can
// only make the edges of its two new triangles flippable, so only those are looked at again
// (sweeping all edges until none flipped took many sweeps over every edge). Returns the flips.
size_t SplitRecoverer::flip_face_edges() {
  std::vector<uint64_t> work;
  std::unordered_set<uint64_t> queued;
  auto push = [&](uint64_t key) {
    if (queued.insert(key).second) work.push_back(key);
  };
  for (uint64_t key : edge_keys_) push(key);
  // Delaunay flips end, but they are decided in floating point: a cap on the work.
  const size_t limit = 100 * work.size() + 1000;
  size_t flips = 0;
  for (size_t head = 0; head < work.size() && head < limit; ++head) {
    const uint64_t key = work[head];
    queued.erase(key);
    if (!still_open(key, false)) continue;
    if (has_edge(uint32_t(key >> 32), uint32_t(key & 0xffffffffu))) continue;
    if (!flip_edge(key, true) && !flip_edge(key, false)) continue;
    ++flips;
    for (size_t k = ct_.size() - 2; k < ct_.size(); ++k)
      for (int i = 0; i < 3; ++i) push(edge_key(ct_[k][i], ct_[k][(i + 1) % 3]));
  }
  drop_settled_keys();
  return flips;
}

// The edges inside input faces that the flips within faces left missing: made by flips of the
// mesh along them, else split (with their two triangles) at a walk's point like an input edge;
// present ones are defended.
void SplitRecoverer::recover_face_edges(size_t cap) {
  const size_t n_keys = edge_keys_.size();
  for (size_t i = 0; i < n_keys && out_.steiner.size() <= cap; ++i) {
    const uint64_t key = edge_keys_[i];
    CEdge* e = still_open(key, false);
    if (!e) continue;
    const auto a = uint32_t(key >> 32), b = uint32_t(key & 0xffffffffu);
    if (has_edge(a, b)) {
      defend_present(*e, a, b);
      continue;
    }
    if (flip_along(a, b)) defend(a, b);
    else if (const uint32_t v = split_edge(key); v != kNone) defend_split(key, v);
  }
  drop_settled_keys();
}

// Splits the missing constraint triangle k (its edges present) at the point where a mesh edge
// crosses it farthest inside (largest smallest barycentric coordinate), else at its centroid.
bool SplitRecoverer::split_triangle(uint32_t k) {
  const Tri t = ct_[k];
  const uint32_t face = ct_face_[k];
  const double* A = mesh_.point(t[0]);
  const double* B = mesh_.point(t[1]);
  const double* C = mesh_.point(t[2]);
  double n[3];
  {
    double ab[3], ac[3];
    sub(B, A, ab);
    sub(C, A, ac);
    cross(ab, ac, n);
  }
  const double nn = dot(n, n);
  auto inner_score = [&](const double* x) {  // smallest barycentric coordinate of x
    const double* P[3] = {A, B, C};
    double least = INFINITY;
    for (int i = 0; i < 3; ++i) {
      double u[3], w[3], c[3];
      sub(P[(i + 1) % 3], x, u);
      sub(P[(i + 2) % 3], x, w);
      cross(u, w, c);
      least = std::min(least, dot(c, n) / nn);
    }
    return least;
  };
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    lo[d] = std::min({A[d], B[d], C[d]});
    hi[d] = std::max({A[d], B[d], C[d]});
  }
  // Tets near the triangle: breadth-first from its corners' balls through tets that meet its
  // bounding box and its plane.
  if (tet_stamp_.size() < mesh_.num_tet_slots()) tet_stamp_.resize(2 * mesh_.num_tet_slots(), 0);
  if (++stamp_ == 0) {
    std::fill(tet_stamp_.begin(), tet_stamp_.end(), 0);
    stamp_ = 1;
  }
  bfs_.clear();
  for (int c = 0; c < 3; ++c)
    for (uint32_t s : ball(t[c]))
      if (tet_stamp_[s] != stamp_) {
        tet_stamp_[s] = stamp_;
        bfs_.push_back(s);
      }
  double best[3] = {0, 0, 0};
  double best_score = -1;
  uint32_t best_tet = kNone;
  const size_t limit = 20000;
  crossings_.clear();
  for (size_t q = 0; q < bfs_.size() && q < limit; ++q) {
    const uint32_t s = bfs_[q];
    if (mesh_.is_ghost(s)) continue;
    int side[4];
    bool box = true;
    double tl[3] = {INFINITY, INFINITY, INFINITY}, th[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < 4; ++i) {
      const double* p = mesh_.point(mesh_.vertex(s, i));
      side[i] = predicates::orient3d(A, B, C, p);
      for (int d = 0; d < 3; ++d) {
        tl[d] = std::min(tl[d], p[d]);
        th[d] = std::max(th[d], p[d]);
      }
    }
    for (int d = 0; d < 3; ++d) box = box && tl[d] <= hi[d] && th[d] >= lo[d];
    const bool pos = side[0] > 0 || side[1] > 0 || side[2] > 0 || side[3] > 0;
    const bool neg = side[0] < 0 || side[1] < 0 || side[2] < 0 || side[3] < 0;
    if (!box || !pos || !neg) continue;
    for (const auto& ev : kEdgeVertex) {
      if (side[ev[0]] * side[ev[1]] >= 0) continue;
      const uint32_t p = mesh_.vertex(s, ev[0]), r = mesh_.vertex(s, ev[1]);
      double x[3];
      if (!line_crosses_triangle(mesh_.point(p), mesh_.point(r), A, B, C, x)) continue;
      crossings_.push_back({s, p, r});
      const double score = inner_score(x);
      if (score > best_score) {
        best_score = score;
        std::copy(x, x + 3, best);
        best_tet = s;
      }
    }
    for (int i = 0; i < 4; ++i) {
      if (mesh_.tet_adj[4 * size_t(s) + i] == kNoNeighbour) continue;
      const uint32_t nb = mesh_.neighbour(s, i);
      if (tet_stamp_[nb] == stamp_) continue;
      tet_stamp_[nb] = stamp_;
      bfs_.push_back(nb);
    }
  }
  // First try removing the edges that cross it (no Steiner point; thin plates and needle fans,
  // where each split leaves pieces crossed again), split_crossing_flips times per triangle.
  if (opt_.split_flips && !crossings_.empty() && ct_flipped_[k] < opt_.split_crossing_flips) {
    ++ct_flipped_[k];
    bool any = false;
    std::vector<uint32_t> created;
    for (const auto& c : crossings_) {
      if (mesh_.is_deleted(c[0]) || edges_.count(edge_key(c[1], c[2]))) continue;
      // The tet may have been replaced by an earlier removal: it must still hold the edge.
      if (!meshops::tet_has_vertex(mesh_, c[0], c[1]) || !meshops::tet_has_vertex(mesh_, c[0], c[2])) continue;
      EdgeRing ring;
      if (!edge_ring(mesh_, c[0], c[1], c[2], ring)) continue;
      created.clear();
      if (!remove_edge(mesh_, ring, nullptr, 0, &created, oracle())) continue;
      tets_made(created);
      ++out_.stats.flips;
      any = true;
    }
    if (any) {
      protect(k);  // when the removals made it a facet
      return true;
    }
  }
  std::vector<std::array<double, 3>> tries;
  if (best_score > 0) {
    // Not too near an edge of the triangle (thin pieces cascade): pulled towards the centroid
    // until its smallest barycentric coordinate is kMinBary.
    constexpr double kMinBary = 0.1;
    if (best_score < kMinBary) {
      const double lambda = (1.0 / 3.0 - kMinBary) / (1.0 / 3.0 - best_score);
      for (int d = 0; d < 3; ++d) {
        const double c = (A[d] + B[d] + C[d]) / 3;
        best[d] = c + lambda * (best[d] - c);
      }
    }
    tries.push_back({best[0], best[1], best[2]});
  }
  tries.push_back({(A[0] + B[0] + C[0]) / 3, (A[1] + B[1] + C[1]) / 3, (A[2] + B[2] + C[2]) / 3});
  const double bary[3][3] = {{0.4, 0.3, 0.3}, {0.3, 0.4, 0.3}, {0.3, 0.3, 0.4}};
  for (const auto& w : bary)
    tries.push_back({w[0] * A[0] + w[1] * B[0] + w[2] * C[0], w[0] * A[1] + w[1] * B[1] + w[2] * C[1],
                     w[0] * A[2] + w[1] * B[2] + w[2] * C[2]});
  uint32_t v = kNone;
  for (size_t i = 0; i < tries.size() && v == kNone; ++i) {
    const double* x = tries[i].data();
    if (!sees_apex(A, B, x, face) || !sees_apex(B, C, x, face) || !sees_apex(C, A, x, face)) continue;
    v = insert(x, SteinerHost::kFace, face, 0.0, i == 0 && best_tet != kNone ? best_tet : vt_.tet_of(mesh_, t[0]));
  }
  if (v == kNone) return false;
  remove_tri(k);
  add_tri(t[0], t[1], v, face);
  add_tri(t[1], t[2], v, face);
  add_tri(t[2], t[0], v, face);
  return true;
}

Status SplitRecoverer::run() {
  n_in_ = S_.num_vertices();
  const auto t0 = Clock::now();
  if (Status s = build_delaunay(); !s.ok()) return s;
  out_.stats.seconds_delaunay = seconds_since(t0);
  const auto t1 = Clock::now();
  build_constraints();
  build_planes();
  if (Status st = check_apexes(); !st.ok()) return st;
  if (opt_.split_cap_degrees < 180.0) split_caps();
  const size_t cap = size_t(opt_.split_max_steiner_per_face * double(S_.num_triangles())) + 1000;
  size_t pass = 0;
  bool done = false, cascade = false;
  constexpr size_t kGrowthLimit = 4;
  size_t growths = 0, last_missing = ~size_t(0);
  // The edge phase stalls (pieces split as fast as others are lost) on thin plates and needle
  // fans: give up when its count of missing edges has not reached a new low for kStallPasses
  // passes in a row, instead of running on to the Steiner cap.
  constexpr size_t kStallPasses = 30;
  size_t fewest_missing_edges = ~size_t(0), passes_since_fewest = 0;
  bool stalled = false;
  for (; pass < opt_.max_passes; ++pass) {
    if (out_.steiner.size() > cap || seconds_since(t1) > opt_.split_max_seconds) break;
    // Subsegments of the input edges first (the edges that already existed when the sweep
    // began): their chains are fixed, so a missing one is split.
    size_t missing_edges = 0;
    const size_t n_keys = edge_keys_.size();
    snapshot_tets(n_keys);
    for (size_t i = 0; i < n_keys; ++i) {
      const uint64_t key = edge_keys_[i];
      CEdge* e = still_open(key, true);
      if (!e) continue;
      if (has_edge(uint32_t(key >> 32), uint32_t(key & 0xffffffffu))) {
        defend_present(*e, uint32_t(key >> 32), uint32_t(key & 0xffffffffu));
        continue;
      }
      ++missing_edges;
      if (opt_.split_flips && (flip_in(uint32_t(key >> 32), uint32_t(key & 0xffffffffu)) ||
                               flip_along(uint32_t(key >> 32), uint32_t(key & 0xffffffffu))))
        continue;
      if (const uint32_t v = split_edge(key); v != kNone) defend_split(key, v);
      if (out_.steiner.size() > cap || ((missing_edges & 255) == 0 && seconds_since(t1) > opt_.split_max_seconds)) break;
    }
    drop_settled_keys();
    if (missing_edges > 0) {
      if (missing_edges < fewest_missing_edges) {
        fewest_missing_edges = missing_edges;
        passes_since_fewest = 0;
      } else if (++passes_since_fewest >= kStallPasses) {
        stalled = true;
        break;
      }
      continue;
    }
    const size_t flips = flip_face_edges();
    out_.stats.flips += flips;
    if (opt_.split_face_edges) recover_face_edges(cap);
    // Protect every triangle present, then split the missing ones.
    snapshot_tets(size_t(std::count(ct_state_.begin(), ct_state_.end(), kMissing)));
    std::vector<uint32_t> missing;
    for (uint32_t k = 0; k < ct_.size(); ++k) {
      if (ct_state_[k] != kMissing) continue;
      uint32_t t;
      int i;
      if (find_facet(ct_[k], t, i)) protect(k);
      else missing.push_back(k);
    }
    if (missing.empty()) {
      done = true;
      break;
    }
    // Splitting thin triangles can cascade (each split leaving more pieces missing): give up
    // when the count of missing triangles has grown kGrowthLimit face phases in a row.
    growths = missing.size() > last_missing ? growths + 1 : 0;
    last_missing = missing.size();
    if (growths >= kGrowthLimit) {
      cascade = true;
      break;
    }
    for (size_t i = 0; i < missing.size(); ++i) {
      if (ct_state_[missing[i]] != kMissing) continue;
      if (opt_.split_flips && flip_in_tri(missing[i])) continue;
      split_triangle(missing[i]);
      if (out_.steiner.size() > cap || ((i & 255) == 255 && seconds_since(t1) > opt_.split_max_seconds)) break;
    }
  }
  out_.stats.passes = pass;
  out_.stats.early_refusals = inserter_.stats().early_refusals;
  if (!done) {
    const std::string why = cascade ? " (splits cascading: the missing pieces grew " + std::to_string(kGrowthLimit) +
                                          " passes in a row)"
                            : stalled ? " (edge splits stalled: no fewer missing edges for " +
                                            std::to_string(kStallPasses) + " passes)"
                                      : "";
    for (size_t i = 0; i < edge_keys_.size(); ++i) {
      const uint64_t key = edge_keys_[i];
      auto it = edges_.find(key);
      if (it == edges_.end()) continue;
      const auto a = uint32_t(key >> 32), b = uint32_t(key & 0xffffffffu);
      if (has_edge(a, b)) continue;
      const uint32_t k = it->second.tri[0] != kNone ? it->second.tri[0] : it->second.tri[1];
      return Status(Error::RecoveryFailed,
                    "recover_boundary: an edge (" + shown_id(a) + " " + shown_id(b) +
                        ") of " + describe_tri(k) + " not recovered after " + std::to_string(pass) +
                        " passes, " + std::to_string(out_.steiner.size()) + " Steiner points and " +
                        std::to_string(seconds_since(t1)) + " s" + why);
    }
    for (uint32_t k = 0; k < ct_.size(); ++k)
      if (ct_state_[k] == kMissing)
        return Status(Error::RecoveryFailed, "recover_boundary: " + describe_tri(k) + " not recovered after " +
                                                 std::to_string(pass) + " passes, " +
                                                 std::to_string(out_.steiner.size()) + " Steiner points and " +
                                                 std::to_string(seconds_since(t1)) + " s" + why);
  }
  // S2: the recovered constraint triangles, oriented like their input faces.
  for (uint32_t k = 0; k < ct_.size(); ++k) {
    if (ct_state_[k] != kRecovered) continue;
    for (uint32_t v : ct_[k]) out_.s2_tri.push_back(v);
    out_.s2_face.push_back(ct_face_[k]);
    out_.s2_patch.push_back(ct_face_[k] < S_.patch.size() ? S_.patch[ct_face_[k]] : 0);
  }
  // Constrained edge bits on every subsegment of an input edge: each tet marks its own edges, on
  // every core (a ball walk per edge, one edge after the other, ran on one core only).
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, mesh_.num_tet_slots(), 4096),
                    [&](const tbb::blocked_range<uint32_t>& r) {
                      for (uint32_t t = r.begin(); t != r.end(); ++t) {
                        if (mesh_.is_deleted(t)) continue;
                        for (int k = 0; k < 6; ++k) {
                          const auto it = edges_.find(
                              edge_key(mesh_.vertex(t, kEdgeVertex[k][0]), mesh_.vertex(t, kEdgeVertex[k][1])));
                          if (it != edges_.end() && it->second.input_edge != kNone)
                            mesh_.set_edge_constrained(t, k, true);
                        }
                      }
                    });
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

// Components of tets connected through unprotected facets. A component holding a ghost tet is
// outside; any other is outside when its bounding constraint triangles, oriented outward from the
// material, point into it (same cyclic order as the facet seen from inside the tet).
Status SplitRecoverer::carve() {
  changed();
  const size_t nslots = mesh_.num_tet_slots();
  std::unordered_map<Tri, uint32_t, TriHash> tri_of;
  for (uint32_t k = 0; k < ct_.size(); ++k)
    if (ct_state_[k] == kRecovered) tri_of.emplace(sorted(ct_[k]), k);
  struct Comp {
    bool ghost = false;
    size_t outside_votes = 0, inside_votes = 0;
    uint32_t min_face = kNone;
  };
  std::vector<int32_t> comp(nslots, -1);
  std::vector<Comp> comps;
  std::vector<uint32_t> stack;
  for (uint32_t s = 0; s < nslots; ++s) {
    if (mesh_.is_deleted(s) || comp[s] >= 0) continue;
    const auto c = static_cast<int32_t>(comps.size());
    comps.push_back({});
    comp[s] = c;
    stack.assign(1, s);
    while (!stack.empty()) {
      const uint32_t t = stack.back();
      stack.pop_back();
      if (mesh_.is_ghost(t)) comps[c].ghost = true;
      for (int i = 0; i < 4; ++i) {
        if (mesh_.tet_adj[4 * size_t(t) + i] == kNoNeighbour) continue;
        if (mesh_.facet_protected(t, i)) {
          const Tri fv = {mesh_.vertex(t, kFacetVertex[i][0]), mesh_.vertex(t, kFacetVertex[i][1]),
                          mesh_.vertex(t, kFacetVertex[i][2])};
          auto it = tri_of.find(sorted(fv));
          if (it == tri_of.end()) continue;
          const Tri& ct = ct_[it->second];
          comps[c].min_face = std::min(comps[c].min_face, ct_face_[it->second]);
          int r = 0;
          while (ct[r] != fv[0]) ++r;
          const bool same = ct[(r + 1) % 3] == fv[1];
          if (same) ++comps[c].outside_votes;
          else ++comps[c].inside_votes;
          continue;
        }
        const uint32_t n = mesh_.neighbour(t, i);
        if (comp[n] >= 0) continue;
        comp[n] = c;
        stack.push_back(n);
      }
    }
  }
  std::vector<int32_t> order;
  for (int32_t c = 0; c < int32_t(comps.size()); ++c) {
    const Comp& cc = comps[c];
    if (cc.ghost || cc.inside_votes == 0) continue;
    if (cc.outside_votes > 0)
      return Status(Error::RecoveryFailed, "recover_boundary: a component of tets lies on both sides of the recovered "
                                           "surface (" + std::to_string(cc.inside_votes) + " facets say inside, " +
                                           std::to_string(cc.outside_votes) + " outside)");
    order.push_back(c);
  }
  std::sort(order.begin(), order.end(), [&](int32_t a, int32_t b) { return comps[a].min_face < comps[b].min_face; });
  std::vector<int32_t> region(comps.size(), -1);
  for (size_t k = 0; k < order.size(); ++k) region[order[k]] = int32_t(k);
  out_.stats.regions = order.size();
  keep_regions(mesh_, comp, region);
  return Status::success();
}

}  // namespace

Status recover_by_splitting(const SurfaceMesh& S, const RecoveryOptions& options, RecoveryOutput& out) {
  SplitRecoverer r(S, options, out);
  return r.run();
}

}  // namespace anitet::recovery_detail
