// The Bowyer-Watson insertion kernel shared by delaunay_tetrahedralize() and PointInserter
// (internal header).
//
// It works on a TetMesh's arrays through TetStorage (tet_storage.hpp). The coordinates it reads
// are given separately (vertex v at coords[3v]): the bulk build works on a copy of the points in
// insertion order, so the points of neighbouring tets sit close in memory, and renumbers the mesh
// at the end.
//
// No heap allocation per insertion once the scratch vectors have grown.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/tet_mesh.hpp"
#include "delaunay/static_filters.hpp"
#include "delaunay/tet_marks.hpp"
#include "delaunay/tet_storage.hpp"
#include "predicates/predicates.hpp"

namespace anitet {
class DegeneracyOracle;  // delaunay.hpp
}

namespace anitet::delaunay_detail {

// Exact test: a, b, c on one line (all three coordinate projections degenerate).
bool exactly_collinear(const double* a, const double* b, const double* c);

struct KernelCounters {
  uint64_t walk_steps = 0;
  uint64_t walk_fallbacks = 0;
  uint64_t early_refusals = 0;
  uint64_t cavity_tets = 0;
  uint64_t tets_created = 0;
  uint64_t orient3d_calls = 0, insphere_calls = 0;  // all calls, static filter included
  predicates::PredicateCounters predicates;  // calls made on behalf of the kernel

  // Adds this thread's predicate calls since `before` (a copy of thread_counters()).
  void add_predicates_since(const predicates::PredicateCounters& before);
};

// Copies the counters into the public stats.
template <class Stats>
void copy_counters(const KernelCounters& c, Stats& s) {
  s.walk_steps = c.walk_steps;
  s.walk_fallbacks = c.walk_fallbacks;
  s.early_refusals = c.early_refusals;
  s.cavity_tets = c.cavity_tets;
  s.tets_created = c.tets_created;
  s.orient3d_calls = c.orient3d_calls;
  s.orient3d_exact = c.predicates.orient3d_exact;
  s.insphere_calls = c.insphere_calls;
  s.insphere_exact = c.predicates.insphere_exact;
  s.sos_ties = c.predicates.sos_ties;
}

enum class Located {
  kInTet,      // a real tet whose closure contains the point
  kInGhost,    // a ghost tet whose hull facet the point lies strictly beyond
  kDuplicate,  // the point equals a vertex
  kOutside,    // the walk left the mesh through a facet without neighbour
  kForeign,    // locate_owned(): the walk met a tet of another part (or went on too long)
};

struct Location {
  Located what;
  uint32_t tet;     // the tet found (kInTet, kInGhost) or the last one visited
  uint32_t vertex;  // kDuplicate: the vertex at the point
};

class CavityKernel {
 public:
  explicit CavityKernel(uint64_t seed);

  // Points the kernel at a storage and at the coordinates its predicates read (num_points
  // vertices at coords[3v]); sos_ids[v] is vertex v's id for Simulation of Simplicity (null: v
  // itself). Call again whenever the mesh grew or the coordinates may have moved.
  void bind(TetStorage& storage, const double* coords, size_t num_points, const uint32_t* sos_ids);

  // Enables the static filters for queries whose coordinate differences with every vertex are
  // at most `extent` (the points' bounding box; a larger box is fine, a smaller one is not).
  // Until then every predicate goes through the predicates module.
  void set_extent(double extent) { filters_ = StaticFilters::for_extent(extent); }

  // The first tet (a b c d, positive) and the four ghost tets around it, in an empty mesh.
  void make_first_tet(uint32_t a, uint32_t b, uint32_t c, uint32_t d);

  // Randomized visibility walk from live tet `start` towards p.
  Location locate(uint32_t start, const double* p);

  // Plain Delaunay insertion of vertex pid from the conflicting tet t0 (from locate), for the bulk
  // build: no protected facets, no regions or constrained edges to carry, marks in tet_flags.
  // Returns one of the new tets, a good start for the next walk.
  uint32_t insert_delaunay(uint32_t t0, uint32_t pid);

