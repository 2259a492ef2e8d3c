#include "refine/refine.hpp"

#include <algorithm>
#include <functional>
#include <chrono>
#include <cmath>
#include <new>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

#include "core/bvh.hpp"
#include "core/closest_point.hpp"
#include "core/flat_key_map.hpp"
#include "delaunay/delaunay.hpp"
#include "delaunay/spatial_sort.hpp"
#include "predicates/predicates.hpp"
#include "refine/edges.hpp"
#include "refine/mesh_ops.hpp"

namespace anitet {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Points inserted in the current batch, in a hash grid per size level so that a query only
// looks at 8 cells per level: a point q of radius r_q = spacing * (the largest size of M_q, see
// meshops::metric_max_size) sits at the level whose cell is at least 2 r_q, and two points p, q
// conflict when their distance is below `spacing` in both metrics M_p and M_q (isotropic:
// closer than spacing * min(h_p, h_q)). The radii bound the Euclidean extent of those balls, so
// a conflicting q lies within min(r_p, half a cell) of p on every axis: in the 2x2x2 cells
// around p at most.
class SpacingGrid {
 public:
  SpacingGrid(const double origin[3], double base) : base_(base) { std::copy_n(origin, 3, origin_); }
  // m: the metric at p, or nullptr when isotropic (then r = spacing * h_p).
  bool conflicts(const double p[3], double r, const double* m, double spacing) const {
    for (int level = 0; level < kLevels; ++level) {
      if (!(levels_used_ & (1u << level))) continue;
      const double cell = std::ldexp(base_, level);
      // A conflicting q is closer than min(r, r_q) <= min(r, cell / 2) on every axis: only the
      // cells that box meets (the 2x2x2 around p at most; at the levels of points larger than
      // p, mostly one).
      const double w = std::min(r, 0.5 * cell) * (1.0 + 1e-9);  // (a margin for rounding)
      int64_t lo[3], hi[3];
      for (int k = 0; k < 3; ++k) {
        lo[k] = static_cast<int64_t>(std::floor((p[k] - origin_[k] - w) / cell));
        hi[k] = static_cast<int64_t>(std::floor((p[k] - origin_[k] + w) / cell));
      }
      for (int64_t cx = lo[0]; cx <= hi[0]; ++cx)
        for (int64_t cy = lo[1]; cy <= hi[1]; ++cy)
          for (int64_t cz = lo[2]; cz <= hi[2]; ++cz) {
            for (uint32_t q = cells_.find(key(level, cx, cy, cz)); q != kEnd; q = next_[q]) {
              const double* x = pts_[q].x;
              const double d2 = (x[0] - p[0]) * (x[0] - p[0]) + (x[1] - p[1]) * (x[1] - p[1]) +
                                (x[2] - p[2]) * (x[2] - p[2]);
              const double rr = std::min(r, pts_[q].r);
              if (!(d2 < rr * rr)) continue;
              if (!m && !aniso_[q]) return true;  // both isotropic: closer than spacing * min(h)
              const double d[3] = {x[0] - p[0], x[1] - p[1], x[2] - p[2]};
              const double lp = m ? metric_norm(m, d) : std::sqrt(d2) * spacing / r;
              const double lq = aniso_[q] ? metric_norm(&metric_[6 * size_t(q)], d) : std::sqrt(d2) * spacing / pts_[q].r;
              if (std::max(lp, lq) < spacing) return true;
            }
          }
    }
    return false;
  }
  void add(const double p[3], double r, const double* m) {
    const int level = level_of(2.0 * r);
    const double cell = std::ldexp(base_, level);
    int64_t c[3];
    for (int k = 0; k < 3; ++k) c[k] = static_cast<int64_t>(std::floor((p[k] - origin_[k]) / cell));
    const auto id = static_cast<uint32_t>(pts_.size());
    pts_.push_back({{p[0], p[1], p[2]}, r});
    aniso_.push_back(m != nullptr);
    if (m) metric_.insert(metric_.end(), m, m + 6);
    else metric_.resize(metric_.size() + 6, 0.0);
    // The cell's list is headed by its last point (the others follow through next_).
    next_.push_back(std::exchange(cells_.find_or_insert(key(level, c[0], c[1], c[2]), kEnd), id));
    levels_used_ |= 1u << level;
  }

 private:
  static constexpr int kLevels = 24;
  static constexpr uint32_t kEnd = FlatKeyMap::kAbsent;
  int level_of(double r) const {
    int level = 0;
    double cell = base_;
    while (cell < r && level < kLevels - 1) {
      cell *= 2.0;
      ++level;
    }
    return level;
  }
  static uint64_t key(int level, int64_t i, int64_t j, int64_t k) {
    const uint64_t m = (uint64_t(1) << 19) - 1;
    return (uint64_t(level) << 57) | ((uint64_t(i) & m) << 38) | ((uint64_t(j) & m) << 19) | (uint64_t(k) & m);
  }
  double origin_[3];
  double base_;
  FlatKeyMap cells_;  // cell key -> its last point
  struct Point {  // a point and its radius together: one cache line to read per candidate
    double x[3];
    double r;
  };
  std::vector<Point> pts_;
  std::vector<double> metric_;  // 6 per point (unused for isotropic points)
  std::vector<uint8_t> aniso_;  // 1 per point: its metric is anisotropic
  std::vector<uint32_t> next_;
  uint32_t levels_used_ = 0;
};

class Refiner {
 public:
  Refiner(TetMesh& mesh, const SizingField& field, const RefineOptions& options)
      : mesh_(mesh), field_(field), options_(options), inserter_(mesh), batch_(mesh, options.insert_partitions) {}

  Result<RefineStats> run();

 private:
  bool fixed(uint32_t v) const { return (mesh_.vflags[v] & (vflag::kOnInputSurface | vflag::kLocked)) != 0; }
  void update_metric(uint32_t v) {
    double m[6];
    field_.metric(mesh_.point(v), m);
    set_metric(v, m);
  }
  // v's metric, already measured at its point.
  void set_metric(uint32_t v, const double m[6]) {
    if (metrics_.size() < 6 * mesh_.num_vertices()) {
      metrics_.resize(6 * mesh_.num_vertices());
      size_.resize(mesh_.num_vertices());
    }
    std::copy(m, m + 6, &metrics_[6 * size_t(v)]);
    size_[v] = metric_size(m);
  }
  void metric_midpoint(uint32_t a, uint32_t b, double m[3]) const;
  // The protected facets (S, and any other protected ones) in a BVH, once at the start: their
  // vertices are never moved by refinement.
  void index_protected_facets();
  void reserve_for_refinement();
  // Whether m (metric mm there) is within facet_clearance (anisotropic_facet_clearance with an
  // anisotropic metric), a metric length, of a protected facet.
  bool too_close_to_protected_facet(const double m[3], const double mm[6]) const;
  uint32_t insert_in_metric(const double p[3], const double mp[6], int32_t region);
  size_t metric_flip_pass();
  // Up to max_sweeps metric flip passes, until one flips nothing; then the debug check.
  Status metric_flip_sweeps(int max_sweeps) {
    const auto t = Clock::now();
    for (int sweep = 0; sweep < max_sweeps; ++sweep) {
      const size_t f = metric_flip_pass();
      stats_.metric_flips += f;
      if (f == 0) break;
    }
    stats_.seconds_flips += seconds_since(t);
    return check("after metric flips");
  }
  // The mean of the n vertices' metrics (measured at their points): the metric flips measure a
  // region in it, as the optimizer measures a tet (optimize_detail::Quality). A field query at
  // the region's centroid instead (a background mesh's walk and a log-Euclidean mean) took most
  // of the flips' time.
  meshops::MetricMap map_of_vertices(const uint32_t* v, size_t n) const;
  double metric_quality(const meshops::MetricMap& map, const meshops::TetVerts& v) const {
    return meshops::metric_shape_quality(map, mesh_.point(v[0]), mesh_.point(v[1]), mesh_.point(v[2]),
                                         mesh_.point(v[3]));
  }
  size_t split_pass(refine_detail::EdgeList& edges);
  struct Chosen;
  void choose_splits(refine_detail::EdgeList& edges, std::vector<Chosen>& chosen,
                     std::vector<double>& chosen_xyz, double lo[3], double hi[3]);
  // A live tet holding edge e's end a: the tet it was collected from when that still holds both
  // ends, else one of a's tets.
  uint32_t edge_hint(const refine_detail::Edge& e) {
    return holds_edge(e) ? e.tet : vt_.tet_of(mesh_, e.a);
  }
  bool holds_edge(const refine_detail::Edge& e) const {
    return meshops::tet_has_vertex(mesh_, e.tet, e.a) && meshops::tet_has_vertex(mesh_, e.tet, e.b);
  }
  size_t collapse_pass(const refine_detail::EdgeList& edges);
  bool collapse(uint32_t v, uint32_t w, const double q[3]);
  // A collapse's balls, replacement and replace_tets scratch (one per thread in a trial).
  struct CollapseScratch {
    std::vector<uint32_t> old, ball_w;
    std::vector<meshops::TetVerts> fresh;
    meshops::ReplaceScratch replace;
  };
  // Whether the collapse of v onto w, put at q, would be made, its replacement (collapse_tets or
  // collapse_replacement) in s.old and s.fresh; changes nothing (several threads may ask at once).
  bool collapse_fits(uint32_t v, uint32_t w, const double q[3], bool moves, CollapseScratch& s) const;
  // Which of collapse_pass's alternatives for edge e would be made first (0, 1, 2), or none
  // (kTrialRefused), against the mesh as it is; kTrialUnknown when it cannot tell without the
  // sequential path (a stale vertex entry, a large ball).
  static constexpr int kTrialRefused = -1, kTrialUnknown = -2;
  int collapse_trial(const refine_detail::Edge& e, CollapseScratch& s) const;
  CollapseScratch collapse_scratch_;
  // Per vertex: the last trial block (collapse_pass) in which a collapse replaced one of its tets.
  std::vector<uint32_t> collapse_changed_;
  uint32_t collapse_block_ = 0;
  Status check(const char* when) const;
  Status check_room(const refine_detail::EdgeList& edges) const;
  // check_each_pass: the pass's edge list (update_edges) against a full collection.
  Status check_edge_list(const refine_detail::EdgeList& edges, size_t edge_count) const;
  refine_detail::EdgeFilter edge_filter() const {
    return {options_.collapse_length, options_.split_length, uint8_t(vflag::kOnInputSurface | vflag::kLocked)};
  }

