// BatchInserter (delaunay.hpp): a batch of constrained insertions, one task per slab, then the
// points the tasks left, one at a time.
#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/bvh.hpp"
#include "delaunay/cavity_kernel.hpp"
#include "delaunay/delaunay.hpp"
#include "delaunay/slab_parts.hpp"

namespace anitet {

using delaunay_detail::CavityKernel;
using delaunay_detail::Located;
using delaunay_detail::Location;
using delaunay_detail::SlotPool;
using delaunay_detail::TetStorage;

struct BatchInserter::Part {
  std::unique_ptr<CavityKernel> kernel;
  SlotPool pool;
  std::vector<uint32_t> points;  // batch indices, in batch order
  std::vector<uint32_t> left;    // those left to the one-by-one inserts
  std::vector<uint32_t> tets;    // the tets its insertions created, point after point
  size_t inserted = 0;
};

struct BatchInserter::Impl {
  Impl(TetMesh& m, int np, size_t min, uint64_t seed)
      : mesh(m), parallel_min(min), kernel(seed), parts(size_t(std::max(np, 1))) {
    for (size_t k = 0; k < parts.size(); ++k) parts[k].kernel = std::make_unique<CavityKernel>(seed + 0x9e37 * (k + 1));
  }

  TetMesh& mesh;
  size_t parallel_min;
  CavityKernel kernel;  // the one-by-one inserts
  std::vector<Part> parts;
  uint32_t last = TetMesh::kNone;  // the last tet the one-by-one inserts made
  delaunay_detail::VertexBox box;
  double extent = 0.0;

  // The batch being inserted.
  const double* points = nullptr;
  const uint32_t* hints = nullptr;
  size_t n = 0;
  uint32_t n0 = 0;  // the vertex of point i is n0 + i until compact()
  InsertOptions options;
  BatchInsertion* out = nullptr;
  std::vector<uint32_t> tets;  // the one-by-one inserts' tets
  std::vector<uint8_t> vertex_part, tet_part;
  std::vector<uint8_t> hint_usable;  // per point: its hint was live at the start, in its part or none

  void record(uint32_t i, uint8_t in_list, std::vector<uint32_t>& into, const CavityKernel& k) {
    out->status[i] = InsertStatus::kInserted;
    out->vertex[i] = n0 + i;
    out->list[i] = in_list;
    out->first[i] = static_cast<uint32_t>(into.size());
    out->count[i] = static_cast<uint32_t>(k.new_tets().size());
    into.insert(into.end(), k.new_tets().begin(), k.new_tets().end());
  }

  void insert_one(uint32_t i) {
    const uint32_t pid = n0 + i;
    const uint32_t hint = hints ? hints[i] : TetMesh::kNone;
    const uint32_t start = delaunay_detail::walk_start(mesh, hint, last);
    if (start == TetMesh::kNone) {
      out->status[i] = InsertStatus::kInvalidMesh;
      return;
    }
    const Location loc = kernel.locate(start, mesh.point(pid));
    switch (loc.what) {
      case Located::kDuplicate: out->status[i] = InsertStatus::kDuplicate; return;
      case Located::kOutside:
      case Located::kForeign: out->status[i] = InsertStatus::kOutsideMesh; return;
      case Located::kInTet:
      case Located::kInGhost: break;
    }
    if (!kernel.insert_constrained(loc.tet, pid, options.respect_protected)) {
      out->status[i] = InsertStatus::kBlocked;
      return;
    }
    record(i, static_cast<uint8_t>(parts.size()), tets, kernel);
    last = kernel.last_real_tet();
  }

