// MetricField's side in the library: every call goes to the OpenVDB module (vdb_backend.hpp),
// which this file opens on the first field built or read.
#include "metric_field.hpp"

#include <dlfcn.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <vector>

#include <tbb/task_group.h>

#include "io/lazy_library.hpp"
#include "spd.hpp"
#include "vdb_backend.hpp"

namespace anitet {
namespace metric {

namespace {

// Where the module may be: $ANITET_VDB_MODULE alone when set; else beside the binary holding this code, or where an
// install puts it relative to that binary (lib/anitet/ from lib/ or bin/: a relocated install);
// then the build's and the install's own places (CMake).
std::vector<std::string> module_candidates() {
  std::vector<std::string> out;
  if (const char* env = std::getenv("ANITET_VDB_MODULE"); env && *env) {
    out.emplace_back(env);  // the user's choice: nothing else is tried
    return out;
  }
  Dl_info info;
  if (dladdr(reinterpret_cast<void*>(&module_candidates), &info) && info.dli_fname) {
    std::string self = info.dli_fname;
    const size_t slash = self.rfind('/');
    if (slash != std::string::npos) {
      const std::string dir = self.substr(0, slash + 1);
      out.push_back(dir + ANITET_VDB_MODULE_NAME);
      out.push_back(dir + "anitet/" + ANITET_VDB_MODULE_NAME);
      out.push_back(dir + "../" + ANITET_VDB_MODULE_LIBDIR + "/anitet/" + ANITET_VDB_MODULE_NAME);
    }
  }
  out.emplace_back(ANITET_VDB_MODULE_BUILD_PATH);
  out.emplace_back(ANITET_VDB_MODULE_INSTALL_PATH);
  return out;
}

struct Loaded {
  const VdbBackend* backend = nullptr;
  LazyLibrary* library = nullptr;  // never closed: the backend lives in it
  std::string error;
};

const Loaded& load() {
  static const Loaded loaded = [] {
    Loaded l;
    std::string tried;
    for (const std::string& path : module_candidates()) {
      // RTLD_LOCAL: the module's copies of the library's own code stay its own.
      auto* lib = new LazyLibrary(path.c_str());
      const char* (*interface)() = nullptr;
      const VdbBackend* (*entry)() = nullptr;
      if (lib->bind(interface, "anitet_vdb_interface") && lib->bind(entry, "anitet_vdb_backend_v1")) {
        if (std::strcmp(interface(), ANITET_VDB_INTERFACE) == 0) {
          l.library = lib;
          l.backend = entry();
          return l;
        }
        tried += "\n  " + path + ": built for another anitet (interface " + interface() +
                 ", this one " + ANITET_VDB_INTERFACE + ")";
      } else {
        tried += "\n  " + lib->error();
      }
      delete lib;
    }
    l.error = "the OpenVDB module " + std::string(ANITET_VDB_MODULE_NAME) +
              " could not be loaded (metric fields need it; set ANITET_VDB_MODULE to its path):" +
              tried;
    return l;
  }();
  return loaded;
}

const VdbBackend& backend() { return loaded_vdb_backend(); }

Result<MetricField> adopt(Status st, MetricField::Impl* impl) {
  if (!st.ok()) return st;
  return MetricField(impl);
}

}  // namespace

const VdbBackend* vdb_backend(std::string* error) {
  const Loaded& l = load();
  if (!l.backend && error) *error = l.error;
  return l.backend;
}

const VdbBackend& loaded_vdb_backend() { return *load().backend; }

namespace {
// Whether some VdbModulePreload started its thread (or found none to be had).
std::atomic<bool> preload_started{false};
}  // namespace

struct VdbModulePreload::Task {
  tbb::task_group group;
};

VdbModulePreload::VdbModulePreload() {
  // One opening per process: a second one, asked for while the first holds the loader's lock
  // (the CLI's preload, then the Mesher's), would wait for that lock.
  if (preload_started.exchange(true)) return;
  task_ = std::make_unique<Task>();
  task_->group.run([] {
    try {
      load();
    } catch (const std::bad_alloc&) {
      // The first field built tries again and reports it.
    }
  });
}

VdbModulePreload::~VdbModulePreload() {
  if (task_) task_->group.wait();
}

// ---- Sampler -----------------------------------------------------------------------------------

void MetricField::Sampler::StateDeleter::operator()(State* state) const {
  if (state) backend().delete_sampler(state);
}

MetricField::Sampler::Sampler(const MetricField& field)
    : state_(backend().new_sampler(*field.impl_)) {}
MetricField::Sampler::Sampler(Sampler&&) noexcept = default;
MetricField::Sampler::~Sampler() = default;

void MetricField::Sampler::metric(const double p[3], double m[6]) {
  backend().sampler_metric(*state_, p, m);
}

void MetricField::Sampler::metrics(const double* points, size_t n, double* out) {
  backend().sampler_batch(*state_, points, n, out, false);
}

void MetricField::Sampler::log_metrics(const double* points, size_t n, double* out) {
  backend().sampler_batch(*state_, points, n, out, true);
}

void MetricField::Sampler::log_metric(const double p[3], double l[6]) {
  backend().sampler_log_metric(*state_, p, l);
}

double MetricField::Sampler::edge_length(const double a[3], const double b[3]) {
  // 3-point Gauss-Legendre on [0, 1].
  static const double kT[3] = {0.5 - 0.5 * 0.7745966692414834, 0.5, 0.5 + 0.5 * 0.7745966692414834};
  static const double kW[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  const double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const VdbBackend& vdb = backend();
  double len = 0.0;
  for (int q = 0; q < 3; ++q) {
    const double p[3] = {a[0] + kT[q] * e[0], a[1] + kT[q] * e[1], a[2] + kT[q] * e[2]};
    double m[6];
    vdb.sampler_metric(*state_, p, m);
    len += kW[q] * metric_norm(m, e);
  }
  return len;
}

// ---- MetricField -------------------------------------------------------------------------------

void MetricField::ImplDeleter::operator()(Impl* impl) const {
  if (impl) backend().destroy(impl);
}

MetricField::MetricField(Impl* impl) : impl_(impl) {}
MetricField::MetricField(MetricField&&) noexcept = default;
MetricField& MetricField::operator=(MetricField&&) noexcept = default;
MetricField::~MetricField() = default;

MetricField::Kind MetricField::kind() const { return backend().kind(*impl_); }
double MetricField::voxel_size() const { return backend().voxel_size(*impl_); }
size_t MetricField::active_voxels() const { return backend().active_voxels(*impl_); }
size_t MetricField::leaf_count() const { return backend().leaf_count(*impl_); }
size_t MetricField::memory_bytes() const { return backend().memory_bytes(*impl_); }

void MetricField::metric(const double p[3], double m[6]) const {
  // One sampler per thread, kept for the last field this thread asked: consecutive queries are
  // usually close, so its cached tree nodes pay off. Field ids are never reused, so a sampler of
  // a destroyed field is never used again (an unsafe accessor's destructor does not touch its
  // tree). The cache lives here, not in the module: thread_local storage in a dlopen'ed library
  // is allocated per thread on demand, and LeakSanitizer's exit scan crashed now and then on
  // the blocks of TBB's exiting workers.
  struct Cache {
    uint64_t id = 0;
    std::unique_ptr<Sampler::State, Sampler::StateDeleter> state;
  };
  thread_local Cache cache;
  const VdbBackend& vdb = backend();
  if (const uint64_t id = vdb.field_id(*impl_); cache.id != id) {
    cache.state.reset(vdb.new_sampler(*impl_));
    cache.id = id;
  }
  vdb.sampler_metric(*cache.state, p, m);
}

void MetricField::metrics(const double* points, size_t n, double* out) const {
  Sampler s(*this);
  s.metrics(points, n, out);
}

void MetricField::edge_lengths(const double* a, const double* b, size_t n, double* out) const {
  Sampler s(*this);
  for (size_t i = 0; i < n; ++i) out[i] = s.edge_length(a + 3 * i, b + 3 * i);
}

Result<MetricField> MetricField::from_lattice(const Lattice& lat, double prune_tolerance) {
  std::string error;
  const VdbBackend* vdb = vdb_backend(&error);
  if (!vdb) return Status(Error::NotImplemented, error);
  Impl* impl = nullptr;
  Status st = vdb->from_lattice(lat, prune_tolerance, &impl);
  return adopt(std::move(st), impl);
}

Result<MetricField> MetricField::from_function(
    const std::function<void(const double p[3], double m[6])>& metric_at, const double lo[3],
    const double hi[3], double spacing, size_t max_voxels) {
  if (!(spacing > 0.0)) return Status(Error::InvalidArgument, "spacing must be positive");
  Lattice lat;
  lat.spacing = spacing;
  lat.components = 6;
  double count = 1.0;
  for (int k = 0; k < 3; ++k) {
    if (!(hi[k] >= lo[k])) return Status(Error::InvalidArgument, "empty or non-finite box");
    const double n = std::ceil((hi[k] - lo[k]) / spacing - 1e-9) + 1.0;
    count *= n;
    if (count > double(max_voxels))
      return Status(Error::OutOfMemory, "the box needs more than max_voxels voxels");
    lat.dims[k] = int(n);
    lat.origin[k] = lo[k];
  }
  lat.values.resize(6 * lat.num_nodes());
  for (int k = 0; k < lat.dims[2]; ++k)
    for (int j = 0; j < lat.dims[1]; ++j)
      for (int i = 0; i < lat.dims[0]; ++i) {
        double p[3], m[6];
        lat.position(i, j, k, p);
        metric_at(p, m);
        if (!sym_log(m, &lat.values[6 * lat.node(i, j, k)]))
          return Status(Error::InvalidArgument, "the function's metric is not SPD at (" +
                                                    std::to_string(p[0]) + ", " +
                                                    std::to_string(p[1]) + ", " +
                                                    std::to_string(p[2]) + ")");
      }
  return from_lattice(lat);
}

Result<Lattice> MetricField::to_lattice(size_t max_nodes) const {
  Lattice lat;
  Status st = backend().to_lattice(*impl_, max_nodes, lat);
  if (!st.ok()) return st;
  return lat;
}

Result<MetricField> bound_and_grade(const MetricField& field, double hmin, double hmax,
                                    double hgrad, GradationStats* stats) {
  Result<Lattice> lat = field.to_lattice();
  if (!lat.ok()) return lat.status();
  if (hmin > 0.0 || hmax > 0.0) {
    Status st = bound_sizes(lat.value(), hmin, hmax);
    if (!st.ok()) return st;
  }
  if (hgrad > 0.0) {
    Result<GradationStats> g = grade(lat.value(), hgrad);
    if (!g.ok()) return g.status();
    if (stats) *stats = g.value();
  }
  return MetricField::from_lattice(lat.value());
}

Result<MetricField> read_metric_vdb(const std::string& path) {
  std::string error;
  const VdbBackend* vdb = vdb_backend(&error);
  if (!vdb) return Status(Error::NotImplemented, error);
  MetricField::Impl* impl = nullptr;
  Status st = vdb->read_vdb(path, &impl);
  return adopt(std::move(st), impl);
}

Status write_metric_vdb(const MetricField& field, const std::string& path, bool double_precision) {
  return backend().write_vdb(*field.impl_, path, double_precision);
}

}  // namespace metric
}  // namespace anitet