  TetMesh& mesh_;
  const SizingField& field_;
  const RefineOptions& options_;
  PointInserter inserter_;
  BatchInserter batch_;
  std::vector<uint32_t> live_created_;
  meshops::VertexTets vt_;
  meshops::ReplaceScratch scratch_;
  refine_detail::EdgeScratch edge_scratch_;
  std::vector<double> metrics_;  // 6 per vertex
  std::vector<double> size_;     // scalar size per vertex
  std::vector<uint8_t> touched_;
  // Edges (a << 32 | b) whose collapse was refused, with epoch_ then. Isotropic: never tried
  // again. Anisotropic (the metric flips change the neighbourhoods): tried again once the tets of
  // an end changed (vertex_epoch_), which is all a trial reads (the two balls, their points and
  // metrics); retrying every refused edge at every pass made the same verdicts again.
  std::unordered_map<uint64_t, uint32_t> refused_;
  bool refused_unchanged(const refine_detail::Edge& e) const {
    const auto it = refused_.find(e.key());
    if (it == refused_.end()) return false;
    if (!anisotropic_) return true;
    for (uint32_t v : {e.a, e.b})
      if (v < vertex_epoch_.size() && vertex_epoch_[v] > it->second) return false;
    return true;
  }
  // Change stamps for the metric flips: epoch_ grows with every change of the tets, a vertex
  // keeps the epoch of the last change of its tets, a tet slot the epoch at which it was made
  // and the one at which no flip took it (0: none since it was made). Refinement moves no point
  // without remaking its tets, so a tet found not poor stays so while its slot lives. A flip of a
  // tet reads only the tets around its edges (its facets' neighbours among them), and a change
  // that replaces one of those while keeping the tet makes a tet on that edge: when none of them
  // was made since the failure, the same flips would fail again, and the tet is skipped. (After
  // a pass's splits and flips most failed tets have a vertex whose tets changed: the vertices'
  // epochs name the edges that may have new tets, and only their rings are walked.)
  uint32_t epoch_ = 1;
  std::vector<uint32_t> vertex_epoch_, flip_failed_at_, made_at_;
  std::vector<uint8_t> not_poor_;  // per tet slot: measured not poor (0: not since it was made)
  // After a point's insertion: its tets become its vertices' (vt_), their vertices are touched
  // (no collapse this pass) and changed (the metric flips' memo).
  void note_created(const std::vector<uint32_t>& created) {
    touched_.resize(mesh_.num_vertices(), 0);
    for (uint32_t t : created) {
      vt_.note(mesh_, t);
      for (int i = 0; i < 4; ++i) touched_[mesh_.vertex(t, i)] = 1;
    }
    note_changed(created);
  }
  void note_changed(const std::vector<uint32_t>& created) {
    ++epoch_;
    if (vertex_epoch_.size() < mesh_.num_vertices()) vertex_epoch_.resize(mesh_.num_vertices(), 0);
    if (changed_.size() < mesh_.num_tet_slots()) changed_.resize(mesh_.num_tet_slots(), 0);
    if (made_at_.size() < mesh_.num_tet_slots()) made_at_.resize(mesh_.num_tet_slots(), 0);
    for (uint32_t t : created) {
      for (int i = 0; i < 4; ++i) vertex_epoch_[mesh_.vertex(t, i)] = epoch_;
      if (t < flip_failed_at_.size()) flip_failed_at_[t] = 0;
      if (t < not_poor_.size()) not_poor_[t] = 0;
      made_at_[t] = epoch_;
      changed_[t] = 1;
    }
  }
  // Per tet slot: made since the pass's edge list was built (the next list measures only the
  // edges around these again: refine_detail::update_edges).
  std::vector<uint8_t> changed_;
  // A tet made on edge ab stamps both a and b: an edge of t with an end unchanged since t's
  // failure has no new tet around it; the others' rings are looked at.
  bool failed_unchanged(uint32_t t) const {
    if (t >= flip_failed_at_.size() || flip_failed_at_[t] == 0) return false;
    unsigned newer = 0;
    for (int i = 0; i < 4; ++i) {
      const uint32_t v = mesh_.vertex(t, i);
      if (v < vertex_epoch_.size() && vertex_epoch_[v] > flip_failed_at_[t]) newer |= 1u << i;
    }
    for (int k = 0; k < 6; ++k)
      if ((newer >> kEdgeVertex[k][0] & 1u) && (newer >> kEdgeVertex[k][1] & 1u) && !edge_ring_unchanged(t, k))
        return false;
    return true;
  }
  // No tet around edge k of t was made after t's failure (see epoch_).
  bool edge_ring_unchanged(uint32_t t, int k) const;
  std::vector<uint32_t> old_, ring_tets_, ring_;
  // One split pass's candidate midpoints (one per long edge, in length order), and the chosen
  // ones with their edges (one record to read per insertion). split_pass keeps them in locals,
  // so that the first pass's long lists do not stay allocated to the end.
  struct Candidate {
    double m[3];   // the metric midpoint
    double mm[6];  // the metric there
    double r;      // its radius in the spacing grid
    bool iso;      // mm is isotropic
  };
  struct Chosen {
    refine_detail::Edge e;
    Candidate c;
  };
  std::vector<uint32_t> facet_tri_;  // protected facets, 3 vertex ids each
  TriangleBVH facet_bvh_;
  std::vector<meshops::TetVerts> fresh_;
  bool anisotropic_ = false;  // some vertex has an anisotropic metric: metric kernel and flips
  std::vector<uint32_t> cavity_;
  std::vector<uint8_t> in_cavity_;  // per tet slot: 1 in the cavity, 2 in the edge's ring
  RefineStats stats_;
  size_t protected_facets_ = 0;
  // Per vertex of S: the normalized length of its longest edge of S (measure_s_edges; vertices
  // added later are not on S: 0). Empty without collapse_to_s_edge_length.
  std::vector<double> longest_s_edge_;
  void measure_s_edges();
  double longest_s_edge(uint32_t v) const { return v < longest_s_edge_.size() ? longest_s_edge_[v] : 0.0; }
};

// The tets refinement will make, about: each tet's volume over that of the regular tet whose edge
// is its vertices' mean size (the refined counts exceed it by up to about half). The mesh's arrays
// are reserved for 1.6 times as many, so that they are not moved while the mesh grows: each move
// held the old arrays and the new ones at once (38 bytes per tet each), which set the peak memory
// of large runs. Pages not written are not resident, so a generous reservation costs address space
// only.
void Refiner::reserve_for_refinement() {
  double expected = 0.0;
  for (uint32_t t = 0; t < mesh_.num_tet_slots(); ++t) {
    if (mesh_.is_deleted(t)) continue;
    const double* p[4];
    double h = 0.0;
    for (int i = 0; i < 4; ++i) {
      p[i] = mesh_.point(mesh_.vertex(t, i));
      h += 0.25 * size_[mesh_.vertex(t, i)];
    }
    const double ab[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double ac[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const double ad[3] = {p[3][0] - p[0][0], p[3][1] - p[0][1], p[3][2] - p[0][2]};
    const double volume = std::fabs(ab[0] * (ac[1] * ad[2] - ac[2] * ad[1]) - ab[1] * (ac[0] * ad[2] - ac[2] * ad[0]) +
                                    ab[2] * (ac[0] * ad[1] - ac[1] * ad[0])) / 6.0;
    const double regular = h * h * h / (6.0 * std::sqrt(2.0));
    if (regular > 0.0) expected += volume / regular;
  }
  // At most a quarter of the machine's memory for the tet arrays (an estimate gone wild on a
  // strange metric must not ask for more address space than the system grants), and the most
  // tet slots a mesh holds (2^30: 32-bit adjacency).
  double cap = double(TetMesh::kMaxTetSlots);
#if defined(_SC_PHYS_PAGES) && defined(_SC_PAGESIZE)
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages > 0 && page > 0) cap = std::min(cap, 0.25 * double(pages) * double(page) / 38.0);
#endif
  const double slots = std::min(1.6 * expected + double(mesh_.num_tet_slots()), cap);
  if (!(slots > double(mesh_.num_tet_slots()))) return;
  const auto n = static_cast<size_t>(slots);
  try {
    mesh_.reserve_tets(n);
    mesh_.xyz.reserve(3 * (n / 5 + mesh_.num_vertices()));
    mesh_.vflags.reserve(n / 5 + mesh_.num_vertices());
  } catch (const std::bad_alloc&) {
    // Only a reservation: the arrays grow as they would have.
  }
}

void Refiner::index_protected_facets() {
  facet_tri_.clear();
  for (uint32_t t = 0; t < mesh_.num_tet_slots(); ++t) {
    if (mesh_.is_deleted(t)) continue;
    for (int i = 0; i < 4; ++i) {
      if (!mesh_.facet_protected(t, i)) continue;
      uint32_t f[3] = {mesh_.vertex(t, kFacetVertex[i][0]), mesh_.vertex(t, kFacetVertex[i][1]),
                       mesh_.vertex(t, kFacetVertex[i][2])};
      // An interior protected facet is seen from both sides: keep one copy.
      if (mesh_.tet_adj[4 * size_t(t) + i] != TetMesh::kNoNeighbour && mesh_.neighbour(t, i) < t) continue;
      facet_tri_.insert(facet_tri_.end(), f, f + 3);
    }
  }
  facet_bvh_.build(mesh_.xyz.data(), facet_tri_.data(), facet_tri_.size() / 3);
}

bool Refiner::too_close_to_protected_facet(const double m[3], const double mm[6]) const {
  const double clearance = anisotropic_ ? options_.anisotropic_facet_clearance : options_.facet_clearance;
  if (!(clearance > 0.0) || facet_tri_.empty()) return false;
  const double reach = clearance * meshops::metric_max_size(mm);
  bool close = false;
  facet_bvh_.query(box_around(m, reach), [&](uint32_t f) {
    double q[3];
    closest_point_on_triangle(m, mesh_.point(facet_tri_[3 * size_t(f)]), mesh_.point(facet_tri_[3 * size_t(f) + 1]),
                              mesh_.point(facet_tri_[3 * size_t(f) + 2]), q);
    const double offset[3] = {m[0] - q[0], m[1] - q[1], m[2] - q[2]};
    close = metric_norm(mm, offset) < clearance;
    return !close;
  });
  return close;
}

void Refiner::metric_midpoint(uint32_t a, uint32_t b, double m[3]) const {
  // The sizes along the edge at its ends: h_a, h_b for isotropic ends, else (up to the common
  // factor |ab|, which t does not see) 1 / (length of ab in M_a) and 1 / (length in M_b).
  const double* pa = mesh_.point(a);
  const double* pb = mesh_.point(b);
  const double e[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
  double ha = size_[a], hb = size_[b];
  if (!meshops::MetricMap::of(&metrics_[6 * size_t(a)]).identity ||
      !meshops::MetricMap::of(&metrics_[6 * size_t(b)]).identity) {
    const double la = metric_norm(&metrics_[6 * size_t(a)], e), lb = metric_norm(&metrics_[6 * size_t(b)], e);
    ha = la > 0.0 ? 1.0 / la : 1.0;
    hb = lb > 0.0 ? 1.0 / lb : 1.0;
  }
  double t = 0.5;
  if (std::fabs(hb - ha) > 1e-9 * (ha + hb)) t = (std::sqrt(ha * hb) - ha) / (hb - ha);
  t = std::clamp(t, 0.2, 0.8);
  for (int k = 0; k < 3; ++k) m[k] = pa[k] + t * (pb[k] - pa[k]);
}

// The anisotropic Delaunay kernel (the insphere test in the metric M_p of the new point p, as in
// Borouchaki-George): p lies inside the edge whose ring is ring_tets_. The cavity starts with the
// ring, grows across facets that are neither protected nor without neighbour into tets of the
// same region, without constrained edges, whose circumsphere in M_p holds p (measured on the
// tets mapped by M_p^(1/2); a tet flat in M_p joins too); then tets whose boundary facet does not
// see p strictly (exact orient3d) are taken out again until the cavity is star-shaped around p.
// Returns the new vertex, or kNone (mesh unchanged) when a ring tet would have to leave.
uint32_t Refiner::insert_in_metric(const double p[3], const double mp[6], int32_t region) {
  constexpr size_t kMaxCavity = 4096;
  const meshops::MetricMap map = meshops::MetricMap::of(mp);
  double pm[3];
  map.apply(p, pm);
  in_cavity_.resize(mesh_.num_tet_slots(), 0);
  cavity_ = ring_tets_;
  for (uint32_t t : cavity_) in_cavity_[t] = 2;
  bool frozen_hit = false;
  if (options_.defer_at_frozen)
    for (uint32_t t : ring_tets_) frozen_hit |= mesh_.tet_region[t] < 0;
  auto in_metric_sphere = [&](uint32_t n) {
    double q[4][3];
    for (int j = 0; j < 4; ++j) map.apply(mesh_.point(mesh_.vertex(n, j)), q[j]);
    return !(predicates::orient3d(q[0], q[1], q[2], q[3]) > 0 && predicates::insphere(q[0], q[1], q[2], q[3], pm) <= 0);
  };
  for (size_t k = 0; k < cavity_.size() && cavity_.size() < kMaxCavity && !frozen_hit; ++k) {
    const uint32_t t = cavity_[k];
    for (int i = 0; i < 4; ++i) {
      if (mesh_.facet_protected(t, i)) {
        // (defer_at_frozen: a frozen tet in conflict behind it puts the point off.)
        const uint32_t n = mesh_.neighbour(t, i);
        if (options_.defer_at_frozen && mesh_.tet_adj[4 * size_t(t) + i] != TetMesh::kNoNeighbour &&
            mesh_.tet_region[n] < 0 && in_metric_sphere(n))
          frozen_hit = true;
        continue;
      }
      const uint32_t n = mesh_.neighbour(t, i);
      if (n == TetMesh::kNone || in_cavity_[n] || mesh_.is_deleted(n) || mesh_.is_ghost(n)) continue;
      if (mesh_.tet_region[n] != region || (mesh_.tet_flags[n] & tflag::kEdgeConstrainedMask)) continue;
      if (!in_metric_sphere(n)) continue;
      in_cavity_[n] = 1;
      cavity_.push_back(n);
    }
  }
  // Star-shapedness: facet i of t sees p when t with vertex i replaced by p is positive.
  bool ok = !frozen_hit;
  for (bool changed = true; changed && ok;) {
    changed = false;
    for (uint32_t t : cavity_) {
      if (!in_cavity_[t]) continue;
      for (int i = 0; i < 4 && in_cavity_[t]; ++i) {
        const uint32_t n = mesh_.neighbour(t, i);
        if (n != TetMesh::kNone && !mesh_.facet_protected(t, i) && in_cavity_[n]) continue;
        const double* v[4];
        for (int j = 0; j < 4; ++j) v[j] = j == i ? p : mesh_.point(mesh_.vertex(t, j));
        if (predicates::orient3d(v[0], v[1], v[2], v[3]) > 0) continue;
        if (in_cavity_[t] == 2) {
          ok = false;
          break;
        }
        in_cavity_[t] = 0;
        changed = true;
      }
      if (!ok) break;
    }
  }
  old_.clear();
  for (uint32_t t : cavity_)
    if (in_cavity_[t]) old_.push_back(t);
  for (uint32_t t : cavity_) in_cavity_[t] = 0;
  if (!ok) return TetMesh::kNone;
  const uint32_t v = mesh_.add_vertex(p, 0);
  fresh_.clear();
  for (uint32_t t : old_) in_cavity_[t] = 1;
  for (uint32_t t : old_)
    for (int i = 0; i < 4; ++i) {
      const uint32_t n = mesh_.neighbour(t, i);
      if (n != TetMesh::kNone && !mesh_.facet_protected(t, i) && in_cavity_[n]) continue;
      meshops::TetVerts tv;
      for (int j = 0; j < 4; ++j) tv[j] = j == i ? v : mesh_.vertex(t, j);
      fresh_.push_back(tv);
    }
  for (uint32_t t : old_) in_cavity_[t] = 0;
  if (!meshops::replace_tets(mesh_, old_, fresh_, vt_, scratch_)) {
    // Not expected (every new tet was checked positive); the vertex stays unused.
    vt_.forget(v);
    return TetMesh::kNone;
  }
  in_cavity_.resize(mesh_.num_tet_slots(), 0);
  return v;
}

meshops::MetricMap Refiner::map_of_vertices(const uint32_t* v, size_t n) const {
  double m[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  for (size_t k = 0; k < n; ++k)
    for (int j = 0; j < 6; ++j) m[j] += metrics_[6 * size_t(v[k]) + j] / double(n);
  return meshops::MetricMap::of(m);
}

bool Refiner::edge_ring_unchanged(uint32_t t, int k) const {
  const uint32_t since = flip_failed_at_[t];
  const uint32_t a = mesh_.vertex(t, kEdgeVertex[k][0]), b = mesh_.vertex(t, kEdgeVertex[k][1]);
  // Around ab from t one way, and when the ring is open (a facet without neighbour), the other
  // way too: across the facets of ab opposite each of t's two other vertices in turn.
  for (int side = 0; side < 2; ++side) {
    uint32_t s = t, x = mesh_.vertex(t, kEdgeVertex[5 - k][side]);
    for (int steps = 0; steps < 64; ++steps) {
      int ix = 0;
      while (mesh_.vertex(s, ix) != x) ++ix;
      if (mesh_.tet_adj[4 * size_t(s) + ix] == TetMesh::kNoNeighbour) break;
      const uint32_t n = mesh_.neighbour(s, ix);
      if (n == t) return true;
      if (n < made_at_.size() && made_at_[n] > since) return false;
      // Next, n is left across its other facet of ab (not the one just crossed, opposite its
      // new vertex).
      const int back = mesh_.neighbour_facet(s, ix);
      for (int i = 0; i < 4; ++i) {
        const uint32_t w = mesh_.vertex(n, i);
        if (w != a && w != b && i != back) x = w;
      }
      s = n;
      if (steps == 63) return false;  // (not expected: a ring of 64 tets)
    }
  }
  return true;
}

// Anisotropic metrics: flips that raise the worst shape in the metric (measured in the mean of
// the flipped region's vertices' metrics), around the tets below metric_flip_quality: 2-3 across a
// facet, 3-2 removing an edge of three tets. The Euclidean flips of optimize/ would undo the
// stretched shapes the metric asks for. Protected facets and constrained edges are never
// flipped (replace_tets refuses them), and tets of different regions are never merged.
size_t Refiner::metric_flip_pass() {
  constexpr double kFlipQuality = 0.3;
  size_t flips = 0;
  std::vector<uint32_t> old(3);
  std::vector<meshops::TetVerts> fresh;
  auto tet_verts = [&](uint32_t t) {
    meshops::TetVerts tv;
    for (int i = 0; i < 4; ++i) tv[i] = mesh_.vertex(t, i);
    return tv;
  };
  auto poor = [&](uint32_t t) {
    const meshops::TetVerts tv = tet_verts(t);
    return metric_quality(map_of_vertices(tv.data(), 4), tv) < kFlipQuality;
  };
  // The tets as the pass finds them are measured on every core; the loop measures again only
  // the slots its own flips filled (refilled) and the failed ones whose neighbourhood its flips
  // changed, so the flips are the ones of a sequential loop that tries every poor tet.
  const uint32_t n_start = mesh_.num_tet_slots();
  std::vector<uint8_t> poor_at_start(n_start, 0), refilled(n_start, 0);
  flip_failed_at_.resize(n_start, 0);
  not_poor_.resize(n_start, 0);
  // A tet found not poor is marked so, and not measured again while its slot lives (see epoch_).
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n_start, 1024), [&](const tbb::blocked_range<uint32_t>& r) {
    for (uint32_t t = r.begin(); t < r.end(); ++t) {
      if (mesh_.is_deleted(t) || mesh_.is_ghost(t) || not_poor_[t]) continue;
      poor_at_start[t] = failed_unchanged(t) ? 2 : poor(t) ? 1 : 0;
      not_poor_[t] = poor_at_start[t] == 0;
      // Unchanged since its failure: it would fail now, so its failure dates from now (fewer
      // vertices are newer than that, and fewer rings walked at the next look).
      if (poor_at_start[t] == 2) flip_failed_at_[t] = epoch_;
    }
  });
  auto note_refilled = [&] {
    for (uint32_t c : scratch_.created)
      if (c < n_start) refilled[c] = 1;
    note_changed(scratch_.created);
  };
  for (uint32_t t = 0; t < mesh_.num_tet_slots(); ++t) {
    if (mesh_.is_deleted(t) || mesh_.is_ghost(t)) continue;
    // 2: skipped at the start as failed and unchanged, which the flips before t may have changed.
    const bool measured = t < n_start && !refilled[t] && poor_at_start[t] != 2;
    if (measured) {
      if (poor_at_start[t] != 1) continue;
    } else if (failed_unchanged(t)) {
      flip_failed_at_[t] = epoch_;  // (as above)
      continue;
    } else if (!poor(t)) {
      continue;
    }
    const meshops::TetVerts tv = tet_verts(t);
    bool flipped = false;
    // 2-3 across facet i: the new tets are t with one facet vertex replaced by the apex b of n.
    for (int i = 0; i < 4 && !flipped; ++i) {
      if (mesh_.facet_protected(t, i) || mesh_.tet_adj[4 * size_t(t) + i] == TetMesh::kNoNeighbour) continue;
      const uint32_t n = mesh_.neighbour(t, i);
      if (mesh_.is_deleted(n) || mesh_.is_ghost(n) || mesh_.tet_region[n] != mesh_.tet_region[t]) continue;
      const uint32_t b = mesh_.vertex(n, mesh_.neighbour_facet(t, i));
      meshops::TetVerts nv;
      for (int j = 0; j < 4; ++j) nv[j] = mesh_.vertex(n, j);
      const uint32_t all[5] = {tv[0], tv[1], tv[2], tv[3], b};
      const meshops::MetricMap map = map_of_vertices(all, 5);
      const double before = std::min(metric_quality(map, tv), metric_quality(map, nv));
      fresh.clear();
      double after = 1.0;
      // (after only falls: the first new tet that brings it to before + 1e-3 decides)
      for (int j = 0; j < 4 && after > before + 1e-3; ++j) {
        if (j == i) continue;
        meshops::TetVerts f = tv;
        f[j] = b;
        after = std::min(after, metric_quality(map, f));
        fresh.push_back(f);
      }
      if (!(after > before + 1e-3)) continue;
      old.assign({t, n});
      if (meshops::replace_tets(mesh_, old, fresh, vt_, scratch_)) {
        flipped = true;
        note_refilled();
      }
    }
    // 3-2 removing edge k of t when three tets surround it.
    for (int k = 0; k < 6 && !flipped; ++k) {
      const uint32_t a = tv[kEdgeVertex[k][0]], b = tv[kEdgeVertex[k][1]];
      if (!meshops::edge_ring(mesh_, a, b, t, ring_tets_, ring_, 3) || ring_tets_.size() != 3) continue;
      bool same_region = true;
      for (uint32_t r : ring_tets_) same_region &= mesh_.tet_region[r] == mesh_.tet_region[t];
      if (!same_region) continue;
      const uint32_t all[5] = {a, b, ring_[0], ring_[1], ring_[2]};
      const meshops::MetricMap map = map_of_vertices(all, 5);
      double before = 1.0;
      for (uint32_t r : ring_tets_) {
        meshops::TetVerts rv;
        for (int j = 0; j < 4; ++j) rv[j] = mesh_.vertex(r, j);
        before = std::min(before, metric_quality(map, rv));
      }
      meshops::TetVerts fa = {ring_[0], ring_[1], ring_[2], a}, fb = {ring_[0], ring_[2], ring_[1], b};
      if (predicates::orient3d(mesh_.point(fa[0]), mesh_.point(fa[1]), mesh_.point(fa[2]), mesh_.point(fa[3])) < 0) {
        std::swap(fa[1], fa[2]);
        std::swap(fb[1], fb[2]);
      }
      const double after = std::min(metric_quality(map, fa), metric_quality(map, fb));
      if (!(after > before + 1e-3)) continue;
      fresh.assign({fa, fb});
      if (meshops::replace_tets(mesh_, ring_tets_, fresh, vt_, scratch_)) {
        flipped = true;
        note_refilled();
      }
    }
    flips += flipped;
    if (!flipped) {
      if (flip_failed_at_.size() <= t) flip_failed_at_.resize(size_t(t) + 1, 0);
      flip_failed_at_[t] = epoch_;
    }
  }
  return flips;
}

// Two phases: the midpoints are chosen on the mesh as the pass found it (longest edge first, each
// checked against the batch's spacing grid, the edge's ring and the protected facets), then
// inserted in the order of a Hilbert curve through them. Inserting in length order jumped across
// the mesh at every point (cold caches, long walks): most of refinement's time.
// The choice half of split_pass: its lists (88 bytes per long edge and the spacing grid) go
// when it returns, before the insertions allocate theirs.
void Refiner::choose_splits(refine_detail::EdgeList& edges, std::vector<Chosen>& chosen,
                            std::vector<double>& chosen_xyz, double lo[3], double hi[3]) {
  const auto choice_start = Clock::now();
  // The long edges by value, sorted on every core: sorting pointers read the edges at random
  // (millions of them in a large mesh's first pass). The order is total (a, b name one edge). An
  // edge vetoed in an earlier pass with no tet around it changed since would be vetoed again (the
  // veto reads only its ring and its ends): it is not measured again (most of the last passes'
  // long edges).
  refine_detail::EdgeList longs;
  for (const refine_detail::Edge& e : edges) {
    if (e.on_surface || !(e.length > options_.split_length)) continue;
    if (e.vetoed) ++stats_.split_rejected;
    else longs.push_back(e);
  }
  tbb::parallel_sort(longs.begin(), longs.end(), [](const refine_detail::Edge& x, const refine_detail::Edge& y) {
    return x.length != y.length ? x.length > y.length : (x.a != y.a ? x.a < y.a : x.b < y.b);
  });
  if (longs.empty()) return;
  for (int k = 0; k < 3; ++k) lo[k] = hi[k] = mesh_.xyz[size_t(k)];
  double hmin = size_[longs.front().a];
  for (size_t v = 0; v < mesh_.num_vertices(); ++v) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], mesh_.xyz[3 * v + k]);
      hi[k] = std::max(hi[k], mesh_.xyz[3 * v + k]);
    }
    hmin = std::min(hmin, size_[v]);
  }
  SpacingGrid grid(lo, std::max(options_.spacing * hmin, 1e-300));
  // Each edge's midpoint and metric, on every core (the mesh is only read), then the spacing filter
  // in length order (each point is checked against the ones chosen before it; most long edges are
  // put off by the grid) with the local vetoes, block by block below. The same points are chosen as
  // in one sequential loop.
  std::vector<Candidate> candidates(longs.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, longs.size(), 512), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i != range.end(); ++i) {
      const refine_detail::Edge* e = &longs[i];
      Candidate& c = candidates[i];
      metric_midpoint(e->a, e->b, c.m);
      field_.metric(c.m, c.mm);
      c.iso = meshops::MetricMap::of(c.mm).identity;
      c.r = options_.spacing * (c.iso ? metric_size(c.mm) : meshops::metric_max_size(c.mm));
    }
  });
  // A midpoint that would sit closer than collapse_length to a vertex of the edge's ring would
  // only be collapsed again (split/collapse ping-pong): such an edge is left to the flips. Not
  // with an anisotropic metric: optimize/'s flips are Euclidean, and the metric kernel
  // re-triangulates the cavity (the long edges there are mostly flat tets' diagonals).
  // (e->tet holds the edge: the edges were collected on this mesh, which the choice only reads.)
  auto vetoed = [&](const refine_detail::Edge* e, const Candidate& c, std::vector<uint32_t>& ring_tets,
                    std::vector<uint32_t>& ring) {
    if (!anisotropic_ && holds_edge(*e) && meshops::edge_ring(mesh_, e->a, e->b, e->tet, ring_tets, ring))
      for (uint32_t v : ring)
        if (metric_edge_length(c.mm, c.m, &metrics_[6 * size_t(v)], mesh_.point(v)) < options_.collapse_length)
          return true;
    return too_close_to_protected_facet(c.m, c.mm);
  };
  // The choice, block by block in length order. A block's candidates are first checked on every
  // core against the grid as it stands at the block's start, and the vetoes measured for those it
  // lets through; then, in order, the grid is asked again only for those (it only grows, so the
  // others would be refused anyway) and only when the block has added a point. The same points
  // as a sequential loop, the vetoes (edge rings: random reads) off the sequential path.
  constexpr size_t kBlock = 4096;
  enum : uint8_t { kRefused = 0, kVetoed = 1, kFree = 2 };
  std::vector<uint8_t> verdict(longs.size());  // per candidate: refused by the grid, vetoed, or free
  std::vector<uint64_t> vetoed_keys;
  for (size_t b0 = 0; b0 < longs.size(); b0 += kBlock) {
    const size_t b1 = std::min(longs.size(), b0 + kBlock);
    tbb::parallel_for(tbb::blocked_range<size_t>(b0, b1, 256), [&](const tbb::blocked_range<size_t>& range) {
      std::vector<uint32_t> ring_tets, ring;
      for (size_t i = range.begin(); i != range.end(); ++i) {
        const Candidate& c = candidates[i];
        verdict[i] = grid.conflicts(c.m, c.r, c.iso ? nullptr : c.mm, options_.spacing) ? kRefused
                      : vetoed(&longs[i], c, ring_tets, ring)                             ? kVetoed
                                                                                           : kFree;
      }
    });
    bool added = false;
    for (size_t i = b0; i < b1; ++i) {
      const Candidate& c = candidates[i];
      if (verdict[i] == kVetoed) vetoed_keys.push_back(longs[i].key());
      if (verdict[i] != kFree || (added && grid.conflicts(c.m, c.r, c.iso ? nullptr : c.mm, options_.spacing))) {
        ++stats_.split_rejected;
        continue;
      }
      grid.add(c.m, c.r, c.iso ? nullptr : c.mm);
      added = true;
      chosen.push_back({longs[i], c});
      chosen_xyz.insert(chosen_xyz.end(), c.m, c.m + 3);
    }
  }
  // The vetoes, kept in the edge list for the next pass (update_edges drops an edge whose tets
  // changed).
  refine_detail::mark_vetoed(edges, vetoed_keys, options_.split_length);
  stats_.seconds_choice += seconds_since(choice_start);
}

