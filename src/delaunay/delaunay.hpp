// Incremental 3D Delaunay triangulation on TetMesh, and the modified Delaunay kernel that later
// stages (boundary recovery, refinement, CVT) use to insert points one at a time.
//
// delaunay_tetrahedralize() builds the Delaunay triangulation of a point set: points are inserted
// in a biased randomized order (BRIO) sorted along a Hilbert curve inside each round, each one
// located by a randomized visibility walk from the last created tet, and inserted with the
// Bowyer-Watson cavity (exact insphere, ties broken by Simulation of Simplicity on the input point
// ids, so cospherical inputs such as grids are handled). A ghost vertex closes the convex hull (see
// core/tet_mesh.hpp). Same input, same options: same mesh, bit for bit.
//
// PointInserter (and the insert_point() shorthand) inserts one point into an existing mesh: the
// cavity never crosses a protected facet, keeps a tet of every constrained edge out, and is then
// shrunk until it is star-shaped from the new point, so every new tet is positive and no protected
// facet or constrained edge is destroyed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/bvh.hpp"
#include "core/status.hpp"
#include "core/tet_mesh.hpp"
#include "delaunay/slab_parts.hpp"

namespace anitet {

struct DelaunayOptions {
  uint64_t seed = 0x5eed;  // randomization of the insertion order and of the walk
  double brio_ratio = 0.25;  // each BRIO round holds this share of the points of the next one
  size_t brio_min_round = 1024;  // the first round holds at most this many points
  // Parallel build: a round of at least parallel_min_round points is cut into `partitions` slabs
  // along the longest axis, each filled by its own task (on as many threads as the TBB arena has),
  // then the points a task left (their cavity reached another slab) in slabs along the next axis,
  // then the rest one by one. The mesh depends on `partitions`, never on the thread count.
  // partitions = 1: one point at a time throughout.
  int partitions = 2;
  size_t parallel_min_round = 32768;
};

// An input point that was not inserted because an earlier point has the same coordinates.
struct DuplicatePoint {
  uint32_t point;    // input index of the duplicate
  uint32_t same_as;  // input index of the inserted point with the same coordinates
};

struct DelaunayStats {
  size_t num_points = 0;     // input points
  size_t num_inserted = 0;   // points that are mesh vertices (num_points - duplicates)
  size_t num_tets = 0;       // live tets, ghosts excluded
  size_t num_ghost_tets = 0; // = number of convex hull triangles
  std::vector<DuplicatePoint> duplicates;

  double seconds_sort = 0;    // BRIO + Hilbert ordering
  double seconds_insert = 0;  // walks and cavities, renumbering
  double seconds_total = 0;

  uint64_t walk_steps = 0;       // tets visited by the walks
  uint64_t cavity_tets = 0;      // tets removed by cavities (sum over insertions)
  uint64_t tets_created = 0;     // tets created by cavities (sum over insertions)
  uint64_t walk_fallbacks = 0;  // walks that gave up and located the point by a full scan
  uint64_t parallel_points = 0;  // points inserted by the parallel tasks (DelaunayOptions::partitions)
  uint64_t early_refusals = 0;   // PointInserter: refused before the cavity grew (InsertOptions::early_refusal)
  // Predicate calls (the kernel's own static filter included) and how many reached the exact
  // stages of src/predicates (from predicates::thread_counters()).
  uint64_t orient3d_calls = 0, orient3d_exact = 0;
  uint64_t insphere_calls = 0, insphere_exact = 0;
  uint64_t sos_ties = 0;
};

// Replaces the contents of `mesh` with the Delaunay tetrahedralization of the n points
// xyz[3i..3i+2]. Vertex i of the mesh is input point i (duplicates stay as unused vertices and are
// listed in the stats). Ghost tets close the convex hull. Fails with InvalidArgument when fewer
// than four points are affinely independent, NonFiniteCoordinate on NaN or infinity.
Result<DelaunayStats> delaunay_tetrahedralize(TetMesh& mesh, const double* xyz, size_t n,
                                              const DelaunayOptions& options = {});

enum class InsertStatus {
  kInserted = 0,
  kDuplicate,        // the point coincides with an existing vertex (InsertResult::vertex)
  kBlocked,          // the tet containing the point cannot join the cavity: the point lies on a
                     // protected facet, or no star-shaped cavity around it exists
  kOutsideMesh,      // the point lies beyond a facet without neighbour (a mesh without ghosts)
  kInvalidMesh,      // the mesh has no live tet
  kInvalidPoint,     // a coordinate is NaN or infinite
};
const char* insert_status_name(InsertStatus s);

// Tells which tets are flat in exact geometry although their rounded points make a positive
// one: a Steiner point computed on a segment or a plane lies on it only to rounding, so three
// points of one input segment, or four of one plane, can pass the exact orient3d with a volume
// of rounding size, and such slivers then hide the constraints around them from every later test.
class DegeneracyOracle {
 public:
  virtual ~DegeneracyOracle() = default;
  // True when the tet (a b c d) would be flat if every point were exactly where it belongs.
  virtual bool flat(uint32_t a, uint32_t b, uint32_t c, uint32_t d) const = 0;
};

struct InsertOptions {
  // Protected facets stop the cavity, and constrained edges (tflag edge bits) keep at least one
  // of their tets out of it, so both survive the insertion.
  bool respect_protected = true;
  uint8_t vertex_flags = 0;       // vflag bits of the new vertex
  // Tets that must be in the cavity (the new vertex is then joined to all their vertices): the
  // insertion is refused (kBlocked) when the empty-sphere test or the shrinking leaves one out.
  const uint32_t* keep_tets = nullptr;
  size_t keep_count = 0;
  // The keep_tets join the cavity whatever the empty-sphere test says (the cavity then grows from
  // them by that test as usual); only the star-shape shrinking may refuse the point. A point of a
  // missing segment is then joined to its end through a chain of tets that is not Delaunay.
  bool force_keep = false;
  // When set, the cavity is also shrunk where coning a boundary facet to the new point would make
  // a tet this oracle calls flat (as the exact orient3d does with a zero volume). The new vertex
  // is mesh.num_vertices() - 1 while it is asked.
  const DegeneracyOracle* degeneracy = nullptr;
  // With force_keep: refuse the point before growing the cavity when a quick local test shows
  // the shrinking would eject a kept tet (same outcome, same mesh; off only to compare).
  bool early_refusal = true;
  // A point in a frozen tet (a negative region: the halo of a part in distributed/), or whose
  // cavity has a protected facet with a frozen tet in conflict behind it, is refused (kBlocked):
  // its Delaunay cavity would take a tet of another part, so the point waits for the round
  // where that part is its own.
  // Cutting the cavity short there instead left tets that no later insertion removes.
  bool refuse_frozen_conflict = false;
};

struct InsertResult {
  InsertStatus status = InsertStatus::kInvalidMesh;
  uint32_t vertex = TetMesh::kNone;  // kInserted: the new vertex; kDuplicate: the existing one
  uint32_t tet = TetMesh::kNone;     // the tet where the point was located
  bool ok() const { return status == InsertStatus::kInserted; }
};

namespace delaunay_detail {
class CavityKernel;
}

// Inserts points one at a time into a mesh (modified Delaunay kernel). Keeps its scratch memory
// between calls, so reuse one inserter for many points. The mesh must not be modified by others
// between two inserts if the default hint (the last created tet) is used. The kernel's static
// filters are sized by the bounding box of the vertices the inserter has seen (each insert looks
// at the vertices added since): a caller that moves a vertex keeps it inside that box (a move
// inside a mesh whose boundary vertices stay put does).
class PointInserter {
 public:
  explicit PointInserter(TetMesh& mesh, uint64_t seed = 0x5eed);
  ~PointInserter();
  PointInserter(const PointInserter&) = delete;
  PointInserter& operator=(const PointInserter&) = delete;

