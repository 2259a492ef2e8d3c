#include "delaunay/delaunay.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <string>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/bvh.hpp"
#include "delaunay/cavity_kernel.hpp"
#include "delaunay/slab_parts.hpp"
#include "delaunay/spatial_sort.hpp"
#include "delaunay/tet_storage.hpp"
#include "predicates/predicates.hpp"

namespace anitet {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

bool same_point(const double* a, const double* b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }

// Moves four affinely independent points to the front of `order`, keeping the others in order.
// The first point stays first, so the start keeps the spatial locality of the order.
bool move_initial_simplex_first(const double* xyz, std::vector<uint32_t>& order) {
  const size_t n = order.size();
  auto p = [&](size_t k) { return xyz + 3 * size_t(order[k]); };
  size_t i1 = 1;
  while (i1 < n && same_point(p(0), p(i1))) ++i1;
  if (i1 >= n) return false;
  std::rotate(order.begin() + 1, order.begin() + long(i1), order.begin() + long(i1) + 1);
  size_t i2 = 2;
  while (i2 < n && delaunay_detail::exactly_collinear(p(0), p(1), p(i2))) ++i2;
  if (i2 >= n) return false;
  std::rotate(order.begin() + 2, order.begin() + long(i2), order.begin() + long(i2) + 1);
  size_t i3 = 3;
  while (i3 < n && predicates::orient3d(p(0), p(1), p(2), p(i3)) == 0) ++i3;
  if (i3 >= n) return false;
  std::rotate(order.begin() + 3, order.begin() + long(i3), order.begin() + long(i3) + 1);
  return true;
}

using delaunay_detail::CavityKernel;
using delaunay_detail::Located;
using delaunay_detail::TetStorage;

// Inserts point r sequentially (the bulk build's one-at-a-time path).
Status insert_one(CavityKernel& kernel, const std::vector<double>& coords, const std::vector<uint32_t>& order,
                  size_t r, uint32_t& last, DelaunayStats& stats) {
  const delaunay_detail::Location loc = kernel.locate(last, &coords[3 * r]);
  switch (loc.what) {
    case Located::kDuplicate:
      stats.duplicates.push_back({order[r], order[loc.vertex]});
      break;
    case Located::kInTet:
    case Located::kInGhost:
      last = kernel.insert_delaunay(loc.tet, static_cast<uint32_t>(r));
      break;
    case Located::kOutside:
    case Located::kForeign:
      return Status(Error::Internal, "point " + std::to_string(order[r]) + " could not be located");
  }
  return Status::success();
}

void add_counters(delaunay_detail::KernelCounters& into, const delaunay_detail::KernelCounters& c) {
  into.walk_steps += c.walk_steps;
  into.walk_fallbacks += c.walk_fallbacks;
  into.cavity_tets += c.cavity_tets;
  into.tets_created += c.tets_created;
  into.orient3d_calls += c.orient3d_calls;
  into.insphere_calls += c.insphere_calls;
  into.predicates.orient3d_exact += c.predicates.orient3d_exact;
  into.predicates.insphere_exact += c.predicates.insphere_exact;
  into.predicates.sos_ties += c.predicates.sos_ties;
}

// The parallel part of the bulk build: the points todo (insertion-order indices, in order) are cut
// into slabs along `axis` at quantiles; each slab's task inserts its points with its own kernel
// and slot pool (see CavityKernel::set_part). Returns the points the tasks left, in order.
class ParallelBuild {
 public:
  ParallelBuild(TetMesh& mesh, TetStorage& store, const std::vector<double>& coords, const std::vector<uint32_t>& order,
                double extent, uint64_t seed, int partitions)
      : mesh_(mesh), store_(store), coords_(coords), order_(order), parts_(size_t(partitions)) {
    for (size_t k = 0; k < parts_.size(); ++k) {
      parts_[k].kernel = std::make_unique<CavityKernel>(seed + 0x9e37 * (k + 1));
      parts_[k].kernel->set_extent(extent);
    }
  }