size_t Refiner::split_pass(refine_detail::EdgeList& edges) {
  std::vector<Chosen> chosen;
  std::vector<double> chosen_xyz;  // their points, 3 each, for the Hilbert sort
  double lo[3], hi[3];
  choose_splits(edges, chosen, chosen_xyz, lo, hi);
  if (chosen.empty()) return 0;
  const auto insertion_start = Clock::now();
  std::vector<uint32_t> split_order(chosen.size());  // the insertion order (indices in chosen)
  for (size_t k = 0; k < split_order.size(); ++k) split_order[k] = uint32_t(k);
  // Anisotropic metrics keep the length order: the metric kernel needs the edge's ring, which
  // earlier insertions of the batch destroy less often when the longest edges go first.
  if (!anisotropic_) delaunay_detail::hilbert_sort(chosen_xyz.data(), split_order.data(), split_order.size(), lo, hi);
  size_t done = 0;
  // Isotropic points: a batch, on every core (BatchInserter).
  const bool all_iso = std::all_of(chosen.begin(), chosen.end(), [](const Chosen& c) { return c.c.iso; });
  if (all_iso && options_.insert_partitions > 1) {
    // (Locals: the pass's lists go when it ends, before the next pass collects its edges.)
    // The chosen records (112 bytes each) give way to what the batch reads, in curve order.
    const size_t n = chosen.size();
    std::vector<double> batch_points(3 * n), batch_metrics(6 * n);
    std::vector<uint32_t> batch_hints(n);
    BatchInsertion batch_out;
    for (size_t j = 0; j < n; ++j) {
      const Chosen& c = chosen[split_order[j]];
      std::copy_n(c.c.m, 3, &batch_points[3 * j]);
      std::copy_n(c.c.mm, 6, &batch_metrics[6 * j]);
      batch_hints[j] = c.e.tet;  // live: nothing changed the mesh since the edges were collected
    }
    std::vector<Chosen>().swap(chosen);
    std::vector<double>().swap(chosen_xyz);
    std::vector<uint32_t>().swap(split_order);
    InsertOptions insert_options;
    insert_options.refuse_frozen_conflict = options_.defer_at_frozen;
    batch_.insert(batch_points.data(), batch_hints.data(), n, insert_options, batch_out);
    stats_.parallel_splits += batch_out.parallel;
    for (size_t j = 0; j < n; ++j) {
      const uint32_t nv = batch_out.vertex[j];
      if (nv == TetMesh::kNone) {
        ++stats_.split_rejected;
        continue;
      }
      set_metric(nv, &batch_metrics[6 * j]);
      // (Later points of the batch may have replaced some of these tets: only the live ones.)
      live_created_.clear();
      for (const uint32_t* t = batch_out.created_begin(j); t != batch_out.created_end(j); ++t)
        if (!mesh_.is_deleted(*t)) live_created_.push_back(*t);
      note_created(live_created_);
      ++done;
    }
    stats_.seconds_insertion += seconds_since(insertion_start);
    return done;
  }
  for (uint32_t k : split_order) {
    // (In curve order: one record per point, not the edge and the candidate far apart.)
    const refine_detail::Edge* e = &chosen[k].e;
    const Candidate& c = chosen[k].c;
    const double* m = c.m;
    const double* mm = c.mm;
    const bool iso = c.iso;
    // The edge's tet when it is still there (earlier points of the batch may have replaced it),
    // else the inserter walks from its last new tet: the previous point, near along the curve.
    const uint32_t hint = holds_edge(*e) ? e->tet : TetMesh::kNone;
    // An anisotropic metric at the midpoint: the metric kernel (the Euclidean one would connect
    // the points by Euclidean proximity, across the stretched direction).
    uint32_t nv = TetMesh::kNone;
    const std::vector<uint32_t>* created = nullptr;
    if (!iso) {
      const uint32_t h = edge_hint(*e);
      if (meshops::tet_has_vertex(mesh_, h, e->b) && meshops::edge_ring(mesh_, e->a, e->b, h, ring_tets_, ring_)) {
        nv = insert_in_metric(m, mm, mesh_.tet_region[ring_tets_.front()]);
        created = &scratch_.created;
      }
    }
    if (!created) {
      InsertOptions insert_options;
      insert_options.refuse_frozen_conflict = options_.defer_at_frozen;
      const InsertResult res = inserter_.insert(m, hint, insert_options);
      if (res.ok()) nv = res.vertex;
      created = &inserter_.new_tets();
    }
    if (nv == TetMesh::kNone) {
      ++stats_.split_rejected;
      continue;
    }
    set_metric(nv, mm);  // measured at m above, the new vertex's point
    note_created(*created);
    ++done;
  }
  stats_.seconds_insertion += seconds_since(insertion_start);
  return done;
}

