#include "partition/part.hpp"

#include <cstdint>
#include <cstring>
#include <string>

namespace anitet::partition {
namespace {

Status bad(const std::string& what) { return Status(Error::Parse, "part: " + what); }

template <class T>
bool all_below(const std::vector<T>& v, int64_t limit) {
  for (T x : v)
    if (x < 0 || int64_t(x) >= limit) return false;
  return true;
}

Status check_halo(const Part& p, const HaloList& h, int64_t items_limit, const char* name) {
  if (h.start.size() != p.neighbours.size() + 1 || h.start.front() != 0) return bad(std::string(name) + " offsets");
  for (size_t i = 0; i + 1 < h.start.size(); ++i)
    if (h.start[i] > h.start[i + 1]) return bad(std::string(name) + " offsets decrease");
  if (h.start.back() != int64_t(h.items.size())) return bad(std::string(name) + " length");
  if (!all_below(h.items, items_limit)) return bad(std::string(name) + " item out of range");
  return Status::success();
}

// Bytes: "ANITETPT", a format version, the scalars, then each array as a count and its values.
constexpr char kMagic[8] = {'A', 'N', 'I', 'T', 'E', 'T', 'P', 'T'};
constexpr uint32_t kFormat = 1;

struct Writer {
  std::vector<uint8_t> out;
  template <class T>
  void scalar(T v) {
    const size_t at = out.size();
    out.resize(at + sizeof(T));
    std::memcpy(out.data() + at, &v, sizeof(T));
  }
  template <class T>
  void array(const std::vector<T>& v) {
    scalar<uint64_t>(v.size());
    const size_t at = out.size();
    out.resize(at + v.size() * sizeof(T));
    if (!v.empty()) std::memcpy(out.data() + at, v.data(), v.size() * sizeof(T));
  }
};

struct Reader {
  const uint8_t* at;
  const uint8_t* end;
  bool failed = false;
  template <class T>
  T scalar() {
    T v{};
    if (size_t(end - at) < sizeof(T)) {
      failed = true;
      return v;
    }
    std::memcpy(&v, at, sizeof(T));
    at += sizeof(T);
    return v;
  }
  template <class T>
  void array(std::vector<T>& v) {
    const uint64_t n = scalar<uint64_t>();
    if (failed || n > uint64_t(end - at) / sizeof(T)) {
      failed = true;
      return;
    }
    v.resize(size_t(n));
    if (n) std::memcpy(v.data(), at, size_t(n) * sizeof(T));
    at += n * sizeof(T);
  }
};

// One list of every array, so that writing and reading cannot disagree.
template <class P, class F>
void for_each_array(P& p, F&& f) {
  f(p.xyz);
  f(p.vertex_global);
  f(p.vertex_owner);
  f(p.tet);
  f(p.tet_global);
  f(p.tet_owner);
  f(p.tet_layer);
  f(p.region);
  f(p.bnd_tri);
  f(p.bnd_patch);
  f(p.bnd_global);
  f(p.neighbours);
  for (auto& h : p.halo) {
    f(h.start);
    f(h.items);
  }
}

}  // namespace

Status check_part(const Part& p) {
  const int64_t nv = p.num_vertices(), nt = p.num_tets(), nb = p.num_boundary_triangles();
  if (p.num_parts < 1 || p.index < 0 || p.index >= p.num_parts || p.ghost_layers < 0) return bad("numbering");
  if (p.xyz.size() != size_t(3 * nv) || p.vertex_owner.size() != size_t(nv)) return bad("vertex array sizes");
  if (p.tet.size() != size_t(4 * nt) || p.tet_owner.size() != size_t(nt) || p.tet_layer.size() != size_t(nt) ||
      p.region.size() != size_t(nt)) {
    return bad("tet array sizes");
  }
  if (p.bnd_tri.size() != size_t(3 * nb) || p.bnd_patch.size() != size_t(nb)) return bad("boundary array sizes");
  if (p.owned_vertices < 0 || p.owned_vertices > nv || p.owned_tets < 0 || p.owned_tets > nt ||
      p.owned_boundary_triangles < 0 || p.owned_boundary_triangles > nb) {
    return bad("owned counts");
  }
  if (!all_below(p.tet, nv) || !all_below(p.bnd_tri, nv)) return bad("a local vertex out of range");
  constexpr int64_t kAny = INT64_MAX;
  if (!all_below(p.vertex_global, kAny) || !all_below(p.tet_global, kAny) || !all_below(p.bnd_global, kAny)) {
    return bad("a negative global id");
  }
  if (!all_below(p.vertex_owner, p.num_parts) || !all_below(p.tet_owner, p.num_parts) ||
      !all_below(p.neighbours, p.num_parts)) {
    return bad("a part number out of range");
  }
  if (!all_below(p.tet_layer, int64_t(p.ghost_layers) + 1)) return bad("a ghost layer out of range");
  for (size_t i = 1; i < p.neighbours.size(); ++i)
    if (p.neighbours[i - 1] >= p.neighbours[i]) return bad("neighbours not ascending");
  const char* names[kNumHalos] = {"vertex send", "vertex recv", "tet send", "tet recv"};
  for (int h = 0; h < kNumHalos; ++h) {
    Status s = check_halo(p, p.halo[size_t(h)], h < kTetSend ? nv : nt, names[h]);
    if (!s.ok()) return s;
  }
  return Status::success();
}

std::vector<uint8_t> serialize_part(const Part& part) {
  Writer w;
  for (char c : kMagic) w.scalar(c);
  w.scalar(kFormat);
  w.scalar(part.index);
  w.scalar(part.num_parts);
  w.scalar(part.ghost_layers);
  w.scalar(part.owned_vertices);
  w.scalar(part.owned_tets);
  w.scalar(part.owned_boundary_triangles);
  for_each_array(part, [&](const auto& v) { w.array(v); });
  return std::move(w.out);
}

Result<Part> deserialize_part(const uint8_t* bytes, size_t size) {
  if (bytes == nullptr && size > 0) return bad("no bytes");
  Reader r{bytes, bytes + size};
  for (char c : kMagic)
    if (r.scalar<char>() != c || r.failed) return bad("not a part (magic)");
  const uint32_t format = r.scalar<uint32_t>();
  if (r.failed || format != kFormat) return bad("format " + std::to_string(format) + ", not " + std::to_string(kFormat));
  Part p;
  p.index = r.scalar<int32_t>();
  p.num_parts = r.scalar<int32_t>();
  p.ghost_layers = r.scalar<int32_t>();
  p.owned_vertices = r.scalar<int64_t>();
  p.owned_tets = r.scalar<int64_t>();
  p.owned_boundary_triangles = r.scalar<int64_t>();
  for_each_array(p, [&](auto& v) { r.array(v); });
  if (r.failed) return bad("truncated");
  if (r.at != r.end) return bad(std::to_string(r.end - r.at) + " bytes after the end");
  Status s = check_part(p);
  if (!s.ok()) return s;
  return p;
}

}  // namespace anitet::partition
