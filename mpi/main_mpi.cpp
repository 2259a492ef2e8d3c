// anitet-mpi: `anitet mesh` on MPI ranks. Every rank reads the surface and runs stages 1, 2 and
// the coupling (deterministic: the same coupled mesh everywhere) and builds the sizing field;
// then stages 3b/3c run in parts, one per rank. With -o NAME.pvtu, no rank ever holds the whole
// mesh (distributed::run_rank_parts: PT-Scotch parts of the coarse mesh, rank-local rounds, tets
// migrated point to point, one piece written per rank); with another output,
// distributed::run_in_parts merges the parts on rank 0 after each round and rank 0 writes the
// mesh and prints the report. Usage: mpirun -np N anitet-mpi mesh IN -o OUT [options of
// `anitet mesh`]. docs/distributed.md has the design and its road to 10^9 tets.
#include <mpi.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "core/process_memory.hpp"
#include "distributed/memory_trace.hpp"
#include "distributed/parts.hpp"
#include "distributed/rank_mesh.hpp"
#include "exit_codes.hpp"
#include "mpi_comm.hpp"
#include "pieces.hpp"

namespace {

using anitet::Error;
using anitet::Result;
using anitet::Status;

using anitet::mpi::kPiece;
using anitet::mpi::mpi_status;

class MpiExchange final : public anitet::distributed::Exchange {
 public:
  MpiExchange(int rank, int ranks) : rank_(rank), ranks_(ranks) {}
  int rank() const override { return rank_; }
  int ranks() const override { return ranks_; }