// From index_protected_facets' list (each protected facet once): those with all three vertices
// on S are S's triangles.
void Refiner::measure_s_edges() {
  longest_s_edge_.assign(mesh_.num_vertices(), 0.0);
  auto on_s = [&](uint32_t v) { return (mesh_.vflags[v] & vflag::kOnInputSurface) != 0; };
  for (size_t f = 0; f < facet_tri_.size(); f += 3) {
    const uint32_t* fv = &facet_tri_[f];
    if (!on_s(fv[0]) || !on_s(fv[1]) || !on_s(fv[2])) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = fv[k], b = fv[(k + 1) % 3];
      const double len = refine_detail::normalized_length(mesh_, metrics_, a, b);
      longest_s_edge_[a] = std::max(longest_s_edge_[a], len);
      longest_s_edge_[b] = std::max(longest_s_edge_[b], len);
    }
  }
}

bool Refiner::collapse_fits(uint32_t v, uint32_t w, const double q[3], bool moves, CollapseScratch& s) const {
  double mq[6];
  if (moves) field_.metric(q, mq);
  else std::copy_n(&metrics_[6 * size_t(w)], 6, mq);
  // A collapse must not make the worst changed tet worse than min_collapse_quality, or than the
  // worst one it replaces when that was already below (so that bad regions can still coarsen).
  // Shapes are measured in the metric at q (for an isotropic field: as they are).
  const meshops::MetricMap in_mq = meshops::MetricMap::of(mq);
  const double max_result =
      anisotropic_ ? options_.anisotropic_max_collapse_result : options_.max_collapse_result;
  // An edge from w to a vertex x of S may be as long as x's longest edge of S, which no split
  // shortens (collapse_to_s_edge_length): beside sliver triangles of S every collapse otherwise
  // made such an edge and was refused, and the recovery's Steiner points stayed: far more tets than
  // the sizes ask, their count sensitive to rounding.
  using refine_detail::normalized_length;
  const bool degenerate = normalized_length(mesh_, metrics_, w, v) < options_.degenerate_length;
  for (const meshops::TetVerts& f : s.fresh)
    for (uint32_t x : f) {
      if (x == w) continue;
      const double len = metric_edge_length(mq, q, &metrics_[6 * size_t(x)], mesh_.point(x));
      if (len > max_result && len > longest_s_edge(x) &&
          !(degenerate && len <= std::max(normalized_length(mesh_, metrics_, v, x),
                                          normalized_length(mesh_, metrics_, w, x))))
        return false;
    }
  // Then the shapes (the lengths are cheaper to measure): the floor is the lower of
  // min_collapse_quality and the worst old tet, measured only when a new tet is below the first.
  const double bar = options_.min_collapse_quality;
  double floor = bar;
  bool floor_known = !(bar > 0.0);
  auto point = [&](uint32_t x) { return x == w ? q : mesh_.point(x); };  // w at q
  for (const meshops::TetVerts& f : s.fresh) {
    const double qf = meshops::metric_shape_quality(in_mq, point(f[0]), point(f[1]), point(f[2]), point(f[3]));
    if (qf >= bar) continue;
    if (!floor_known) {
      floor = std::min(bar, meshops::min_quality(mesh_, s.old, in_mq));  // w still at its place
      floor_known = true;
    }
    if (qf < floor) return false;
  }
  return meshops::replacement_fits(mesh_, s.old, s.fresh, s.replace, meshops::ConstrainedEdges::kRefuse, w, q);
}

