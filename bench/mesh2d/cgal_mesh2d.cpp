// CGAL's Delaunay_mesher_2 on a Triangle .poly (points, segments, hole points), for
// bench/mesh2d/run_bench.sh: conforming Delaunay refinement (Ruppert, points added on segments)
// with a shape bound B (0.125: angles >= 20.7 deg) and a size bound S (the longest edge), then
// the mesh as a 2D Medit .mesh for tests/tools/check2d.py. Prints the meshing's wall seconds.
//
// usage: cgal_mesh2d IN.poly OUT.mesh SIZE_BOUND [SHAPE_BOUND] [LLOYD_ITERATIONS]
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/lloyd_optimize_mesh_2.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Delaunay_mesh_vertex_base_2<K>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<CDT>;
using Point = CDT::Point;

namespace {

// Whitespace tokens of a .poly without its '#' comments.
std::vector<std::string> tokens(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  std::string line;
  while (std::getline(in, line)) {
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream ss(line);
    std::string t;
    while (ss >> t) out.push_back(t);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s IN.poly OUT.mesh SIZE_BOUND [SHAPE_BOUND] [LLOYD_ITERATIONS]\n", argv[0]);
    return 2;
  }
  const double size = std::atof(argv[3]), shape = argc > 4 ? std::atof(argv[4]) : 0.125;
  const int lloyd = argc > 5 ? std::atoi(argv[5]) : 0;
  const std::vector<std::string> t = tokens(argv[1]);
  size_t i = 0;
  auto next = [&]() { return std::atof(t.at(i++).c_str()); };
  const int np = int(next()), dim = int(next()), na = int(next()), nm = int(next());
  if (dim != 2 || np == 0) return std::fprintf(stderr, "need a 2D .poly with its points\n"), 2;
  std::vector<Point> pts;
  int base = -1;
  for (int k = 0; k < np; ++k) {
    const int id = int(next());
    if (base < 0) base = id;
    const double x = next(), y = next();
    pts.emplace_back(x, y);
    for (int a = 0; a < na + nm; ++a) next();
  }
  const int ns = int(next()), sm = int(next());
  std::vector<std::pair<int, int>> segs;
  for (int k = 0; k < ns; ++k) {
    next();
    const int a = int(next()) - base, b = int(next()) - base;
    segs.emplace_back(a, b);
    for (int m = 0; m < sm; ++m) next();
  }
  const int nh = int(next());
  std::vector<Point> seeds;
  for (int k = 0; k < nh; ++k) {
    next();
    const double x = next(), y = next();
    seeds.emplace_back(x, y);
  }

  const auto start = std::chrono::steady_clock::now();
  CDT cdt;
  std::vector<CDT::Vertex_handle> vh;
  for (const Point& p : pts) vh.push_back(cdt.insert(p));
  for (const auto& [a, b] : segs) cdt.insert_constraint(vh[size_t(a)], vh[size_t(b)]);
  CGAL::refine_Delaunay_mesh_2(cdt, seeds.begin(), seeds.end(), Criteria(shape, size), false);
  if (lloyd > 0) CGAL::lloyd_optimize_mesh_2(cdt, CGAL::parameters::max_iteration_number = lloyd);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // The mesh: the input's points first (check2d.py matches them by coordinates anyway).
  std::map<CDT::Vertex_handle, size_t> id;
  std::vector<Point> out;
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
    id[v] = out.size();
    out.push_back(v->point());
  }
  std::ofstream f(argv[2]);
  f.precision(17);
  f << "MeshVersionFormatted 2\nDimension 2\nVertices\n" << out.size() << "\n";
  for (const Point& p : out) f << p.x() << " " << p.y() << " 0\n";
  size_t nt = 0;
  for (auto fc = cdt.finite_faces_begin(); fc != cdt.finite_faces_end(); ++fc) nt += fc->is_in_domain();
  f << "Triangles\n" << nt << "\n";
  for (auto fc = cdt.finite_faces_begin(); fc != cdt.finite_faces_end(); ++fc)
    if (fc->is_in_domain())
      f << id[fc->vertex(0)] + 1 << " " << id[fc->vertex(1)] + 1 << " " << id[fc->vertex(2)] + 1 << " 0\n";
  f << "End\n";
  std::printf("%.6f\n", seconds);
  return 0;
}