  Result<std::vector<std::vector<uint8_t>>> gather(const std::vector<uint8_t>& mine) override {
    const uint64_t size = mine.size();
    std::vector<uint64_t> sizes(size_t(ranks_), 0);
    if (Status st = mpi_status(MPI_Gather(&size, 1, MPI_UINT64_T, sizes.data(), 1, MPI_UINT64_T, 0, MPI_COMM_WORLD),
                               "gather of sizes");
        !st.ok())
      return st;
    std::vector<std::vector<uint8_t>> all;
    if (rank_ != 0) {
      for (size_t at = 0; at < mine.size(); at += kPiece) {
        const int n = int(std::min(kPiece, mine.size() - at));
        if (Status st = mpi_status(MPI_Send(mine.data() + at, n, MPI_BYTE, 0, 0, MPI_COMM_WORLD), "send"); !st.ok())
          return st;
      }
      return all;
    }
    all.resize(size_t(ranks_));
    all[0] = mine;
    for (int r = 1; r < ranks_; ++r) {
      all[size_t(r)].resize(sizes[size_t(r)]);
      for (size_t at = 0; at < all[size_t(r)].size(); at += kPiece) {
        const int n = int(std::min(kPiece, all[size_t(r)].size() - at));
        if (Status st = mpi_status(
                MPI_Recv(all[size_t(r)].data() + at, n, MPI_BYTE, r, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "receive");
            !st.ok())
          return st;
      }
    }
    return all;
  }

  Result<std::vector<uint8_t>> broadcast(const std::vector<uint8_t>& root_bytes) override {
    uint64_t size = rank_ == 0 ? root_bytes.size() : 0;
    if (Status st = mpi_status(MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "broadcast of the size"); !st.ok())
      return st;
    std::vector<uint8_t> bytes = rank_ == 0 ? root_bytes : std::vector<uint8_t>(size);
    for (size_t at = 0; at < bytes.size(); at += kPiece) {
      const int n = int(std::min(kPiece, bytes.size() - at));
      if (Status st = mpi_status(MPI_Bcast(bytes.data() + at, n, MPI_BYTE, 0, MPI_COMM_WORLD), "broadcast"); !st.ok())
        return st;
    }
    return bytes;
  }

 private:
  int rank_, ranks_;
};

// The first collective call of stages 3b/3c: whether every rank got there. A rank that failed
// before (the same error everywhere, or a wall-time budget that ran out on that rank only) makes
// the call from main instead, with `ready` false.
bool all_ranks_ready(bool ready) {
  int failed = ready ? 0 : 1, any = 0;
  MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return any == 0;
}

// Stages 3b/3c with no whole mesh anywhere, and the pieces written (a .pvtu output). The coarse
// mesh is left with the surface's vertices and no tet, for the report of `anitet mesh`.
Status stage3_in_pieces(anitet::TetMesh& mesh, const anitet::SizingField& field,
                        const anitet::RefineOptions& refine_options, const anitet::OptimizeOptions& optimize_options,
                        const anitet::distributed::PartsOptions& options, const anitet::SurfaceMesh& surface,
                        const std::string& output, anitet::RefineStats& refine, anitet::OptimizeStats& optimize) {
  anitet::mpi::MpiComm comm(MPI_COMM_WORLD);
  anitet::mpi::ScotchPartitioner partitioner(comm.comm());
  std::vector<double> surface_xyz(mesh.xyz.begin(), mesh.xyz.begin() + std::ptrdiff_t(3 * surface.num_vertices()));
  std::vector<uint8_t> surface_flags(mesh.vflags.begin(), mesh.vflags.begin() + std::ptrdiff_t(surface.num_vertices()));
  anitet::distributed::trace_memory(comm.rank(), "stages 1-2 and coupling");
  anitet::distributed::RankMesh rm;
  anitet::distributed::RankRunStats stats;
  if (Status st = anitet::distributed::run_rank_parts(mesh, field, refine_options, optimize_options, options, comm,
                                                      partitioner, rm, refine, optimize, &stats);
      !st.ok())
    return st;
  anitet::distributed::trace_memory(comm.rank(), "rounds done");
  if (Status st = anitet::mpi::write_pieces(rm, surface, output, comm); !st.ok()) return st;
  anitet::distributed::trace_memory(comm.rank(), "piece written");
  if (std::getenv("ANITET_RANK_STATS"))
    std::fprintf(stderr,
                 "anitet-mpi: rank %d: %zu coarse splits, %zu own coarse tets after partitioning; %zu own tets, "
                 "%zu vertices at the end; %zu tets migrated; partition %.2f s, rounds %.2f s; peak RSS %.0f MB\n",
                 comm.rank(), stats.coarse_splits, stats.own_tets_after_partition, rm.mesh.num_live_tets(),
                 rm.mesh.num_vertices(), stats.migrated_tets, stats.partition_seconds, stats.rounds_seconds,
                 anitet::peak_resident_bytes() / 1048576.0);
  mesh = anitet::TetMesh();
  mesh.xyz = std::move(surface_xyz);
  mesh.vflags = std::move(surface_flags);
  return Status::success();
}

// The rounds' options, with the pipeline's anisotropic cycles.
anitet::distributed::PartsOptions parts_options(const anitet::cli::CycleOptions& cycles) {
  anitet::distributed::PartsOptions options;
  options.anisotropic_cycles = cycles.cycles;
  options.cycle_gain = cycles.gain;
  options.cycle_optimizer_gain = cycles.optimizer_gain;
  options.cycles_run = cycles.run;
  return options;
}

// The subcommand: the first argument that is not an option.
std::string subcommand(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (argv[i][0] != '-') return argv[i];
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  // PT-Scotch's fold-dup runs its two halves' MPI calls on two threads (scotch_partition.cpp).
  int provided = MPI_THREAD_SINGLE;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &provided);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  int code = anitet::cli::kExitOk;
  bool entered = false;  // this rank reached stages 3b/3c
  const std::string sub = subcommand(argc, argv);
  bool asks_help = false;
  for (int i = 1; i < argc; ++i)
    asks_help |= std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0 ||
                 std::strcmp(argv[i], "--version") == 0;
  if (sub != "mesh" && !asks_help) {
    if (rank == 0)
      std::cerr << "anitet-mpi: runs `anitet mesh` on MPI ranks: mpirun -np N anitet-mpi mesh IN -o OUT "
                   "[options]; the other subcommands are serial: run them with `anitet`\n";
    code = anitet::cli::kExitUsage;
  } else if (asks_help && rank != 0) {
    code = anitet::cli::kExitOk;  // rank 0 prints it
  } else {
    // The ranks on one machine share its cores: each gets its share of TBB threads (two ranks on
    // two cores: one thread each, where each would start two).
    MPI_Comm node;
    int node_ranks = 1;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &node);
    MPI_Comm_size(node, &node_ranks);
    MPI_Comm_free(&node);
    const int threads = std::max(1, tbb::info::default_concurrency() / std::max(1, node_ranks));
    tbb::global_control thread_share(tbb::global_control::max_allowed_parallelism, size_t(threads));
    MpiExchange exchange(rank, ranks);
    anitet::cli::DistributedRun run;
    run.rank = rank;
    run.ranks = ranks;
    run.stage3 = [&exchange, &entered](anitet::TetMesh& mesh, const anitet::SizingField& field,
                                       const anitet::RefineOptions& refine_options,
                                       const anitet::OptimizeOptions& optimize_options,
                                       const anitet::cli::CycleOptions& cycles, anitet::RefineStats& refine,
                                       anitet::OptimizeStats& optimize) {
      entered = true;
      if (!all_ranks_ready(true))
        return Status(Error::Internal, "another rank failed before stages 3b/3c (see its message)");
      return anitet::distributed::run_in_parts(mesh, field, refine_options, optimize_options, parts_options(cycles),
                                               exchange, refine, optimize);
    };
    run.stage3_parts = [&entered](anitet::TetMesh& mesh, const anitet::SizingField& field,
                                  const anitet::RefineOptions& refine_options,
                                  const anitet::OptimizeOptions& optimize_options,
                                  const anitet::cli::CycleOptions& cycles, const anitet::SurfaceMesh& surface,
                                  const std::string& output, anitet::RefineStats& refine,
                                  anitet::OptimizeStats& optimize) {
      entered = true;
      if (!all_ranks_ready(true))
        return Status(Error::Internal, "another rank failed before stages 3b/3c (see its message)");
      return stage3_in_pieces(mesh, field, refine_options, optimize_options, parts_options(cycles), surface, output,
                              refine, optimize);
    };
    anitet::cli::set_distributed_run(&run);
    code = anitet::cli::cli_main(argc, argv);
    anitet::cli::set_distributed_run(nullptr);
  }
  // A rank that stopped before stages 3b/3c (an error, --help) still answers the others' first
  // collective call there, so that none waits for it forever.
  if (!entered) all_ranks_ready(false);
  // Every rank's exit code: the highest (a failure anywhere fails the run).
  int worst = code;
  MPI_Allreduce(&code, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return worst;
}