  std::vector<uint32_t> run(const std::vector<uint32_t>& todo, size_t num_vertices, int axis, CavityKernel& main,
                            uint32_t& last, DelaunayStats& stats) {
    const size_t np = parts_.size();
    // Slab bounds at quantiles of the points to insert; every vertex so far gets its slab.
    std::vector<double> values(todo.size());
    for (size_t i = 0; i < todo.size(); ++i) values[i] = coords_[3 * size_t(todo[i]) + size_t(axis)];
    std::vector<double> cuts;
    for (size_t k = 1; k < np; ++k) {
      auto nth = values.begin() + static_cast<ptrdiff_t>(k * values.size() / np);
      std::nth_element(values.begin(), nth, values.end());
      cuts.push_back(*nth);
    }
    part_.resize(num_vertices);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, num_vertices, 1 << 14), [&](const tbb::blocked_range<size_t>& range) {
      for (size_t v = range.begin(); v < range.end(); ++v) {
        const double x = coords_[3 * v + size_t(axis)];
        part_[v] = static_cast<uint8_t>(std::upper_bound(cuts.begin(), cuts.end(), x) - cuts.begin());
      }
    });
    for (Part& p : parts_) {
      p.points.clear();
      p.left.clear();
      p.duplicates.clear();
    }
    for (uint32_t r : todo) parts_[part_[r]].points.push_back(r);
    // Slot pools: the mesh's free slots dealt out in turn, then fresh ones, for 10% more tets per
    // point than the mesh has so far (about 6.7 in a volume, 5 for points on a sphere, ghosts
    // included); the arrays are not resized while tasks run. A task that runs out leaves its
    // last points to the sequential inserts.
    const double per_point = 1.1 * double(mesh_.num_tet_slots() - mesh_.free_tets.size()) / double(todo.front());
    std::vector<size_t> want(np);
    std::vector<delaunay_detail::SlotPool*> pools(np);
    for (size_t k = 0; k < np; ++k) {
      want[k] = static_cast<size_t>(per_point * double(parts_[k].points.size())) + 256;
      pools[k] = &parts_[k].pool;
    }
    delaunay_detail::fill_slot_pools(mesh_, store_, pools, want);
    delaunay_detail::tet_parts_from_vertices(mesh_, part_, CavityKernel::kNoPart, tet_part_);
    // Each task's walk starts where its first point is (found before the tasks start), or near
    // there in a tet it may enter.
    for (size_t k = 0; k < np; ++k) {
      Part& p = parts_[k];
      p.start = TetMesh::kNone;
      if (p.points.empty()) continue;
      main.set_part(tet_part_.data(), static_cast<uint8_t>(k));
      const delaunay_detail::Location loc = main.locate(last, &coords_[3 * size_t(p.points[0])]);
      p.start = enterable_near(main, loc.tet, static_cast<uint8_t>(k));
    }
    main.set_part(nullptr, CavityKernel::kNoPart);
    tbb::parallel_for(size_t(0), np, [&](size_t k) { fill_part(k); });
    // Unused slots back to the mesh's free list, in a fixed order.
    delaunay_detail::return_slot_pools(mesh_, pools);
    std::vector<uint32_t> left;
    for (Part& p : parts_) {
      left.insert(left.end(), p.left.begin(), p.left.end());
      stats.duplicates.insert(stats.duplicates.end(), p.duplicates.begin(), p.duplicates.end());
      stats.parallel_points += p.inserted;
      if (p.last != TetMesh::kNone) last = p.last;
    }
    std::sort(left.begin(), left.end());
    return left;
  }

  // The tasks' counters, summed.
  void add_counters_to(delaunay_detail::KernelCounters& c) const {
    for (const Part& p : parts_) add_counters(c, p.kernel->counters);
  }

 private:
  struct Part {
    std::unique_ptr<CavityKernel> kernel;
    delaunay_detail::SlotPool pool;
    std::vector<uint32_t> points, left;
    std::vector<DuplicatePoint> duplicates;
    uint32_t start = TetMesh::kNone, last = TetMesh::kNone;
    size_t inserted = 0;
  };

  // t when part k may enter it, else the nearest such tet across a few facets (kNone: none).
  uint32_t enterable_near(const CavityKernel& kernel, uint32_t t, uint8_t k) const {
    std::vector<uint32_t> seen{t};
    for (size_t i = 0; i < seen.size() && i < 256; ++i) {
      const uint8_t o = kernel.owner(seen[i]);
      if (o == k || o == CavityKernel::kNoPart) return seen[i];
      for (int f = 0; f < 4; ++f) {
        const uint32_t adj = mesh_.tet_adj[4 * size_t(seen[i]) + size_t(f)];
        const auto n = static_cast<uint32_t>(adj >> 2);
        if (std::find(seen.begin(), seen.end(), n) == seen.end()) seen.push_back(n);
      }
    }
    return TetMesh::kNone;
  }

  void fill_part(size_t k) {
    Part& p = parts_[k];
    p.last = TetMesh::kNone;
    p.inserted = 0;
    if (p.points.empty()) return;
    if (p.start == TetMesh::kNone) {
      p.left = p.points;
      return;
    }
    const predicates::PredicateCounters before = predicates::thread_counters();
    TetStorage store(mesh_, &p.pool);
    CavityKernel& kernel = *p.kernel;
    kernel.bind(store, coords_.data(), order_.size(), order_.data());
    kernel.set_part(tet_part_.data(), static_cast<uint8_t>(k));
    uint32_t last = p.start;
    for (uint32_t r : p.points) {
      const delaunay_detail::Location loc = kernel.locate_owned(last, &coords_[3 * size_t(r)]);
      if (loc.what == Located::kDuplicate) {
        p.duplicates.push_back({order_[r], order_[loc.vertex]});
      } else if ((loc.what == Located::kInTet || loc.what == Located::kInGhost) &&
                 kernel.insert_delaunay_owned(loc.tet, r)) {
        last = p.last = kernel.last_real_tet();
        ++p.inserted;
      } else {
        p.left.push_back(r);
      }
    }
    // The caller's thread counts its own predicate calls, these tasks' included, once at the end.
    if (std::this_thread::get_id() != caller_) kernel.counters.add_predicates_since(before);
  }

  TetMesh& mesh_;
  TetStorage& store_;
  const std::thread::id caller_ = std::this_thread::get_id();
  const std::vector<double>& coords_;
  const std::vector<uint32_t>& order_;
  std::vector<Part> parts_;
  std::vector<uint8_t> part_;      // per vertex
  std::vector<uint8_t> tet_part_;  // per tet slot
};