bool Refiner::collapse(uint32_t v, uint32_t w, const double q[3]) {
  const uint32_t tv = vt_.tet_of(mesh_, v);
  if (tv == TetMesh::kNone) return false;
  const double* pw = mesh_.point(w);
  const bool moves = q[0] != pw[0] || q[1] != pw[1] || q[2] != pw[2];
  CollapseScratch& s = collapse_scratch_;
  if (!meshops::collapse_tets(mesh_, vt_, v, tv, w, moves, s.old, s.fresh, s.ball_w) ||
      !collapse_fits(v, w, q, moves, s))
    return false;
  // The tets it changes: their vertices' trials are stale (collapse_pass).
  for (uint32_t t : s.old)
    for (int i = 0; i < 4; ++i) collapse_changed_[mesh_.vertex(t, i)] = collapse_block_;
  double* xw = &mesh_.xyz[3 * size_t(w)];
  const double saved[3] = {xw[0], xw[1], xw[2]};
  std::copy_n(q, 3, xw);
  if (!meshops::replace_tets(mesh_, s.old, s.fresh, vt_, scratch_)) {  // collapse_fits said it would
    std::copy_n(saved, 3, xw);
    return false;
  }
  vt_.forget(v);
  if (moves) update_metric(w);
  for (const meshops::TetVerts& f : s.fresh)
    for (uint32_t x : f) touched_[x] = 1;
  note_changed(scratch_.created);
  touched_[v] = 1;
  return true;
}

