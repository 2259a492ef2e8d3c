// The two graphs of a finished mesh that partitioning needs: the tets of each vertex (for ghost
// layers and vertex owners) and the dual graph (tets sharing a face: what the partitioner cuts).
// Both are CSR arrays over tet ids; a mesh of 2^32 - 1 tets or more is refused.
#pragma once

#include <cstdint>
#include <vector>

#include "core/status.hpp"
#include "core/volume_mesh.hpp"

namespace anitet::partition {

// CSR: the items of row r are items[start[r] .. start[r + 1]).
struct Csr {
  std::vector<int64_t> start;
  std::vector<uint32_t> items;
  size_t rows() const { return start.empty() ? 0 : start.size() - 1; }
  int64_t begin(size_t r) const { return start[r]; }
  int64_t end(size_t r) const { return start[r + 1]; }
};

// The tets of each vertex, in ascending tet order. BadIndex for a tet vertex out of range.
Result<Csr> vertex_tets(const VolumeMesh& mesh);

// The tets sharing a face with each tet, in ascending order (at most 4 per tet). InvalidMesh for
// a face of more than two tets (the message names it).
Result<Csr> dual_graph(const VolumeMesh& mesh);

}  // namespace anitet::partition
