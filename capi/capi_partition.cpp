// Partitions and parts (include/anitet.h, "Partitions"): anitet_mesh_partition over the
// partition module, the accessors of a part, and a part as bytes.
#include <cstring>
#include <memory>
#include <string>
#include <vector>


#include "handles.hpp"
#include "partition/partition.hpp"
#include "shim.hpp"

using namespace anitet::capi;
using anitet::partition::Part;

namespace {

// Bytes of an anitet_partition_options of `version` (a valid one): version 1 is the whole struct.
size_t partition_options_size(int32_t) { return sizeof(anitet_partition_options); }

int read_partition_options(const char* function, const anitet_partition_options* given,
                           anitet_partition_options& out) {
  const anitet_partition_options defaults = ANITET_PARTITION_OPTIONS_INIT;
  out = defaults;
  if (given == nullptr) return ANITET_OK;
  if (given->version < 1 || given->version > ANITET_PARTITION_OPTIONS_VERSION) {
    return set_error(ANITET_ERR_INVALID_ARGUMENT,
                     std::string(function) + ": partition options version " + std::to_string(given->version) +
                         " is not supported (1.." + std::to_string(ANITET_PARTITION_OPTIONS_VERSION) +
                         "); initialise with ANITET_PARTITION_OPTIONS_INIT or anitet_partition_options_init");
  }
  std::memcpy(&out, given, partition_options_size(given->version));
  return ANITET_OK;
}

int bad_option(const char* function, const std::string& what) {
  return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(function) + ": " + what);
}

// Local or global ids counted from index_base.
template <class T>
auto plus(int32_t base) {
  return [base](T v) { return T(v + base); };
}

const std::vector<int32_t>& halo_items(const Part& p, int32_t list) { return p.halo[size_t(list)].items; }

bool known_list(int32_t list) { return list >= ANITET_HALO_VERTEX_SEND && list <= ANITET_HALO_TET_RECV; }

int unknown_list(const char* function, int32_t list) {
  return set_error(ANITET_ERR_INVALID_ARGUMENT,
                   std::string(function) + ": list " + std::to_string(list) + " is not an ANITET_HALO_* value");
}

// Every accessor: NULL checks, then body(part).
template <class F>
int with_part(const char* function, const anitet_part* part, F&& body) {
  return guard(function, [&] {
    if (part == nullptr) return null_argument(function, "part");
    return body(part->part);
  });
}

template <class T>
void lend(const std::vector<T>& v, int32_t type, const void** data, int64_t* count, int32_t* element_type) {
  *data = v.data();
  *count = int64_t(v.size());
  if (element_type) *element_type = type;
}

}  // namespace

extern "C" {

int anitet_partition_options_init(anitet_partition_options* options, int32_t version) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (options == nullptr) return null_argument(fn, "options");
    anitet_partition_options wanted = ANITET_PARTITION_OPTIONS_INIT;
    wanted.version = version;
    anitet_partition_options resolved;
    const int code = read_partition_options(fn, &wanted, resolved);
    if (code != ANITET_OK) return code;
    std::memcpy(options, &resolved, partition_options_size(version));  // never past the caller's version
    return ok();
  });
}

int anitet_mesh_partition(const anitet_mesh* mesh, int32_t num_parts, const anitet_partition_options* options,
                          anitet_partition** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (mesh == nullptr) return null_argument(fn, "mesh");
    anitet_partition_options o;
    int code = read_partition_options(fn, options, o);
    if (code != ANITET_OK) return code;
    if (o.num_threads < 0) return bad_option(fn, "num_threads is " + std::to_string(o.num_threads) + ", negative");
    const int64_t num_tets = int64_t(mesh->mesh.num_tets());
    if ((o.tet_weights == nullptr && o.num_tet_weights != 0) ||
        (o.tet_weights != nullptr && o.num_tet_weights != num_tets)) {
      return bad_option(fn, "num_tet_weights is " + std::to_string(o.num_tet_weights) + ", not " +
                                (o.tet_weights ? std::to_string(num_tets) + " (the mesh's tets)" : "0 (tet_weights is NULL)"));
    }
    anitet::partition::PartitionOptions po;
    po.num_parts = num_parts;
    po.ghost_layers = o.ghost_layers;
    po.imbalance = o.imbalance;
    po.tet_weights = o.tet_weights;
    anitet::Result<anitet::partition::Partition> r =
        in_arena(o.num_threads, [&] { return anitet::partition::partition_mesh(mesh->mesh, po); });
    if (!r.ok()) return set_status(fn, r.status());
    auto partition = std::make_unique<anitet_partition>();
    partition->tet_part = std::move(r->tet_part);
    partition->quality = r->quality;
    partition->ghost_layers = o.ghost_layers;
    partition->parts.resize(r->parts.size());
    for (size_t p = 0; p < r->parts.size(); ++p) {
      partition->parts[p].part = std::move(r->parts[p]);
      partition->parts[p].lent = true;
    }
    *out = partition.release();
    return ok();
  });
}