  // The tasks on slabs along the box's longest axis (phase 0) or the next longest (phase 1);
  // returns the points they left, in batch order.
  std::vector<uint32_t> run_parts(const std::vector<uint32_t>& todo, int phase);
  void fill_part(size_t k);
  // Removes the vertices of the points not inserted, renumbering the later ones.
  void compact();
};

std::vector<uint32_t> BatchInserter::Impl::run_parts(const std::vector<uint32_t>& todo, int phase) {
  const size_t np = parts.size();
  // Slabs at quantiles of the points along an axis of their box.
  Box3 b = bounding_box(mesh.point(n0 + todo[0]), 1);
  for (uint32_t i : todo)
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = std::min(b.lo[k], mesh.point(n0 + i)[k]);
      b.hi[k] = std::max(b.hi[k], mesh.point(n0 + i)[k]);
    }
  int axes[3] = {0, 1, 2};
  std::stable_sort(axes, axes + 3, [&b](int x, int y) { return b.hi[x] - b.lo[x] > b.hi[y] - b.lo[y]; });
  const int axis = axes[phase];
  std::vector<double> values(todo.size());
  for (size_t j = 0; j < todo.size(); ++j) values[j] = mesh.point(n0 + todo[j])[axis];
  std::vector<double> cuts;
  for (size_t k = 1; k < np; ++k) {
    auto nth = values.begin() + static_cast<ptrdiff_t>(k * values.size() / np);
    std::nth_element(values.begin(), nth, values.end());
    cuts.push_back(*nth);
  }
  const size_t nv = mesh.num_vertices();
  vertex_part.resize(nv);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nv, 1 << 14), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t v = range.begin(); v < range.end(); ++v)
      vertex_part[v] = static_cast<uint8_t>(std::upper_bound(cuts.begin(), cuts.end(), mesh.xyz[3 * v + size_t(axis)]) - cuts.begin());
  });
  // (p.tets keeps the first phase's lists: its points' first/count index them.)
  for (Part& p : parts) {
    p.points.clear();
    p.left.clear();
    p.inserted = 0;
  }
  for (uint32_t i : todo) parts[vertex_part[n0 + i]].points.push_back(i);
  // Slot pools for 8 new tets per point (a point in a volume adds about 6.5); a task that runs
  // out leaves its last points to the one-by-one inserts.
  std::vector<size_t> want(np);
  std::vector<SlotPool*> pools(np);
  for (size_t k = 0; k < np; ++k) {
    want[k] = 8 * parts[k].points.size() + 64;
    pools[k] = &parts[k].pool;
  }
  const auto slots_before = static_cast<uint32_t>(mesh.num_tet_slots());
  TetStorage store(mesh);
  delaunay_detail::fill_slot_pools(mesh, store, pools, want);
  delaunay_detail::tet_parts_from_vertices(mesh, vertex_part, CavityKernel::kNoPart, tet_part);
  // A hint is a start for its point's task when it was live here and is of that part or none (a
  // tet no task changes); only then may the task read it.
  hint_usable.assign(n, 0);
  if (hints)
    for (uint32_t i : todo) {
      const uint32_t h = hints[i];
      hint_usable[i] = h < slots_before && !mesh.is_deleted(h) &&
                       (tet_part[h] == vertex_part[n0 + i] || tet_part[h] == CavityKernel::kNoPart);
    }
  tbb::parallel_for(size_t(0), np, [&](size_t k) { fill_part(k); }, tbb::simple_partitioner());
  // Unused slots back to the mesh's free list, in a fixed order.
  delaunay_detail::return_slot_pools(mesh, pools);
  std::vector<uint32_t> left;
  for (Part& p : parts) {
    left.insert(left.end(), p.left.begin(), p.left.end());
    out->parallel += p.inserted;
  }
  std::sort(left.begin(), left.end());
  return left;
}

void BatchInserter::Impl::fill_part(size_t k) {
  Part& p = parts[k];
  if (p.points.empty()) return;
  TetStorage store(mesh, &p.pool);
  CavityKernel& kern = *p.kernel;
  kern.bind(store, mesh.xyz.data(), mesh.num_vertices(), nullptr);
  kern.set_extent(extent);
  kern.set_part(tet_part.data(), static_cast<uint8_t>(k));
  kern.set_refuse_frozen(options.refuse_frozen_conflict);
  uint32_t from = TetMesh::kNone;
  for (uint32_t i : p.points) {
    const uint32_t pid = n0 + i;
    uint32_t start = from;
    if (hint_usable[i] && !store.deleted(hints[i])) start = hints[i];
    if (start == TetMesh::kNone) {
      p.left.push_back(i);
      continue;
    }
    const Location loc = kern.locate_owned(start, mesh.point(pid));
    switch (loc.what) {
      case Located::kDuplicate: out->status[i] = InsertStatus::kDuplicate; continue;
      case Located::kOutside: out->status[i] = InsertStatus::kOutsideMesh; continue;
      case Located::kForeign: p.left.push_back(i); continue;
      case Located::kInTet:
      case Located::kInGhost: break;
    }
    if (kern.insert_constrained_owned(loc.tet, pid, options.respect_protected)) {
      record(i, static_cast<uint8_t>(k), p.tets, kern);
      from = kern.last_real_tet();
      ++p.inserted;
    } else if (kern.foreign_refusal()) {
      p.left.push_back(i);
    } else {
      out->status[i] = InsertStatus::kBlocked;
    }
  }
  kern.set_part(nullptr, CavityKernel::kNoPart);
}