  // Modified kernel: the cavity stops at protected facets (when asked) and at facets without a
  // neighbour, then shrinks until star-shaped from pid. Returns false, leaving the mesh
  // unchanged, when t0 itself has to leave the cavity, or one of the `keep` tets is not in it
  // (the caller needs the new vertex joined to their vertices; no constrained edge ejects them:
  // when only kept tets could leave a constrained edge's ring, the insertion is refused).
  // force_keep: the `keep` tets start in the cavity whatever the empty-sphere test says.
  // early_refusal: with force_keep, kept_can_stay() first.
  bool insert_constrained(uint32_t t0, uint32_t pid, bool respect_protected, const uint32_t* keep = nullptr,
                          size_t keep_count = 0, bool force_keep = false,
                          const DegeneracyOracle* degeneracy = nullptr, bool early_refusal = true);

  // insert_constrained() refuses the point when a protected facet of the cavity has a frozen
  // tet (negative region) in conflict behind it (InsertOptions::refuse_frozen_conflict).
  void set_refuse_frozen(bool on) { refuse_frozen_ = on; }

  // Parallel bulk build (delaunay.cpp): tet t belongs to part tet_part[t] (kNoPart: none), the
  // part of all its real vertices; the tets a task creates are its part's. While tasks run, each
  // on its own part with its own kernel and slot pool, a task writes only tets of its part and
  // reads only those and kNoPart tets, which no task writes: a tet of another part is read (its
  // part) only where it touches a tet the task stands on, and such a tet no other task can
  // change. So the tasks need no locks, and what each does does not depend on the others' timing.
  static constexpr uint8_t kNoPart = 0xff;
  void set_part(uint8_t* tet_part, uint8_t me) {
    tet_part_ = tet_part;
    me_ = me;
  }
  uint8_t owner(uint32_t t) const { return tet_part_[t]; }
  // locate() that walks only through tets of this part and kNoPart ones: kForeign when the walk
  // would enter another part's tet, or runs long (no scan of the mesh here).
  Location locate_owned(uint32_t start, const double* p);
  // insert_delaunay() when t0, the cavity and every tet around it are of this part, and the slot
  // pool has room; else false, the mesh unchanged (the caller inserts the point later).
  bool insert_delaunay_owned(uint32_t t0, uint32_t pid);

  // insert_constrained() (no kept tets, no degeneracy oracle) under the same rule, for the
  // parallel batches of BatchInserter: t0, every cavity tet and every tet across a facet of one
  // (protected or not: fill_cavity() links them to the new tets) must be of this part, and the
  // slot pool must have room; else false, the mesh unchanged, and foreign_refusal() says so
  // (the caller inserts the point later, in order). A false with foreign_refusal() unset is the
  // plain kernel's own refusal.
  bool insert_constrained_owned(uint32_t t0, uint32_t pid, bool respect_protected);
  bool foreign_refusal() const { return foreign_hit_; }

  // The tets created by the last insertion.
  const std::vector<uint32_t>& new_tets() const { return new_tets_; }
  // A non-ghost tet among them when there is one.
  uint32_t last_real_tet() const { return last_real_; }

  KernelCounters counters;

 private:
  // A cavity boundary facet, seen from the cavity tet `ctet` (its facet `cfacet`). v[] is that
  // facet oriented with its normal into the cavity, rotated so that a ghost vertex comes last.
  struct BoundaryFacet {
    uint32_t v[3];
    uint32_t ctet;
    uint32_t outside;  // the half-face across, or kNoNeighbour
    int32_t region;
    uint16_t cflags;   // the cavity tet's flags (protected facet, constrained edges)
    uint8_t cfacet;
    uint8_t rot;       // v[k] is the cavity tet's vertex kFacetVertex[cfacet][(k + rot) % 3]
    uint8_t lid[3];    // local vertex ids while filling
  };

  const double* pt(uint32_t v) const { return coords_ + 3 * size_t(v); }
  uint32_t sos_id(uint32_t v) const { return sos_ids_ ? sos_ids_[v] : v; }
  bool is_ghost(uint32_t t) const { return store_->verts(t)[3] == TetMesh::kGhost; }
  uint32_t next_random() {
    rng_ ^= rng_ << 13;
    rng_ ^= rng_ >> 17;
    rng_ ^= rng_ << 5;
    return rng_;
  }