int Refiner::collapse_trial(const refine_detail::Edge& e, CollapseScratch& s) const {
  const uint32_t a = e.a, b = e.b;
  const uint32_t ta = vt_.known_tet(mesh_, a), tb = vt_.known_tet(mesh_, b);
  if (ta == TetMesh::kNone || tb == TetMesh::kNone) return kTrialUnknown;
  // Each alternative of collapse_pass, in its order: v's ball into s.old, w's into s.ball_w when
  // w moves (balls too large for the unmarked traversal are left to the sequential loop).
  constexpr size_t kMaxBall = 256;
  auto fits = [&](uint32_t v, uint32_t tv, uint32_t w, uint32_t tw, const double* q, bool moves, bool& unknown) {
    if (!meshops::vertex_ball_unmarked(mesh_, v, tv, s.old, kMaxBall) ||
        (moves && !meshops::vertex_ball_unmarked(mesh_, w, tw, s.ball_w, kMaxBall))) {
      unknown = true;
      return false;
    }
    return meshops::collapse_replacement(mesh_, v, w, moves ? &s.ball_w : nullptr, s.old, s.fresh) &&
           collapse_fits(v, w, q, moves, s);
  };
  bool unknown = false;
  if (fixed(a)) return fits(b, tb, a, ta, mesh_.point(a), false, unknown) ? 0 : unknown ? kTrialUnknown : kTrialRefused;
  if (fixed(b)) return fits(a, ta, b, tb, mesh_.point(b), false, unknown) ? 0 : unknown ? kTrialUnknown : kTrialRefused;
  double m[3];
  metric_midpoint(a, b, m);
  const double* pb = mesh_.point(b);
  const bool m_moves = m[0] != pb[0] || m[1] != pb[1] || m[2] != pb[2];
  if (fits(a, ta, b, tb, m, m_moves, unknown)) return 0;
  if (unknown) return kTrialUnknown;
  if (fits(a, ta, b, tb, pb, false, unknown)) return 1;
  if (unknown) return kTrialUnknown;
  if (fits(b, tb, a, ta, mesh_.point(a), false, unknown)) return 2;
  return unknown ? kTrialUnknown : kTrialRefused;
}