void anitet_partition_destroy(anitet_partition* partition) { delete partition; }

int anitet_partition_get_info(const anitet_partition* partition, anitet_partition_info* info) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (partition == nullptr) return null_argument(fn, "partition");
    if (info == nullptr) return null_argument(fn, "info");
    if (info->version < 1 || info->version > ANITET_PARTITION_INFO_VERSION) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": info version " + std::to_string(info->version) +
                                                        " is not supported (1.." +
                                                        std::to_string(ANITET_PARTITION_INFO_VERSION) + ")");
    }
    const anitet::partition::PartitionQuality& q = partition->quality;
    anitet_partition_info filled = ANITET_PARTITION_INFO_INIT;
    filled.version = info->version;
    filled.num_parts = int32_t(partition->parts.size());
    filled.ghost_layers = partition->ghost_layers;
    filled.empty_parts = q.empty_parts;
    filled.num_tets = int64_t(partition->tet_part.size());
    filled.edge_cut = q.edge_cut;
    filled.interface_vertices = q.interface_vertices;
    filled.imbalance = q.imbalance;
    filled.total_weight = q.total_weight;
    filled.max_part_weight = q.max_part_weight;
    std::memcpy(info, &filled, sizeof filled);  // version 1 is the whole struct
    return ok();
  });
}

int anitet_partition_get_tet_parts(const anitet_partition* partition, int32_t* parts, int64_t parts_len) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (partition == nullptr) return null_argument(fn, "partition");
    return fill(fn, "parts", partition->tet_part, parts, parts_len, kSame);
  });
}

int anitet_partition_get_part(const anitet_partition* partition, int32_t index, const anitet_part** part) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (part == nullptr) return null_argument(fn, "part");
    *part = nullptr;
    if (partition == nullptr) return null_argument(fn, "partition");
    if (index < 0 || size_t(index) >= partition->parts.size()) {
      return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": index " + std::to_string(index) +
                                                        " is not a part (0.." +
                                                        std::to_string(int64_t(partition->parts.size()) - 1) + ")");
    }
    *part = &partition->parts[size_t(index)];
    return ok();
  });
}

void anitet_part_destroy(anitet_part* part) {
  if (part != nullptr && !part->lent) delete part;
}

int anitet_part_get_index(const anitet_part* part, int32_t* index, int32_t* num_parts, int32_t* num_neighbours,
                          int32_t* ghost_layers) {
  return with_part(__func__, part, [&](const Part& p) {
    if (index) *index = p.index;
    if (num_parts) *num_parts = p.num_parts;
    if (num_neighbours) *num_neighbours = int32_t(p.neighbours.size());
    if (ghost_layers) *ghost_layers = p.ghost_layers;
    return ok();
  });
}

int anitet_part_get_counts(const anitet_part* part, int64_t* num_vertices, int64_t* num_owned_vertices,
                           int64_t* num_tets, int64_t* num_owned_tets, int64_t* num_boundary_triangles,
                           int64_t* num_owned_boundary_triangles) {
  return with_part(__func__, part, [&](const Part& p) {
    if (num_vertices) *num_vertices = p.num_vertices();
    if (num_owned_vertices) *num_owned_vertices = p.owned_vertices;
    if (num_tets) *num_tets = p.num_tets();
    if (num_owned_tets) *num_owned_tets = p.owned_tets;
    if (num_boundary_triangles) *num_boundary_triangles = p.num_boundary_triangles();
    if (num_owned_boundary_triangles) *num_owned_boundary_triangles = p.owned_boundary_triangles;
    return ok();
  });
}

int anitet_part_get_points(const anitet_part* part, double* xyz, int64_t xyz_len) {
  const char* const fn = __func__;
  return with_part(fn, part, [&](const Part& p) { return fill(fn, "xyz", p.xyz, xyz, xyz_len, kSame); });
}

int anitet_part_get_tets(const anitet_part* part, int32_t* tets, int64_t tets_len, int32_t index_base) {
  const char* const fn = __func__;
  return with_part(fn, part, [&](const Part& p) {
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    return fill(fn, "tets", p.tet, tets, tets_len, plus<int32_t>(index_base));
  });
}

int anitet_part_get_regions(const anitet_part* part, int32_t* regions, int64_t regions_len) {
  const char* const fn = __func__;
  return with_part(fn, part, [&](const Part& p) { return fill(fn, "regions", p.region, regions, regions_len, kSame); });
}

