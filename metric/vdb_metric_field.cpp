// MetricField's OpenVDB half, in the module libanitet_vdb.so (vdb_backend.hpp): the grids, the
// samplers and the .vdb files. MetricField (metric_field.cpp) forwards here.
#include "vdb_module.hpp"

#include <openvdb/openvdb.h>
#include <openvdb/io/File.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <string>
#include <fstream>
#include <limits>
#include <vector>

#include "io/file_bytes.hpp"
#include "spd.hpp"

// The per-point helpers of the batched loops: GCC would otherwise call them out of line.
#if defined(__GNUC__)
#define ANITET_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define ANITET_ALWAYS_INLINE inline
#endif

namespace anitet {
namespace metric {

using openvdb::Coord;
using openvdb::DoubleGrid;
using openvdb::FloatGrid;
using openvdb::Vec3d;
using openvdb::Vec3DGrid;
using DoubleTree = DoubleGrid::TreeType;
using Vec3DTree = Vec3DGrid::TreeType;

struct MetricField::Impl {
  uint64_t id = 0;  // unique per field ever built: keys the per-thread sampler of MetricField::metric
  Kind kind = Kind::Isotropic;
  DoubleGrid::Ptr size;  // isotropic: h
  Vec3DGrid::Ptr diag;   // tensor: log(M) xx yy zz
  Vec3DGrid::Ptr off;    // tensor: log(M) xy xz yz
  double origin[3] = {0, 0, 0};
  double dx = 1.0, inv_dx = 1.0;
  int bmin[3] = {0, 0, 0}, bmax[3] = {0, 0, 0};  // active bounding box, inclusive
  bool vdb_transform = true;  // the grids carry the world transform (false: voxels too small)

