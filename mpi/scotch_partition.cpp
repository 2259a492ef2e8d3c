// The coarse mesh's partition by PT-Scotch (Debian libptscotch-dev, 32-bit SCOTCH_Num).
#include <cstdio>  // ptscotch.h needs FILE
#include <mpi.h>
#include <scotch/ptscotch.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "mpi_comm.hpp"

namespace anitet::mpi {

namespace {

Status scotch_failed(const char* what) {
  return Status(Error::Internal, std::string("PT-Scotch: ") + what + " failed");
}

}  // namespace

Result<std::vector<int32_t>> ScotchPartitioner::partition(const TetMesh& coarse, const std::vector<double>& weights,
                                                          int parts) {
  // Debian's PT-Scotch folds the graph on two threads that both call MPI: below
  // MPI_THREAD_MULTIPLE its ranks may wait in different collectives forever (1 run in 3 on 4
  // ranks did, here).
  int level = MPI_THREAD_SINGLE;
  MPI_Query_thread(&level);
  if (level < MPI_THREAD_MULTIPLE)
    return Status(Error::InvalidArgument,
                  "PT-Scotch needs MPI initialized with MPI_Init_thread(..., MPI_THREAD_MULTIPLE, ...)");
  int rank = 0, ranks = 1;
  MPI_Comm_rank(comm_, &rank);
  MPI_Comm_size(comm_, &ranks);
  const auto slots = static_cast<uint32_t>(coarse.num_tet_slots());
  // The live tets, numbered 0 .. C-1 in slot order (the vertices of Scotch's graph).
  std::vector<int64_t> index(slots, -1);
  std::vector<uint32_t> slot_of;
  for (uint32_t t = 0; t < slots; ++t)
    if (!coarse.is_deleted(t) && !coarse.is_ghost(t)) {
      index[t] = int64_t(slot_of.size());
      slot_of.push_back(t);
    }
  const auto c = static_cast<int64_t>(slot_of.size());
  if (c == 0) return Status(Error::EmptyInput, "distributed: the coarse mesh has no tet");
  if (c >= INT32_MAX / 4)
    return Status(Error::NotImplemented, "distributed: a coarse mesh too large for 32-bit PT-Scotch");
  std::vector<int32_t> part_of(slots, -1);
  if (parts == 1) {
    for (uint32_t t : slot_of) part_of[t] = 0;
    return part_of;
  }
  double total = 0.0;
  for (uint32_t t : slot_of) total += weights[t];
  // Integer loads: the predicted tets, at least 1, scaled down when their sum would pass 2^31 - 1.
  const double scale = std::min(1.0, double(INT32_MAX / 2) / std::max(1.0, total + double(c)));
  const int64_t lo = c * rank / ranks, hi = c * (rank + 1) / ranks;
  // Arc loads: the final facets the field predicts across the coarse facet, about the 2/3 power
  // of the predicted tets on either side. Counting coarse facets instead, PT-Scotch cuts through
  // the largest coarse tets (fewest facets), which refinement's first round then leaves coarse
  // several rings deep beside its frozen interfaces.
  auto facets_across = [&](uint32_t a, uint32_t b) {
    const double f = 0.5 * (std::cbrt(weights[a] * weights[a]) + std::cbrt(weights[b] * weights[b]));
    return SCOTCH_Num(std::max(1.0, std::min(1e6, std::round(f))));
  };
  std::vector<SCOTCH_Num> vertloctab, veloloctab, edgeloctab, edloloctab;
  vertloctab.push_back(0);
  for (int64_t k = lo; k < hi; ++k) {
    const uint32_t t = slot_of[size_t(k)];
    veloloctab.push_back(SCOTCH_Num(std::max(1.0, std::round(weights[t] * scale))));
    for (int i = 0; i < 4; ++i) {
      if (coarse.tet_adj[4 * size_t(t) + size_t(i)] == TetMesh::kNoNeighbour) continue;
      const uint32_t u = coarse.neighbour(t, i);
      if (u < slots && index[u] >= 0) {
        edgeloctab.push_back(SCOTCH_Num(index[u]));
        edloloctab.push_back(facets_across(t, u));
      }
    }
    vertloctab.push_back(SCOTCH_Num(edgeloctab.size()));
  }
  const auto vertlocnbr = static_cast<SCOTCH_Num>(hi - lo);
  const auto edgelocnbr = static_cast<SCOTCH_Num>(edgeloctab.size());
  if (edgeloctab.empty()) {  // Scotch wants valid pointers
    edgeloctab.push_back(0);
    edloloctab.push_back(1);
  }
  SCOTCH_Dgraph graph;
  SCOTCH_Strat strat;
  if (SCOTCH_dgraphInit(&graph, comm_) != 0) return scotch_failed("SCOTCH_dgraphInit");
  std::vector<SCOTCH_Num> partloctab(size_t(std::max<SCOTCH_Num>(1, vertlocnbr)), 0);
  int rc = SCOTCH_dgraphBuild(&graph, 0, vertlocnbr, vertlocnbr, vertloctab.data(), nullptr, veloloctab.data(),
                              nullptr, edgelocnbr, edgelocnbr, edgeloctab.data(), nullptr, edloloctab.data());
  SCOTCH_stratInit(&strat);
  if (rc == 0) rc = SCOTCH_stratDgraphMapBuild(&strat, SCOTCH_STRATBALANCE, parts, parts, 0.05) == 0 ? 0 : 2;
  // The same seed on every call: the same input gives the same parts from run to run (as far as
  // PT-Scotch's own message order allows).
  SCOTCH_randomReset();
  if (rc == 0) rc = SCOTCH_dgraphPart(&graph, parts, &strat, partloctab.data()) == 0 ? 0 : 3;
  SCOTCH_stratExit(&strat);
  SCOTCH_dgraphExit(&graph);
  if (rc != 0) return scotch_failed(rc == 2 ? "SCOTCH_stratDgraphMapBuild" : rc == 3 ? "SCOTCH_dgraphPart" : "SCOTCH_dgraphBuild");
  // Every rank gets every tet's part.
  std::vector<int> counts(static_cast<size_t>(ranks)), displs(static_cast<size_t>(ranks));
  for (int q = 0; q < ranks; ++q) {
    displs[size_t(q)] = int(c * q / ranks);
    counts[size_t(q)] = int(c * (q + 1) / ranks) - displs[size_t(q)];
  }
  std::vector<int32_t> mine(partloctab.begin(), partloctab.begin() + vertlocnbr), all(static_cast<size_t>(c));
  if (Status st = mpi_status(MPI_Allgatherv(mine.data(), vertlocnbr, MPI_INT32_T, all.data(), counts.data(),
                                            displs.data(), MPI_INT32_T, comm_),
                             "allgather of the parts");
      !st.ok())
    return st;
  for (int64_t k = 0; k < c; ++k) {
    if (all[size_t(k)] < 0 || all[size_t(k)] >= parts) return Status(Error::Internal, "PT-Scotch: a part out of range");
    part_of[slot_of[size_t(k)]] = all[size_t(k)];
  }
  return part_of;
}

}  // namespace anitet::mpi
