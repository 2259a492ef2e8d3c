#include "partition/mesh_graph.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/buckets.hpp"
#include "core/tet_mesh.hpp"

namespace anitet::partition {
namespace {

constexpr uint32_t kNone = 0xffffffffu;

Status check_sizes(const VolumeMesh& mesh) {
  if (mesh.num_tets() >= size_t(kNone)) {
    return Status(Error::InvalidArgument, std::to_string(mesh.num_tets()) +
                                              " tets: partitioning takes fewer than 2^32 - 1");
  }
  const size_t nv = mesh.num_vertices();
  for (size_t i = 0; i < mesh.tet.size(); ++i) {
    if (mesh.tet[i] >= nv) {
      return Status(Error::BadIndex, "tet " + std::to_string(i / 4) + " refers to vertex " +
                                         std::to_string(mesh.tet[i]) + " of " + std::to_string(nv));
    }
  }
  return Status::success();
}

void sorted_facet(const VolumeMesh& mesh, size_t t, int i, uint32_t v[3]) {
  for (int k = 0; k < 3; ++k) v[k] = mesh.tet[4 * t + size_t(kFacetVertex[i][k])];
  if (v[0] > v[1]) std::swap(v[0], v[1]);
  if (v[1] > v[2]) std::swap(v[1], v[2]);
  if (v[0] > v[1]) std::swap(v[0], v[1]);
}

}  // namespace

Result<Csr> vertex_tets(const VolumeMesh& mesh) {
  Status ok = check_sizes(mesh);
  if (!ok.ok()) return ok;
  Csr out;
  std::vector<int64_t> counts;
  parallel_bucket_by_key(
      mesh.num_vertices(), mesh.num_tets(),
      [&](size_t first, size_t last, auto&& emit) {
        for (size_t t = first; t < last; ++t)
          for (int k = 0; k < 4; ++k) emit(mesh.tet[4 * t + size_t(k)], uint32_t(t));
      },
      out.start, out.items, counts);
  return out;
}

Result<Csr> dual_graph(const VolumeMesh& mesh) {
  Status ok = check_sizes(mesh);
  if (!ok.ok()) return ok;
  const size_t nt = mesh.num_tets();
  const size_t nv = mesh.num_vertices();
  // Facets grouped by their smallest vertex, then paired within each group (as
  // TetMesh::build_adjacency does, with 64-bit facet ids).
  std::vector<int64_t> start, counts;
  std::vector<uint64_t> facets;  // 4 t + i
  parallel_bucket_by_key(
      nv, nt,
      [&](size_t first, size_t last, auto&& emit) {
        for (size_t t = first; t < last; ++t)
          for (int i = 0; i < 4; ++i) {
            uint32_t v[3];
            sorted_facet(mesh, t, i, v);
            emit(v[0], 4 * uint64_t(t) + uint64_t(i));
          }
      },
      start, facets, counts);
  counts = {};
  std::vector<uint32_t> across(4 * nt, kNone);  // the tet behind each facet
  constexpr size_t kChunk = 4096;
  const size_t chunks = (nv + kChunk - 1) / kChunk;
  std::vector<std::string> errors(chunks);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<std::pair<uint64_t, uint64_t>> group;  // (other two vertices, facet id)
    for (size_t c = r.begin(); c != r.end(); ++c) {
      for (size_t key = c * kChunk; key < std::min(nv, (c + 1) * kChunk) && errors[c].empty(); ++key) {
        group.clear();
        for (int64_t k = start[key]; k < start[key + 1]; ++k) {
          uint32_t v[3];
          sorted_facet(mesh, size_t(facets[size_t(k)] >> 2), int(facets[size_t(k)] & 3), v);
          group.emplace_back((uint64_t(v[1]) << 32) | v[2], facets[size_t(k)]);
        }
        std::sort(group.begin(), group.end());
        for (size_t a = 0; a < group.size();) {
          size_t b = a + 1;
          while (b < group.size() && group[b].first == group[a].first) ++b;
          if (b - a > 2) {
            errors[c] = "face (" + std::to_string(key) + ", " + std::to_string(group[a].first >> 32) +
                        ", " + std::to_string(group[a].first & 0xffffffffu) +
                        ") is shared by more than two tets (tets " + std::to_string(group[a].second >> 2) +
                        ", " + std::to_string(group[a + 1].second >> 2) + ", " +
                        std::to_string(group[a + 2].second >> 2) + " among them)";
            break;
          }
          if (b - a == 2) {
            across[group[a].second] = uint32_t(group[a + 1].second >> 2);
            across[group[a + 1].second] = uint32_t(group[a].second >> 2);
          }
          a = b;
        }
      }
    }
  });
  for (const std::string& e : errors)
    if (!e.empty()) return Status(Error::InvalidMesh, e);
  facets = {};
  start = {};
  Csr out;
  out.start.assign(nt + 1, 0);
  for (size_t t = 0; t < nt; ++t) {
    int n = 0;
    for (int i = 0; i < 4; ++i) n += across[4 * t + size_t(i)] != kNone;
    out.start[t + 1] = out.start[t] + n;
  }
  out.items.resize(size_t(out.start[nt]));
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nt, 16384), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t t = r.begin(); t != r.end(); ++t) {
      uint32_t* at = out.items.data() + out.start[t];
      uint32_t* const first = at;
      for (int i = 0; i < 4; ++i)
        if (across[4 * t + size_t(i)] != kNone) *at++ = across[4 * t + size_t(i)];
      std::sort(first, at);
    }
  });
  return out;
}

}  // namespace anitet::partition