  openvdb::math::Transform::Ptr transform() const {
    return (kind == Kind::Isotropic ? size->transform() : diag->transform()).copy();
  }
};

namespace {

constexpr double kMinVdbDeterminant = 1e-14;  // OpenVDB's limit is 3e-15

// All three grids always exist (empty when unused), so that samplers can hold accessors to each.
std::unique_ptr<MetricField::Impl> make_impl(MetricField::Kind kind, double background_size) {
  static std::atomic<uint64_t> next_id{1};
  auto impl = std::make_unique<MetricField::Impl>();
  impl->id = next_id.fetch_add(1, std::memory_order_relaxed);
  impl->kind = kind;
  impl->size = DoubleGrid::create(background_size);
  impl->diag = Vec3DGrid::create(Vec3d(0.0));
  impl->off = Vec3DGrid::create(Vec3d(0.0));
  impl->size->setName("size");
  return impl;
}

// Sets the transform of every grid and caches the index-space mapping and the active box.
Status finish_impl(MetricField::Impl& f, double dx, const double origin[3]) {
  // OpenVDB refuses a linear transform whose determinant dx^3 is below 3e-15 (voxels under about
  // 1.4e-5). Sampling does not need it (the index mapping below is our own), so such a field
  // keeps the default transform and only refuses to be written as .vdb.
  f.vdb_transform = dx * dx * dx >= kMinVdbDeterminant;
  if (f.vdb_transform) {
    auto xf = openvdb::math::Transform::createLinearTransform(dx);
    xf->postTranslate(Vec3d(origin[0], origin[1], origin[2]));
    f.size->setTransform(xf);
    f.diag->setTransform(xf->copy());
    f.off->setTransform(xf->copy());
  }
  f.dx = dx;
  f.inv_dx = 1.0 / dx;
  for (int k = 0; k < 3; ++k) f.origin[k] = origin[k];
  openvdb::CoordBBox box;
  const bool any = f.kind == MetricField::Kind::Isotropic
                       ? f.size->tree().evalActiveVoxelBoundingBox(box)
                       : f.diag->tree().evalActiveVoxelBoundingBox(box);
  if (!any) return Status(Error::EmptyInput, "the metric field has no active voxel");
  for (int k = 0; k < 3; ++k) {
    f.bmin[k] = box.min()[k];
    f.bmax[k] = box.max()[k];
  }
  return Status::success();
}

// The 8 values around base voxel c: corner bit 0 = +x, bit 1 = +y, bit 2 = +z. Each leaf the
// 2x2x2 block touches is probed once (one leaf 7 times in 8 per axis) and read directly; a
// corner outside every leaf reads its tile or the background.
template <class Acc, class T>
inline void gather(Acc& acc, const Coord& c, T v[8]) {
  using Leaf = typename Acc::TreeType::LeafNodeType;
  const int cross[3] = {(c.x() & 7) == 7, (c.y() & 7) == 7, (c.z() & 7) == 7};
  if (!(cross[0] | cross[1] | cross[2])) {
    if (const Leaf* leaf = acc.probeConstLeaf(c)) {
      const T* d = leaf->buffer().data();
      const openvdb::Index o = Leaf::coordToOffset(c);
      v[0] = d[o];
      v[1] = d[o + 64];
      v[2] = d[o + 8];
      v[3] = d[o + 72];
      v[4] = d[o + 1];
      v[5] = d[o + 65];
      v[6] = d[o + 9];
      v[7] = d[o + 73];
      return;
    }
  }
  const T* data[8];  // per leaf combination (bit 0: +x leaf, ...), null outside leaves
  for (int l = 0; l < 8; ++l) {
    if (((l & 1) && !cross[0]) || ((l & 2) && !cross[1]) || ((l & 4) && !cross[2])) continue;
    const Leaf* leaf =
        acc.probeConstLeaf(Coord(c.x() + (l & 1), c.y() + ((l >> 1) & 1), c.z() + ((l >> 2) & 1)));
    data[l] = leaf ? leaf->buffer().data() : nullptr;
  }
  for (int i = 0; i < 8; ++i) {
    const Coord q(c.x() + (i & 1), c.y() + ((i >> 1) & 1), c.z() + ((i >> 2) & 1));
    const int l = (i & 1 & cross[0]) | ((i & 2) & (cross[1] << 1)) | ((i & 4) & (cross[2] << 2));
    v[i] = data[l] ? data[l][Leaf::coordToOffset(q)] : acc.getValue(q);
  }
}

// log(M) as xx xy yy xz yz zz from the grids' (xx yy zz) and (xy xz yz).
ANITET_ALWAYS_INLINE void log_components(const Vec3d& diag, const Vec3d& off, double l[6]) {
  l[0] = diag[0];
  l[2] = diag[1];
  l[5] = diag[2];
  l[1] = off[0];
  l[3] = off[1];
  l[4] = off[2];
}

template <class T>
inline T trilinear(const T v[8], double fx, double fy, double fz) {
  const T a = v[0] + (v[1] - v[0]) * fx, b = v[2] + (v[3] - v[2]) * fx;
  const T c = v[4] + (v[5] - v[4]) * fx, d = v[6] + (v[7] - v[6]) * fx;
  const T e = a + (b - a) * fy, g = c + (d - c) * fy;
  return e + (g - e) * fz;
}

}  // namespace

// ---- Sampler -----------------------------------------------------------------------------------

struct MetricField::Sampler::State {
  const MetricField::Impl& f;
  DoubleGrid::ConstUnsafeAccessor size;
  Vec3DGrid::ConstUnsafeAccessor diag, off;
  explicit State(const MetricField::Impl& field)
      : f(field),
        size(field.size->tree()),
        diag(field.diag->tree()),
        off(field.off->tree()) {}

  // Base voxel and fractions of p, clamped to the active box.
  ANITET_ALWAYS_INLINE Coord locate(const double p[3], double frac[3]) const {
    int base[3];
    for (int k = 0; k < 3; ++k) {
      double x = (p[k] - f.origin[k]) * f.inv_dx;
      if (!(x >= f.bmin[k])) x = f.bmin[k];  // also NaN
      if (x > f.bmax[k]) x = f.bmax[k];
      int i = int(std::floor(x));
      if (i >= f.bmax[k]) i = std::max(f.bmax[k] - 1, f.bmin[k]);
      base[k] = i;
      frac[k] = x - i;
    }
    return Coord(base[0], base[1], base[2]);
  }

  inline void log_metric(const double p[3], double l[6]) {
    double t[3];
    const Coord c = locate(p, t);
    if (f.kind == Kind::Isotropic) {
      const double h = size_at(c, t);
      l[0] = l[2] = l[5] = -2.0 * std::log(h);
      l[1] = l[3] = l[4] = 0.0;
      return;
    }
    Vec3d d[8], o[8];
    gather(diag, c, d);
    gather(off, c, o);
    log_components(trilinear(d, t[0], t[1], t[2]), trilinear(o, t[0], t[1], t[2]), l);
  }

