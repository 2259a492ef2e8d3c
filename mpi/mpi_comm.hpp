// The MPI side of src/distributed: its Comm over an MPI communicator, and the coarse mesh's
// partitioner, PT-Scotch on the distributed dual graph.
#pragma once
#include <mpi.h>

#include "distributed/rank_mesh.hpp"

namespace anitet::mpi {

// A duplicate of `comm`, so that these messages never meet the caller's.
class MpiComm final : public distributed::Comm {
 public:
  explicit MpiComm(MPI_Comm comm);
  ~MpiComm() override;
  MpiComm(const MpiComm&) = delete;
  MpiComm& operator=(const MpiComm&) = delete;
  int rank() const override { return rank_; }
  int ranks() const override { return ranks_; }
  Result<std::vector<std::vector<uint8_t>>> exchange(const std::vector<std::vector<uint8_t>>& to) override;
  Result<std::vector<double>> allreduce(const std::vector<double>& values, bool max) override;
  Result<uint64_t> exscan(uint64_t value) override;
  MPI_Comm comm() const { return comm_; }

 private:
  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0, ranks_ = 1;
};

// An MPI return code as a Status (its message named by `what`).
Status mpi_status(int rc, const char* what);
// Messages go in pieces below INT_MAX bytes (MPI counts are ints).
inline constexpr size_t kPiece = size_t(1) << 30;

// SCOTCH_dgraphPart on the coarse mesh's dual graph (tets sharing a facet), each rank building
// the slice [r C/P, (r+1) C/P) of its live tets from its copy of the mesh (no message), the loads
// the predicted tets (at least 1), 5% imbalance; the parts gathered to every rank.
class ScotchPartitioner final : public distributed::CoarsePartitioner {
 public:
  explicit ScotchPartitioner(MPI_Comm comm) : comm_(comm) {}
  Result<std::vector<int32_t>> partition(const TetMesh& coarse, const std::vector<double>& weights, int parts) override;

 private:
  MPI_Comm comm_;
};

}  // namespace anitet::mpi
