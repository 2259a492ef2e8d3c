// Under mpirun (2-4 ranks): the knight's coarse (coupled) mesh partitioned by PT-Scotch, each
// rank's part extracted and the coarse mesh freed; then the halo received from the other ranks.
// Asserts through the arrays' sizes that no rank holds more than its part plus its one-ring halo:
// the counts partition::build_parts gives for the same assignment on one process (ghost layer 1),
// and that the coarse mesh's arrays are gone. Exit code 0 when every rank agrees.
#include <mpi.h>

#include <cstdio>
#include <string>

#include "core/tet_mesh.hpp"
#include "distributed/rank_mesh.hpp"
#include "io/surface_io.hpp"
#include "mpi_comm.hpp"
#include "partition/partition.hpp"
#include "pipeline/mesher.hpp"
#include "refine/refine.hpp"

using namespace anitet;

namespace {

int check(bool ok, int rank, const char* what, size_t got, size_t limit) {
  if (!ok) std::fprintf(stderr, "rank %d: %s: %zu, at most %zu\n", rank, what, got, limit);
  return ok ? 0 : 1;
}

int run(const std::string& surface_path) {
  mpi::MpiComm comm(MPI_COMM_WORLD);
  Result<SurfaceMesh> surface = read_surface(surface_path);
  if (!surface.ok()) return std::fprintf(stderr, "%s\n", surface.status().message().c_str()), 1;
  int failures = 0;
  MesherOptions options;
  options.stage3 = [&](TetMesh& coarse, const SizingField& field, RefineStats&, OptimizeStats&) {
    mpi::ScotchPartitioner partitioner(comm.comm());
    const std::vector<double> weights = estimate_refined_tets_per_tet(coarse, field);
    Result<std::vector<int32_t>> part_of = partitioner.partition(coarse, weights, comm.ranks());
    if (!part_of.ok()) return part_of.status();
    // The reference: build_parts on the whole coarse mesh, as one process would.
    std::vector<int32_t> tet_part;
    for (uint32_t t = 0; t < coarse.num_tet_slots(); ++t)
      if (!coarse.is_deleted(t) && !coarse.is_ghost(t)) tet_part.push_back(part_of.value()[t]);
    const VolumeMesh whole = coarse.to_volume_mesh(false);
    Result<partition::Csr> vt = partition::vertex_tets(whole);
    if (!vt.ok()) return vt.status();
    Result<std::vector<partition::Part>> ref = partition::build_parts(whole, vt.value(), tet_part, comm.ranks(), 1);
    if (!ref.ok()) return ref.status();
    const partition::Part& mine = ref.value()[size_t(comm.rank())];
    Result<distributed::RankMesh> rm = distributed::own_coarse_part(coarse, part_of.value(), comm.rank());
    if (!rm.ok()) return rm.status();
    coarse = TetMesh();  // as run_rank_parts does
    const int r = comm.rank();
    failures += check(coarse.xyz.capacity() == 0 && coarse.tet_v.capacity() == 0, r, "coarse arrays left",
                      coarse.tet_v.capacity(), 0);
    const auto own = size_t(mine.owned_tets);
    failures += check(rm->mesh.num_tet_slots() == own, r, "own tets", rm->mesh.num_tet_slots(), own);
    failures += check(rm->mesh.tet_v.size() / 4 <= own, r, "tet_v / 4", rm->mesh.tet_v.size() / 4, own);
    Result<distributed::Sharing> sharing = distributed::find_sharing(rm.value(), comm);
    if (!sharing.ok()) return sharing.status();
    Result<distributed::LocalMesh> local = distributed::with_halo(rm.value(), sharing.value(), comm);
    if (!local.ok()) return local.status();
    const auto own_and_halo = size_t(mine.num_tets()), vertices = size_t(mine.num_vertices());
    failures += check(local->mesh.tet_v.size() / 4 == own_and_halo, r, "own + halo tets", local->mesh.tet_v.size() / 4,
                      own_and_halo);
    failures += check(local->mesh.xyz.size() / 3 == vertices, r, "own + halo vertices", local->mesh.xyz.size() / 3,
                      vertices);
    std::printf("rank %d: %zu own coarse tets, %zu with the halo, %zu vertices (build_parts: %zu, %zu, %zu)\n", r,
                rm->mesh.num_tet_slots(), local->mesh.tet_v.size() / 4, local->mesh.xyz.size() / 3, own, own_and_halo,
                vertices);
    coarse.xyz.assign(3 * surface->num_vertices(), 0.0);  // the mesher's report wants the surface's vertices
    coarse.vflags.assign(surface->num_vertices(), 0);
    return Status::success();
  };
  Result<MesherResult> result = Mesher(options).run(surface.value());
  if (!result.ok()) return std::fprintf(stderr, "%s\n", result.status().message().c_str()), 1;
  int any = 0;
  MPI_Allreduce(&failures, &any, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  return any == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  // PT-Scotch's fold-dup runs its two halves' MPI calls on two threads (scotch_partition.cpp).
  int provided = MPI_THREAD_SINGLE;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &provided);
  const int code = argc > 1 ? run(argv[1]) : 2;
  MPI_Finalize();
  return code;
}
