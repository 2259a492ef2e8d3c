#include <algorithm>
#include <cmath>

#include "delaunay/cavity_kernel.hpp"
#include "delaunay/delaunay.hpp"

namespace anitet {

const char* insert_status_name(InsertStatus s) {
  switch (s) {
    case InsertStatus::kInserted: return "inserted";
    case InsertStatus::kDuplicate: return "duplicate";
    case InsertStatus::kBlocked: return "blocked";
    case InsertStatus::kOutsideMesh: return "outside_mesh";
    case InsertStatus::kInvalidMesh: return "invalid_mesh";
    case InsertStatus::kInvalidPoint: return "invalid_point";
  }
  return "unknown";
}

PointInserter::PointInserter(TetMesh& mesh, uint64_t seed)
    : mesh_(mesh), kernel_(std::make_unique<delaunay_detail::CavityKernel>(seed)) {}

PointInserter::~PointInserter() = default;

const std::vector<uint32_t>& PointInserter::new_tets() const { return kernel_->new_tets(); }

DelaunayStats PointInserter::stats() const {
  DelaunayStats s;
  delaunay_detail::copy_counters(kernel_->counters, s);
  return s;
}

InsertResult PointInserter::insert(const double p[3], uint32_t hint, const InsertOptions& options) {
  const predicates::PredicateCounters predicates_before = predicates::thread_counters();
  struct CountOnExit {
    delaunay_detail::KernelCounters& counters;
    const predicates::PredicateCounters& before;
    ~CountOnExit() { counters.add_predicates_since(before); }
  } count_on_exit{kernel_->counters, predicates_before};
  InsertResult result;
  const uint32_t start = delaunay_detail::walk_start(mesh_, hint, last_tet_);
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
    result.status = InsertStatus::kInvalidPoint;
    return result;
  }
  if (start == TetMesh::kNone) {
    result.status = InsertStatus::kInvalidMesh;
    return result;
  }

  // The point goes in as a vertex first so the predicates can read it; it is taken back out if the
  // insertion fails. (Copied first: p may point into mesh.xyz, which add_vertex may move.)
  const double q[3] = {p[0], p[1], p[2]};
  const auto pid = static_cast<uint32_t>(mesh_.num_vertices());
  mesh_.add_vertex(q, options.vertex_flags);
  delaunay_detail::TetStorage store(mesh_);
  kernel_->bind(store, mesh_.xyz.data(), mesh_.num_vertices(), nullptr);
  see_new_vertices();
  auto undo_vertex = [&] {
    mesh_.xyz.resize(3 * size_t(pid));
    box_.forget_from(pid);  // the next point takes its index (the box may stay larger)
    mesh_.vflags.resize(pid);
  };

  const delaunay_detail::Location loc = kernel_->locate(start, mesh_.point(pid));
  result.tet = loc.tet;
  switch (loc.what) {
    case delaunay_detail::Located::kDuplicate:
      undo_vertex();
      result.status = InsertStatus::kDuplicate;
      result.vertex = loc.vertex;
      return result;
    case delaunay_detail::Located::kOutside:
    case delaunay_detail::Located::kForeign:  // only locate_owned() says so
      undo_vertex();
      result.status = InsertStatus::kOutsideMesh;
      return result;
    case delaunay_detail::Located::kInTet:
    case delaunay_detail::Located::kInGhost:
      break;
  }
  kernel_->set_refuse_frozen(options.refuse_frozen_conflict);
  if (!kernel_->insert_constrained(loc.tet, pid, options.respect_protected, options.keep_tets, options.keep_count,
                                   options.force_keep, options.degeneracy, options.early_refusal)) {
    undo_vertex();
    result.status = InsertStatus::kBlocked;
    return result;
  }
  last_tet_ = kernel_->last_real_tet();
  result.status = InsertStatus::kInserted;
  result.vertex = pid;
  return result;
}

void PointInserter::see_new_vertices() {
  // The filters hold for coordinate differences up to the extent (non-finite: disabled).
  kernel_->set_extent(box_.update(mesh_));
}

InsertResult insert_point(TetMesh& mesh, const double p[3], uint32_t hint, const InsertOptions& options,
                          std::vector<uint32_t>* new_tets) {
  PointInserter inserter(mesh);
  InsertResult r = inserter.insert(p, hint, options);
  if (new_tets) {
    if (r.ok()) *new_tets = inserter.new_tets();
    else new_tets->clear();
  }
  return r;
}

}  // namespace anitet