size_t Refiner::collapse_pass(const refine_detail::EdgeList& edges) {
  refine_detail::EdgeList shorts;  // by value, as in split_pass
  for (const refine_detail::Edge& e : edges)
    if (e.length < options_.collapse_length && !(fixed(e.a) && fixed(e.b))) shorts.push_back(e);
  tbb::parallel_sort(shorts.begin(), shorts.end(), [](const refine_detail::Edge& x, const refine_detail::Edge& y) {
    return x.length != y.length ? x.length < y.length : (x.a != y.a ? x.a < y.a : x.b < y.b);
  });
  touched_.resize(mesh_.num_vertices(), 0);
  auto skipped = [&](const refine_detail::Edge& e) {
    return touched_[e.a] || touched_[e.b] || vt_.removed(e.a) || vt_.removed(e.b) || refused_unchanged(e);
  };
  // Block by block in length order, each collapse is tried on every core against the mesh as the
  // block starts (most are refused); then the block's collapses are made one by one: an edge none
  // of whose ends' tets a collapse of the block changed meanwhile gets its trial's verdict, the
  // others are tried again. The same collapses as trying each edge in turn. Blocks, not the whole
  // pass at once: an edge a collapse before it skips is not tried (airplane at --size 1.542 tried
  // 104k edges for 19k sequential attempts with one block). Not on one thread: there the trials
  // only add work.
  const size_t block = std::max<size_t>(1, options_.collapse_trial_block);
  const bool trials = options_.collapse_trials && tbb::this_task_arena::max_concurrency() > 1;
  std::vector<int8_t> trial(std::min(shorts.size(), block));
  tbb::enumerable_thread_specific<CollapseScratch> scratches;
  collapse_changed_.assign(mesh_.num_vertices(), 0);
  size_t done = 0;
  for (size_t b0 = 0; b0 < shorts.size(); b0 += block) {
    const size_t b1 = std::min(shorts.size(), b0 + block);
    ++collapse_block_;
    std::fill(trial.begin(), trial.end(), int8_t(kTrialUnknown));
    if (trials)
      tbb::parallel_for(tbb::blocked_range<size_t>(b0, b1, 64), [&](const tbb::blocked_range<size_t>& r) {
        CollapseScratch& s = scratches.local();
        for (size_t i = r.begin(); i < r.end(); ++i)
          if (!skipped(shorts[i])) trial[i - b0] = static_cast<int8_t>(collapse_trial(shorts[i], s));
      });
    for (size_t i = b0; i < b1; ++i) {
      const refine_detail::Edge& e = shorts[i];
      if (skipped(e)) continue;
      const uint32_t a = e.a, b = e.b;
      int known = trial[i - b0];
      if (collapse_changed_[a] == collapse_block_ || collapse_changed_[b] == collapse_block_) known = kTrialUnknown;
      bool ok = false;
      if (known == kTrialRefused) {
        ok = false;
      } else if (fixed(a)) {
        ok = collapse(b, a, mesh_.point(a));
      } else if (fixed(b)) {
        ok = collapse(a, b, mesh_.point(b));
      } else {
        double m[3];
        metric_midpoint(a, b, m);
        // Alternatives its trial found refused are not made again.
        const int first = known == kTrialUnknown ? 0 : known;
        ok = (first <= 0 && collapse(a, b, m)) || (first <= 1 && collapse(a, b, mesh_.point(b))) ||
             collapse(b, a, mesh_.point(a));
      }
      if (ok) {
        ++done;
      } else {
        ++stats_.collapse_rejected;
        refused_[e.key()] = epoch_;
      }
    }
  }
  return done;
}

Status Refiner::check(const char* when) const {
  if (!options_.check_each_pass) return Status::success();
  Status st = check_mesh(mesh_);
  if (!st.ok()) return Status(Error::Internal, std::string("refine: mesh broken ") + when + ": " + st.message());
  const size_t pf = count_protected_facets(mesh_);
  if (pf != protected_facets_)
    return Status(Error::Internal, std::string("refine: protected facets changed ") + when + ": " +
                                       std::to_string(protected_facets_) + " -> " + std::to_string(pf));
  return Status::success();
}

Status Refiner::check_edge_list(const refine_detail::EdgeList& edges, size_t edge_count) const {
  if (!options_.check_each_pass) return Status::success();
  refine_detail::EdgeList all;
  refine_detail::EdgeScratch scratch;
  refine_detail::collect_edges(mesh_, metrics_, all, scratch);
  if (all.size() != edge_count)
    return Status(Error::Internal, "refine: " + std::to_string(all.size()) + " edges, counted " +
                                       std::to_string(edge_count));
  const refine_detail::EdgeFilter filter = edge_filter();
  refine_detail::EdgeList wanted, listed;
  for (const refine_detail::Edge& e : all)
    if (filter.wanted(mesh_, e.a, e.b, e.length)) wanted.push_back(e);
  for (const refine_detail::Edge& e : edges)
    if (filter.wanted(mesh_, e.a, e.b, e.length)) listed.push_back(e);
  auto by_ends = [](const refine_detail::Edge& x, const refine_detail::Edge& y) {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  };
  std::sort(wanted.begin(), wanted.end(), by_ends);
  std::sort(listed.begin(), listed.end(), by_ends);
  bool same = wanted.size() == listed.size();
  for (size_t k = 0; same && k < wanted.size(); ++k) {
    const refine_detail::Edge &x = wanted[k], &y = listed[k];
    same = x.a == y.a && x.b == y.b && x.tet == y.tet && x.on_surface == y.on_surface && x.length == y.length;
  }
  if (!same)
    return Status(Error::Internal, "refine: the pass's edge list (" + std::to_string(listed.size()) +
                                       " edges to split or collapse) differs from the mesh's (" +
                                       std::to_string(wanted.size()) + ")");
  return Status::success();
}

// A mesh holds TetMesh::kMaxTetSlots tet slots (32-bit adjacency): the pass's splits, at most one
// per long edge, must leave room for 16 new tets each (an insertion makes about 6 on average).
Status Refiner::check_room(const refine_detail::EdgeList& edges) const {
  size_t long_edges = 0;
  for (const refine_detail::Edge& e : edges) long_edges += e.length > options_.split_length ? 1 : 0;
  if (mesh_.num_tet_slots() + 16 * long_edges <= TetMesh::kMaxTetSlots) return Status::success();
  return Status(Error::InvalidArgument, "refine: " + std::to_string(mesh_.num_live_tets()) + " tets with " +
                                            std::to_string(long_edges) +
                                            " edges still to split: more than one mesh holds (2^30 tet "
                                            "slots); use a coarser size");
}

