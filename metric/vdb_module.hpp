// The functions of the module libanitet_vdb.so (internal to it): vdb_metric_field.cpp and
// vdb_boundary_layer.cpp define them, vdb_module.cpp puts them behind the VdbBackend.
#pragma once

#include <cstddef>
#include <string>

#include "vdb_backend.hpp"

namespace anitet {
namespace metric {

// vdb_metric_field.cpp
Status build_from_lattice(const Lattice& lattice, double prune_tolerance, MetricField::Impl** out);
Status read_vdb_file(const std::string& path, MetricField::Impl** out);
Status write_vdb_file(const MetricField::Impl& field, const std::string& path, bool double_precision);
Status field_to_lattice(const MetricField::Impl& field, size_t max_nodes, Lattice& out);
void delete_field(MetricField::Impl* field);
MetricField::Kind field_kind(const MetricField::Impl& field);
double field_voxel_size(const MetricField::Impl& field);
size_t field_active_voxels(const MetricField::Impl& field);
size_t field_leaf_count(const MetricField::Impl& field);
size_t field_memory_bytes(const MetricField::Impl& field);
uint64_t field_id(const MetricField::Impl& field);
MetricField::Sampler::State* new_sampler(const MetricField::Impl& field);
void delete_sampler(MetricField::Sampler::State* state);
void sampler_metric(MetricField::Sampler::State& state, const double p[3], double m[6]);
void sampler_log_metric(MetricField::Sampler::State& state, const double p[3], double l[6]);
void sampler_batch(MetricField::Sampler::State& state, const double* points, size_t n,
                   double* out, bool log_only);

// vdb_boundary_layer.cpp
Status create_layer(const SurfaceMesh& surface, const SizingField& background,
                    const BoundaryLayerOptions& options, BoundaryLayerStats* stats,
                    BoundaryLayerField::Impl** out);
void delete_layer(BoundaryLayerField::Impl* layer);
void layer_metric(const BoundaryLayerField::Impl& layer, const double p[3], double m[6]);
bool layer_wall_distance(const BoundaryLayerField::Impl& layer, const double p[3], double& d,
                         double closest[3]);

}  // namespace metric
}  // namespace anitet