int anitet_part_get_vertex_global_ids(const anitet_part* part, int64_t* ids, int64_t ids_len, int32_t index_base) {
  const char* const fn = __func__;
  return with_part(fn, part, [&](const Part& p) {
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    return fill(fn, "ids", p.vertex_global, ids, ids_len, plus<int64_t>(index_base));
  });
}

int anitet_part_get_vertex_owners(const anitet_part* part, int32_t* owners, int64_t owners_len) {
  const char* const fn = __func__;
  return with_part(fn, part, [&](const Part& p) { return fill(fn, "owners", p.vertex_owner, owners, owners_len, kSame); });
}

int anitet_part_get_tet_global_ids(const anitet_part* part, int64_t* ids, int64_t ids_len, int32_t index_base) {
  const char* const fn = __func__;
  return with_part(fn, part, [&](const Part& p) {
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    return fill(fn, "ids", p.tet_global, ids, ids_len, plus<int64_t>(index_base));
  });
}

int anitet_part_get_tet_owners(const anitet_part* part, int32_t* owners, int64_t owners_len) {
  const char* const fn = __func__;
  return with_part(fn, part, [&](const Part& p) { return fill(fn, "owners", p.tet_owner, owners, owners_len, kSame); });
}

int anitet_part_get_tet_layers(const anitet_part* part, int32_t* layers, int64_t layers_len) {
  const char* const fn = __func__;
  return with_part(fn, part, [&](const Part& p) { return fill(fn, "layers", p.tet_layer, layers, layers_len, kSame); });
}

int anitet_part_get_boundary_triangles(const anitet_part* part, int32_t* tri, int64_t tri_len, int32_t index_base) {
  const char* const fn = __func__;
  return with_part(fn, part, [&](const Part& p) {
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    return fill(fn, "tri", p.bnd_tri, tri, tri_len, plus<int32_t>(index_base));
  });
}

int anitet_part_get_boundary_patches(const anitet_part* part, int32_t* patch, int64_t patch_len) {
  const char* const fn = __func__;
  return with_part(fn, part, [&](const Part& p) { return fill(fn, "patch", p.bnd_patch, patch, patch_len, kSame); });
}

int anitet_part_get_boundary_global_ids(const anitet_part* part, int64_t* ids, int64_t ids_len, int32_t index_base) {
  const char* const fn = __func__;
  return with_part(fn, part, [&](const Part& p) {
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    return fill(fn, "ids", p.bnd_global, ids, ids_len, plus<int64_t>(index_base));
  });
}

int anitet_part_get_neighbours(const anitet_part* part, int32_t* neighbours, int64_t neighbours_len) {
  const char* const fn = __func__;
  return with_part(fn, part,
                   [&](const Part& p) { return fill(fn, "neighbours", p.neighbours, neighbours, neighbours_len, kSame); });
}

int anitet_part_get_halo_size(const anitet_part* part, int32_t list, int64_t* size) {
  const char* const fn = __func__;
  return with_part(fn, part, [&](const Part& p) {
    if (size == nullptr) return null_argument(fn, "size");
    if (!known_list(list)) return unknown_list(fn, list);
    *size = int64_t(halo_items(p, list).size());
    return ok();
  });
}

int anitet_part_get_halo(const anitet_part* part, int32_t list, int64_t* offsets, int64_t offsets_len,
                         int32_t* items, int64_t items_len, int32_t index_base) {
  const char* const fn = __func__;
  return with_part(fn, part, [&](const Part& p) {
    if (!known_list(list)) return unknown_list(fn, list);
    if (index_base != 0 && index_base != 1) return bad_index_base(fn, index_base);
    const anitet::partition::HaloList& h = p.halo[size_t(list)];
    // Both lengths are checked before anything is written.
    if (offsets == nullptr) return null_argument(fn, "offsets");
    if (offsets_len < 0 || uint64_t(offsets_len) < h.start.size()) {
      return too_small(fn, "offsets", offsets_len, h.start.size());
    }
    if (!h.items.empty() && items == nullptr) return null_argument(fn, "items");
    if (items_len < 0 || uint64_t(items_len) < h.items.size()) return too_small(fn, "items", items_len, h.items.size());
    fill(fn, "offsets", h.start, offsets, offsets_len, plus<int64_t>(index_base));
    return fill(fn, "items", h.items, items, items_len, plus<int32_t>(index_base));
  });
}

