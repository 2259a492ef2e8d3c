// MetricField: a metric tensor field stored sparsely in OpenVDB grids (this header includes none
// of it). The OpenVDB code lives in a module, libanitet_vdb.so, opened on the first field built
// or read (vdb_backend.hpp): linked, OpenVDB's 69,000 relocations took 60 ms at every start of
// every program using the library; the pipeline now pays them on a thread of their own while
// stage 1 runs (VdbModulePreload). Without the module, building or reading a field fails with
// Error::NotImplemented.
//
// Two kinds share one uniform linear transform (voxel size, origin):
//  - Isotropic: one grid of sizes h, trilinearly interpolated in h (so constant and linear size
//    fields are reproduced exactly); M = I / h^2.
//  - Tensor: log(M) in two Vec3d grids with one topology, (xx, yy, zz) and (xy, xz, yz),
//    trilinearly interpolated in log space and mapped back with exp (log-Euclidean: the result is
//    SPD and anisotropy is kept; log-linear fields are reproduced exactly).
// Queries outside the active bounding box are clamped to it. Inactive voxels inside it read the
// grid's background value.
//
// The field is immutable and may be shared by threads. Each thread that queries in bulk makes
// its own Sampler (it caches tree nodes, so it is cheap per query and not thread-safe).
//
// .vdb files (write_metric_vdb / read_metric_vdb), grid names:
//   "size"                                          one scalar grid, the size h (isotropic)
//   "log_metric_xx" "log_metric_xy" "log_metric_yy"
//   "log_metric_xz" "log_metric_yz" "log_metric_zz"  six scalar grids, the components of log(M)
//   "metric_xx" ... "metric_zz"                      six scalar grids, M itself (read only; each
//                                                    voxel is converted to log(M))
// Float or double grids are read; writing uses float (what viewers expect) unless asked for
// double. All grids of one field must share their transform, which must be linear and uniform.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "core/sizing.hpp"
#include "core/status.hpp"
#include "lattice.hpp"

namespace anitet {
namespace metric {

// Opens the module as a task of the caller's TBB arena (60-90 ms of relocations on one core:
// another thread of the arena takes it up), so that a field built later finds it open and the
// arena's size bounds the threads that work. Meanwhile the loader's lock is held: a thread's
// first use of a thread_local with a destructor (glibc's __cxa_thread_atexit_impl) waits for it,
// which is why the pipeline starts this before stage 1 rather than beside stage 2. Building a
// field while it runs waits for it; the destructor waits for the task. Nothing happens for any
// preload after a process's first (the module is open or opening then); callers on one thread
// have nothing to overlap and need none.
class VdbModulePreload {
 public:
  VdbModulePreload();
  ~VdbModulePreload();
  VdbModulePreload(const VdbModulePreload&) = delete;
  VdbModulePreload& operator=(const VdbModulePreload&) = delete;

 private:
  struct Task;
  std::unique_ptr<Task> task_;
};

class MetricField final : public SizingField {
 public:
  enum class Kind { Isotropic, Tensor };
  struct Impl;  // in the module
  struct ImplDeleter {
    void operator()(Impl* impl) const;
  };

  MetricField(MetricField&&) noexcept;
  MetricField& operator=(MetricField&&) noexcept;
  ~MetricField() override;

  // Stores a lattice sparsely: node (i,j,k) becomes voxel (i,j,k). Leaf nodes whose values all lie
  // within `prune_tolerance` of each other (relative to their mean for sizes, absolute for log
  // components) collapse into one tile: 0 keeps every voxel exactly.
  static Result<MetricField> from_lattice(const Lattice& lattice, double prune_tolerance = 0.0);
  // Samples a callable (p -> M) on a lattice covering [lo, hi] with the given spacing.
  static Result<MetricField> from_function(
      const std::function<void(const double p[3], double m[6])>& metric_at, const double lo[3],
      const double hi[3], double spacing, size_t max_voxels = size_t(1) << 24);

  void metric(const double p[3], double m[6]) const override;
  // n points (3 doubles each) -> n metrics (6 doubles each), with one Sampler.
  void metrics(const double* points, size_t n, double* out) const;
  // Normalized lengths of n edges (a[3i..], b[3i..]): the metric length integrated along the edge
  // with 3-point Gauss-Legendre quadrature.
  void edge_lengths(const double* a, const double* b, size_t n, double* out) const;

  // The field over its active bounding box as a dense lattice (Error::OutOfMemory above
  // max_nodes), e.g. to grade it; from_lattice brings it back. Inactive voxels are marked in
  // `active` and hold the background value.
  Result<Lattice> to_lattice(size_t max_nodes = size_t(1) << 24) const;

  Kind kind() const;
  double voxel_size() const;
  size_t active_voxels() const;  // voxels and tiles' voxels
  size_t leaf_count() const;
  size_t memory_bytes() const;   // OpenVDB's memUsage of the grids

  class Sampler {
   public:
    explicit Sampler(const MetricField& field);
    Sampler(Sampler&&) noexcept;
    ~Sampler();
    void metric(const double p[3], double m[6]);
    // Batched: the points are visited in the memory order of the grid's leaves (sorted by their
    // leaf's Morton code), which is what makes large batches of scattered points fast.
    void metrics(const double* points, size_t n, double* out);
    // log(M) without the exp (for interpolating further, or for fast comparisons).
    void log_metric(const double p[3], double l[6]);
    void log_metrics(const double* points, size_t n, double* out);
    double edge_length(const double a[3], const double b[3]);

    struct State;  // in the module
    struct StateDeleter {
      void operator()(State* state) const;
    };

   private:
    std::unique_ptr<State, StateDeleter> state_;
  };

  // Internal (the module's result): takes ownership.
  explicit MetricField(Impl* impl);

 private:
  std::unique_ptr<Impl, ImplDeleter> impl_;
  friend Status write_metric_vdb(const MetricField&, const std::string&, bool);
  friend Result<MetricField> read_metric_vdb(const std::string&);
};

// Writes the field's grids (names above) to a .vdb file.
Status write_metric_vdb(const MetricField& field, const std::string& path,
                        bool double_precision = false);
// Reads a field from a .vdb file holding "size", the six "log_metric_*" or the six "metric_*"
// grids (tried in that order). Error::FileNotFound, Error::Parse (not a .vdb),
// Error::UnsupportedFormat (no such grids, non-uniform transform), Error::InvalidArgument
// (a size <= 0 or a metric that is not SPD).
Result<MetricField> read_metric_vdb(const std::string& path);

// Bounds then grades a field on its own voxels (see lattice.hpp); hmin/hmax <= 0 and hgrad <= 0
// skip that step. The result has the input's voxel size and voxel positions and keeps its
// inactive voxels inactive (gradation is computed through them as if they were active).
Result<MetricField> bound_and_grade(const MetricField& field, double hmin, double hmax,
                                    double hgrad, GradationStats* stats = nullptr);

}  // namespace metric
}  // namespace anitet