  // Batches: points are visited in Morton order of their leaves (a radix sort), so that each
  // leaf and the tree nodes above it are fetched from memory once per batch rather than once per
  // point; results go back to the callers' order.
  template <bool log_only>
  void batch(const double* points, size_t n, double* out) {
    if (n < 256 || n > size_t(UINT32_MAX)) {
      for (size_t i = 0; i < n; ++i) {
        if (log_only) log_metric(points + 3 * i, out + 6 * i);
        else metric(points + 3 * i, out + 6 * i);
      }
      return;
    }
    keys.resize(n);
    order.resize(n);
    uint64_t all_or = 0;
    for (size_t i = 0; i < n; ++i) {
      double t[3];
      const Coord c = locate(points + 3 * i, t);
      // The leaf's index in the box (leaves sit at multiples of 8): one key per leaf.
      keys[i] = morton(uint32_t((c.x() >> 3) - (f.bmin[0] >> 3)),
                       uint32_t((c.y() >> 3) - (f.bmin[1] >> 3)),
                       uint32_t((c.z() >> 3) - (f.bmin[2] >> 3)));
      order[i] = uint32_t(i);
      all_or |= keys[i];
    }
    radix_sort(all_or);
    if (f.kind == Kind::Isotropic) {
      // One double per point: read each point where it is, write h to its slot (8 random bytes
      // instead of 48), then expand to metrics in a sequential pass.
      gather_points(points, n);
      sorted_out.resize(n);
      // The leaves come from memory in key order: a few points ahead of the one evaluated, the
      // first point of the next leaf has its leaf prefetched, so its misses overlap our work.
      constexpr size_t kAhead = 16;
      for (size_t k = 0; k < n; ++k) {
        const size_t a = k + kAhead;
        if (a < n && keys[a] != keys[a - 1]) prefetch_size_leaf(&sorted_pts[3 * a]);
        double t[3];
        const Coord c = locate(&sorted_pts[3 * k], t);
        sorted_out[k] = size_at(c, t);
      }
      sizes.resize(n);
      for (size_t k = 0; k < n; ++k) sizes[order[k]] = sorted_out[k];
      for (size_t i = 0; i < n; ++i) {
        double* m = out + 6 * i;
        const double d = log_only ? -2.0 * std::log(sizes[i]) : 1.0 / (sizes[i] * sizes[i]);
        m[0] = m[2] = m[5] = d;
        m[1] = m[3] = m[4] = 0.0;
      }
      return;
    }
    // Gather, evaluate in order, scatter: the gather and scatter loops have independent
    // iterations, so their cache misses overlap instead of stalling the evaluation.
    gather_points(points, n);
    sorted_out.resize(6 * n);
    for (size_t k = 0; k < n; ++k) {
      if (log_only) log_metric(&sorted_pts[3 * k], &sorted_out[6 * k]);
      else metric(&sorted_pts[3 * k], &sorted_out[6 * k]);
    }
    for (size_t k = 0; k < n; ++k) {
      const double* src = &sorted_out[6 * k];
      double* dst = out + 6 * size_t(order[k]);
      for (int c = 0; c < 6; ++c) dst[c] = src[c];
    }
  }

  void gather_points(const double* points, size_t n) {
    sorted_pts.resize(3 * n);
    for (size_t k = 0; k < n; ++k) {
      const double* p = points + 3 * size_t(order[k]);
      sorted_pts[3 * k] = p[0];
      sorted_pts[3 * k + 1] = p[1];
      sorted_pts[3 * k + 2] = p[2];
    }
  }

  void prefetch_size_leaf(const double p[3]) {
    double t[3];
    const DoubleTree::LeafNodeType* leaf = size.probeConstLeaf(locate(p, t));
    if (!leaf) return;
    const char* d = reinterpret_cast<const char*>(leaf->buffer().data());
    for (size_t b = 0; b < 512 * sizeof(double); b += 64) __builtin_prefetch(d + b);
  }