  // Inserts p. The walk starts at `hint` when it is a live tet, else at the last created tet.
  // On success the new vertex is mesh.num_vertices() - 1; on failure the mesh is unchanged.
  InsertResult insert(const double p[3], uint32_t hint = TetMesh::kNone,
                      const InsertOptions& options = {});

  // The tets created by the last successful insert (all contain the new vertex).
  const std::vector<uint32_t>& new_tets() const;
  // Counters accumulated over all inserts (time fields unused).
  DelaunayStats stats() const;

 private:
  TetMesh& mesh_;
  std::unique_ptr<delaunay_detail::CavityKernel> kernel_;
  uint32_t last_tet_ = TetMesh::kNone;
  delaunay_detail::VertexBox box_;  // of the vertices, for the static filters
  void see_new_vertices();
};

// What BatchInserter::insert() did with point i of its batch: status[i], and vertex[i] the new
// vertex (kNone unless inserted). created_begin(i) .. created_end(i): the tets its insertion
// created; later points of the batch may have replaced some of them since (a slot may hold
// another tet, or be free): read them as live slots near the point, not as the point's star.
struct BatchInsertion {
  std::vector<InsertStatus> status;
  std::vector<uint32_t> vertex;
  size_t parallel = 0;  // points inserted by the parallel tasks
  size_t deferred = 0;  // points the tasks left to the one-by-one inserts (their cavity left its slab)

  const uint32_t* created_begin(size_t i) const { return lists[list[i]].data() + first[i]; }
  const uint32_t* created_end(size_t i) const { return created_begin(i) + count[i]; }

  // Where the tets are: the lists of the tasks and of the one-by-one inserts as they made them
  // (not copied into one), and per point its list, first tet and count.
  std::vector<std::vector<uint32_t>> lists;
  std::vector<uint8_t> list;
  std::vector<uint32_t> first, count;
};

// Inserts a batch of points with PointInserter's kernel (InsertOptions: respect_protected,
// vertex_flags and refuse_frozen_conflict; no kept tets, no degeneracy oracle).
// A batch of at least parallel_min points is cut into `partitions` slabs at quantiles along the
// longest axis of the points' box; one task per slab inserts its points, in batch order, into
// the tets all of whose vertices lie in its slab (CavityKernel::insert_constrained_owned), so the
// tasks share nothing. The points whose cavity reaches past the slab go through slabs along the
// next longest axis, and those left then one at a time, in batch order. The mesh depends on `partitions`, never on the thread count.
// The walk for point i starts at hints[i] when that is a live tet (null: none).
// The new vertices are numbered in batch order after the mesh's vertices; a refused point leaves
// no vertex.
class BatchInserter {
 public:
  explicit BatchInserter(TetMesh& mesh, int partitions = 2, size_t parallel_min = 2048, uint64_t seed = 0x5eed);
  ~BatchInserter();
  BatchInserter(const BatchInserter&) = delete;
  BatchInserter& operator=(const BatchInserter&) = delete;

  // points: 3 per point, finite (checked: a non-finite point is kInvalidPoint).
  void insert(const double* points, const uint32_t* hints, size_t n, const InsertOptions& options,
              BatchInsertion& out);

 private:
  struct Part;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One-shot insertion (allocates scratch memory on each call; prefer PointInserter in loops).
// new_tets, when given, receives the created tets.
InsertResult insert_point(TetMesh& mesh, const double p[3], uint32_t hint = TetMesh::kNone,
                          const InsertOptions& options = {},
                          std::vector<uint32_t>* new_tets = nullptr);

}  // namespace anitet
