// The parts of an assignment of tets to parts: ghost layers, local numbering, vertex owners,
// boundary triangles and the halo lists (the orders are part.hpp's).
#include <algorithm>
#include <string>
#include <utility>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/buckets.hpp"
#include "partition/partition.hpp"

namespace anitet::partition {
namespace {

constexpr uint32_t kNone = 0xffffffffu;

// What every part looks up: the owner of each vertex, the tets of each part, and the boundary
// triangles of each tet with the owner of each triangle.
struct Shared {
  std::vector<int32_t> vertex_owner;  // -1: a vertex in no tet
  std::vector<uint8_t> interface;     // 1: the vertex's tets are in more than one part
  Csr part_tets;                      // the tets of each part, ascending
  Csr tet_triangles;                  // the boundary triangles that are faces of each tet
  std::vector<int32_t> triangle_owner;
};

// Lists grouped by part: the items of parts[i] are items[start[i] .. start[i + 1]).
struct Grouped {
  std::vector<int32_t> parts;
  std::vector<int64_t> start{0};
  std::vector<int32_t> items;
};

bool has_face(const VolumeMesh& mesh, uint32_t t, const uint32_t* tri) {
  const uint32_t* v = &mesh.tet[4 * size_t(t)];
  for (int k = 0; k < 3; ++k)
    if (v[0] != tri[k] && v[1] != tri[k] && v[2] != tri[k] && v[3] != tri[k]) return false;
  return true;
}

Shared shared_tables(const VolumeMesh& mesh, const Csr& vtets, const std::vector<int32_t>& tet_part, int num_parts) {
  Shared s;
  const size_t nv = mesh.num_vertices(), nt = mesh.num_tets(), nb = mesh.num_boundary_triangles();
  s.vertex_owner.assign(nv, -1);
  s.interface.assign(nv, 0);
  tbb::parallel_for(size_t(0), nv, [&](size_t v) {
    int32_t owner = -1;
    for (int64_t k = vtets.begin(v); k < vtets.end(v); ++k) {
      const int32_t p = tet_part[vtets.items[size_t(k)]];
      if (owner >= 0 && p != owner) s.interface[v] = 1;
      if (owner < 0 || p < owner) owner = p;
    }
    s.vertex_owner[v] = owner;
  });
  std::vector<int64_t> fill;
  bucket_by_key(
      size_t(num_parts),
      [&](auto&& emit) {
        for (size_t t = 0; t < nt; ++t) emit(size_t(tet_part[t]), uint32_t(t));
      },
      s.part_tets.start, s.part_tets.items, fill);
  // A boundary triangle is a face of one or two tets (two: between regions); a triangle of no
  // tet is in no part.
  std::vector<uint32_t> tets_of(2 * nb, kNone);
  s.triangle_owner.assign(nb, -1);
  tbb::parallel_for(size_t(0), nb, [&](size_t b) {
    const uint32_t* tri = &mesh.bnd_tri[3 * b];
    if (tri[0] >= nv) return;
    int found = 0;
    for (int64_t k = vtets.begin(tri[0]); k < vtets.end(tri[0]) && found < 2; ++k) {
      const uint32_t t = vtets.items[size_t(k)];
      if (!has_face(mesh, t, tri)) continue;
      tets_of[2 * b + size_t(found++)] = t;
      if (s.triangle_owner[b] < 0 || tet_part[t] < s.triangle_owner[b]) s.triangle_owner[b] = tet_part[t];
    }
  });
  bucket_by_key(
      nt,
      [&](auto&& emit) {
        for (size_t i = 0; i < 2 * nb; ++i)
          if (tets_of[i] != kNone) emit(tets_of[i], uint32_t(i / 2));
      },
      s.tet_triangles.start, s.tet_triangles.items, fill);
  return s;
}

void sort_unique(std::vector<uint32_t>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

// Per-thread marks over the whole mesh, so that a part costs in proportion to its own size: an
// entry equal to `stamp` was seen while building the current part (a new stamp per part).
struct Scratch {
  std::vector<uint32_t> vertex_seen, tet_seen;
  std::vector<int32_t> local;  // the local id of a vertex seen in the current part
  uint32_t stamp = 0;
  void begin_part(size_t nv, size_t nt) {
    if (vertex_seen.size() != nv) vertex_seen.assign(nv, 0), local.assign(nv, 0);
    if (tet_seen.size() != nt) tet_seen.assign(nt, 0);
    ++stamp;
  }
};

// Own tets, then the ghost layers, each ascending; `vertices` gets every vertex of them,
// ascending, marked in the scratch.
std::vector<std::vector<uint32_t>> local_tets(const VolumeMesh& mesh, const Csr& vtets, const Shared& s, int p,
                                              int ghost_layers, Scratch& x, std::vector<uint32_t>& vertices) {
  x.begin_part(mesh.num_vertices(), mesh.num_tets());
  std::vector<std::vector<uint32_t>> layers(1);
  layers[0].assign(s.part_tets.items.begin() + s.part_tets.begin(size_t(p)),
                   s.part_tets.items.begin() + s.part_tets.end(size_t(p)));
  // The frontier: vertices whose tets may not all be held yet. For the own tets, the interface
  // vertices only (the other vertices have no tet of another part); then every new vertex.
  std::vector<uint32_t> frontier;
  auto hold_vertices = [&](const std::vector<uint32_t>& tets, bool interface_only) {
    frontier.clear();
    for (uint32_t t : tets) {
      x.tet_seen[t] = x.stamp;
      for (int k = 0; k < 4; ++k) {
        const uint32_t v = mesh.tet[4 * size_t(t) + size_t(k)];
        if (x.vertex_seen[v] == x.stamp) continue;
        x.vertex_seen[v] = x.stamp;
        vertices.push_back(v);
        if (!interface_only || s.interface[v]) frontier.push_back(v);
      }
    }
  };
  vertices.clear();
  hold_vertices(layers[0], true);
  for (int layer = 1; layer <= ghost_layers && !frontier.empty(); ++layer) {
    // Every tet of a vertex held earlier is held already: only the frontier's tets are new.
    std::vector<uint32_t> fresh;
    for (uint32_t v : frontier)
      for (int64_t k = vtets.begin(v); k < vtets.end(v); ++k) {
        const uint32_t t = vtets.items[size_t(k)];
        if (x.tet_seen[t] != x.stamp) {
          x.tet_seen[t] = x.stamp;
          fresh.push_back(t);
        }
      }
    if (fresh.empty()) break;
    std::sort(fresh.begin(), fresh.end());
    hold_vertices(fresh, false);
    layers.push_back(std::move(fresh));
  }
  std::sort(vertices.begin(), vertices.end());
  return layers;
}

// Items (local ids) grouped by the part of each, ascending part then ascending global id.
Grouped group_by_part(std::vector<std::pair<int32_t, int32_t>> part_and_local,
                      const std::vector<int64_t>& global) {
  std::sort(part_and_local.begin(), part_and_local.end(), [&](const auto& a, const auto& b) {
    return a.first != b.first ? a.first < b.first : global[size_t(a.second)] < global[size_t(b.second)];
  });
  Grouped g;
  for (const auto& [part, local] : part_and_local) {
    if (g.parts.empty() || g.parts.back() != part) {
      g.parts.push_back(part);
      g.start.push_back(g.start.back());
    }
    g.items.push_back(local);
    ++g.start.back();
  }
  return g;
}

struct Built {
  Part part;
  Grouped recv[2];  // vertices, tets: by owner
  Grouped send[2];  // vertices, tets: by the part that holds them
};

Status build_one(const VolumeMesh& mesh, const Csr& vtets, const std::vector<int32_t>& tet_part, const Shared& s,
                 int p, int num_parts, int ghost_layers, Scratch& x, Built& out) {
  std::vector<uint32_t> vertices;
  const std::vector<std::vector<uint32_t>> layers = local_tets(mesh, vtets, s, p, ghost_layers, x, vertices);
  size_t num_tets = 0;
  for (const auto& l : layers) num_tets += l.size();
  if (vertices.size() >= size_t(INT32_MAX) || num_tets >= size_t(INT32_MAX)) {
    return Status(Error::NotImplemented, "part " + std::to_string(p) + " holds " + std::to_string(vertices.size()) +
                                             " vertices and " + std::to_string(num_tets) +
                                             " tets: local ids are int32_t; use more parts");
  }
  Part& part = out.part;
  part.index = p;
  part.num_parts = num_parts;
  part.ghost_layers = ghost_layers;
  // Local vertices: own first, then the others, each ascending.
  for (int pass = 0; pass < 2; ++pass)
    for (size_t i = 0; i < vertices.size(); ++i)
      if ((s.vertex_owner[vertices[i]] == p) == (pass == 0)) {
        x.local[vertices[i]] = int32_t(part.vertex_global.size());
        part.vertex_global.push_back(vertices[i]);
        part.vertex_owner.push_back(s.vertex_owner[vertices[i]]);
        part.xyz.insert(part.xyz.end(), mesh.point(vertices[i]), mesh.point(vertices[i]) + 3);
        if (pass == 0) ++part.owned_vertices;
      }
  auto local = [&](uint32_t v) { return x.local[v]; };
  for (size_t layer = 0; layer < layers.size(); ++layer)
    for (uint32_t t : layers[layer]) {
      part.tet_global.push_back(t);
      part.tet_owner.push_back(tet_part[t]);
      part.tet_layer.push_back(int32_t(layer));
      part.region.push_back(mesh.region.empty() ? 0 : mesh.region[t]);
      for (int k = 0; k < 4; ++k) part.tet.push_back(local(mesh.tet[4 * size_t(t) + size_t(k)]));
    }
  part.owned_tets = int64_t(layers[0].size());
  // Boundary triangles of the local tets: own first, then the others, each ascending.
  std::vector<uint32_t> triangles;
  for (int64_t t : part.tet_global)
    triangles.insert(triangles.end(), s.tet_triangles.items.begin() + s.tet_triangles.begin(size_t(t)),
                     s.tet_triangles.items.begin() + s.tet_triangles.end(size_t(t)));
  sort_unique(triangles);
  for (int pass = 0; pass < 2; ++pass)
    for (uint32_t b : triangles)
      if ((s.triangle_owner[b] == p) == (pass == 0)) {
        part.bnd_global.push_back(b);
        part.bnd_patch.push_back(mesh.bnd_patch.empty() ? 0 : mesh.bnd_patch[b]);
        for (int k = 0; k < 3; ++k) part.bnd_tri.push_back(local(mesh.bnd_tri[3 * size_t(b) + size_t(k)]));
        if (pass == 0) ++part.owned_boundary_triangles;
      }
  // What this part receives: the vertices and tets other parts own.
  std::vector<std::pair<int32_t, int32_t>> from;
  for (int64_t i = part.owned_vertices; i < part.num_vertices(); ++i) from.emplace_back(part.vertex_owner[size_t(i)], int32_t(i));
  out.recv[0] = group_by_part(std::move(from), part.vertex_global);
  from.clear();
  for (int64_t i = part.owned_tets; i < part.num_tets(); ++i) from.emplace_back(part.tet_owner[size_t(i)], int32_t(i));
  out.recv[1] = group_by_part(std::move(from), part.tet_global);
  return Status::success();
}

// What part p sends: for each part q (ascending) that receives from p, q's list mapped to p's
// local ids (p's own items are its first ones, ascending by global id).
void collect_sends(std::vector<Built>& built, int p) {
  Part& part = built[size_t(p)].part;
  for (int kind = 0; kind < 2; ++kind) {
    const std::vector<int64_t>& mine = kind == 0 ? part.vertex_global : part.tet_global;
    const int64_t owned = kind == 0 ? part.owned_vertices : part.owned_tets;
    Grouped& send = built[size_t(p)].send[kind];
    for (size_t q = 0; q < built.size(); ++q) {
      const Grouped& recv = built[q].recv[kind];
      const auto at = std::lower_bound(recv.parts.begin(), recv.parts.end(), p);
      if (at == recv.parts.end() || *at != p) continue;
      const size_t g = size_t(at - recv.parts.begin());
      const std::vector<int64_t>& theirs = kind == 0 ? built[q].part.vertex_global : built[q].part.tet_global;
      send.parts.push_back(int32_t(q));
      for (int64_t k = recv.start[g]; k < recv.start[g + 1]; ++k) {
        const int64_t global = theirs[size_t(recv.items[size_t(k)])];
        send.items.push_back(int32_t(std::lower_bound(mine.begin(), mine.begin() + owned, global) - mine.begin()));
      }
      send.start.push_back(int64_t(send.items.size()));
    }
  }
}

// The halo lists aligned to the part's neighbours (every part it sends to or receives from).
void assemble_halos(Built& b) {
  Part& part = b.part;
  const Grouped* lists[kNumHalos] = {&b.send[0], &b.recv[0], &b.send[1], &b.recv[1]};
  for (const Grouped* g : lists) part.neighbours.insert(part.neighbours.end(), g->parts.begin(), g->parts.end());
  std::sort(part.neighbours.begin(), part.neighbours.end());
  part.neighbours.erase(std::unique(part.neighbours.begin(), part.neighbours.end()), part.neighbours.end());
  for (int h = 0; h < kNumHalos; ++h) {
    const Grouped& g = *lists[h];
    HaloList& out = part.halo[size_t(h)];
    out.start.assign(1, 0);
    size_t at = 0;
    for (int32_t q : part.neighbours) {
      if (at < g.parts.size() && g.parts[at] == q) {
        out.items.insert(out.items.end(), g.items.begin() + g.start[at], g.items.begin() + g.start[at + 1]);
        ++at;
      }
      out.start.push_back(int64_t(out.items.size()));
    }
  }
}

}  // namespace

Result<std::vector<Part>> build_parts(const VolumeMesh& mesh, const Csr& vertex_tets,
                                      const std::vector<int32_t>& tet_part, int num_parts, int ghost_layers) {
  if (num_parts < 1 || ghost_layers < 0 || tet_part.size() != mesh.num_tets()) {
    return Status(Error::InvalidArgument, "build_parts: bad part count, ghost layers or assignment size");
  }
  for (int32_t p : tet_part)
    if (p < 0 || p >= num_parts) return Status(Error::InvalidArgument, "build_parts: a tet's part out of range");
  const Shared s = shared_tables(mesh, vertex_tets, tet_part, num_parts);
  std::vector<Built> built(static_cast<size_t>(num_parts));
  std::vector<Status> status(static_cast<size_t>(num_parts));
  tbb::enumerable_thread_specific<Scratch> scratch;
  tbb::parallel_for(0, num_parts, [&](int p) {
    status[size_t(p)] =
        build_one(mesh, vertex_tets, tet_part, s, p, num_parts, ghost_layers, scratch.local(), built[size_t(p)]);
  });
  for (const Status& st : status)
    if (!st.ok()) return st;
  tbb::parallel_for(0, num_parts, [&](int p) { collect_sends(built, p); });
  std::vector<Part> parts(static_cast<size_t>(num_parts));
  tbb::parallel_for(0, num_parts, [&](int p) {
    assemble_halos(built[size_t(p)]);
    parts[size_t(p)] = std::move(built[size_t(p)].part);
  });
  return parts;
}

}  // namespace anitet::partition