  // The size at base voxel c and fractions t. Reads the leaves' buffers directly, keeping the
  // data pointers of the base voxel's leaf and of its 7 neighbours on the + sides (fetched on
  // first use): batched points come leaf by leaf, and neither the accessor's probe nor
  // LeafBuffer::data() is free. A block touching a tile or the background goes through gather.
  ANITET_ALWAYS_INLINE double size_at(const Coord& c, const double t[3]) {
    const Coord o(c.x() & ~7, c.y() & ~7, c.z() & ~7);
    if (o != leaf_origin) {
      leaf_origin = o;
      leaves_known = 0;
    }
    const int cx = (c.x() & 7) == 7, cy = (c.y() & 7) == 7, cz = (c.z() & 7) == 7;
    bool direct = true;
    for (int l = 0; l < 8; ++l) {
      if (((l & 1) && !cx) || ((l & 2) && !cy) || ((l & 4) && !cz)) continue;
      if (!(leaves_known & (1u << l))) {
        const auto* leaf = size.probeConstLeaf(
            Coord(o.x() + 8 * (l & 1), o.y() + 4 * (l & 2), o.z() + 2 * (l & 4)));
        leaf_data[l] = leaf ? leaf->buffer().data() : nullptr;
        leaves_known |= 1u << l;
      }
      direct &= leaf_data[l] != nullptr;
    }
    double v[8];
    if (direct) {
      for (int i = 0; i < 8; ++i) {
        const int ix = i & 1, iy = (i >> 1) & 1, iz = (i >> 2) & 1;
        const int l = (ix & cx) | ((iy & cy) << 1) | ((iz & cz) << 2);
        const int at = (((c.x() + ix) & 7) << 6) | (((c.y() + iy) & 7) << 3) | ((c.z() + iz) & 7);
        v[i] = leaf_data[l][at];
      }
    } else {
      gather(size, c, v);
    }
    return trilinear(v, t[0], t[1], t[2]);
  }

  static uint64_t spread(uint32_t v) {  // bits of v at every third position
    uint64_t x = v & 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffULL;
    x = (x | x << 16) & 0x1f0000ff0000ffULL;
    x = (x | x << 8) & 0x100f00f00f00f00fULL;
    x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
  }
  static uint64_t morton(uint32_t x, uint32_t y, uint32_t z) {
    return spread(x) | spread(y) << 1 | spread(z) << 2;
  }

  // LSD radix sort of `order` by `keys`, 8 bits a pass, only over the bytes some key uses.
  void radix_sort(uint64_t all_or) {
    const size_t n = keys.size();
    keys2.resize(n);
    order2.resize(n);
    for (int shift = 0; shift < 64 && (all_or >> shift) != 0; shift += 8) {
      size_t count[257] = {0};
      for (size_t i = 0; i < n; ++i) ++count[((keys[i] >> shift) & 0xff) + 1];
      for (int b = 0; b < 256; ++b) count[b + 1] += count[b];
      for (size_t i = 0; i < n; ++i) {
        const size_t dst = count[(keys[i] >> shift) & 0xff]++;
        keys2[dst] = keys[i];
        order2[dst] = order[i];
      }
      keys.swap(keys2);
      order.swap(order2);
    }
  }

  std::vector<uint64_t> keys, keys2;
  std::vector<uint32_t> order, order2;
  std::vector<double> sorted_pts, sorted_out, sizes;
  Coord leaf_origin{std::numeric_limits<int32_t>::max()};  // size_at's leaf (none yet)
  const double* leaf_data[8] = {};  // its buffer and its + neighbours' (bit 0: +x, 1: +y, 2: +z)
  unsigned leaves_known = 0;        // which of leaf_data are fetched

