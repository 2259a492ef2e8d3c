// Stages 3b/3c on parts of the mesh: the coupled mesh is cut into parts, each part is refined and
// optimized on its own with its interface frozen, the parts are merged into one conformal mesh,
// and a second round with the interfaces moved (each old interface inside one part) remeshes
// where the first round could not (the approach of ParMmg and of NASA's refine). Nothing here
// knows MPI: the ranks of the MPI driver (mpi/) each run one part, and the unit tests run all the
// parts in one process, with the same bytes in between.
//
// A part holds its own tets plus a halo: every other tet that shares a vertex with one of them,
// frozen as the boundary layer is (every facet protected, every vertex locked), so nothing a part
// does can reach a tet of another: refinement splits no edge on a protected facet, cavities,
// flips and collapses stop at protected facets, and locked vertices never move or go. The halo
// tets carry the region -1 - region and are dropped again by merge_parts.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/status.hpp"
#include "core/tet_mesh.hpp"
#include "optimize/optimize.hpp"
#include "refine/refine.hpp"

namespace anitet::distributed {

// The tet flags that travel with a tet between parts and ranks (the others are a round's own).
inline constexpr uint16_t kKeptFlags = tflag::kFacetProtectedMask | tflag::kEdgeConstrainedMask;

// The part of each tet slot (-1 for deleted and ghost slots): `parts` runs of equal tet counts
// along a Hilbert curve through the tets' centroids, the first starting `shift` of a run along
// the curve (the last run wraps around to the curve's start).
std::vector<int32_t> hilbert_parts(const TetMesh& mesh, int parts, double shift = 0.0);

// A tet no part meshes in a round is kept as it is; its part of the round before is still read
// from the label (kept(p) <= -2).
inline int32_t kept(int32_t part) { return -2 - part; }
inline int32_t part_of_label(int32_t label) { return label <= -2 ? -2 - label : label; }

// The parts of the next round: `rings` times, every vertex takes the lowest part of its tets and
// every tet the lowest part of its vertices. Every vertex where parts met (an interface) is then
// inside the lowest of them, with `rings` - 1 layers of tets around it, and the new interfaces lie
// in what the round before meshed inside a part. With zone > 0, only the tets within `zone` rings
// of an old interface vertex get a part; the others are kept (they were meshed inside a part
// already), so the round costs in proportion to the interfaces, not to the mesh.
std::vector<int32_t> move_interfaces(const TetMesh& mesh, const std::vector<int32_t>& part_of, int rings,
                                     int zone);

struct MeshPart {
  TetMesh mesh;                    // own tets and halo; the halo's regions are -1 - region
  std::vector<uint32_t> global_of; // the part's first vertices -> vertex of the whole mesh
  std::vector<uint8_t> frozen;     // per first vertex: locked here because a tet of another part has it
  // Facets between the part and its halo that the whole mesh does not protect (sorted global
  // vertex ids): merge_parts unprotects them again.
  std::vector<std::array<uint32_t, 3>> interface_facets;
  RefineStats refine;
  OptimizeStats optimize;
};

// Part p of the whole mesh (part_of from hilbert_parts or move_interfaces), which has no
// ghost tets.
Result<MeshPart> extract_part(const TetMesh& whole, const std::vector<int32_t>& part_of, int32_t p);

// What every run in parts refuses: ghost tets (InvalidArgument). Anisotropic fields are meshed:
// refinement's metric kernel and flips and the optimizer's metric measures stop at protected
// facets and locked vertices as the isotropic ones do, and each rank evaluates the field at its
// own vertices (the metric never travels).
Status check_meshable_in_parts(const TetMesh& mesh);

// What a round does to each part: refinement (refine_mesh, then the new vertices renumbered for
// locality), or optimization (optimize_mesh with the field scaled by refine.size_scale).
enum class Step { kRefine, kOptimize };
Status mesh_part(MeshPart& part, Step step, const SizingField& field, const RefineOptions& refine,
                 const OptimizeOptions& optimize);

// The parts, refined and optimized, as one mesh: the vertices of `whole` keep their ids (a frozen
// vertex its place, a free one the place its part gave it), each part's new vertices follow in
// part order, the tets are the kept tets of `whole` (part_of <= -2), then the parts' own tets in
// part order (the part of each in *tet_part; a kept tet's part of the round before), the
// interface facets unprotected. Fails when the parts do not fit (a halo tet changed, a facet of
// more than two tets).
// `boundary_facets` is the whole mesh's count of facets without a neighbour (the domain's
// boundary), which the merged mesh must have too: a gap or an overlap between parts changes it.
Result<TetMesh> merge_parts(const TetMesh& whole, const std::vector<int32_t>& part_of,
                            const std::vector<MeshPart>& parts, size_t boundary_facets,
                            std::vector<int32_t>* tet_part);

// Facets of live tets without a neighbour (the mesh's adjacency built).
size_t count_boundary_facets(const TetMesh& mesh);

// Bytes for the ranks' messages: a part (after mesh_part), and a whole mesh with the part of
// each tet (or none). Only the live tets are sent, not the adjacency: a part comes back without
// it (merge_parts needs none), a mesh with it when asked (extract_part, hilbert_parts and
// move_interfaces need none either).
std::vector<uint8_t> serialize_part(const MeshPart& part);
Result<MeshPart> deserialize_part(const std::vector<uint8_t>& bytes);
std::vector<uint8_t> serialize_mesh(const TetMesh& mesh, const std::vector<int32_t>& tet_part);
Result<TetMesh> deserialize_mesh(const std::vector<uint8_t>& bytes, std::vector<int32_t>& tet_part,
                                 bool with_adjacency);

// Adds a part's refinement and optimization counts to the totals (lengths and qualities are
// left to the caller, who measures the merged mesh).
void add_counts(const MeshPart& part, RefineStats& refine, OptimizeStats& optimize);

// The messages between the ranks of run_in_parts: rank 0 gathers the parts and sends every rank
// the merged mesh. Each call is collective (every rank makes it, in the same order).
class Exchange {
 public:
  virtual ~Exchange() = default;
  virtual int rank() const = 0;
  virtual int ranks() const = 0;
  // Every rank's bytes, in rank order, on rank 0 (an empty list elsewhere).
  virtual Result<std::vector<std::vector<uint8_t>>> gather(const std::vector<uint8_t>& mine) = 0;
  // Rank 0's bytes on every rank (`root_bytes` is read on rank 0 only).
  virtual Result<std::vector<uint8_t>> broadcast(const std::vector<uint8_t>& root_bytes) = 0;
};

struct PartsOptions {
  int rings = 4;   // move_interfaces' rings
  int zone = 6;    // and its zone (<= 0: every tet in a part in the second round too)
  // run_rank_parts' moves (PT-Scotch parts of the split coarse mesh), after refinement's first
  // round and after each optimization round but the last. Refinement's: 4/6 left fandisk's min
  // radius ratio at 0.12-0.19 in 2 runs of 3 on 3 ranks (6/8: 0.34-0.40 in 3); armadillo at 1.3M
  // tets on 4 ranks, the largest part over the mean: 1.11 at 4/6, 1.15 at 6/8, 1.19 at 8/10.
  // Optimization's: 6/8 (twice) left that largest part at 1.39 times the mean, 3/4 at 1.22
  // (fandisk on 4 ranks: 1.6-1.8 and 1.11), with the interfaces as good.
  int refine_rings = 6, refine_zone = 8;
  int optimize_rings = 3, optimize_zone = 4;
  // run_rank_parts' optimization: after its first round, this many times a move and a round in
  // the zone (refinement: one). With one, tets below radius ratio 0.3 were 3.2 times as frequent
  // within two rings of the final interfaces as elsewhere (armadillo, 1.3M tets, 4 ranks), and
  // fandisk's min on 3 ranks 0.26-0.38; with two, 0.4 times and 0.39-0.40 (one process: 0.40).
  int optimize_moves = 2;
  // run_rank_parts splits the coarse mesh until every part has about this many coarse tets or
  // more (split_coarse_for_parts); <= 0: no split.
  double coarse_tets_per_part = 2000;
  // With an anisotropic field: the pipeline's extra cycles (MesherOptions::anisotropic_cycles and
  // their gains, as refine_optimize_cycles runs them), each a refinement's rounds then an
  // optimization's. 0: none.
  int anisotropic_cycles = 0;
  double cycle_gain = 0.01, cycle_optimizer_gain = 0.045;
  int* cycles_run = nullptr;  // when set: the cycles that ran
};

// The metric of `field` scaled by `scale` at each vertex of `mesh` (6 per vertex): what the
// runs in parts measure edge lengths in (refine_detail::summarize_edge_lengths).
std::vector<double> vertex_metrics(const TetMesh& mesh, const SizingField& field, double scale);

// Refinement's rounds then optimization's (`steps`, which with an anisotropic field measures
// `refined_in_range` and optimize.length_in_range_before/after), then up to
// options.anisotropic_cycles more of both, gated as the pipeline's refine_optimize_cycles: no
// cycle after an optimization that gained less than cycle_optimizer_gain, no more after one
// whose refinement gained less than cycle_gain. run_in_parts and run_rank_parts share it.
Status run_steps_and_cycles(const PartsOptions& options, bool anisotropic, const double& refined_in_range,
                            const OptimizeStats& optimize, const std::function<Status(Step)>& steps);

// Stages 3b/3c of `mesh` (the coupled mesh; rank 0's is sent to all) in ranks() parts, rank r
// meshing part r. Refinement, then optimization, each in two rounds: on Hilbert parts of the
// mesh as it is, then on parts with the interfaces moved, only within PartsOptions::zone of them
// (what the first round could not touch). Each round ends with the merged mesh on every rank.
// Refining and optimizing in separate rounds keeps the optimizer away from the coarse coupled
// tets that freeze the first refinement's interfaces: with both in one round it spent 20 times
// the serial perturbations on tets there that no move could lift. Anisotropic fields run the
// same rounds, then PartsOptions::anisotropic_cycles more of both as the pipeline's cycles run
// (their gates read the shares of edges in [1/sqrt2, sqrt2], measured on the whole mesh, which
// every rank holds between rounds: OptimizeStats::length_in_range_*). `refine` and `optimize` get the parts'
// counts summed (rank 0: all parts; elsewhere its own), the lengths and qualities of the final
// mesh. A failure on any rank fails every rank, with its message. The result depends on ranks()
// (the parts), not on the threads of each rank.
Status run_in_parts(TetMesh& mesh, const SizingField& field, const RefineOptions& refine_options,
                    const OptimizeOptions& optimize_options, const PartsOptions& options, Exchange& exchange,
                    RefineStats& refine, OptimizeStats& optimize);

}  // namespace anitet::distributed
