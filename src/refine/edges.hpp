// The edges of a TetMesh with their normalized lengths (shared by refinement and the reports).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "core/sizing.hpp"
#include "core/tet_mesh.hpp"
#include "core/uninit_vector.hpp"

namespace anitet::refine_detail {

// Normalized length of the edge between vertices a and b: sqrt(|e|_Ma * |e|_Mb), with each
// vertex's metric at metrics[6 v].
inline double normalized_length(const TetMesh& mesh, const std::vector<double>& metrics, uint32_t a, uint32_t b) {
  return metric_edge_length(&metrics[6 * size_t(a)], mesh.point(a), &metrics[6 * size_t(b)], mesh.point(b));
}

struct Edge {
  uint32_t a, b;         // a < b
  uint32_t tet;          // the live tet of lowest id holding the edge (when collected)
  bool on_surface;       // on a protected facet (an edge of S)
  bool vetoed;           // refinement: its split was vetoed, and no tet around it changed since
  double length;         // normalized: sqrt(|e|_Ma * |e|_Mb)
  uint64_t key() const { return (uint64_t(a) << 32) | b; }
};
// (No member initializers: an EdgeList's resize writes nothing, its fill writes every field.)
using EdgeList = UninitVector<Edge>;

// Working memory of collect_edges, kept between calls (large meshes: page faults dominated); its
// buckets are not (6 entries per tet slot: held beside the lists, they set refinement's peak memory).
struct EdgeScratch {
  std::vector<uint32_t> start;  // per vertex: its bucket's first entry
  std::vector<uint32_t> fill;   // per chunk of tets and vertex: counts, then fill positions
  // Per thread: the position of each upper end's edge in the bucket being scanned, else kNone
  // (collect_edges). Kept here, not thread_local, so that the memory goes with the scratch.
  tbb::enumerable_thread_specific<std::vector<uint32_t>> where;
  void release() {
    std::vector<uint32_t>().swap(start);
    std::vector<uint32_t>().swap(fill);
    where.clear();
  }
};

// Every edge of the live tets once, a < b, grouped by a (ascending); within a group the order
// follows the tets (deterministic). metrics: 6 per vertex. The mesh must have fewer than 2^31
// tet slots.
void collect_edges(const TetMesh& mesh, const std::vector<double>& metrics, EdgeList& edges,
                   EdgeScratch& scratch);

// The edges refinement acts on: longer than split_length (split unless on S) or shorter than
// collapse_length with an end whose vflags have none of fixed_flags (collapsed).
struct EdgeFilter {
  double collapse_length, split_length;
  uint8_t fixed_flags;
  bool wanted(const TetMesh& mesh, uint32_t a, uint32_t b, double length) const {
    return length > split_length ||
           (length < collapse_length && !((mesh.vflags[a] & fixed_flags) && (mesh.vflags[b] & fixed_flags)));
  }
};

// What the tets around edge ab (a tet of them: start) show, walking across every facet through
// ab that has a neighbour (protected ones too): the lowest tet id (collect_edges's Edge::tet),
// whether a facet through ab is protected (Edge::on_surface), and the lowest id among the tets
// with changed[t] != 0 (kNone: none).
struct EdgeStar {
  uint32_t min_tet, min_changed;
  bool on_surface;
};
EdgeStar edge_star(const TetMesh& mesh, uint32_t a, uint32_t b, uint32_t start, const uint8_t* changed);

// The edge list of the next refinement pass without collecting every edge again: the edges of
// `previous` that the filter wants and no tet around which changed (changed[t] != 0 for every
// tet slot made since `previous` was collected), as they were (vetoed kept), and the wanted
// edges of the changed live tets, measured. The same edges with the same fields as collect_edges
// followed by the filter (Edge::vetoed aside), in another order; or, when most tets changed,
// collect_edges's whole list with the vetoes carried. previous is replaced.
void update_edges(const TetMesh& mesh, const std::vector<double>& metrics, const std::vector<uint8_t>& changed,
                  const EdgeFilter& filter, EdgeList& previous, EdgeScratch& scratch);

// Sets Edge::vetoed on the edges longer than split_length whose key() is in `keys` (sorted here).
void mark_vetoed(EdgeList& edges, std::vector<uint64_t>& keys, double split_length);

// Vertices used by a live tet.
size_t live_vertex_count(const TetMesh& mesh);

// Mean normalized length of the live tets' edges not on a protected facet (collect_edges's), and
// the share of them in [collapse_length, split_length] (1 when there are none); without their
// list, in about a third of collect_edges's memory. The mean is summed in chunks of vertices, in
// the same order on any number of threads.
void summarize_edge_lengths(const TetMesh& mesh, const std::vector<double>& metrics, double collapse_length,
                            double split_length, double& mean, double& in_range);

}  // namespace anitet::refine_detail
