#include "delaunay/delaunay.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "core/bvh.hpp"
#include "delaunay/cavity_kernel.hpp"
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

// Inserts the points in order (coords in insertion order, vertex r = point order[r]) into an
// empty mesh.
Status insert_all(TetStorage& store, CavityKernel& kernel, const std::vector<double>& coords,
                  const std::vector<uint32_t>& order, double extent, DelaunayStats& stats) {
  const size_t n = order.size();
  kernel.bind(store, coords.data(), n, order.data());
  kernel.set_extent(extent);
  const double* c = coords.data();
  if (predicates::orient3d(c, c + 3, c + 6, c + 9) > 0) kernel.make_first_tet(0, 1, 2, 3);
  else kernel.make_first_tet(1, 0, 2, 3);
  uint32_t last = kernel.last_real_tet();
  for (size_t r = 4; r < n; ++r) {
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
        return Status(Error::Internal, "point " + std::to_string(order[r]) + " could not be located");
    }
  }
  return Status::success();
}

}  // namespace

Result<DelaunayStats> delaunay_tetrahedralize(TetMesh& mesh, const double* xyz, size_t n,
                                              const DelaunayOptions& options) {
  const auto t_start = Clock::now();
  const predicates::PredicateCounters predicates_before = predicates::thread_counters();
  if (n == 0 || xyz == nullptr) return Status(Error::EmptyInput, "no points to tetrahedralize");
  if (n >= size_t(TetMesh::kGhost))
    return Status(Error::InvalidArgument, "too many points: " + std::to_string(n));
  for (size_t i = 0; i < 3 * n; ++i)
    if (!std::isfinite(xyz[i]))
      return Status(Error::NonFiniteCoordinate,
                    "point " + std::to_string(i / 3) + " has a non-finite coordinate");

  delaunay_detail::BrioOptions brio;
  brio.seed = options.seed;
  brio.ratio = options.brio_ratio;
  brio.min_round = options.brio_min_round;
  std::vector<uint32_t> order = delaunay_detail::brio_order(xyz, n, brio);
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
  const size_t expected_tets = 7 * n + 64;
  mesh.tet_v.reserve(4 * expected_tets);
  mesh.tet_adj.reserve(4 * expected_tets);
  mesh.tet_flags.reserve(expected_tets);
  mesh.tet_region.reserve(expected_tets);
  TetStorage store(mesh);
  CavityKernel kernel(options.seed);
  const Status st = insert_all(store, kernel, coords, order, extent, stats);
  delaunay_detail::KernelCounters counters = kernel.counters;
  if (!st.ok()) {
    mesh = TetMesh();
    return st;
  }
  // Back to the caller's numbering.
  for (uint32_t& v : mesh.tet_v)
    if (v != TetMesh::kGhost) v = order[v];
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
