// The k-way cut of the dual graph by METIS.
#include <cmath>
#include <limits>
#include <mutex>
#include <string>

#include <metis.h>

#include "partition/partition.hpp"

namespace anitet::partition {

static_assert(IDXTYPEWIDTH == 32 || IDXTYPEWIDTH == 64, "unknown METIS index width");

Result<std::vector<int32_t>> cut_dual_graph(const Csr& dual, int num_parts, const std::vector<int32_t>& weights,
                                            double imbalance) {
  const size_t n = dual.rows();
  if (num_parts < 1 || size_t(num_parts) > n) {
    return Status(Error::InvalidArgument, "cut_dual_graph: " + std::to_string(num_parts) + " parts of " +
                                              std::to_string(n) + " tets");
  }
  if (num_parts == 1) return std::vector<int32_t>(n, 0);  // (METIS 5.1 mishandles one part)
  constexpr uint64_t kMaxIdx = uint64_t(std::numeric_limits<idx_t>::max());
  if (dual.items.size() > kMaxIdx || n > kMaxIdx) {
    return Status(Error::NotImplemented,
                  "the dual graph has " + std::to_string(dual.items.size()) + " adjacency entries; this METIS (" +
                      std::to_string(IDXTYPEWIDTH) + "-bit indices) takes at most " + std::to_string(kMaxIdx));
  }
  std::vector<idx_t> xadj(dual.start.begin(), dual.start.end());
  std::vector<idx_t> adjncy(dual.items.begin(), dual.items.end());
  std::vector<idx_t> vwgt(weights.begin(), weights.end());
  std::vector<idx_t> part(n);
  idx_t nvtxs = idx_t(n), ncon = 1, nparts = num_parts, objval = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  // METIS's tolerance is in thousandths; its default (30) is the options' default 0.03.
  options[METIS_OPTION_UFACTOR] = idx_t(std::lround(imbalance * 1000.0));
  int rc = METIS_OK;
  {
    // METIS swaps process-wide signal handlers (SIGABRT, SIGTERM) during a call for its error
    // recovery: two calls at once could leave its handler installed. One call at a time.
    static std::mutex one_at_a_time;
    std::lock_guard<std::mutex> lock(one_at_a_time);
    rc = METIS_PartGraphKway(&nvtxs, &ncon, xadj.data(), adjncy.data(), vwgt.empty() ? nullptr : vwgt.data(),
                             nullptr, nullptr, &nparts, nullptr, nullptr, options, &objval, part.data());
  }
  if (rc == METIS_ERROR_MEMORY) return Status(Error::OutOfMemory, "METIS ran out of memory");
  if (rc != METIS_OK) return Status(Error::Internal, "METIS_PartGraphKway failed (" + std::to_string(rc) + ")");
  return std::vector<int32_t>(part.begin(), part.end());
}

}  // namespace anitet::partition
