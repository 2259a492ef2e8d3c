// One part of a partitioned mesh: what one rank of a solver holds. Everything in it is local or
// a global id, nothing refers to the whole mesh or to another rank's memory, so a distributed
// mesher can fill one on every rank without any root (issue 20), and a part travels as bytes.
//
// Agreed orders (so that a halo exchange needs no negotiation):
//  - local vertices: the part's own vertices first, then the others; each group by ascending
//    global id. A vertex's owner is the lowest part among the parts whose own tets hold it.
//  - local tets: the part's own tets first, then the ghost tets of layer 1, 2, ...; each group by
//    ascending global id. Ghost layer 1 holds every tet of another part sharing a vertex with an
//    own tet; layer k every tet not yet held sharing a vertex with layer k - 1.
//  - boundary triangles: those that are a face of a local tet; the part's own first (a triangle
//    belongs to the lowest part among its tets' owners), each group by ascending global id.
//  - neighbours: ascending part number. For neighbour q, recv lists the local vertices (tets)
//    owned by q, send the own vertices (tets) that q holds; each by ascending global id, so
//    send of p towards q and recv of q from p name the same global ids in the same order.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/status.hpp"

namespace anitet::partition {

// The halo lists of a part, CSR by neighbour: the items of neighbour i (neighbours[i]) are
// items[start[i] .. start[i + 1]), local ids.
struct HaloList {
  std::vector<int64_t> start;
  std::vector<int32_t> items;
};
enum Halo : int { kVertexSend = 0, kVertexRecv = 1, kTetSend = 2, kTetRecv = 3, kNumHalos = 4 };

struct Part {
  int32_t index = 0;        // this part's number (a rank), 0-based
  int32_t num_parts = 0;
  int32_t ghost_layers = 0;
  int64_t owned_vertices = 0;            // the first owned_vertices local vertices are own
  int64_t owned_tets = 0;                // the first owned_tets local tets are own
  int64_t owned_boundary_triangles = 0;  // the first ones are own
  std::vector<double> xyz;               // 3 per local vertex
  std::vector<int64_t> vertex_global;    // per local vertex: its vertex in the whole mesh
  std::vector<int32_t> vertex_owner;     // per local vertex: the part owning it
  std::vector<int32_t> tet;              // 4 local vertices per local tet (0-based), as oriented in the mesh
  std::vector<int64_t> tet_global;
  std::vector<int32_t> tet_owner;
  std::vector<int32_t> tet_layer;        // 0: own, k: ghost layer k
  std::vector<int32_t> region;
  std::vector<int32_t> bnd_tri;          // 3 local vertices per boundary triangle
  std::vector<int32_t> bnd_patch;
  std::vector<int64_t> bnd_global;       // its index among the whole mesh's boundary triangles
  std::vector<int32_t> neighbours;       // ascending
  std::array<HaloList, kNumHalos> halo;

  int64_t num_vertices() const { return int64_t(vertex_global.size()); }
  int64_t num_tets() const { return int64_t(tet_global.size()); }
  int64_t num_boundary_triangles() const { return int64_t(bnd_global.size()); }
};

// Checks that the arrays of a part agree (sizes, local ids in range, owners and neighbours below
// num_parts, halo offsets increasing): what deserialize_part runs on bytes from elsewhere.
Status check_part(const Part& part);

// A part as bytes (native byte order: for the ranks of one machine type) and back. The bytes
// are checked: wrong or truncated ones give Error::Parse, never a part that breaks its reader.
std::vector<uint8_t> serialize_part(const Part& part);
Result<Part> deserialize_part(const uint8_t* bytes, size_t size);

}  // namespace anitet::partition