  inline void metric(const double p[3], double m[6]) {
    if (f.kind == Kind::Isotropic) {
      double t[3];
      const Coord c = locate(p, t);
      isotropic_metric(size_at(c, t), m);
      return;
    }
    double l[6];
    log_metric(p, l);
    sym_exp(l, m);
  }
};

// ---- MetricField -------------------------------------------------------------------------------

using Kind = MetricField::Kind;
using Impl = MetricField::Impl;

uint64_t field_id(const Impl& field) { return field.id; }

Status build_from_lattice(const Lattice& lat, double prune_tolerance, Impl** out) {
  Status st = check_lattice(lat);
  if (!st.ok()) return st;
  const bool iso = lat.components == 1;
  double hmax = 0.0;
  if (iso)  // the background, read by inactive voxels: the coarsest size
    for (double h : lat.values) hmax = std::max(hmax, h);
  auto impl = make_impl(iso ? Kind::Isotropic : Kind::Tensor, iso ? hmax : 1.0);
  try {
    if (iso) {
      auto acc = impl->size->getAccessor();
      for (int k = 0; k < lat.dims[2]; ++k)
        for (int j = 0; j < lat.dims[1]; ++j)
          for (int i = 0; i < lat.dims[0]; ++i) {
            const size_t n = lat.node(i, j, k);
            if (lat.active.empty() || lat.active[n]) acc.setValue(Coord(i, j, k), lat.values[n]);
          }
    } else {
      auto dacc = impl->diag->getAccessor();
      auto oacc = impl->off->getAccessor();
      for (int k = 0; k < lat.dims[2]; ++k)
        for (int j = 0; j < lat.dims[1]; ++j)
          for (int i = 0; i < lat.dims[0]; ++i) {
            if (!lat.active.empty() && !lat.active[lat.node(i, j, k)]) continue;
            const double* l = &lat.values[6 * lat.node(i, j, k)];
            dacc.setValue(Coord(i, j, k), Vec3d(l[0], l[2], l[5]));
            oacc.setValue(Coord(i, j, k), Vec3d(l[1], l[3], l[4]));
          }
    }
    if (prune_tolerance > 0.0) {
      // Collapse near-constant leaves into tiles (same decision for both tensor grids, so they
      // keep one topology). Only leaves fully inside the lattice: a partial leaf's tile would
      // activate voxels outside it.
      std::vector<Coord> collapse;  // origins of the leaves to replace by tiles
      if (iso) {
        for (auto leaf = impl->size->tree().cbeginLeaf(); leaf; ++leaf) {
          if (!leaf->isValueMaskOn()) continue;
          double lo = HUGE_VAL, hi = -HUGE_VAL, sum = 0.0;
          for (auto v = leaf->cbeginValueOn(); v; ++v) {
            lo = std::min(lo, *v);
            hi = std::max(hi, *v);
            sum += *v;
          }
          if (hi - lo <= prune_tolerance * sum / 512.0) collapse.push_back(leaf->origin());
        }
        for (const Coord& c : collapse) {
          const auto* leaf = impl->size->tree().probeConstLeaf(c);
          double sum = 0.0;
          for (auto v = leaf->cbeginValueOn(); v; ++v) sum += *v;
          impl->size->tree().addTile(1, c, sum / 512.0, true);
        }
      } else {
        for (auto leaf = impl->diag->tree().cbeginLeaf(); leaf; ++leaf) {
          if (!leaf->isValueMaskOn()) continue;
          const auto* other = impl->off->tree().probeConstLeaf(leaf->origin());
          Vec3d lo(HUGE_VAL), hi(-HUGE_VAL), olo(HUGE_VAL), ohi(-HUGE_VAL);
          for (openvdb::Index n = 0; n < 512; ++n) {
            lo = openvdb::math::minComponent(lo, leaf->getValue(n));
            hi = openvdb::math::maxComponent(hi, leaf->getValue(n));
            olo = openvdb::math::minComponent(olo, other->getValue(n));
            ohi = openvdb::math::maxComponent(ohi, other->getValue(n));
          }
          const Vec3d d = hi - lo, od = ohi - olo;
          if (std::max({d[0], d[1], d[2], od[0], od[1], od[2]}) <= prune_tolerance)
            collapse.push_back(leaf->origin());
        }
        for (const Coord& c : collapse) {
          Vec3d ds(0.0), os(0.0);
          const auto* dl = impl->diag->tree().probeConstLeaf(c);
          const auto* ol = impl->off->tree().probeConstLeaf(c);
          for (openvdb::Index n = 0; n < 512; ++n) {
            ds += dl->getValue(n);
            os += ol->getValue(n);
          }
          impl->diag->tree().addTile(1, c, ds / 512.0, true);
          impl->off->tree().addTile(1, c, os / 512.0, true);
        }
      }
    }
    st = finish_impl(*impl, lat.spacing, lat.origin);
  } catch (const std::bad_alloc&) {
    return Status(Error::OutOfMemory, "out of memory while building the metric grids");
  } catch (const std::exception& e) {
    return Status(Error::Internal, std::string("OpenVDB: ") + e.what());
  }
  if (!st.ok()) return st;
  *out = impl.release();
  return Status::success();
}

Status field_to_lattice(const Impl& f, size_t max_nodes, Lattice& lat) {
  lat.spacing = f.dx;
  lat.components = f.kind == Kind::Isotropic ? 1 : 6;
  double count = 1.0;
  for (int k = 0; k < 3; ++k) {
    lat.dims[k] = f.bmax[k] - f.bmin[k] + 1;
    count *= lat.dims[k];
    lat.origin[k] = f.origin[k] + f.dx * f.bmin[k];
  }
  if (count > double(max_nodes))
    return Status(Error::OutOfMemory, "the field's box has more than max_nodes voxels");
  lat.values.resize(lat.num_nodes() * size_t(lat.components));
  MetricField::Sampler::State s(f);
  for (int k = 0; k < lat.dims[2]; ++k)
    for (int j = 0; j < lat.dims[1]; ++j)
      for (int i = 0; i < lat.dims[0]; ++i) {
        const Coord c(f.bmin[0] + i, f.bmin[1] + j, f.bmin[2] + k);
        const size_t n = lat.node(i, j, k);
        const bool on = lat.components == 1 ? s.size.isValueOn(c) : s.diag.isValueOn(c);
        if (!on) {
          if (lat.active.empty()) lat.active.assign(lat.num_nodes(), 1);
          lat.active[n] = 0;
        }
        if (lat.components == 1) {
          lat.values[n] = s.size.getValue(c);
        } else {
          log_components(s.diag.getValue(c), s.off.getValue(c), &lat.values[6 * n]);
        }
      }
  return Status::success();
}

// ---- .vdb files --------------------------------------------------------------------------------

namespace {

const char* const kLogNames[6] = {"log_metric_xx", "log_metric_xy", "log_metric_yy",
                                  "log_metric_xz", "log_metric_yz", "log_metric_zz"};
const char* const kRawNames[6] = {"metric_xx", "metric_xy", "metric_yy",
                                  "metric_xz", "metric_yz", "metric_zz"};

// Copies the active values (voxels and tiles, tiles kept as tiles) of src into dst through f.
template <class SrcTree, class DstGrid, class F>
void copy_active(const SrcTree& src, DstGrid& dst, F&& f) {
  auto acc = dst.getAccessor();
  for (auto it = src.cbeginValueOn(); it; ++it) {
    if (it.isVoxelValue()) acc.setValue(it.getCoord(), f(*it, it.getCoord()));
    else acc.addTile(it.getLevel(), it.getCoord(), f(*it, it.getCoord()), true);
  }
}

// A scalar grid of the file as a DoubleGrid (float grids are widened), or null.
DoubleGrid::Ptr read_scalar(openvdb::io::File& file, const std::string& name) {
  if (!file.hasGrid(name)) return nullptr;
  openvdb::GridBase::Ptr base = file.readGrid(name);
  if (auto d = openvdb::gridPtrCast<DoubleGrid>(base)) return d;
  if (auto g = openvdb::gridPtrCast<FloatGrid>(base)) {
    auto d = DoubleGrid::create(double(g->background()));
    d->setTransform(g->transform().copy());
    copy_active(g->tree(), *d, [](float v, const Coord&) { return double(v); });
    return d;
  }
  return nullptr;
}

// The grid's voxel size and origin when its transform is a uniform scale plus translation.
bool uniform_transform(const openvdb::math::Transform& xf, double& dx, double origin[3]) {
  if (!xf.isLinear()) return false;
  const Vec3d o = xf.indexToWorld(Vec3d(0.0));
  dx = xf.voxelSize()[0];
  if (!(dx > 0.0)) return false;
  for (int k = 0; k < 3; ++k) {
    Vec3d e(0.0);
    e[k] = 1.0;
    const Vec3d d = xf.indexToWorld(e) - o;
    for (int i = 0; i < 3; ++i)
      if (std::fabs(d[i] - (i == k ? dx : 0.0)) > 1e-12 * dx) return false;
    origin[k] = o[k];
  }
  return true;
}

Status read_vdb_impl(const std::string& path, std::unique_ptr<MetricField::Impl>& out) {
  openvdb::initialize();
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) return Status(Error::FileNotFound, "cannot open " + path);
  }
  openvdb::io::File file(path);
  try {
    file.open(false);
  } catch (const std::exception& e) {
    return Status(Error::Parse, path + " is not a readable .vdb file: " + e.what());
  }
  std::unique_ptr<MetricField::Impl> impl;
  double dx = 0.0, origin[3] = {0, 0, 0};
  if (DoubleGrid::Ptr size = read_scalar(file, "size")) {
    if (!uniform_transform(size->transform(), dx, origin))
      return Status(Error::UnsupportedFormat, path + ": grid 'size' has a non-uniform transform");
    double hmax = 0.0;
    for (auto it = size->tree().cbeginValueOn(); it; ++it) {
      if (!(*it > 0.0) || !std::isfinite(*it))
        return Status(Error::InvalidArgument, path + ": grid 'size' has a size <= 0 at " +
                                                  it.getCoord().asVec3i().str());
      hmax = std::max(hmax, *it);
    }
    // Inactive voxels inside the box read the background: keep it a valid (the largest) size.
    const double bg = size->background() > 0.0 ? size->background() : hmax;
    impl = make_impl(MetricField::Kind::Isotropic, bg);
    copy_active(size->tree(), *impl->size, [](double v, const Coord&) { return v; });
  } else {
    const char* const* names = nullptr;
    if (file.hasGrid(kLogNames[0])) names = kLogNames;
    else if (file.hasGrid(kRawNames[0])) names = kRawNames;
    if (!names)
      return Status(Error::UnsupportedFormat,
                    path + " has no grid named 'size', 'log_metric_xx' or 'metric_xx'");
    DoubleGrid::Ptr g[6];
    for (int c = 0; c < 6; ++c) {
      g[c] = read_scalar(file, names[c]);
      if (!g[c])
        return Status(Error::UnsupportedFormat,
                      path + ": missing float/double grid '" + names[c] + "'");
      double d2 = 0.0, o2[3];
      if (!uniform_transform(g[c]->transform(), d2, o2) ||
          (c > 0 && (d2 != dx || o2[0] != origin[0] || o2[1] != origin[1] || o2[2] != origin[2])))
        return Status(Error::UnsupportedFormat,
                      path + ": grid '" + names[c] + "' has a non-uniform or different transform");
      if (c == 0) {
        dx = d2;
        std::copy(o2, o2 + 3, origin);
      }
    }
    const bool raw = names == kRawNames;
    impl = make_impl(MetricField::Kind::Tensor, 1.0);
    std::vector<DoubleGrid::ConstAccessor> acc;
    for (int c = 0; c < 6; ++c) acc.push_back(g[c]->getConstAccessor());
    auto to_log = [&](const Coord& xyz, double l[6]) -> bool {
      double m[6];
      for (int c = 0; c < 6; ++c) m[c] = acc[c].getValue(xyz);
      if (!raw) {
        std::copy(m, m + 6, l);
        for (int c = 0; c < 6; ++c)
          if (!std::isfinite(l[c])) return false;
        return true;
      }
      return sym_log(m, l);
    };
    auto dacc = impl->diag->getAccessor();
    auto oacc = impl->off->getAccessor();
    for (auto it = g[0]->tree().cbeginValueOn(); it; ++it) {
      double l[6];
      if (!to_log(it.getCoord(), l))
        return Status(Error::InvalidArgument,
                      path + ": the metric at voxel " + it.getCoord().asVec3i().str() +
                          " is not SPD (or not finite)");
      const Vec3d d(l[0], l[2], l[5]), o(l[1], l[3], l[4]);
      if (it.isVoxelValue()) {
        dacc.setValue(it.getCoord(), d);
        oacc.setValue(it.getCoord(), o);
      } else {
        dacc.addTile(it.getLevel(), it.getCoord(), d, true);
        oacc.addTile(it.getLevel(), it.getCoord(), o, true);
      }
    }
  }
  file.close();
  out = std::move(impl);
  return finish_impl(*out, dx, origin);
}

}  // namespace