int anitet_part_get_array(const anitet_part* part, int32_t array, const void** data, int64_t* count,
                          int32_t* element_type) {
  const char* const fn = __func__;
  return with_part(fn, part, [&](const Part& p) {
    if (data == nullptr) return null_argument(fn, "data");
    if (count == nullptr) return null_argument(fn, "count");
    constexpr int32_t I32 = ANITET_TYPE_INT32, I64 = ANITET_TYPE_INT64;
    switch (array) {
      case ANITET_PART_POINTS: lend(p.xyz, ANITET_TYPE_DOUBLE, data, count, element_type); break;
      case ANITET_PART_VERTEX_GLOBAL_IDS: lend(p.vertex_global, I64, data, count, element_type); break;
      case ANITET_PART_VERTEX_OWNERS: lend(p.vertex_owner, I32, data, count, element_type); break;
      case ANITET_PART_TETS: lend(p.tet, I32, data, count, element_type); break;
      case ANITET_PART_TET_GLOBAL_IDS: lend(p.tet_global, I64, data, count, element_type); break;
      case ANITET_PART_TET_OWNERS: lend(p.tet_owner, I32, data, count, element_type); break;
      case ANITET_PART_TET_LAYERS: lend(p.tet_layer, I32, data, count, element_type); break;
      case ANITET_PART_REGIONS: lend(p.region, I32, data, count, element_type); break;
      case ANITET_PART_BOUNDARY_TRIANGLES: lend(p.bnd_tri, I32, data, count, element_type); break;
      case ANITET_PART_BOUNDARY_PATCHES: lend(p.bnd_patch, I32, data, count, element_type); break;
      case ANITET_PART_BOUNDARY_GLOBAL_IDS: lend(p.bnd_global, I64, data, count, element_type); break;
      case ANITET_PART_NEIGHBOURS: lend(p.neighbours, I32, data, count, element_type); break;
      default: {
        // The halo arrays: offsets then items of each list, in ANITET_HALO_* order.
        const int32_t k = array - ANITET_PART_VERTEX_SEND_OFFSETS;
        if (k < 0 || k >= 2 * anitet::partition::kNumHalos) {
          return set_error(ANITET_ERR_INVALID_ARGUMENT,
                           std::string(fn) + ": array " + std::to_string(array) + " is not an ANITET_PART_* value");
        }
        const anitet::partition::HaloList& h = p.halo[size_t(k / 2)];
        if (k % 2 == 0) lend(h.start, I64, data, count, element_type);
        else lend(h.items, I32, data, count, element_type);
      }
    }
    return ok();
  });
}

int anitet_part_serialize(const anitet_part* part, void* buf, int64_t buf_len, int64_t* needed) {
  const char* const fn = __func__;
  return with_part(fn, part, [&](const Part& p) {
    const std::vector<uint8_t> bytes = anitet::partition::serialize_part(p);
    if (needed) *needed = int64_t(bytes.size());
    if (buf == nullptr && buf_len == 0) return ok();  // size query
    if (buf == nullptr) return null_argument(fn, "buf");
    if (buf_len < 0 || uint64_t(buf_len) < bytes.size()) return too_small(fn, "buf", buf_len, bytes.size());
    std::memcpy(buf, bytes.data(), bytes.size());
    return ok();
  });
}

int anitet_part_deserialize(const void* bytes, int64_t size, anitet_part** out) {
  const char* const fn = __func__;
  return guard(fn, [&] {
    if (out == nullptr) return null_argument(fn, "out");
    *out = nullptr;
    if (bytes == nullptr) return null_argument(fn, "bytes");
    if (size < 0) return set_error(ANITET_ERR_INVALID_ARGUMENT, std::string(fn) + ": size is negative");
    anitet::Result<Part> r = anitet::partition::deserialize_part(static_cast<const uint8_t*>(bytes), size_t(size));
    if (!r.ok()) return set_status(fn, r.status());
    auto part = std::make_unique<anitet_part>();
    part->part = std::move(r).value();
    *out = part.release();
    return ok();
  });
}

}  // extern "C"

// The layout the Fortran and Python mirrors assume: no padding.
static_assert(sizeof(anitet_partition_options) == 4 * sizeof(int32_t) + sizeof(double) + sizeof(void*) + sizeof(int64_t),
              "anitet_partition_options has padding");
static_assert(sizeof(anitet_partition_info) == 4 * sizeof(int32_t) + 3 * sizeof(int64_t) + 3 * sizeof(double),
              "anitet_partition_info has padding");
static_assert(ANITET_HALO_VERTEX_SEND == anitet::partition::kVertexSend &&
                  ANITET_HALO_VERTEX_RECV == anitet::partition::kVertexRecv &&
                  ANITET_HALO_TET_SEND == anitet::partition::kTetSend &&
                  ANITET_HALO_TET_RECV == anitet::partition::kTetRecv &&
                  ANITET_PART_TET_RECV == ANITET_PART_VERTEX_SEND_OFFSETS + 2 * anitet::partition::kNumHalos - 1,
              "the halo numbering of anitet.h and partition/part.hpp differ");