void BatchInserter::Impl::compact() {
  std::vector<uint32_t> renumber(n, TetMesh::kNone);
  uint32_t next = n0;
  for (size_t i = 0; i < n; ++i)
    if (out->status[i] == InsertStatus::kInserted) renumber[i] = next++;
  if (next == n0 + n) return;
  // Only tets made by this batch hold its vertices; a scan of all is simplest and cheap.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.num_tet_slots(), 1 << 14), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t t = range.begin(); t < range.end(); ++t) {
      if (mesh.tet_flags[t] & tflag::kDeleted) continue;
      for (int k = 0; k < 4; ++k) {
        uint32_t& v = mesh.tet_v[4 * t + size_t(k)];
        if (v >= n0 && v != TetMesh::kGhost) v = renumber[v - n0];
      }
    }
  });
  for (size_t i = 0; i < n; ++i) {
    const uint32_t to = renumber[i];
    if (to == TetMesh::kNone) continue;
    std::copy_n(&mesh.xyz[3 * (size_t(n0) + i)], 3, &mesh.xyz[3 * size_t(to)]);
    mesh.vflags[to] = mesh.vflags[n0 + i];
    out->vertex[i] = to;
  }
  mesh.xyz.resize(3 * size_t(next));
  mesh.vflags.resize(next);
  box.forget_from(next);
}

BatchInserter::BatchInserter(TetMesh& mesh, int partitions, size_t parallel_min, uint64_t seed)
    : impl_(std::make_unique<Impl>(mesh, partitions, parallel_min, seed)) {}

BatchInserter::~BatchInserter() = default;

void BatchInserter::insert(const double* points, const uint32_t* hints, size_t n, const InsertOptions& options,
                           BatchInsertion& out) {
  Impl& m = *impl_;
  TetMesh& mesh = m.mesh;
  m.points = points;
  m.hints = hints;
  m.n = n;
  m.n0 = static_cast<uint32_t>(mesh.num_vertices());
  m.options = options;
  m.out = &out;
  out.status.assign(n, InsertStatus::kBlocked);
  out.vertex.assign(n, TetMesh::kNone);
  out.parallel = out.deferred = 0;
  // (Point i's tets: list parts.size() is the one-by-one inserts'.)
  out.list.assign(n, static_cast<uint8_t>(m.parts.size()));
  out.first.assign(n, 0);
  out.count.assign(n, 0);
  m.tets.clear();
  for (Part& p : m.parts) p.tets.clear();
  // Every point is a vertex first, so that the tasks never resize the arrays; compact() takes
  // the refused ones out again.
  std::vector<uint32_t> todo;
  todo.reserve(n);
  mesh.xyz.reserve(mesh.xyz.size() + 3 * n);
  mesh.vflags.reserve(mesh.vflags.size() + n);
  for (size_t i = 0; i < n; ++i) {
    const double* p = points + 3 * i;
    const bool finite = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
    const double zero[3] = {0.0, 0.0, 0.0};
    mesh.add_vertex(finite ? p : zero, options.vertex_flags);
    if (finite) todo.push_back(static_cast<uint32_t>(i));
    else out.status[i] = InsertStatus::kInvalidPoint;
  }
  m.extent = m.box.update(mesh);
  // The points left by slabs along the longest axis mostly lie near the cuts: slabs along the
  // next axis take most of them.
  if (m.parts.size() >= 2 && todo.size() >= m.parallel_min) {
    todo = m.run_parts(todo, 0);
    if (todo.size() >= m.parallel_min / 4) todo = m.run_parts(todo, 1);
    out.deferred = todo.size();
  }

  TetStorage store(mesh);
  m.kernel.bind(store, mesh.xyz.data(), mesh.num_vertices(), nullptr);
  m.kernel.set_extent(m.extent);
  m.kernel.set_refuse_frozen(options.refuse_frozen_conflict);
  for (uint32_t i : todo) m.insert_one(i);
  m.compact();
  out.lists.resize(m.parts.size() + 1);
  for (size_t k = 0; k < m.parts.size(); ++k) out.lists[k].swap(m.parts[k].tets);
  out.lists.back().swap(m.tets);
}

}  // namespace anitet
