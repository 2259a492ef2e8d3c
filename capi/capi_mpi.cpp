// libanitet_mpi (include/anitet_mpi.h): the MPI hand-off over the public C ABI only. The root
// partitions with anitet_mesh_partition and sends each rank its part as anitet_part_serialize's
// bytes; the halo exchange reads the part's lent halo arrays.
#include "anitet_mpi.h"

#include <algorithm>
#include <climits>
#include <new>
#include <cstdint>
#include <string>
#include <vector>

namespace {

// Messages in pieces below INT_MAX bytes (MPI counts are ints).
constexpr size_t kPiece = size_t(1) << 30;
constexpr int kPartTag = 1;          // on scatter's duplicate communicator
constexpr uint64_t kFailed = ~uint64_t(0);  // a size that says the root could not send the part

int fail(int code, const std::string& message) { return anitet_set_last_error(code, message.c_str()); }

int mpi_fail(const std::string& fn, int rc, const char* what) {
  char text[MPI_MAX_ERROR_STRING];
  int len = 0;
  if (MPI_Error_string(rc, text, &len) != MPI_SUCCESS) len = 0;
  return fail(ANITET_ERR_INTERNAL, fn + ": MPI " + what + " failed: " + std::string(text, size_t(len)));
}

// A duplicate of the caller's communicator whose MPI errors are returned, freed at the end.
struct Duplicate {
  MPI_Comm comm = MPI_COMM_NULL;
  int rc = MPI_SUCCESS;
  explicit Duplicate(MPI_Comm from) {
    rc = MPI_Comm_dup(from, &comm);
    if (rc == MPI_SUCCESS) rc = MPI_Comm_set_errhandler(comm, MPI_ERRORS_RETURN);
  }
  ~Duplicate() {
    if (comm != MPI_COMM_NULL) MPI_Comm_free(&comm);
  }
};

int send_bytes(const std::vector<uint8_t>& bytes, uint64_t size, int to, MPI_Comm comm) {
  int rc = MPI_Send(&size, 1, MPI_UINT64_T, to, kPartTag, comm);
  for (size_t at = 0; rc == MPI_SUCCESS && size != kFailed && at < bytes.size(); at += kPiece) {
    rc = MPI_Send(bytes.data() + at, int(std::min(kPiece, bytes.size() - at)), MPI_BYTE, to, kPartTag, comm);
  }
  return rc;
}

int receive_bytes(std::vector<uint8_t>& bytes, bool& failed, int from, MPI_Comm comm) {
  uint64_t size = 0;
  int rc = MPI_Recv(&size, 1, MPI_UINT64_T, from, kPartTag, comm, MPI_STATUS_IGNORE);
  failed = size == kFailed;
  if (rc != MPI_SUCCESS || failed) return rc;
  bytes.resize(size_t(size));
  for (size_t at = 0; rc == MPI_SUCCESS && at < bytes.size(); at += kPiece) {
    rc = MPI_Recv(bytes.data() + at, int(std::min(kPiece, bytes.size() - at)), MPI_BYTE, from, kPartTag, comm,
                  MPI_STATUS_IGNORE);
  }
  return rc;
}

// The root: part r as bytes (an empty vector when it could not be made: the rank is told, rather
// than left waiting for bytes that never come).
std::vector<uint8_t> part_bytes(const anitet_partition* partition, int r) {
  const anitet_part* part = nullptr;
  int64_t needed = 0;
  if (anitet_partition_get_part(partition, r, &part) != ANITET_OK ||
      anitet_part_serialize(part, nullptr, 0, &needed) != ANITET_OK) {
    return {};
  }
  try {
    std::vector<uint8_t> bytes(static_cast<size_t>(needed));
    if (anitet_part_serialize(part, bytes.data(), needed, nullptr) != ANITET_OK) return {};
    return bytes;
  } catch (const std::bad_alloc&) {
    return {};
  }
}

// The root's outcome (code and message) on every rank.
int share_outcome(const std::string& fn, int& code, std::string& message, int root, int rank, MPI_Comm comm) {
  int64_t header[2] = {code, int64_t(message.size())};
  int rc = MPI_Bcast(header, 2, MPI_INT64_T, root, comm);
  if (rc != MPI_SUCCESS) return mpi_fail(fn, rc, "broadcast of the root's outcome");
  code = int(header[0]);
  if (code == ANITET_OK) return ANITET_OK;
  message.resize(size_t(header[1]));
  rc = MPI_Bcast(&message[0], int(header[1]), MPI_CHAR, root, comm);
  if (rc != MPI_SUCCESS) return mpi_fail(fn, rc, "broadcast of the root's message");
  if (rank == root) return fail(code, message);
  return fail(code, fn + ": the root (rank " + std::to_string(root) + ") failed: " + message);
}

int scatter(const std::string& fn, const anitet_mesh* mesh, MPI_Comm comm, int32_t root,
            const anitet_partition_options* options, anitet_part** local) {
  if (local == nullptr) return fail(ANITET_ERR_INVALID_ARGUMENT, fn + ": local is NULL");
  *local = nullptr;
  int size = 0, rank = 0;
  int rc = MPI_Comm_size(comm, &size);
  if (rc == MPI_SUCCESS) rc = MPI_Comm_rank(comm, &rank);
  if (rc != MPI_SUCCESS) return mpi_fail(fn, rc, "size or rank of comm");
  if (root < 0 || root >= size) {
    return fail(ANITET_ERR_INVALID_ARGUMENT, fn + ": root " + std::to_string(root) + " is not a rank of comm (0.." +
                                                 std::to_string(size - 1) + ")");
  }
  Duplicate dup(comm);
  if (dup.rc != MPI_SUCCESS) return mpi_fail(fn, dup.rc, "duplicate of comm");
  // 1. The root partitions; its outcome reaches every rank.
  anitet_partition* partition = nullptr;
  int code = ANITET_OK;
  std::string message;
  if (rank == root) {
    code = mesh == nullptr ? fail(ANITET_ERR_INVALID_ARGUMENT, fn + ": mesh is NULL on the root")
                           : anitet_mesh_partition(mesh, size, options, &partition);
    if (code != ANITET_OK) message = anitet_last_error_message();
  }
  const int shared = share_outcome(fn, code, message, root, rank, dup.comm);
  if (shared != ANITET_OK) {
    anitet_partition_destroy(partition);
    return shared;
  }
  // 2. Part r to rank r, from the root.
  std::vector<uint8_t> mine;
  bool failed = false;
  if (rank == root) {
    for (int r = 0; r < size && rc == MPI_SUCCESS; ++r) {
      std::vector<uint8_t> bytes = part_bytes(partition, r);
      const uint64_t n = bytes.empty() ? kFailed : uint64_t(bytes.size());
      if (r == root) {
        failed = bytes.empty();
        mine = std::move(bytes);
      } else {
        rc = send_bytes(bytes, n, r, dup.comm);
      }
    }
    anitet_partition_destroy(partition);
  } else {
    rc = receive_bytes(mine, failed, root, dup.comm);
  }
  if (rc != MPI_SUCCESS) return mpi_fail(fn, rc, "transfer of the parts");
  // 3. Each rank rebuilds its part; every rank returns the same code.
  anitet_part* part = nullptr;
  code = failed ? fail(ANITET_ERR_OUT_OF_MEMORY, fn + ": the root could not write this rank's part")
                : anitet_part_deserialize(mine.data(), int64_t(mine.size()), &part);
  int worst = code;
  rc = MPI_Allreduce(&code, &worst, 1, MPI_INT, MPI_MIN, dup.comm);
  if (rc != MPI_SUCCESS) {
    anitet_part_destroy(part);
    return mpi_fail(fn, rc, "reduction of the outcomes");
  }
  if (worst != ANITET_OK) {
    anitet_part_destroy(part);
    if (code != ANITET_OK) return code;  // this rank's own message stays
    return fail(worst, fn + ": another rank failed to rebuild its part (" + anitet_error_name(worst) + ")");
  }
  *local = part;
  return fail(ANITET_OK, "");
}

template <class T>
const T* lent(const anitet_part* part, int32_t array, int64_t& count) {
  const void* data = nullptr;
  if (anitet_part_get_array(part, array, &data, &count, nullptr) != ANITET_OK) return nullptr;
  return static_cast<const T*>(data);
}

int exchange(const std::string& fn, const anitet_part* part, MPI_Comm comm, int32_t where, double* values,
             int32_t components) {
  if (part == nullptr) return fail(ANITET_ERR_INVALID_ARGUMENT, fn + ": part is NULL");
  if (values == nullptr) return fail(ANITET_ERR_INVALID_ARGUMENT, fn + ": values is NULL");
  if (components < 1) {
    return fail(ANITET_ERR_INVALID_ARGUMENT, fn + ": components is " + std::to_string(components) + ", not >= 1");
  }
  if (where != ANITET_FIELD_ON_VERTICES && where != ANITET_FIELD_ON_TETS) {
    return fail(ANITET_ERR_INVALID_ARGUMENT, fn + ": where is " + std::to_string(where) + ", not ANITET_FIELD_ON_*");
  }
  int32_t index = 0, num_parts = 0;
  if (anitet_part_get_index(part, &index, &num_parts, nullptr, nullptr) != ANITET_OK) return ANITET_ERR_INVALID_ARGUMENT;
  int size = 0, rank = 0;
  int rc = MPI_Comm_size(comm, &size);
  if (rc == MPI_SUCCESS) rc = MPI_Comm_rank(comm, &rank);
  if (rc != MPI_SUCCESS) return mpi_fail(fn, rc, "size or rank of comm");
  if (index != rank || num_parts != size) {
    return fail(ANITET_ERR_INVALID_ARGUMENT, fn + ": part " + std::to_string(index) + " of " + std::to_string(num_parts) +
                                                 " on rank " + std::to_string(rank) + " of " + std::to_string(size) +
                                                 ": not this rank's part");
  }
  const bool on_vertices = where == ANITET_FIELD_ON_VERTICES;
  int64_t n_nb = 0, n_so = 0, n_si = 0, n_ro = 0, n_ri = 0;
  const int32_t* neighbours = lent<int32_t>(part, ANITET_PART_NEIGHBOURS, n_nb);
  const int64_t* so = lent<int64_t>(part, on_vertices ? ANITET_PART_VERTEX_SEND_OFFSETS : ANITET_PART_TET_SEND_OFFSETS, n_so);
  const int32_t* si = lent<int32_t>(part, on_vertices ? ANITET_PART_VERTEX_SEND : ANITET_PART_TET_SEND, n_si);
  const int64_t* ro = lent<int64_t>(part, on_vertices ? ANITET_PART_VERTEX_RECV_OFFSETS : ANITET_PART_TET_RECV_OFFSETS, n_ro);
  const int32_t* ri = lent<int32_t>(part, on_vertices ? ANITET_PART_VERTEX_RECV : ANITET_PART_TET_RECV, n_ri);
  if (so == nullptr || ro == nullptr) return ANITET_ERR_INTERNAL;
  const size_t c = size_t(components);
  std::vector<double> out(size_t(n_si) * c), in(size_t(n_ri) * c);
  for (int64_t k = 0; k < n_si; ++k) std::copy_n(values + size_t(si[k]) * c, c, out.data() + size_t(k) * c);
  for (int64_t i = 0; i < n_nb; ++i)
    if ((so[i + 1] - so[i]) * components > INT_MAX || (ro[i + 1] - ro[i]) * components > INT_MAX)
      return fail(ANITET_ERR_NOT_IMPLEMENTED, fn + ": a message of more than INT_MAX values");
  std::vector<MPI_Request> requests;
  for (int64_t i = 0; i < n_nb && rc == MPI_SUCCESS; ++i) {
    const int64_t sends = (so[i + 1] - so[i]) * components, recvs = (ro[i + 1] - ro[i]) * components;
    requests.emplace_back();
    rc = MPI_Irecv(in.data() + size_t(ro[i]) * c, int(recvs), MPI_DOUBLE, neighbours[i], ANITET_MPI_EXCHANGE_TAG, comm,
                   &requests.back());
    if (rc != MPI_SUCCESS) break;
    requests.emplace_back();
    rc = MPI_Isend(out.data() + size_t(so[i]) * c, int(sends), MPI_DOUBLE, neighbours[i], ANITET_MPI_EXCHANGE_TAG, comm,
                   &requests.back());
  }
  if (rc == MPI_SUCCESS) rc = MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  if (rc != MPI_SUCCESS) return mpi_fail(fn, rc, "halo messages");
  for (int64_t k = 0; k < n_ri; ++k) std::copy_n(in.data() + size_t(k) * c, c, values + size_t(ri[k]) * c);
  return fail(ANITET_OK, "");
}

// No exception may leave the library: only allocations throw here.
template <class F>
int guarded(const std::string& fn, F&& body) noexcept {
  try {
    return body();
  } catch (...) {
    return anitet_set_last_error(ANITET_ERR_OUT_OF_MEMORY, (fn + ": out of memory").c_str());
  }
}

}  // namespace

extern "C" {

int anitet_mesh_scatter(const anitet_mesh* mesh, MPI_Comm comm, int32_t root, const anitet_partition_options* options,
                        anitet_part** local) {
  const char* const fn = __func__;
  return guarded(fn, [&] { return scatter(fn, mesh, comm, root, options, local); });
}

int anitet_mesh_scatter_f(const anitet_mesh* mesh, MPI_Fint comm, int32_t root, const anitet_partition_options* options,
                          anitet_part** local) {
  const char* const fn = __func__;
  return guarded(fn, [&] { return scatter(fn, mesh, MPI_Comm_f2c(comm), root, options, local); });
}

int anitet_part_exchange(const anitet_part* part, MPI_Comm comm, int32_t where, double* values, int32_t components) {
  const char* const fn = __func__;
  return guarded(fn, [&] { return exchange(fn, part, comm, where, values, components); });
}

int anitet_part_exchange_f(const anitet_part* part, MPI_Fint comm, int32_t where, double* values, int32_t components) {
  const char* const fn = __func__;
  return guarded(fn, [&] { return exchange(fn, part, MPI_Comm_f2c(comm), where, values, components); });
}

}  // extern "C"
