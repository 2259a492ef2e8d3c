// METIS against Scotch on the dual graph of a mesh (tets sharing a face), the graph the
// partition module cuts: edge cut, imbalance and time per part count, and the graph in METIS's
// file format for gpmetis. Built with -DANITET_BUILD_BENCH=ON when both libraries are found.
//   partitioner_compare MESH [--graph FILE] [--parts 2,8,64]
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include <metis.h>
extern "C" {
#include <scotch.h>
}

#include "io/volume_io.hpp"
#include "partition/mesh_graph.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Figures {
  int64_t cut = 0;
  double imbalance = 0;
};

Figures measure(const anitet::partition::Csr& g, const std::vector<int64_t>& part, int nparts) {
  Figures f;
  std::vector<int64_t> load(size_t(nparts), 0);
  for (size_t t = 0; t < g.rows(); ++t) {
    ++load[size_t(part[t])];
    for (int64_t k = g.begin(t); k < g.end(t); ++k)
      if (g.items[size_t(k)] > t && part[g.items[size_t(k)]] != part[t]) ++f.cut;
  }
  int64_t max = 0;
  for (int64_t l : load) max = std::max(max, l);
  f.imbalance = double(max) * nparts / double(g.rows()) - 1.0;
  return f;
}

std::vector<int64_t> run_metis(const anitet::partition::Csr& g, int nparts) {
  idx_t n = idx_t(g.rows()), ncon = 1, np = nparts, cut = 0;
  std::vector<idx_t> xadj(g.start.begin(), g.start.end()), adj(g.items.begin(), g.items.end()),
      part(g.rows());
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);  // as gpmetis: k-way, ufactor 30 (3%), seed fixed
  if (METIS_PartGraphKway(&n, &ncon, xadj.data(), adj.data(), nullptr, nullptr, nullptr, &np, nullptr,
                          nullptr, options, &cut, part.data()) != METIS_OK) {
    std::fprintf(stderr, "METIS failed\n");
    std::exit(1);
  }
  return std::vector<int64_t>(part.begin(), part.end());
}

std::vector<int64_t> run_scotch(const anitet::partition::Csr& g, int nparts, SCOTCH_Num flags) {
  std::vector<SCOTCH_Num> xadj(g.start.begin(), g.start.end()), adj(g.items.begin(), g.items.end()),
      part(g.rows());
  SCOTCH_Graph graph;
  SCOTCH_Strat strat;
  SCOTCH_graphInit(&graph);
  SCOTCH_stratInit(&strat);
  if (SCOTCH_graphBuild(&graph, 0, SCOTCH_Num(g.rows()), xadj.data(), nullptr, nullptr, nullptr,
                        SCOTCH_Num(adj.size()), adj.data(), nullptr) != 0 ||
      SCOTCH_stratGraphMapBuild(&strat, flags, nparts, 0.03) != 0 ||
      SCOTCH_graphPart(&graph, nparts, &strat, part.data()) != 0) {
    std::fprintf(stderr, "Scotch failed\n");
    std::exit(1);
  }
  SCOTCH_stratExit(&strat);
  SCOTCH_graphExit(&graph);
  return std::vector<int64_t>(part.begin(), part.end());
}

void write_graph(const anitet::partition::Csr& g, const std::string& path) {
  FILE* f = std::fopen(path.c_str(), "w");
  if (!f) {
    std::perror(path.c_str());
    std::exit(1);
  }
  std::fprintf(f, "%zu %zu\n", g.rows(), g.items.size() / 2);
  for (size_t t = 0; t < g.rows(); ++t) {
    for (int64_t k = g.begin(t); k < g.end(t); ++k)
      std::fprintf(f, k == g.begin(t) ? "%u" : " %u", g.items[size_t(k)] + 1);
    std::fputc('\n', f);
  }
  std::fclose(f);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s MESH [--graph FILE] [--parts 2,8,64]\n", argv[0]);
    return 2;
  }
  std::string graph_file, parts_list = "2,8,64";
  for (int i = 2; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--graph") graph_file = argv[i + 1];
    else if (std::string(argv[i]) == "--parts") parts_list = argv[i + 1];
  }
  auto mesh = anitet::read_volume_mesh(argv[1]);
  if (!mesh.ok()) {
    std::fprintf(stderr, "%s\n", mesh.status().message().c_str());
    return 1;
  }
  auto t0 = Clock::now();
  auto g = anitet::partition::dual_graph(mesh.value());
  if (!g.ok()) {
    std::fprintf(stderr, "%s\n", g.status().message().c_str());
    return 1;
  }
  std::printf("%zu tets, %zu dual edges; dual graph built in %.3f s\n", g->rows(), g->items.size() / 2,
              std::chrono::duration<double>(Clock::now() - t0).count());
  if (!graph_file.empty()) write_graph(g.value(), graph_file);
  std::stringstream list(parts_list);
  std::string item;
  std::printf("%-28s %6s %10s %9s %8s\n", "partitioner", "parts", "edge cut", "imbalance", "seconds");
  while (std::getline(list, item, ',')) {
    const int nparts = std::atoi(item.c_str());
    struct Run {
      const char* name;
      int kind;
      SCOTCH_Num flags;
    } runs[] = {{"METIS 5.1 PartGraphKway", 0, 0},
                {"Scotch 7.0 default", 1, SCOTCH_STRATDEFAULT},
                {"Scotch 7.0 quality", 1, SCOTCH_STRATQUALITY},
                {"Scotch 7.0 quality+balance", 1, SCOTCH_STRATQUALITY | SCOTCH_STRATBALANCE}};
    for (const Run& run : runs) {
      auto s = Clock::now();
      std::vector<int64_t> part = run.kind == 0 ? run_metis(g.value(), nparts) : run_scotch(g.value(), nparts, run.flags);
      const double seconds = std::chrono::duration<double>(Clock::now() - s).count();
      Figures f = measure(g.value(), part, nparts);
      std::printf("%-28s %6d %10lld %8.2f%% %8.3f\n", run.name, nparts, (long long)f.cut, 100 * f.imbalance,
                  seconds);
    }
  }
  return 0;
}
