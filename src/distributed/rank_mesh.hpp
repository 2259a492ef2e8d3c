// Stages 3b/3c with no whole mesh anywhere (issue 51, docs/distributed.md "Design: parts from the
// coarse mesh on"): the coarse (coupled) mesh, the same on every rank, is cut by a partitioner
// weighted by the tets the field predicts; each rank keeps its own coarse tets only and from then
// on holds its part plus, during a round, a one-ring halo it receives from the ranks that share
// vertices with it. A round is run_in_parts' round on that local mesh (extract_part, mesh_part);
// between rounds the interfaces move (move_interfaces' rule, the labels exchanged between the
// ranks that share vertices) and the tets that change owner go point to point to their new rank.
// Nothing here knows MPI: the messages go through `Comm` (mpi/ implements it).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.hpp"
#include "core/tet_mesh.hpp"
#include "distributed/parts.hpp"

namespace anitet::distributed {

// The messages between ranks. Every call is collective (all ranks, same order).
class Comm {
 public:
  virtual ~Comm() = default;
  virtual int rank() const = 0;
  virtual int ranks() const = 0;
  // to[q]: the bytes for rank q (empty: nothing); returns what each rank sent this one. Only the
  // pairs with bytes exchange a message (the byte counts go all to all first).
  virtual Result<std::vector<std::vector<uint8_t>>> exchange(const std::vector<std::vector<uint8_t>>& to) = 0;
  // Element-wise sum (or max) over the ranks.
  virtual Result<std::vector<double>> allreduce(const std::vector<double>& values, bool max) = 0;
  // The sum of `value` over the lower ranks.
  virtual Result<uint64_t> exscan(uint64_t value) = 0;
};

// Cuts the coarse mesh: the part (0 .. parts - 1) of every tet slot (-1 for deleted and ghost
// slots), the same on every rank. Collective. `weights` per tet slot (the predicted tets).
class CoarsePartitioner {
 public:
  virtual ~CoarsePartitioner() = default;
  virtual Result<std::vector<int32_t>> partition(const TetMesh& coarse, const std::vector<double>& weights, int parts) = 0;
};

// One rank's part between rounds: its own tets only, compact, adjacency built.
struct RankMesh {
  TetMesh mesh;
  std::vector<uint64_t> gid;      // per vertex: coarse vertex index, or (creator rank + 1) << 40 | counter
  std::vector<uint8_t> meshable;  // per tet: meshed in the next round (else kept there, frozen)
  uint64_t created = 0;           // vertices this rank created so far (its gid counter)
};

inline uint64_t created_gid(int rank, uint64_t counter) { return (uint64_t(rank) + 1) << 40 | counter; }

// Rank `rank`'s own tets of the coarse mesh (part_of from a CoarsePartitioner), all meshable.
Result<RankMesh> own_coarse_part(const TetMesh& coarse, const std::vector<int32_t>& part_of, int rank);

// The vertices a rank shares: (local vertex, other rank whose own tets have it), sorted.
struct Sharing {
  std::vector<std::pair<uint32_t, int32_t>> pairs;
};
// Collective: each rank's vertices on a facet without an own neighbour go to a home rank (by
// their gid), which tells every holder the others.
Result<Sharing> find_sharing(const RankMesh& rm, Comm& comm);

// Collective: the rank's own tets (meshable: label 0; kept: kept(0), only those with a vertex of a
// meshable one: the others are in neither the part nor its halo) plus the halo (every tet of
// another rank with a vertex of an own tet; label 1), and the gid of each of its vertices.
struct LocalMesh {
  TetMesh mesh;
  std::vector<int32_t> label;
  std::vector<uint64_t> gid;
};
// `rm` is taken by value: its mesh becomes the local mesh's first tets without a copy.
Result<LocalMesh> with_halo(RankMesh rm, const Sharing& sharing, Comm& comm);

// Collective: one round on every rank's part, the halo frozen: the meshable tets refined or
// optimized; the result (own tets, kept ones too) in `rm`. Checks that the part's boundary
// (domain boundary and interfaces) kept its facet count. The part's counts are added to
// refine_counts and optimize_counts.
Status mesh_round(RankMesh& rm, Step step, const SizingField& field, const RefineOptions& refine,
                  const OptimizeOptions& optimize, Comm& comm, RefineStats& refine_counts,
                  OptimizeStats& optimize_counts);

// Collective: move_interfaces on the distributed mesh (rings, zone as there), then the own tets
// labelled with another rank are sent to it; the tets in the zone are meshable, the others kept.
// The rule's "lowest" is in the order `priority` gives the ranks (rank q's place, 0 first; a
// permutation, the same on every rank), so that the caller chooses who takes the zones. Returns
// the tets this rank sent.
Result<size_t> move_and_migrate(RankMesh& rm, int rings, int zone, const std::vector<int32_t>& priority, Comm& comm);

// Collective: contiguous ids 0 .. V-1 for the vertices (a shared one owned by the lowest rank
// holding it, which numbers it and sends its id to the others) and the first id of this rank's
// tets (they are numbered in order from it).
struct GlobalIds {
  std::vector<uint64_t> vertex;
  std::vector<int32_t> vertex_owner;
  uint64_t first_tet = 0;
  uint64_t total_vertices = 0, total_tets = 0;
};
Result<GlobalIds> number_globally(const RankMesh& rm, Comm& comm);

// Splits the coarse mesh (replicated, before it is partitioned: refinement's splits only, at most
// 8 passes, with the field's lengths times cbrt(cap)) towards no tet predicting more than cap =
// (predicted tets) / (parts * tets_per_part) final tets, so that every part gets many coarse tets:
// a part of a few huge ones stays coarse beside its frozen interfaces in the first round and went
// whole to a neighbour at the first move. Deterministic, so the same on every rank. Returns the
// splits made (0: no tet predicted more than cap).
Result<size_t> split_coarse_for_parts(TetMesh& coarse, const SizingField& field, const RefineOptions& refine_options,
                                      int parts, double tets_per_part);

// Stages 3b/3c in parts with no gather: the coarse mesh `coarse` (replicated) split
// (split_coarse_for_parts), partitioned, freed, then the rounds: refinement, a move, refinement;
// optimization, then optimize_moves times a move and optimization (PartsOptions); with an
// anisotropic field, PartsOptions::anisotropic_cycles more of both, gated as run_in_parts gates
// them. `rm` is this rank's part at the end; refine/optimize get
// the counts summed over the ranks and the quality of the whole (summed from the parts).
struct RankRunStats {
  double partition_seconds = 0, rounds_seconds = 0;
  size_t migrated_tets = 0;  // sent by this rank over all moves
  size_t own_tets_after_partition = 0;
  size_t coarse_splits = 0;  // split_coarse_for_parts' splits
};
Status run_rank_parts(TetMesh& coarse, const SizingField& field, const RefineOptions& refine_options,
                      const OptimizeOptions& optimize_options, const PartsOptions& options, Comm& comm,
                      CoarsePartitioner& partitioner, RankMesh& rm, RefineStats& refine, OptimizeStats& optimize,
                      RankRunStats* stats = nullptr);

}  // namespace anitet::distributed
