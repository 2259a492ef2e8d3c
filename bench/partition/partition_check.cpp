// Issue 50's partition figures on one mesh: partition_mesh into each part count, its edge cut
// against METIS's own cut of the same dual graph with METIS's defaults (what gpmetis runs), the
// imbalance, and the checks: every tet own in exactly one part, every ghost tet own on the part
// its owner field names, the halo lists of each pair of neighbours naming the same global ids.
//   partition_check MESH [--parts 2,8,64] [--ghost-layers 1]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "io/volume_io.hpp"
#include "partition/partition.hpp"

namespace {

using namespace anitet::partition;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

bool owns(const Part& p, int64_t tet) {
  return std::binary_search(p.tet_global.begin(), p.tet_global.begin() + p.owned_tets, tet);
}

// The problems found, "" when none.
std::string check(const anitet::VolumeMesh& mesh, const Partition& r) {
  std::vector<int> own(mesh.num_tets(), 0);
  for (const Part& p : r.parts) {
    for (int64_t i = 0; i < p.num_tets(); ++i) {
      const int64_t g = p.tet_global[size_t(i)];
      if (i < p.owned_tets) {
        ++own[size_t(g)];
        if (r.tet_part[size_t(g)] != p.index) return "an own tet of another part";
      } else if (!owns(r.parts[size_t(p.tet_owner[size_t(i)])], g)) {
        return "ghost tet " + std::to_string(g) + " of part " + std::to_string(p.index) + " not own on its owner";
      }
    }
    for (size_t n = 0; n < p.neighbours.size(); ++n) {
      const Part& q = r.parts[size_t(p.neighbours[n])];
      const size_t back = size_t(std::lower_bound(q.neighbours.begin(), q.neighbours.end(), p.index) - q.neighbours.begin());
      for (int kind = 0; kind < 2; ++kind) {
        const HaloList& send = p.halo[kind == 0 ? kVertexSend : kTetSend];
        const HaloList& recv = q.halo[kind == 0 ? kVertexRecv : kTetRecv];
        const auto& pg = kind == 0 ? p.vertex_global : p.tet_global;
        const auto& qg = kind == 0 ? q.vertex_global : q.tet_global;
        if (send.start[n + 1] - send.start[n] != recv.start[back + 1] - recv.start[back]) return "halo sizes differ";
        for (int64_t k = 0; k < send.start[n + 1] - send.start[n]; ++k)
          if (pg[size_t(send.items[size_t(send.start[n] + k)])] != qg[size_t(recv.items[size_t(recv.start[back] + k)])])
            return "halo lists differ";
      }
    }
  }
  for (int c : own)
    if (c != 1) return "a tet own in " + std::to_string(c) + " parts";
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s MESH [--parts 2,8,64] [--ghost-layers 1]\n", argv[0]);
    return 2;
  }
  std::string parts_list = "2,8,64";
  int ghost_layers = 1;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--parts") parts_list = argv[i + 1];
    else if (std::string(argv[i]) == "--ghost-layers") ghost_layers = std::atoi(argv[i + 1]);
  }
  auto mesh = anitet::read_volume_mesh(argv[1]);
  if (!mesh.ok()) {
    std::fprintf(stderr, "%s\n", mesh.status().message().c_str());
    return 1;
  }
  auto dual = dual_graph(mesh.value());
  auto vtets = vertex_tets(mesh.value());
  if (!dual.ok() || !vtets.ok()) return 1;
  std::printf("%s: %zu tets, %zu vertices, %zu dual graph edges, ghost layers %d\n", argv[1], mesh->num_tets(),
              mesh->num_vertices(), dual->items.size() / 2, ghost_layers);
  std::printf("%6s %10s %10s %7s %10s %10s %8s %8s %s\n", "parts", "edge cut", "METIS cut", "ratio", "imbalance",
              "METIS imb", "seconds", "METIS s", "checks");
  bool all_ok = true;
  std::stringstream list(parts_list);
  std::string item;
  while (std::getline(list, item, ',')) {
    const int n = std::atoi(item.c_str());
    PartitionOptions o;
    o.num_parts = n;
    o.ghost_layers = ghost_layers;
    auto t0 = Clock::now();
    auto r = partition_mesh(mesh.value(), o);
    const double seconds = since(t0);
    if (!r.ok()) {
      std::fprintf(stderr, "%d parts: %s\n", n, r.status().message().c_str());
      return 1;
    }
    t0 = Clock::now();
    auto metis = cut_dual_graph(dual.value(), n, {}, 0.03);
    const double metis_seconds = since(t0);
    if (!metis.ok()) return 1;
    const PartitionQuality mq = measure_partition(dual.value(), vtets.value(), metis.value(), n, nullptr);
    const std::string problems = check(mesh.value(), r.value());
    const double ratio = double(r->quality.edge_cut) / double(std::max<int64_t>(1, mq.edge_cut));
    const bool ok = problems.empty() && r->quality.imbalance <= 0.03 + 1e-12 && ratio <= 1.10;
    all_ok = all_ok && ok;
    std::printf("%6d %10lld %10lld %7.3f %9.2f%% %9.2f%% %8.2f %8.2f %s\n", n, (long long)r->quality.edge_cut,
                (long long)mq.edge_cut, ratio, 100 * r->quality.imbalance, 100 * mq.imbalance, seconds, metis_seconds,
                problems.empty() ? "ok" : problems.c_str());
  }
  return all_ok ? 0 : 1;
}