// Moves the last live tets into the free slots below them, so that the slots are exactly the live
// tets (the parallel build leaves its pools' unused slots free). Deterministic.
void compact_tets(TetMesh& mesh) {
  std::vector<uint32_t>& free = mesh.free_tets;
  std::sort(free.begin(), free.end());
  size_t end = mesh.num_tet_slots();
  size_t f = 0;
  for (;;) {
    while (end > 0 && mesh.is_deleted(static_cast<uint32_t>(end - 1))) --end;
    if (f >= free.size() || free[f] >= end) break;
    const uint32_t to = free[f++], from = static_cast<uint32_t>(end - 1);
    for (int i = 0; i < 4; ++i) {
      mesh.tet_v[4 * size_t(to) + size_t(i)] = mesh.tet_v[4 * size_t(from) + size_t(i)];
      const uint32_t adj = mesh.tet_adj[4 * size_t(from) + size_t(i)];
      mesh.tet_adj[4 * size_t(to) + size_t(i)] = adj;
      if (adj != TetMesh::kNoNeighbour) mesh.tet_adj[adj] = 4 * uint32_t(to) + uint32_t(i);
    }
    mesh.tet_flags[to] = mesh.tet_flags[from];
    mesh.tet_region[to] = mesh.tet_region[from];
    mesh.tet_flags[from] = tflag::kDeleted;
    --end;
  }
  mesh.tet_v.resize(4 * end);
  mesh.tet_adj.resize(4 * end);
  mesh.tet_flags.resize(end);
  mesh.tet_region.resize(end);
  free.clear();
}

// Inserts the points in order (coords in insertion order, vertex r = point order[r]) into an
// empty mesh; round_begin: where each BRIO round starts in the order.
Status insert_all(TetMesh& mesh, TetStorage& store, CavityKernel& kernel, const std::vector<double>& coords,
                  const std::vector<uint32_t>& order, const std::vector<size_t>& round_begin, double extent,
                  const DelaunayOptions& options, DelaunayStats& stats) {
  const size_t n = order.size();
  kernel.bind(store, coords.data(), n, order.data());
  kernel.set_extent(extent);
  const double* c = coords.data();
  if (predicates::orient3d(c, c + 3, c + 6, c + 9) > 0) kernel.make_first_tet(0, 1, 2, 3);
  else kernel.make_first_tet(1, 0, 2, 3);
  uint32_t last = kernel.last_real_tet();
  std::unique_ptr<ParallelBuild> parallel;
  for (size_t round = 0; round < round_begin.size(); ++round) {
    const size_t begin = std::max<size_t>(round_begin[round], 4);
    const size_t end = round + 1 < round_begin.size() ? round_begin[round + 1] : n;
    if (begin >= end) continue;
    if (options.partitions < 2 || end - begin < options.parallel_min_round) {
      for (size_t r = begin; r < end; ++r)
        if (Status st = insert_one(kernel, coords, order, r, last, stats); !st.ok()) return st;
      continue;
    }
    if (!parallel) parallel = std::make_unique<ParallelBuild>(mesh, store, coords, order, extent, options.seed, options.partitions);
    // Slabs across the longest extent of the round's points, then across the next one.
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t r = begin; r < end; ++r)
      for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], c[3 * r + size_t(d)]), hi[d] = std::max(hi[d], c[3 * r + size_t(d)]);
    int axes[3] = {0, 1, 2};
    std::sort(axes, axes + 3, [&](int a, int b) { return hi[a] - lo[a] > hi[b] - lo[b]; });
    std::vector<uint32_t> todo(end - begin);
    std::iota(todo.begin(), todo.end(), static_cast<uint32_t>(begin));
    for (int phase = 0; phase < 2 && todo.size() >= options.parallel_min_round / 8; ++phase)
      todo = parallel->run(todo, end, axes[phase], kernel, last, stats);
    for (uint32_t r : todo)
      if (Status st = insert_one(kernel, coords, order, r, last, stats); !st.ok()) return st;
  }
  if (parallel) {
    parallel->add_counters_to(kernel.counters);
    compact_tets(mesh);
  }
  return Status::success();
}

}  // namespace