Status read_vdb_file(const std::string& path, Impl** out) {
  std::unique_ptr<MetricField::Impl> impl;
  try {
    Status st = read_vdb_impl(path, impl);
    if (!st.ok()) return st;
  } catch (const std::bad_alloc&) {
    return Status(Error::OutOfMemory, "out of memory reading " + path);
  } catch (const std::exception& e) {
    return Status(Error::Parse, path + ": " + e.what());
  }
  *out = impl.release();
  return Status::success();
}

MetricField::Kind field_kind(const Impl& f) { return f.kind; }
double field_voxel_size(const Impl& f) { return f.dx; }
size_t field_active_voxels(const Impl& f) {
  return f.kind == Kind::Isotropic ? size_t(f.size->activeVoxelCount())
                                   : size_t(f.diag->activeVoxelCount());
}
size_t field_leaf_count(const Impl& f) {
  return f.kind == Kind::Isotropic ? size_t(f.size->tree().leafCount())
                                   : size_t(f.diag->tree().leafCount());
}
size_t field_memory_bytes(const Impl& f) {
  return size_t(f.size->memUsage() + f.diag->memUsage() + f.off->memUsage());
}
void delete_field(Impl* f) { delete f; }

MetricField::Sampler::State* new_sampler(const Impl& f) { return new MetricField::Sampler::State(f); }
void delete_sampler(MetricField::Sampler::State* s) { delete s; }
void sampler_metric(MetricField::Sampler::State& s, const double p[3], double m[6]) { s.metric(p, m); }
void sampler_log_metric(MetricField::Sampler::State& s, const double p[3], double l[6]) {
  s.log_metric(p, l);
}
void sampler_batch(MetricField::Sampler::State& s, const double* points, size_t n, double* out,
                   bool log_only) {
  if (log_only) s.batch<true>(points, n, out);
  else s.batch<false>(points, n, out);
}