Result<RefineStats> Refiner::run() {
  const auto start = Clock::now();
  if (!(options_.size_scale > 0.0) || !(options_.split_length > options_.collapse_length) ||
      !(options_.collapse_length > 0.0))
    return Status(Error::InvalidArgument, "refine: need size_scale > 0 and split_length > collapse_length > 0");
  for (uint32_t t = 0; t < mesh_.num_tet_slots(); ++t)
    if (!mesh_.is_deleted(t) && mesh_.is_ghost(t))
      return Status(Error::InvalidArgument, "refine: the mesh has ghost tets");
  vt_.build(mesh_);
  index_protected_facets();
  metrics_.resize(6 * mesh_.num_vertices());
  size_.resize(mesh_.num_vertices());
  // The field's metric at every vertex, on every core (its queries are thread-safe, as the
  // split choice's are).
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(mesh_.num_vertices()), 1024),
                    [&](const tbb::blocked_range<uint32_t>& r) {
                      for (uint32_t v = r.begin(); v < r.end(); ++v) update_metric(v);
                    });
  for (uint32_t v = 0; v < mesh_.num_vertices(); ++v) {
    const double* m = &metrics_[6 * size_t(v)];
    const bool identity = meshops::MetricMap::of(m).identity;
    anisotropic_ |= !identity;
    // A tensor that is not SPD to rounding (its Cholesky fails) is measured as the Euclidean
    // metric by MetricMap: the count is reported, not hidden.
    stats_.metric_not_spd += identity && !metric_is_isotropic(m);
  }
  protected_facets_ = count_protected_facets(mesh_);
  // (Without collapse_to_s_edge_length the list stays empty: every vertex reads 0.)
  if (options_.collapse_to_s_edge_length) measure_s_edges();
  reserve_for_refinement();
  stats_.vertices_before = refine_detail::live_vertex_count(mesh_);
  stats_.tets_before = mesh_.num_live_tets();
  if (Status st = check("before refinement"); !st.ok()) return st;

  if (anisotropic_)
    if (Status st = metric_flip_sweeps(5); !st.ok()) return st;
  refine_detail::EdgeList edges;
  // The mesh's edge count, for the stop rule: every change re-triangulates a ball and keeps the
  // boundary, so V - E + F - T and the boundary faces stay and E changes by dV + dT.
  size_t edges_at_start = 0, vertices_at_start = 0, tets_at_start = 0, edge_count = 0;
  for (int pass = 0; pass < options_.max_passes; ++pass) {
    // One edge list serves both halves of the pass: the splits mark the vertices whose edges
    // they changed, and the collapses skip those edges (they are measured again next pass).
    // Every edge is measured in the first pass; after it, only around the tets the pass before
    // made (update_edges), and the list holds only the edges a pass acts on.
    auto t = Clock::now();
    if (pass == 0) {
      refine_detail::collect_edges(mesh_, metrics_, edges, edge_scratch_);
      edges_at_start = edge_count = edges.size();
      vertices_at_start = stats_.vertices_before;
      tets_at_start = mesh_.num_live_tets();
    } else {
      changed_.resize(mesh_.num_tet_slots(), 0);
      refine_detail::update_edges(mesh_, metrics_, changed_, edge_filter(), edges, edge_scratch_);
      edge_count = edges_at_start + (refine_detail::live_vertex_count(mesh_) - vertices_at_start) +
                   (mesh_.num_live_tets() - tets_at_start);
    }
    changed_.assign(mesh_.num_tet_slots(), 0);
    stats_.seconds_edges += seconds_since(t);
    if (Status st = check_edge_list(edges, edge_count); !st.ok()) return st;
    touched_.assign(mesh_.num_vertices(), 0);
    if (Status st = check_room(edges); !st.ok()) return st;
    const size_t splits = split_pass(edges);
    if (Status st = check("after a split pass"); !st.ok()) return st;
    size_t collapses = 0;
    if (options_.collapse) {
      t = Clock::now();
      collapses = collapse_pass(edges);
      stats_.seconds_collapses += seconds_since(t);
      if (Status st = check("after a collapse pass"); !st.ok()) return st;
    }
    if (anisotropic_)
      if (Status st = metric_flip_sweeps(3); !st.ok()) return st;
    stats_.splits += splits;
    stats_.collapses += collapses;
    stats_.passes = pass + 1;
    if (options_.progress) {
      const double share = options_.expected_tets > 0 ? double(mesh_.num_live_tets()) / options_.expected_tets
                                                       : double(pass + 1) / double(options_.max_passes);
      options_.progress(std::min(0.95, share));
    }
    if (double(splits + collapses) < options_.stop_fraction * double(edge_count)) break;
    stats_.stopped_at_pass_cap = pass + 1 == options_.max_passes;
  }
  const auto t = Clock::now();
  // The summary of every edge, without their list: the run's peak memory was the full list and its
  // buckets here, beside the grown mesh (issue 49). The last pass's list and scratch go first.
  refine_detail::EdgeList().swap(edges);
  edge_scratch_.release();
  refine_detail::summarize_edge_lengths(mesh_, metrics_, options_.collapse_length, options_.split_length,
                                        stats_.length_mean, stats_.length_in_range);
  stats_.seconds_edges += seconds_since(t);
  stats_.vertices_after = refine_detail::live_vertex_count(mesh_);
  stats_.tets_after = mesh_.num_live_tets();
  stats_.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return stats_;
}

}  // namespace

double metric_size(const double m[6]) {
  // Isotropic: 1/sqrt(m), correctly rounded, so a surface scaled by a power of two gets sizes
  // scaled exactly (pow is not, and an ulp moved split points and then whole meshes).
  if (m[1] == 0.0 && m[3] == 0.0 && m[4] == 0.0 && m[0] == m[2] && m[0] == m[5] && m[0] > 0.0)
    return 1.0 / std::sqrt(m[0]);
  const double det = m[0] * (m[2] * m[5] - m[4] * m[4]) - m[1] * (m[1] * m[5] - m[4] * m[3]) +
                     m[3] * (m[1] * m[4] - m[2] * m[3]);
  return det > 0.0 ? std::pow(det, -1.0 / 6.0) : 1.0;
}

size_t count_protected_facets(const TetMesh& mesh) {
  size_t n = 0;
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (mesh.is_deleted(t)) continue;
    for (int i = 0; i < 4; ++i) n += mesh.facet_protected(t, i) ? 1 : 0;
  }
  return n;
}

Result<RefineStats> refine_mesh(TetMesh& mesh, const SizingField& field, const RefineOptions& options) {
  if (options.num_threads < 0) return Status(Error::InvalidArgument, "refine: num_threads must be >= 0");
  const ScaledSizing scaled(field, options.size_scale > 0.0 ? options.size_scale : 1.0);
  Refiner refiner(mesh, scaled, options);
  if (options.num_threads == 0) return refiner.run();
  tbb::task_arena arena(options.num_threads);
  return arena.execute([&] { return refiner.run(); });
}

namespace {

// The metric volume per tet of refined and optimized meshes (sqrt(det M) vol over the tets, per
// tet), measured on the shared surfaces' meshes with the default sizing: a regular tet of unit
// edges has 1/(6 sqrt 2) = 0.118; the meshes' tets are smaller than that (their edges are spread
// around 1 and Delaunay tets are not regular).
constexpr double kMetricVolumePerTet = 0.1;

double det_sqrt(const double m[6]) {
  const double d = m[0] * (m[2] * m[5] - m[4] * m[4]) - m[1] * (m[1] * m[5] - m[4] * m[3]) +
                   m[3] * (m[1] * m[4] - m[2] * m[3]);
  return d > 0.0 ? std::sqrt(d) : 0.0;
}

}  // namespace

namespace {

// Each live tet's volume times its averaged sqrt(det M) (0 for deleted and ghost slots): the
// terms of estimate_refined_tets before its common factor.
std::vector<double> metric_volumes(const TetMesh& mesh, const SizingField& field) {
  const size_t nv = mesh.num_vertices();
  std::vector<double> at_vertex(nv, -1.0);
  std::vector<uint8_t> used(nv, 0);
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t)
    if (!mesh.is_deleted(t) && !mesh.is_ghost(t))
      for (int i = 0; i < 4; ++i) used[mesh.vertex(t, i)] = 1;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nv, 1024), [&](const tbb::blocked_range<size_t>& r) {
    double m[6];
    for (size_t v = r.begin(); v < r.end(); ++v) {
      if (!used[v]) continue;
      field.metric(mesh.point(uint32_t(v)), m);
      at_vertex[v] = det_sqrt(m);
    }
  });
  std::vector<double> terms(mesh.num_tet_slots(), 0.0);
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, mesh.num_tet_slots(), 4096), [&](const tbb::blocked_range<uint32_t>& r) {
    double m[6];
    for (uint32_t t = r.begin(); t < r.end(); ++t) {
      if (mesh.is_deleted(t) || mesh.is_ghost(t)) continue;
      const double *a = mesh.point(mesh.vertex(t, 0)), *b = mesh.point(mesh.vertex(t, 1)),
                   *c = mesh.point(mesh.vertex(t, 2)), *d = mesh.point(mesh.vertex(t, 3));
      const double centroid[3] = {(a[0] + b[0] + c[0] + d[0]) / 4, (a[1] + b[1] + c[1] + d[1]) / 4,
                                  (a[2] + b[2] + c[2] + d[2]) / 4};
      field.metric(centroid, m);
      double density = 4.0 * det_sqrt(m);
      for (int i = 0; i < 4; ++i) density += at_vertex[mesh.vertex(t, i)];
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]},
                   z[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
      const double volume = std::fabs(u[0] * (w[1] * z[2] - w[2] * z[1]) - u[1] * (w[0] * z[2] - w[2] * z[0]) +
                                      u[2] * (w[0] * z[1] - w[1] * z[0])) / 6.0;
      terms[t] = volume * density / 8.0;
    }
  });
  return terms;
}

}  // namespace

std::vector<double> estimate_refined_tets_per_tet(const TetMesh& mesh, const SizingField& field, double size_scale) {
  const double factor = 1.0 / (size_scale * size_scale * size_scale) / kMetricVolumePerTet;
  std::vector<double> terms = metric_volumes(mesh, field);
  for (double& w : terms) w *= factor;
  return terms;
}

double estimate_refined_tets(const TetMesh& mesh, const SizingField& field, double size_scale) {
  const double inv3 = 1.0 / (size_scale * size_scale * size_scale);  // sqrt(det(M / s^2)) = sqrt(det M) / s^3
  const std::vector<double> terms = metric_volumes(mesh, field);
  // (Deterministic: the same sum, bit for bit, on any number of threads; the same chunks and
  // order as when the terms were summed where computed.)
  return tbb::parallel_deterministic_reduce(
             tbb::blocked_range<uint32_t>(0, mesh.num_tet_slots(), 4096), 0.0,
             [&](const tbb::blocked_range<uint32_t>& r, double sum) {
               for (uint32_t t = r.begin(); t < r.end(); ++t)
                 if (!mesh.is_deleted(t) && !mesh.is_ghost(t)) sum += terms[t];
               return sum;
             },
             std::plus<double>()) *
         inv3 / kMetricVolumePerTet;
}

}  // namespace anitet
