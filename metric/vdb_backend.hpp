// The OpenVDB half of metric/ (internal header): MetricField and BoundaryLayerField forward to a
// VdbBackend, which the module libanitet_vdb.so implements (vdb_metric_field.cpp,
// vdb_boundary_layer.cpp, the only sources that include OpenVDB). The library opens the module on
// the first field built or read, so that programs start without loading OpenVDB (see
// metric_field.hpp). Both sides come from one build: C++ types cross freely.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "boundary_layer.hpp"
#include "metric_field.hpp"

namespace anitet {
namespace metric {

class VdbBackend {
 public:
  using Field = MetricField::Impl;
  using State = MetricField::Sampler::State;
  using Layer = BoundaryLayerField::Impl;

  virtual ~VdbBackend() = default;

  // MetricField (see metric_field.hpp). *out owns the new field on success.
  virtual Status from_lattice(const Lattice& lattice, double prune_tolerance, Field** out) const = 0;
  virtual Status read_vdb(const std::string& path, Field** out) const = 0;
  virtual Status write_vdb(const Field& field, const std::string& path, bool double_precision) const = 0;
  virtual Status to_lattice(const Field& field, size_t max_nodes, Lattice& out) const = 0;
  virtual void destroy(Field* field) const = 0;
  virtual MetricField::Kind kind(const Field& field) const = 0;
  virtual double voxel_size(const Field& field) const = 0;
  virtual size_t active_voxels(const Field& field) const = 0;
  virtual size_t leaf_count(const Field& field) const = 0;
  virtual size_t memory_bytes(const Field& field) const = 0;
  // Unique per field ever built (keys MetricField::metric's per-thread sampler).
  virtual uint64_t field_id(const Field& field) const = 0;

  // MetricField::Sampler.
  virtual State* new_sampler(const Field& field) const = 0;
  virtual void delete_sampler(State* state) const = 0;
  virtual void sampler_metric(State& state, const double p[3], double m[6]) const = 0;
  virtual void sampler_log_metric(State& state, const double p[3], double l[6]) const = 0;
  virtual void sampler_batch(State& state, const double* points, size_t n, double* out,
                             bool log_only) const = 0;

  // BoundaryLayerField (see boundary_layer.hpp). *out owns the new field on success.
  virtual Status create_layer(const SurfaceMesh& surface, const SizingField& background,
                              const BoundaryLayerOptions& options, BoundaryLayerStats* stats,
                              Layer** out) const = 0;
  virtual void destroy(Layer* layer) const = 0;
  virtual void layer_metric(const Layer& layer, const double p[3], double m[6]) const = 0;
  virtual bool wall_distance(const Layer& layer, const double p[3], double& d,
                             double closest[3]) const = 0;
};

// The module's backend, opened on the first call (thread-safe); null when the module cannot be
// loaded, with the reason in *error. Looked for at $ANITET_VDB_MODULE alone when it is set; else
// beside the binary that holds this library, then where the build and the install put it. A
// module built with another interface (a hash of the headers that cross it) is passed over.
const VdbBackend* vdb_backend(std::string* error = nullptr);

// The backend of a field that exists (it was made by the backend, so the module is loaded).
const VdbBackend& loaded_vdb_backend();

}  // namespace metric
}  // namespace anitet

// The module's entry point, and the interface hash it was built with (compared first).
extern "C" const anitet::metric::VdbBackend* anitet_vdb_backend_v1();
extern "C" const char* anitet_vdb_interface();