Status write_vdb_file(const Impl& f, const std::string& path, bool double_precision) {
  if (!f.vdb_transform)
    return Status(Error::InvalidArgument, "write_metric_vdb: '" + path + "': the voxel size " + std::to_string(f.dx) +
                                              " is below what an OpenVDB transform holds (about 2e-5); scale the "
                                              "model up to write its field as .vdb");
  const std::string partial = partial_path(path);
  try {
    openvdb::initialize();
    openvdb::GridPtrVec grids;
    auto add_component = [&](const auto& tree, const char* name, auto pick, double background) {
      if (double_precision) {
        auto g = DoubleGrid::create(background);
        copy_active(tree, *g, [&](const auto& v, const Coord&) { return double(pick(v)); });
        g->setTransform(f.transform());
        g->setName(name);
        grids.push_back(g);
      } else {
        auto g = FloatGrid::create(float(background));
        copy_active(tree, *g, [&](const auto& v, const Coord&) { return float(pick(v)); });
        g->setTransform(f.transform());
        g->setName(name);
        grids.push_back(g);
      }
    };
    if (f.kind == MetricField::Kind::Isotropic) {
      add_component(f.size->tree(), "size", [](double v) { return v; }, f.size->background());
      grids.back()->setGridClass(openvdb::GRID_UNKNOWN);
    } else {
      // xx xy yy xz yz zz from diag (xx yy zz) and off (xy xz yz).
      const int from_diag[6] = {0, -1, 1, -1, -1, 2};
      const int from_off[6] = {-1, 0, -1, 1, 2, -1};
      for (int c = 0; c < 6; ++c) {
        if (from_diag[c] >= 0) {
          const int k = from_diag[c];
          add_component(f.diag->tree(), kLogNames[c], [k](const Vec3d& v) { return v[k]; }, 0.0);
        } else {
          const int k = from_off[c];
          add_component(f.off->tree(), kLogNames[c], [k](const Vec3d& v) { return v[k]; }, 0.0);
        }
      }
    }
    // Written beside its name and moved into place when complete (io/file_bytes.hpp).
    openvdb::io::File file(partial);
    file.write(grids);
    file.close();
  } catch (const std::bad_alloc&) {
    std::remove(partial.c_str());
    return Status(Error::OutOfMemory, "out of memory writing " + path);
  } catch (const std::exception& e) {
    std::remove(partial.c_str());
    return Status(Error::FileNotFound, "cannot write " + path + ": " + e.what());
  }
  return move_into_place(partial, path);
}

}  // namespace metric
}  // namespace anitet
