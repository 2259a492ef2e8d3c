// A finished mesh cut into parts for the ranks of a solver: METIS on the dual graph (tets
// sharing a face), then each part with its ghost layers, vertex owners and halo lists (part.hpp
// says what a part holds and in which order).
//
// Why METIS (5.1, Debian's libmetis-dev) and not Scotch (7.0, libscotch-dev): METIS was as fast at
// few parts and several times faster at many; Scotch's best cuts were somewhat smaller, but they
// changed from run to run, and Debian's Scotch starts threads of its own (with thread affinity)
// that a solver's threads would have to share (the figures: bench/results/partition,
// docs/partitions.md). METIS is serial, deterministic (a fixed seed), returns its errors and is
// Apache-2.0. Its cost: Debian builds it with 32-bit indices, so a dual graph of more than 2^31 - 1
// adjacency entries (about 5 * 10^8 tets) is refused (Error::NotImplemented); meshes that size are
// for a parallel partitioner on many ranks (ParMETIS, PT-Scotch) anyway.
//
// A mesh whose tets form several pieces without a face in common (two bodies, or regions that
// meet along an edge or a vertex only) is one graph with several components to METIS: the parts
// are balanced over all the tets, so a part may hold tets of several pieces and a piece may be
// split among parts. Ghost layers follow shared vertices, so they cross where pieces touch at a
// vertex or an edge and stop at a gap.
#pragma once

#include <cstdint>
#include <vector>

#include "core/status.hpp"
#include "core/volume_mesh.hpp"
#include "partition/mesh_graph.hpp"
#include "partition/part.hpp"

namespace anitet::partition {

struct PartitionOptions {
  int num_parts = 1;
  int ghost_layers = 1;                 // >= 0
  double imbalance = 0.03;              // heaviest part <= (1 + imbalance) * mean, in (0, 1]
  const double* tet_weights = nullptr;  // one per tet, finite, >= 0, one > 0; null: all 1
};

struct PartitionQuality {
  int64_t edge_cut = 0;            // faces between tets of different parts
  int64_t interface_vertices = 0;  // vertices whose tets are in more than one part
  double imbalance = 0;            // heaviest part's weight / mean part weight - 1
  double total_weight = 0;
  double max_part_weight = 0;
  int32_t empty_parts = 0;         // parts without a tet (only when parts are nearly as many as tets)
};

struct Partition {
  std::vector<int32_t> tet_part;  // the part of each tet of the mesh
  std::vector<Part> parts;
  PartitionQuality quality;
};

// The mesh in options.num_parts parts (1 .. number of tets). Errors: InvalidArgument (a part
// count, ghost layer count, imbalance or weight out of range), EmptyInput (no tet), BadIndex,
// InvalidMesh (a face of more than two tets), NotImplemented (a mesh too large for METIS).
Result<Partition> partition_mesh(const VolumeMesh& mesh, const PartitionOptions& options);

// The parts of a given assignment of tets to parts (0 .. num_parts - 1), ghost_layers deep.
Result<std::vector<Part>> build_parts(const VolumeMesh& mesh, const Csr& vertex_tets,
                                      const std::vector<int32_t>& tet_part, int num_parts, int ghost_layers);

// METIS's k-way cut of the dual graph: the part of each tet. weights: one integer per tet or
// empty for all 1 (their sum below 2^31).
Result<std::vector<int32_t>> cut_dual_graph(const Csr& dual, int num_parts, const std::vector<int32_t>& weights,
                                            double imbalance);

// Edge cut, interface vertices and balance of an assignment (weights: one per tet or null).
PartitionQuality measure_partition(const Csr& dual, const Csr& vertex_tets, const std::vector<int32_t>& tet_part,
                                   int num_parts, const double* weights);

}  // namespace anitet::partition
