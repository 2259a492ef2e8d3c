#include "delaunay/cavity_kernel.hpp"

#include <algorithm>

#include "delaunay/delaunay.hpp"
#include "predicates/predicates.hpp"

namespace anitet::delaunay_detail {

namespace {

constexpr uint32_t kGhost = TetMesh::kGhost;
constexpr uint32_t kNoNeighbour = TetMesh::kNoNeighbour;

// The facets of a ghost tet (ghost in slot 3) that contain the ghost, rotated so that the ghost
// comes last: kGhostFacet[i][k] = kFacetVertex[i][(k + kGhostFacetRot[i]) % 3].
constexpr int kGhostFacet[3][3] = {{2, 1, 3}, {0, 2, 3}, {1, 0, 3}};
constexpr uint8_t kGhostFacetRot[3] = {2, 0, 2};

// Where the vertices of a boundary triangle (v0 v1 v2) go in the new tet built on it:
// (v0 v1 v2 p), or (v1 v0 p G) when v2 is the ghost (same orientation, ghost in slot 3).
constexpr int kSlotReal[3] = {0, 1, 2};
constexpr int kSlotGhost[3] = {1, 0, 3};

constexpr int kEdgeIndex[4][4] = {{-1, 0, 1, 2}, {0, -1, 3, 4}, {1, 3, -1, 5}, {2, 4, 5, -1}};

}  // namespace

bool exactly_collinear(const double* a, const double* b, const double* c) {
  for (int d = 0; d < 3; ++d) {
    const int e = (d + 1) % 3;
    const double pa[2] = {a[d], a[e]}, pb[2] = {b[d], b[e]}, pc[2] = {c[d], c[e]};
    if (predicates::orient2d(pa, pb, pc) != 0) return false;
  }
  return true;
}

void KernelCounters::add_predicates_since(const predicates::PredicateCounters& before) {
  const predicates::PredicateCounters& now = predicates::thread_counters();
  predicates.orient2d_calls += now.orient2d_calls - before.orient2d_calls;
  predicates.orient2d_exact += now.orient2d_exact - before.orient2d_exact;
  predicates.orient3d_calls += now.orient3d_calls - before.orient3d_calls;
  predicates.orient3d_exact += now.orient3d_exact - before.orient3d_exact;
  predicates.insphere_calls += now.insphere_calls - before.insphere_calls;
  predicates.insphere_exact += now.insphere_exact - before.insphere_exact;
  predicates.orient4d_calls += now.orient4d_calls - before.orient4d_calls;
  predicates.orient4d_exact += now.orient4d_exact - before.orient4d_exact;
  predicates.sos_ties += now.sos_ties - before.sos_ties;
}

CavityKernel::CavityKernel(uint64_t seed)
    : rng_(static_cast<uint32_t>(seed ^ (seed >> 32)) | 1u), edge_table_(kTableSide * kTableSide) {}

void CavityKernel::bind(TetStorage& storage, const double* coords, size_t num_points,
                        const uint32_t* sos_ids) {
  store_ = &storage;
  coords_ = coords;
  sos_ids_ = sos_ids;
  if (local_of_.size() < num_points)
    local_of_.resize(std::max(num_points, 2 * local_of_.size()), uint8_t(0xff));
}

int CavityKernel::orient3d_slow(const double* a, const double* b, const double* c, const double* p) {
  return predicates::orient3d(a, b, c, p);
}

int CavityKernel::insphere_slow(uint32_t t, const double* p, uint32_t pid) {
  const uint32_t* v = store_->verts(t);
  return predicates::insphere_sos(pt(v[0]), pt(v[1]), pt(v[2]), pt(v[3]), p, sos_id(v[0]),
                                  sos_id(v[1]), sos_id(v[2]), sos_id(v[3]), sos_id(pid));
}

void CavityKernel::make_first_tet(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  const uint32_t t = store_->append(5);
  store_->init_tet(t, 0, 0);
  uint32_t* tv = store_->verts(t);
  tv[0] = a, tv[1] = b, tv[2] = c, tv[3] = d;
  for (int i = 0; i < 4; ++i) {
    const uint32_t g = t + 1 + static_cast<uint32_t>(i);
    store_->init_tet(g, 0, 0);
    uint32_t* gv = store_->verts(g);
    // Reversed: the hull facet faces the ghost.
    gv[0] = tv[kFacetVertex[i][0]];
    gv[1] = tv[kFacetVertex[i][2]];
    gv[2] = tv[kFacetVertex[i][1]];
    gv[3] = kGhost;
    store_->set_adj(4 * uint32_t(t) + uint32_t(i), 4 * uint32_t(g) + 3);
    store_->set_adj(4 * uint32_t(g) + 3, 4 * uint32_t(t) + uint32_t(i));
  }
  // Ghost facets through the ghost: pair those with the same two real vertices.
  for (uint32_t g = t + 1; g < t + 5; ++g)
    for (int i = 0; i < 3; ++i)
      for (uint32_t h = g + 1; h < t + 5; ++h)
        for (int j = 0; j < 3; ++j) {
          const uint32_t* gv = store_->verts(g);
          const uint32_t* hv = store_->verts(h);
          const uint32_t g0 = gv[(i + 1) % 3], g1 = gv[(i + 2) % 3];
          const uint32_t h0 = hv[(j + 1) % 3], h1 = hv[(j + 2) % 3];
          if ((g0 == h0 && g1 == h1) || (g0 == h1 && g1 == h0)) {
            store_->set_adj(4 * uint32_t(g) + uint32_t(i), 4 * uint32_t(h) + uint32_t(j));
            store_->set_adj(4 * uint32_t(h) + uint32_t(j), 4 * uint32_t(g) + uint32_t(i));
          }
        }
  last_real_ = t;
}

// A ghost tet conflicts with p when p lies strictly beyond its hull facet, or on that facet's
// plane and in conflict with the real tet behind it (inside the facet's circumcircle, ties
// broken by the same SoS as that tet's insphere).
template <bool kStorageMarks>
inline bool CavityKernel::in_conflict(uint32_t t, const double* p, uint32_t pid) {
  const uint32_t* v = store_->verts(t);
  if (v[3] != kGhost) return insphere(t, p, pid) > 0;
  const int o = orient3d(pt(v[0]), pt(v[1]), pt(v[2]), p);
  if (o != 0) return o > 0;
  const uint32_t behind = store_->adj(t, 3);
  if (behind == kNoNeighbour) return false;
  const auto r = static_cast<uint32_t>(behind >> 2);
  const uint32_t mark = kStorageMarks ? store_->mark(r) : marks_.get(r);
  if (mark != 0) return mark == kMarkIn;
  return insphere(r, p, pid) > 0;
}

bool CavityKernel::equals_vertex(uint32_t v, const double* p) const {
  const double* q = pt(v);
  return q[0] == p[0] && q[1] == p[1] && q[2] == p[2];
}

// The walk of locate() and locate_owned(): kOwned enters only tets of this part and kNoPart ones
// and gives up (kForeign) where the plain walk goes on, or falls back to a scan.
template <bool kOwned>
Location CavityKernel::walk(uint32_t t, const double* p) {
  const Location foreign{Located::kForeign, t, TetMesh::kNone};
  auto enterable = [&](uint32_t n) {
    if constexpr (kOwned) return owner(n) == me_ || owner(n) == kNoPart;
    (void)n;
    return true;
  };
  if (!enterable(t)) return foreign;
  const size_t limit = 8 * store_->num_slots() + 1024;
  int entry = -1;  // the facet we came through: p is not beyond it
  if (is_ghost(t)) {
    const uint32_t* v = store_->verts(t);
    if (orient3d(pt(v[0]), pt(v[1]), pt(v[2]), p) > 0) return {Located::kInGhost, t, TetMesh::kNone};
    const uint32_t adj = store_->adj(t, 3);
    if (adj == kNoNeighbour) return kOwned ? foreign : locate_by_scan(p);
    t = static_cast<uint32_t>(adj >> 2);
    if (!enterable(t)) return foreign;
    entry = static_cast<int>(adj & 3);
  }
  for (size_t steps = 0;; ++steps) {
    if (steps > limit) {
      if constexpr (kOwned) return foreign;
      ++counters.walk_fallbacks;
      return locate_by_scan(p);
    }
    ++counters.walk_steps;
    const uint32_t* v = store_->verts(t);
    const double* P[4] = {pt(v[0]), pt(v[1]), pt(v[2]), pt(v[3])};
    // Facets in a random cyclic order: a deterministic order can cycle forever.
    const int first = static_cast<int>(next_random() >> 30);
    int exit = -1;
    for (int k = 0; k < 4; ++k) {
      const int i = (first + k) & 3;
      if (i == entry) continue;
      const int* f = kFacetVertex[i];
      if (orient3d(P[f[0]], P[f[1]], P[f[2]], p) < 0) {
        exit = i;
        break;
      }
    }
    if (exit < 0) {
      for (int k = 0; k < 4; ++k)
        if (equals_vertex(v[k], p)) return {Located::kDuplicate, t, v[k]};
      return {Located::kInTet, t, TetMesh::kNone};
    }
    const uint32_t adj = store_->adj(t, exit);
    if (adj == kNoNeighbour) return {Located::kOutside, t, TetMesh::kNone};
    const auto n = static_cast<uint32_t>(adj >> 2);
    if (!enterable(n)) return foreign;
    if (is_ghost(n)) return {Located::kInGhost, n, TetMesh::kNone};
    t = n;
    entry = static_cast<int>(adj & 3);
  }
}

Location CavityKernel::locate(uint32_t t, const double* p) { return walk<false>(t, p); }
Location CavityKernel::locate_owned(uint32_t t, const double* p) { return walk<true>(t, p); }

// The cavity growth and filling of insert_delaunay() and insert_delaunay_owned(). kOwned gives up
// (false, marks cleared, mesh unchanged) at a tet of another part, including the real tet behind
// a hull tet whose test would read it, or when the slot pool has no room for the new tets.
template <bool kOwned>
bool CavityKernel::grow_and_fill(uint32_t t0, uint32_t pid) {
  const double* p = pt(pid);
  cavity_.clear();
  boundary_.clear();
  store_->set_mark(t0, kMarkIn);
  cavity_.push_back(t0);
  auto give_up = [&] {
    for (uint32_t c : cavity_) store_->clear_mark(c);
    for (const BoundaryFacet& b : boundary_) store_->clear_mark(static_cast<uint32_t>(b.outside >> 2));
    return false;
  };
  // Breadth-first growth over facets; every tet is tested at most once.
  for (size_t k = 0; k < cavity_.size(); ++k) {
    const uint32_t c = cavity_[k];
    uint32_t cadj[4];
    // The four neighbours are usually cache misses: request them all before testing any.
    for (int i = 0; i < 4; ++i) {
      cadj[i] = store_->adj(c, i);
      store_->prefetch_tet(static_cast<uint32_t>(cadj[i] >> 2));
      if constexpr (kOwned) __builtin_prefetch(tet_part_ + (cadj[i] >> 2));
    }
    for (int i = 0; i < 4; ++i) {
      const auto n = static_cast<uint32_t>(cadj[i] >> 2);
      // Its part first: the marks of another part's tet are not ours to read.
      if constexpr (kOwned)
        if (owner(n) != me_) return give_up();
      const uint32_t mark = store_->mark(n);
      if (mark == kMarkIn) continue;
      if (mark == 0) {
        if constexpr (kOwned)
          if (is_ghost(n) && owner(static_cast<uint32_t>(store_->adj(n, 3) >> 2)) != me_) return give_up();
        if (in_conflict<true>(n, p, pid)) {
          store_->set_mark(n, kMarkIn);
          store_->prefetch_adj(n);
          cavity_.push_back(n);
          continue;
        }
        store_->set_mark(n, kMarkOut);
        store_->prefetch_adj(n);  // its link to the new tet is written soon
      }
      add_boundary<false>(c, i, cadj[i]);
    }
  }
  if constexpr (kOwned) {
    const size_t nb = boundary_.size(), nc = cavity_.size();
    if (!store_->can_take(nb > nc ? nb - nc : 0)) return give_up();
  }
  fill_cavity(pid, false);
  if constexpr (kOwned)
    for (uint32_t t : new_tets_) tet_part_[t] = me_;
  return true;
}

bool CavityKernel::insert_delaunay_owned(uint32_t t0, uint32_t pid) {
  return owner(t0) == me_ && grow_and_fill<true>(t0, pid);
}

// The last resort when a walk does not end (possible in non-Delaunay meshes): test every tet.
Location CavityKernel::locate_by_scan(const double* p) {
  const size_t nt = store_->num_slots();
  for (uint32_t t = 0; t < nt; ++t) {
    if (store_->deleted(t) || is_ghost(t)) continue;
    const uint32_t* v = store_->verts(t);
    bool inside = true;
    for (int i = 0; i < 4 && inside; ++i) {
      const int* f = kFacetVertex[i];
      inside = orient3d(pt(v[f[0]]), pt(v[f[1]]), pt(v[f[2]]), p) >= 0;
    }
    if (!inside) continue;
    for (int k = 0; k < 4; ++k)
      if (equals_vertex(v[k], p)) return {Located::kDuplicate, t, v[k]};
    return {Located::kInTet, t, TetMesh::kNone};
  }
  for (uint32_t t = 0; t < nt; ++t) {
    if (store_->deleted(t) || !is_ghost(t)) continue;
    const uint32_t* v = store_->verts(t);
    if (orient3d(pt(v[0]), pt(v[1]), pt(v[2]), p) > 0) return {Located::kInGhost, t, TetMesh::kNone};
  }
  return {Located::kOutside, TetMesh::kNone, TetMesh::kNone};
}

template <bool kCarry>
void CavityKernel::add_boundary(uint32_t c, int i, uint32_t outside) {
  const uint32_t* cv = store_->verts(c);
  // Filled in place: a copy of a stack struct made of narrow stores stalls store forwarding.
  BoundaryFacet& b = boundary_.emplace_back();
  const int* f;
  if (cv[3] == kGhost && i != 3) {
    f = kGhostFacet[i];
    b.rot = kGhostFacetRot[i];
  } else {
    f = kFacetVertex[i];
    b.rot = 0;
  }
  b.v[0] = cv[f[0]];
  b.v[1] = cv[f[1]];
  b.v[2] = cv[f[2]];
  b.ctet = c;
  b.outside = outside;
  // The bulk build has no flags or regions to carry.
  b.region = kCarry ? store_->region(c) : 0;
  b.cflags = kCarry ? static_cast<uint16_t>(store_->flags(c) & ~(tflag::kScratchMask | tflag::kDeleted)) : 0;
  b.cfacet = static_cast<uint8_t>(i);
}

uint32_t CavityKernel::insert_delaunay(uint32_t t0, uint32_t pid) {
  grow_and_fill<false>(t0, pid);
  return last_real_;
}

void CavityKernel::collect_boundary(bool respect_protected) {
  boundary_.clear();
  for (uint32_t c : cavity_) {
    for (int i = 0; i < 4; ++i) {
      const uint32_t adj = store_->adj(c, i);
      // A protected facet bounds the cavity even when its other side is in the cavity too: the
      // side away from the new point then fails the visibility test and leaves.
      if (adj == kNoNeighbour || marks_.get(static_cast<uint32_t>(adj >> 2)) != TetMarks::kIn ||
          (respect_protected && ((store_->flags(c) >> i) & 1u)))
        add_boundary<true>(c, i, adj);
    }
  }
}

bool CavityKernel::boundary_facet_ok(const BoundaryFacet& b, const double* p) {
  if (b.v[2] != kGhost)
    return orient3d(pt(b.v[0]), pt(b.v[1]), pt(b.v[2]), p) > 0 &&
           !(degeneracy_ && degeneracy_->flat(b.v[0], b.v[1], b.v[2], pid_));
  // A facet (a b ghost): the new hull triangle (b a p) must be a proper triangle and the hull must
  // stay convex at edge ab, i.e. the third vertex d of the hull triangle across is not beyond it.
  if (b.outside == kNoNeighbour) return false;
  const uint32_t* nv = store_->verts(static_cast<uint32_t>(b.outside >> 2));
  if (nv[3] != kGhost) return false;
  uint32_t d = TetMesh::kNone;
  for (int k = 0; k < 3; ++k)
    if (nv[k] != b.v[0] && nv[k] != b.v[1]) d = nv[k];
  if (d == TetMesh::kNone) return false;
  const double *a = pt(b.v[0]), *bb = pt(b.v[1]);
  if (orient3d(bb, a, p, pt(d)) > 0) return false;
  return !exactly_collinear(a, bb, p);
}

bool CavityKernel::keep_left() const {
  for (size_t k = 0; k < keep_count_; ++k)
    if (marks_.get(keep_[k]) != TetMarks::kIn) return true;
  return false;
}

bool CavityKernel::insert_constrained(uint32_t t0, uint32_t pid, bool respect_protected, const uint32_t* keep,
                                      size_t keep_count, bool force_keep, const DegeneracyOracle* degeneracy,
                                      bool early_refusal) {
  keep_ = keep;
  keep_count_ = keep_count;
  degeneracy_ = degeneracy;
  pid_ = pid;
  foreign_hit_ = false;
  // A point in a frozen tet belongs to another part.
  frozen_hit_ = refuse_frozen_ && store_->region(t0) < 0;
  if (frozen_hit_) return false;
  cavity_.clear();
  marks_.clear();
  marks_.set(t0, TetMarks::kIn);
  cavity_.push_back(t0);
  if (force_keep)
    for (size_t k = 0; k < keep_count; ++k)
      if (marks_.get(keep[k]) == TetMarks::kNone) {
        marks_.set(keep[k], TetMarks::kIn);
        cavity_.push_back(keep[k]);
      }
  if (force_keep && early_refusal) {
    const size_t forced = cavity_.size();
    if (!kept_can_stay(respect_protected)) {
      ++counters.early_refusals;
      return false;
    }
    // Forget what the test classified, so that the cavity grows in the same order (hence gives
    // the same mesh) as without it.
    marks_.clear();
    cavity_.resize(forced);
    for (uint32_t c : cavity_) marks_.set(c, TetMarks::kIn);
  }
  // Growth visits every facet of every cavity tet once, and the marks it sets are final: the
  // facets it finds bounding the cavity are the star-shape shrinking's first work list.
  shrink_queue_.clear();
  for (size_t k = 0; k < cavity_.size() && !foreign_hit_; ++k) {
    const uint32_t c = cavity_[k];
    for (int i = 0; i < 4; ++i)
      if (bounds_for_sure(c, i, respect_protected)) shrink_queue_.push_back({c, i});
  }
  if (frozen_hit_ || foreign_hit_) return false;
  if (keep_left() || !shrink_to_star(t0, pid, respect_protected) || keep_left()) return false;
  collect_boundary(respect_protected);
  if (owned_) {
    const size_t nb = boundary_.size(), nc = cavity_.size();
    if (!store_->can_take(nb > nc ? nb - nc : 0)) {
      foreign_hit_ = true;
      return false;
    }
  }
  fill_cavity(pid, true);
  // (A reused slot keeps its part: only the pool's fresh slots are written, which no other task
  // reads.)
  if (owned_)
    for (uint32_t t : new_tets_)
      if (tet_part_[t] != me_) tet_part_[t] = me_;
  return true;
}

bool CavityKernel::insert_constrained_owned(uint32_t t0, uint32_t pid, bool respect_protected) {
  foreign_hit_ = false;
  if (owner(t0) != me_) {
    foreign_hit_ = true;
    return false;
  }
  owned_ = true;
  const bool ok = insert_constrained(t0, pid, respect_protected);
  owned_ = false;
  return ok;
}

// A cheap necessary condition for the forced kept tets (already in the cavity), tested before the
// cavity grows: each of their facets that will bound the cavity whatever it grows to (protected, on
// the hull, or facing a tet not in conflict) sees p, and so does each facet towards a neighbour
// that such a facet of its own ejects. Otherwise shrinking would eject a kept tet and the insertion
// would be refused anyway, after growing a cavity that around slivers holds thousands of tets (most
// refusals on sliver-rich fronts are caught here). Leaves marks and cavity_ changed (the neighbours
// it found in conflict join the cavity).
bool CavityKernel::kept_can_stay(bool respect_protected) {
  for (size_t k = 0; k < keep_count_; ++k) {
    const uint32_t c = keep_[k];
    for (int i = 0; i < 4; ++i) {
      if (bounds_for_sure(c, i, respect_protected)) {
        if (!facet_sees_new_point(c, i)) return false;
        continue;
      }
      // The tet n across, in the cavity: when one of its sure boundary facets hides p, n leaves
      // and this facet bounds c.
      const uint32_t adj = store_->adj(c, i);
      const auto n = static_cast<uint32_t>(adj >> 2);
      if (is_kept(n)) continue;
      bool n_leaves = false;
      for (int j = 0; j < 4 && !n_leaves; ++j)
        if (j != int(adj & 3) && bounds_for_sure(n, j, respect_protected) && !facet_sees_new_point(n, j))
          n_leaves = true;
      if (n_leaves && !facet_sees_new_point(c, i)) return false;
    }
  }
  return true;
}

// Whether facet i of cavity tet c bounds the cavity whatever else leaves it: no neighbour, a
// protected facet, or a neighbour not in conflict. Classifies the neighbour when it has no mark
// yet (joining the cavity when in conflict), as growth does; the marks it sets are final.
bool CavityKernel::bounds_for_sure(uint32_t c, int i, bool respect_protected) {
  const uint32_t adj = store_->adj(c, i);
  if (adj == kNoNeighbour) return true;
  // Owned: the tet across is read and linked whatever it is, so it must be this part's.
  if (owned_ && owner(static_cast<uint32_t>(adj >> 2)) != me_) {
    foreign_hit_ = true;
    return true;
  }
  if (respect_protected && ((store_->flags(c) >> i) & 1u)) {
    if (refuse_frozen_ && !frozen_hit_) {
      const auto n = static_cast<uint32_t>(adj >> 2);
      frozen_hit_ = store_->region(n) < 0 && in_conflict<false>(n, pt(pid_), pid_);
    }
    return true;
  }
  const auto n = static_cast<uint32_t>(adj >> 2);
  uint32_t mark = marks_.get(n);
  if (mark == TetMarks::kNone) {
    mark = in_conflict<false>(n, pt(pid_), pid_) ? TetMarks::kIn : TetMarks::kOut;
    marks_.set(n, mark);
    if (mark == TetMarks::kIn) cavity_.push_back(n);
  }
  return mark == TetMarks::kOut;
}

// Coning facet i of cavity tet c to the new point makes a positive tet (boundary_facet_ok()).
bool CavityKernel::facet_sees_new_point(uint32_t c, int i) {
  boundary_.clear();
  add_boundary<true>(c, i, store_->adj(c, i));
  return boundary_facet_ok(boundary_[0], pt(pid_));
}

bool CavityKernel::is_kept(uint32_t t) const {
  return std::find(keep_, keep_ + keep_count_, t) != keep_ + keep_count_;
}

bool CavityKernel::is_boundary_facet(uint32_t c, int i, bool respect_protected) const {
  const uint32_t adj = store_->adj(c, i);
  // A protected facet bounds the cavity even when its other side is in the cavity too.
  return adj == kNoNeighbour || marks_.get(static_cast<uint32_t>(adj >> 2)) != TetMarks::kIn ||
         (respect_protected && ((store_->flags(c) >> i) & 1u));
}

// Shrinks the cavity until every boundary facet sees p strictly from the cavity side: then it is
// star-shaped from p and coning its boundary to p gives positive tets only. A work list of facets:
// when a tet leaves, only its facets shared with cavity tets become new boundary facets to test,
// so the cost is linear in the cavity (re-collecting the whole boundary after each round was
// quadratic on the huge cavities of sliver regions). On entry shrink_queue_ holds the boundary
// facets growth found. False when t0 or a kept tet has to leave (the insertion is then refused:
// no need to finish).
bool CavityKernel::shrink_to_star(uint32_t t0, uint32_t pid, bool respect_protected) {
  auto take_out = [&](uint32_t c) {
    marks_.set(c, TetMarks::kOut);
    for (int j = 0; j < 4; ++j) {
      const uint32_t adj = store_->adj(c, j);
      if (adj == kNoNeighbour) continue;
      const auto n = static_cast<uint32_t>(adj >> 2);
      if (marks_.get(n) == TetMarks::kIn) shrink_queue_.push_back({n, static_cast<int>(adj & 3)});
    }
  };
  for (;;) {
    while (!shrink_queue_.empty()) {
      const auto [c, i] = shrink_queue_.back();
      shrink_queue_.pop_back();
      if (marks_.get(c) != TetMarks::kIn || !is_boundary_facet(c, i, respect_protected)) continue;
      if (facet_sees_new_point(c, i)) continue;
      take_out(c);
      if (marks_.get(t0) != TetMarks::kIn) return false;
      if (keep_count_ > 0 && is_kept(c)) return false;
    }
    cavity_.erase(std::remove_if(cavity_.begin(), cavity_.end(),
                                 [this](uint32_t t) { return marks_.get(t) != TetMarks::kIn; }),
                  cavity_.end());
    if (!respect_protected) return true;
    ejected_.clear();
    if (!defend_constrained_edges(t0, pid)) return true;
    for (uint32_t c : ejected_) {
      marks_.set(c, TetMarks::kIn);  // take_out() sets it again and queues its cavity neighbours
      take_out(c);
    }
    if (marks_.get(t0) != TetMarks::kIn) return false;
  }
}

// A constrained edge must keep a tet outside the cavity (else coning would delete it): when all
// the tets around one are in the cavity, one of them other than t0 leaves. True when one left.
bool CavityKernel::closure_contains(uint32_t t, const double* p) {
  const uint32_t* v = store_->verts(t);
  if (v[3] == kGhost) return orient3d(pt(v[0]), pt(v[1]), pt(v[2]), p) >= 0;
  for (int i = 0; i < 4; ++i) {
    const int* f = kFacetVertex[i];
    if (orient3d(pt(v[f[0]]), pt(v[f[1]]), pt(v[f[2]]), p) < 0) return false;
  }
  return true;
}

// A tet whose closure holds the new point must stay (or the point would end on the cavity's
// boundary), so another tet of the edge's ring is chosen.
bool CavityKernel::defend_constrained_edges(uint32_t t0, uint32_t pid) {
  bool removed = false;
  for (uint32_t c : cavity_) {
    if (marks_.get(c) != TetMarks::kIn) continue;
    const uint16_t f = store_->flags(c);
    if (!(f & tflag::kEdgeConstrainedMask)) continue;
    for (int k = 0; k < 6 && marks_.get(c) == TetMarks::kIn; ++k) {
      if (!(f & tflag::edge_constrained_bit(k))) continue;
      const uint32_t* cv = store_->verts(c);
      const uint32_t a = cv[kEdgeVertex[k][0]], b = cv[kEdgeVertex[k][1]];
      // Walk around edge ab: leave each tet through the facet (a b y) opposite its vertex x.
      uint32_t t = c, x = kGhost, y = kGhost;
      for (int i = 0, n = 0; i < 4; ++i)
        if (i != kEdgeVertex[k][0] && i != kEdgeVertex[k][1]) (n++ == 0 ? x : y) = cv[i];
      bool all_in = true, kept_in_ring = false;
      uint32_t eject = TetMesh::kNone;
      for (size_t steps = 0; steps < 1024; ++steps) {
        if (marks_.get(t) != TetMarks::kIn) {
          all_in = false;
          break;
        }
        if (t != t0 && eject == TetMesh::kNone && !closure_contains(t, pt(pid))) {
          if (is_kept(t)) kept_in_ring = true;
          else eject = t;
        }
        const uint32_t* tv = store_->verts(t);
        int ix = -1;
        for (int i = 0; i < 4; ++i)
          if (tv[i] == x) ix = i;
        const uint32_t adj = ix < 0 ? kNoNeighbour : store_->adj(t, ix);
        if (adj == kNoNeighbour) {
          all_in = false;
          break;
        }
        const auto n = static_cast<uint32_t>(adj >> 2);
        const uint32_t* nv = store_->verts(n);
        uint32_t z = kGhost;
        for (int i = 0; i < 4; ++i)
          if (nv[i] != a && nv[i] != b && nv[i] != y) z = nv[i];
        x = y;
        y = z;
        t = n;
        if (t == c) break;
      }
      if (all_in && eject != TetMesh::kNone) {
        marks_.set(eject, TetMarks::kOut);
        ejected_.push_back(eject);
        removed = true;
      } else if (all_in && kept_in_ring) {
        // Only kept tets could leave: the edge would be lost, so the insertion is refused.
        marks_.set(t0, TetMarks::kOut);
        ejected_.push_back(t0);
        return true;
      }
    }
  }
  if (removed)
    cavity_.erase(std::remove_if(cavity_.begin(), cavity_.end(),
                                 [this](uint32_t t) { return marks_.get(t) != TetMarks::kIn; }),
                  cavity_.end());
  return removed;
}

void CavityKernel::take_slots(size_t count) {
  new_tets_.clear();
  const size_t reuse = std::min(count, cavity_.size());
  new_tets_.insert(new_tets_.end(), cavity_.begin(), cavity_.begin() + static_cast<ptrdiff_t>(reuse));
  size_t need = count - reuse;
  uint32_t t;
  while (need > 0 && store_->reuse_free(t)) {
    new_tets_.push_back(t);
    --need;
  }
  if (need == 0) return;
  const uint32_t first = store_->append(need);
  for (size_t k = 0; k < need; ++k) new_tets_.push_back(first + static_cast<uint32_t>(k));
}

uint8_t CavityKernel::local_id(uint32_t v) {
  if (v == kGhost) {
    if (ghost_local_ < 0) {
      if (local_vertices_.size() + 1 >= size_t(kTableSide)) return 0xff;
      ghost_local_ = static_cast<int>(local_vertices_.size());
      local_vertices_.push_back(kGhost);
    }
    return static_cast<uint8_t>(ghost_local_);
  }
  uint8_t& l = local_of_[v];
  if (l == 0xff) {
    if (local_vertices_.size() + 1 >= size_t(kTableSide)) return 0xff;
    l = static_cast<uint8_t>(local_vertices_.size());
    local_vertices_.push_back(v);
  }
  return l;
}

void CavityKernel::fill_cavity(uint32_t pid, bool carry) {
  const size_t nb = boundary_.size(), nc = cavity_.size();
  counters.cavity_tets += nc;
  counters.tets_created += nb;
  take_slots(nb);
  for (size_t k = nb; k < nc; ++k) store_->release(cavity_[k]);

  last_real_ = new_tets_[0];
  bool found_real = false;
  for (size_t k = 0; k < nb; ++k) {
    const BoundaryFacet& b = boundary_[k];
    const uint32_t s = new_tets_[k];
    uint32_t* w = store_->verts(s);
    const bool ghost = b.v[2] == kGhost;
    const int* slot = ghost ? kSlotGhost : kSlotReal;
    const int ps = ghost ? 2 : 3;  // the slot of p, opposite the boundary facet
    if (ghost) {
      w[0] = b.v[1];
      w[1] = b.v[0];
      w[2] = pid;
      w[3] = kGhost;
    } else {
      w[0] = b.v[0];
      w[1] = b.v[1];
      w[2] = b.v[2];
      w[3] = pid;
      if (!found_real) {
        found_real = true;
        last_real_ = s;
      }
    }
    const uint32_t hf = 4 * uint32_t(s) + uint32_t(ps);
    store_->set_adj(hf, b.outside);
    if (b.outside != kNoNeighbour) {
      store_->set_adj(b.outside, hf);
      store_->clear_mark(static_cast<uint32_t>(b.outside >> 2));
    }
    if (!carry) {  // bulk build: no flags to carry, and every region is 0 already
      store_->clear_flags(s);
      continue;
    }
    uint16_t flags = 0;
    {
      if ((b.cflags >> b.cfacet) & 1u) flags = static_cast<uint16_t>(1u << ps);
      if (b.cflags & tflag::kEdgeConstrainedMask) {
        // Constrained edges of the boundary triangle keep their bit in the new tet.
        for (int k0 = 0; k0 < 3; ++k0) {
          const int k1 = (k0 + 1) % 3;
          const int c0 = kFacetVertex[b.cfacet][(k0 + b.rot) % 3];
          const int c1 = kFacetVertex[b.cfacet][(k1 + b.rot) % 3];
          if (b.cflags & tflag::edge_constrained_bit(kEdgeIndex[c0][c1]))
            flags |= tflag::edge_constrained_bit(kEdgeIndex[slot[k0]][slot[k1]]);
        }
      }
    }
    store_->init_tet(s, flags, b.region);
  }

  // Adjacency between the new tets: each one's facet through p and boundary edge (a b) meets the
  // new tet on the other boundary triangle with that edge, which runs (b a) there.
  bool small = nb / 2 + 2 < size_t(kTableSide);
  if (small) {
    for (BoundaryFacet& b : boundary_) {
      for (int k = 0; k < 3; ++k) {
        b.lid[k] = local_id(b.v[k]);
        if (b.lid[k] == 0xff) small = false;
      }
      if (!small) break;
    }
  }
  if (small) link_by_table();
  else link_by_sort();
  for (uint32_t v : local_vertices_)
    if (v != kGhost) local_of_[v] = 0xff;
  local_vertices_.clear();
  ghost_local_ = -1;
}

void CavityKernel::link_by_table() {
  uint32_t* table = edge_table_.data();
  const size_t nb = boundary_.size();
  for (size_t k = 0; k < nb; ++k) {
    const BoundaryFacet& b = boundary_[k];
    const int* slot = b.v[2] == kGhost ? kSlotGhost : kSlotReal;
    const uint32_t base = 4 * uint32_t(new_tets_[k]);
    table[b.lid[1] * kTableSide + b.lid[2]] = base + uint32_t(slot[0]);
    table[b.lid[2] * kTableSide + b.lid[0]] = base + uint32_t(slot[1]);
    table[b.lid[0] * kTableSide + b.lid[1]] = base + uint32_t(slot[2]);
  }
  for (size_t k = 0; k < nb; ++k) {
    const BoundaryFacet& b = boundary_[k];
    const int* slot = b.v[2] == kGhost ? kSlotGhost : kSlotReal;
    const uint32_t base = 4 * uint32_t(new_tets_[k]);
    store_->set_adj(base + uint32_t(slot[0]), table[b.lid[2] * kTableSide + b.lid[1]]);
    store_->set_adj(base + uint32_t(slot[1]), table[b.lid[0] * kTableSide + b.lid[2]]);
    store_->set_adj(base + uint32_t(slot[2]), table[b.lid[1] * kTableSide + b.lid[0]]);
  }
}

void CavityKernel::link_by_sort() {
  edges_.clear();
  const size_t nb = boundary_.size();
  for (size_t k = 0; k < nb; ++k) {
    const BoundaryFacet& b = boundary_[k];
    const int* slot = b.v[2] == kGhost ? kSlotGhost : kSlotReal;
    const uint32_t base = 4 * uint32_t(new_tets_[k]);
    for (int e = 0; e < 3; ++e) {
      const uint64_t key = (uint64_t(b.v[(e + 1) % 3]) << 32) | b.v[(e + 2) % 3];
      edges_.push_back({key, base + uint32_t(slot[e])});
    }
  }
  std::sort(edges_.begin(), edges_.end(),
            [](const DirectedEdge& x, const DirectedEdge& y) { return x.key < y.key; });
  for (const DirectedEdge& e : edges_) {
    const uint64_t reverse = (e.key << 32) | (e.key >> 32);
    auto it = std::lower_bound(edges_.begin(), edges_.end(), reverse,
                               [](const DirectedEdge& x, uint64_t key) { return x.key < key; });
    store_->set_adj(e.half_face, (it != edges_.end() && it->key == reverse) ? it->half_face : kNoNeighbour);
  }
}

}  // namespace anitet::delaunay_detail