  // Static filter inline, the predicates module out of line.
  [[gnu::always_inline]] int orient3d(const double* a, const double* b, const double* c, const double* p) {
    ++counters.orient3d_calls;
    const int s = orient3d_static(a, b, c, p, filters_.orient3d_bound);
    return s != kUnknown ? s : orient3d_slow(a, b, c, p);
  }
  [[gnu::always_inline]] int insphere(uint32_t t, const double* p, uint32_t pid) {
    const uint32_t* v = store_->verts(t);
    ++counters.insphere_calls;
    const int s = insphere_static(pt(v[0]), pt(v[1]), pt(v[2]), pt(v[3]), p, filters_.insphere_bound);
    return s != kUnknown ? s : insphere_slow(t, p, pid);
  }
  [[gnu::noinline]] int orient3d_slow(const double* a, const double* b, const double* c, const double* p);
  [[gnu::noinline]] int insphere_slow(uint32_t t, const double* p, uint32_t pid);

  template <bool kStorageMarks>
  bool in_conflict(uint32_t t, const double* p, uint32_t pid);
  template <bool kOwned>
  Location walk(uint32_t t, const double* p);
  template <bool kOwned>
  bool grow_and_fill(uint32_t t0, uint32_t pid);
  Location locate_by_scan(const double* p);
  bool equals_vertex(uint32_t v, const double* p) const;

  template <bool kCarry>
  void add_boundary(uint32_t c, int i, uint32_t outside);
  void collect_boundary(bool respect_protected);
  bool defend_constrained_edges(uint32_t t0, uint32_t pid);
  bool kept_can_stay(bool respect_protected);
  bool bounds_for_sure(uint32_t c, int i, bool respect_protected);
  bool facet_sees_new_point(uint32_t c, int i);
  bool is_kept(uint32_t t) const;
  bool shrink_to_star(uint32_t t0, uint32_t pid, bool respect_protected);
  bool is_boundary_facet(uint32_t c, int i, bool respect_protected) const;
  bool closure_contains(uint32_t t, const double* p);
  bool boundary_facet_ok(const BoundaryFacet& b, const double* p);
  // carry: copy protected / constrained-edge bits and regions from the cavity to the new tets.
  void fill_cavity(uint32_t pid, bool carry);
  void link_by_table();
  void link_by_sort();
  uint8_t local_id(uint32_t v);
  void take_slots(size_t count);

  TetStorage* store_ = nullptr;
  uint8_t* tet_part_ = nullptr;
  uint8_t me_ = kNoPart;
  const double* coords_ = nullptr;
  const uint32_t* sos_ids_ = nullptr;
  uint32_t rng_;
  StaticFilters filters_;

  std::vector<uint32_t> cavity_;
  std::vector<std::pair<uint32_t, int>> shrink_queue_;  // cavity facets to test for visibility
  bool keep_left() const;  // a tet of keep_ is out of the cavity
  const uint32_t* keep_ = nullptr;
  size_t keep_count_ = 0;
  const DegeneracyOracle* degeneracy_ = nullptr;  // insert_constrained()'s, else null
  bool refuse_frozen_ = false;  // set_refuse_frozen()
  bool owned_ = false;          // insert_constrained_owned() is running
  bool foreign_hit_ = false;    // it met a tet of another part (or the pool was short)
  bool frozen_hit_ = false;     // this insertion met a frozen tet in conflict
  uint32_t pid_ = TetMesh::kNone;                // the point being inserted (for degeneracy_)
  std::vector<uint32_t> ejected_;                      // tets defend_constrained_edges() took out
  std::vector<BoundaryFacet> boundary_;
  TetMarks marks_;  // the constrained path's marks (the storage's marks serve the bulk build)
  std::vector<uint32_t> new_tets_;
  uint32_t last_real_ = TetMesh::kNone;

  // Local ids (0..62) of the boundary vertices (0xff: none) and the directed-edge table they
  // index. A per-vertex byte array beat a small hash table here.
  static constexpr int kTableSide = 64;
  std::vector<uint8_t> local_of_;
  std::vector<uint32_t> local_vertices_;
  int ghost_local_ = -1;
  std::vector<uint32_t> edge_table_;
  struct DirectedEdge {
    uint64_t key;
    uint32_t half_face;
  };
  std::vector<DirectedEdge> edges_;
};

}  // namespace anitet::delaunay_detail