Result<DelaunayStats> delaunay_tetrahedralize(TetMesh& mesh, const double* xyz, size_t n,
                                              const DelaunayOptions& options) {
  const auto t_start = Clock::now();
  const predicates::PredicateCounters predicates_before = predicates::thread_counters();
  if (n == 0 || xyz == nullptr) return Status(Error::EmptyInput, "no points to tetrahedralize");
  // (Delaunay meshes of points in general position have about 6.5 tets per point; a mesh holds
  // at most 2^30 tet slots.)
  if (n >= size_t(TetMesh::kGhost) || n > TetMesh::kMaxTetSlots / 8)
    return Status(Error::InvalidArgument, "too many points: " + std::to_string(n) + " (at most 2^27, 134217728)");
  for (size_t i = 0; i < 3 * n; ++i)
    if (!std::isfinite(xyz[i]))
      return Status(Error::NonFiniteCoordinate,
                    "point " + std::to_string(i / 3) + " has a non-finite coordinate");

  if (options.partitions < 1 || options.partitions > 64)
    return Status(Error::InvalidArgument, "partitions must be in 1..64, not " + std::to_string(options.partitions));
  delaunay_detail::BrioOptions brio;
  brio.seed = options.seed;
  brio.ratio = options.brio_ratio;
  brio.min_round = options.brio_min_round;
  std::vector<size_t> round_begin;
  std::vector<uint32_t> order = delaunay_detail::brio_order(xyz, n, brio, &round_begin);
  if (n < 4 || !move_initial_simplex_first(xyz, order))
    return Status(Error::InvalidArgument,
                  "the points span no volume: fewer than four are affinely independent");
  const auto t_sorted = Clock::now();

  // The points in insertion order: neighbouring tets read neighbouring memory.
  std::vector<double> coords(3 * n);
  for (size_t r = 0; r < n; ++r) std::copy_n(xyz + 3 * size_t(order[r]), 3, &coords[3 * r]);

  const Box3 box = bounding_box(xyz, n);
  const double extent = std::max({box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]});

  DelaunayStats stats;
  stats.num_points = n;
  mesh = TetMesh();
  const size_t expected_tets = (options.partitions > 1 ? 8 : 7) * n + 64;
  mesh.reserve_tets(expected_tets);
  TetStorage store(mesh);
  CavityKernel kernel(options.seed);
  const Status st = insert_all(mesh, store, kernel, coords, order, round_begin, extent, options, stats);
  delaunay_detail::KernelCounters counters = kernel.counters;
  if (!st.ok()) {
    mesh = TetMesh();
    return st;
  }
  // Back to the caller's numbering.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.tet_v.size(), 1 << 16), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i < range.end(); ++i)
      if (uint32_t& v = mesh.tet_v[i]; v != TetMesh::kGhost) v = order[v];
  });
  const auto t_inserted = Clock::now();
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (mesh.is_deleted(t)) continue;
    if (mesh.is_ghost(t)) ++stats.num_ghost_tets;
    else ++stats.num_tets;
  }
  mesh.xyz.assign(xyz, xyz + 3 * n);
  mesh.vflags.assign(n, 0);

  std::sort(stats.duplicates.begin(), stats.duplicates.end(),
            [](const DuplicatePoint& a, const DuplicatePoint& b) { return a.point < b.point; });
  stats.num_inserted = n - stats.duplicates.size();
  counters.add_predicates_since(predicates_before);
  delaunay_detail::copy_counters(counters, stats);
  const auto t_end = Clock::now();
  stats.seconds_sort = seconds_between(t_start, t_sorted);
  stats.seconds_insert = seconds_between(t_sorted, t_inserted);
  stats.seconds_total = seconds_between(t_start, t_end);
  return stats;
}

}  // namespace anitet
