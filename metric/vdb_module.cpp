// The module's entry point: the VdbBackend over the functions of vdb_module.hpp.
#include "vdb_module.hpp"

namespace anitet {
namespace metric {
namespace {

class Backend final : public VdbBackend {
 public:
  Status from_lattice(const Lattice& lattice, double prune, Field** out) const override {
    return build_from_lattice(lattice, prune, out);
  }
  Status read_vdb(const std::string& path, Field** out) const override {
    return read_vdb_file(path, out);
  }
  Status write_vdb(const Field& f, const std::string& path, bool double_precision) const override {
    return write_vdb_file(f, path, double_precision);
  }
  Status to_lattice(const Field& f, size_t max_nodes, Lattice& out) const override {
    return field_to_lattice(f, max_nodes, out);
  }
  void destroy(Field* f) const override { delete_field(f); }
  MetricField::Kind kind(const Field& f) const override { return field_kind(f); }
  double voxel_size(const Field& f) const override { return field_voxel_size(f); }
  size_t active_voxels(const Field& f) const override { return field_active_voxels(f); }
  size_t leaf_count(const Field& f) const override { return field_leaf_count(f); }
  size_t memory_bytes(const Field& f) const override { return field_memory_bytes(f); }
  uint64_t field_id(const Field& f) const override { return metric::field_id(f); }

  State* new_sampler(const Field& f) const override { return metric::new_sampler(f); }
  void delete_sampler(State* s) const override { metric::delete_sampler(s); }
  void sampler_metric(State& s, const double p[3], double m[6]) const override {
    metric::sampler_metric(s, p, m);
  }
  void sampler_log_metric(State& s, const double p[3], double l[6]) const override {
    metric::sampler_log_metric(s, p, l);
  }
  void sampler_batch(State& s, const double* points, size_t n, double* out,
                     bool log_only) const override {
    metric::sampler_batch(s, points, n, out, log_only);
  }

  Status create_layer(const SurfaceMesh& surface, const SizingField& background,
                      const BoundaryLayerOptions& options, BoundaryLayerStats* stats,
                      Layer** out) const override {
    return metric::create_layer(surface, background, options, stats, out);
  }
  void destroy(Layer* layer) const override { delete_layer(layer); }
  void layer_metric(const Layer& layer, const double p[3], double m[6]) const override {
    metric::layer_metric(layer, p, m);
  }
  bool wall_distance(const Layer& layer, const double p[3], double& d,
                     double closest[3]) const override {
    return layer_wall_distance(layer, p, d, closest);
  }
};

}  // namespace
}  // namespace metric
}  // namespace anitet

extern "C" const anitet::metric::VdbBackend*
anitet_vdb_backend_v1() {
  // Never destroyed: a thread's sampler cache (metric_field.cpp) may be freed after this
  // module's statics at exit (a TBB worker joined late), and its deleter calls the backend.
  static const anitet::metric::Backend* backend = new anitet::metric::Backend();
  return backend;
}

// The interface this module was built with (metric/CMakeLists.txt): checked before the entry point
// is called.
extern "C" const char* anitet_vdb_interface() { return ANITET_VDB_INTERFACE; }
