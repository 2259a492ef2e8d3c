#include "mpi_comm.hpp"

#include <algorithm>
#include <climits>
#include <string>

namespace anitet::mpi {

Status mpi_status(int rc, const char* what) {
  if (rc == MPI_SUCCESS) return Status::success();
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  MPI_Error_string(rc, text, &len);
  return Status(Error::Internal, std::string("MPI ") + what + ": " + std::string(text, size_t(len)));
}

MpiComm::MpiComm(MPI_Comm comm) {
  MPI_Comm_dup(comm, &comm_);
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &ranks_);
}

MpiComm::~MpiComm() {
  if (comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
}

Result<std::vector<std::vector<uint8_t>>> MpiComm::exchange(const std::vector<std::vector<uint8_t>>& to) {
  const auto n = static_cast<size_t>(ranks_);
  if (to.size() != n) return Status(Error::Internal, "distributed: an exchange with a message list of another size");
  std::vector<uint64_t> out_sizes(n), in_sizes(n);
  for (size_t q = 0; q < n; ++q) out_sizes[q] = to[q].size();
  if (Status st = mpi_status(MPI_Alltoall(out_sizes.data(), 1, MPI_UINT64_T, in_sizes.data(), 1, MPI_UINT64_T, comm_),
                             "all-to-all of message sizes");
      !st.ok())
    return st;
  std::vector<std::vector<uint8_t>> from(n);
  std::vector<MPI_Request> requests;
  for (size_t q = 0; q < n; ++q) {
    from[q].resize(in_sizes[q]);
    for (size_t at = 0; at < from[q].size(); at += kPiece) {
      requests.emplace_back();
      MPI_Irecv(from[q].data() + at, int(std::min(kPiece, from[q].size() - at)), MPI_BYTE, int(q), 1, comm_,
                &requests.back());
    }
  }
  for (size_t q = 0; q < n; ++q)
    for (size_t at = 0; at < to[q].size(); at += kPiece) {
      requests.emplace_back();
      MPI_Isend(to[q].data() + at, int(std::min(kPiece, to[q].size() - at)), MPI_BYTE, int(q), 1, comm_,
                &requests.back());
    }
  if (Status st = mpi_status(MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE), "exchange");
      !st.ok())
    return st;
  return from;
}

Result<std::vector<double>> MpiComm::allreduce(const std::vector<double>& values, bool max) {
  std::vector<double> out(values.size());
  if (Status st = mpi_status(MPI_Allreduce(values.data(), out.data(), int(values.size()), MPI_DOUBLE,
                                           max ? MPI_MAX : MPI_SUM, comm_),
                             "allreduce");
      !st.ok())
    return st;
  return out;
}

Result<uint64_t> MpiComm::exscan(uint64_t value) {
  uint64_t below = 0;
  if (Status st = mpi_status(MPI_Exscan(&value, &below, 1, MPI_UINT64_T, MPI_SUM, comm_), "exscan"); !st.ok())
    return st;
  return rank_ == 0 ? 0 : below;  // MPI leaves rank 0's result undefined
}

}  // namespace anitet::mpi
