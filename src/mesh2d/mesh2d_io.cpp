#include "mesh2d/mesh2d_io.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>

#include "io/file_bytes.hpp"
#include "io/number_text.hpp"

namespace anitet::mesh2d {

namespace {

int64_t rounded(double x) { return std::isfinite(x) ? int64_t(std::llround(x)) : 0; }

// Writes `count` items, `chunk` at a time, each appended by item(out, i).
template <class F>
bool stream_items(const std::function<bool(std::string_view)>& write, size_t count, F&& item) {
  std::string out;
  for (size_t i = 0; i < count; ++i) {
    item(out, i);
    if (out.size() > (1u << 20)) {
      if (!write(out)) return false;
      out.clear();
    }
  }
  return write(out);
}

Status write_medit(const std::string& path, const TriMesh2& m) {
  return write_file_with(path, [&](const std::function<bool(std::string_view)>& write) {
    std::string head = "MeshVersionFormatted 2\n\nDimension 2\n\nVertices\n";
    append_int(head, int64_t(m.num_vertices()));
    head += '\n';
    if (!write(head)) return false;
    if (!stream_items(write, m.num_vertices(), [&](std::string& out, size_t v) {
          append_line(out, m.xy[2 * v], m.xy[2 * v + 1], int64_t(v < m.input_points ? 1 : 0));
        }))
      return false;
    std::string mid = "\nEdges\n";
    append_int(mid, int64_t(m.edge_label.size()));
    mid += '\n';
    if (!write(mid)) return false;
    if (!stream_items(write, m.edge_label.size(), [&](std::string& out, size_t e) {
          append_line(out, int64_t(m.edges[2 * e]) + 1, int64_t(m.edges[2 * e + 1]) + 1, int64_t(m.edge_label[e]));
        }))
      return false;
    std::string tri = "\nTriangles\n";
    append_int(tri, int64_t(m.num_triangles()));
    tri += '\n';
    if (!write(tri)) return false;
    if (!stream_items(write, m.num_triangles(), [&](std::string& out, size_t t) {
          append_line(out, int64_t(m.tri[3 * t]) + 1, int64_t(m.tri[3 * t + 1]) + 1, int64_t(m.tri[3 * t + 2]) + 1,
                      rounded(m.attribute[t]));
        }))
      return false;
    return write("\nEnd\n");
  });
}

// Entity tags for distinct values: the values when all are positive integers, else 1, 2, ...
template <class T>
std::map<T, int64_t> entity_tags(const std::vector<T>& values) {
  std::map<T, int64_t> tags;
  for (const T& v : values) tags[v] = 0;
  bool positive = !tags.empty();
  for (const auto& [v, tag] : tags) positive &= double(v) >= 1 && double(v) == std::floor(double(v)) && double(v) < 1e9;
  int64_t next = 1;
  for (auto& [v, tag] : tags) tag = positive ? int64_t(v) : next++;
  return tags;
}

std::string value_text(double v) {
  std::string s;
  if (v == std::floor(v) && std::fabs(v) < 1e15) append_int(s, int64_t(v));
  else append_double(s, v);
  return s;
}

Status write_gmsh(const std::string& path, const TriMesh2& m) {
  const std::map<int32_t, int64_t> curves = entity_tags(m.edge_label);
  std::map<double, int64_t> surfaces = entity_tags(m.attribute);
  if (surfaces.empty()) surfaces[0.0] = 1;
  double box[6] = {0, 0, 0, 0, 0, 0};
  if (m.num_vertices()) {
    box[0] = box[1] = std::numeric_limits<double>::infinity();
    box[3] = box[4] = -box[0];
    for (size_t v = 0; v < m.num_vertices(); ++v)
      for (int k = 0; k < 2; ++k) box[k] = std::min(box[k], m.xy[2 * v + size_t(k)]), box[3 + k] = std::max(box[3 + k], m.xy[2 * v + size_t(k)]);
  }
  std::string out = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n";
  append_int(out, int64_t(curves.size() + surfaces.size()));
  out += '\n';
  for (const auto& [label, tag] : curves) out += "1 " + std::to_string(tag) + " \"label" + std::to_string(label) + "\"\n";
  for (const auto& [attr, tag] : surfaces) out += "2 " + std::to_string(tag) + " \"region" + value_text(attr) + "\"\n";
  out += "$EndPhysicalNames\n$Entities\n0 ";
  append_line(out, int64_t(curves.size()), int64_t(surfaces.size()), int64_t(0));
  auto entity = [&](int64_t tag, bool curve) {
    append_int(out, tag);
    for (double b : box) out += ' ', append_double(out, b);
    out += " 1 " + std::to_string(tag) + (curve ? " 0\n" : " 0\n");
  };
  for (const auto& [label, tag] : curves) entity(tag, true);
  for (const auto& [attr, tag] : surfaces) entity(tag, false);
  out += "$EndEntities\n$Nodes\n";
  const int64_t nv = int64_t(m.num_vertices());
  append_line(out, int64_t(1), nv, int64_t(1), nv);
  append_line(out, int64_t(2), surfaces.begin()->second, int64_t(0), nv);
  for (int64_t v = 1; v <= nv; ++v) append_line(out, v);
  for (size_t v = 0; v < m.num_vertices(); ++v) append_line(out, m.xy[2 * v], m.xy[2 * v + 1], 0.0);
  out += "$EndNodes\n$Elements\n";
  const int64_t ne = int64_t(m.edge_label.size()), nt = int64_t(m.num_triangles());
  append_line(out, int64_t(curves.size() + surfaces.size()), ne + nt, int64_t(1), ne + nt);
  int64_t id = 1;
  for (const auto& [label, tag] : curves) {
    std::vector<size_t> mine;
    for (size_t e = 0; e < m.edge_label.size(); ++e)
      if (m.edge_label[e] == label) mine.push_back(e);
    append_line(out, int64_t(1), tag, int64_t(1), int64_t(mine.size()));
    for (size_t e : mine) append_line(out, id++, int64_t(m.edges[2 * e]) + 1, int64_t(m.edges[2 * e + 1]) + 1);
  }
  for (const auto& [attr, tag] : surfaces) {
    std::vector<size_t> mine;
    for (size_t t = 0; t < m.num_triangles(); ++t)
      if (m.attribute[t] == attr) mine.push_back(t);
    append_line(out, int64_t(2), tag, int64_t(2), int64_t(mine.size()));
    for (size_t t : mine)
      append_line(out, id++, int64_t(m.tri[3 * t]) + 1, int64_t(m.tri[3 * t + 1]) + 1, int64_t(m.tri[3 * t + 2]) + 1);
  }
  out += "$EndElements\n";
  return write_file_bytes(path, out);
}

Status write_vtu(const std::string& path, const TriMesh2& m) {
  const size_t nv = m.num_vertices(), nt = m.num_triangles(), ne = m.edge_label.size();
  std::string out =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"";
  append_int(out, int64_t(nv));
  out += "\" NumberOfCells=\"";
  append_int(out, int64_t(nt + ne));
  out += "\">\n      <Points>\n        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (size_t v = 0; v < nv; ++v) append_line(out, m.xy[2 * v], m.xy[2 * v + 1], 0.0);
  out += "        </DataArray>\n      </Points>\n      <Cells>\n"
         "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (size_t t = 0; t < nt; ++t) append_line(out, m.tri[3 * t], m.tri[3 * t + 1], m.tri[3 * t + 2]);
  for (size_t e = 0; e < ne; ++e) append_line(out, m.edges[2 * e], m.edges[2 * e + 1]);
  out += "        </DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for (size_t c = 0; c < nt + ne; ++c) append_line(out, uint64_t(c < nt ? 3 * (c + 1) : 3 * nt + 2 * (c - nt + 1)));
  out += "        </DataArray>\n        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (size_t c = 0; c < nt + ne; ++c) append_line(out, int64_t(c < nt ? 5 : 3));
  out += "        </DataArray>\n      </Cells>\n      <CellData>\n"
         "        <DataArray type=\"Float64\" Name=\"region\" format=\"ascii\">\n";
  for (size_t c = 0; c < nt + ne; ++c) append_line(out, c < nt ? m.attribute[c] : 0.0);
  out += "        </DataArray>\n        <DataArray type=\"Int32\" Name=\"label\" format=\"ascii\">\n";
  for (size_t c = 0; c < nt + ne; ++c) append_line(out, int64_t(c < nt ? 0 : m.edge_label[c - nt]));
  out += "        </DataArray>\n      </CellData>\n";
  if (m.metric.size() == 3 * nv && nv > 0) {
    out += "      <PointData>\n        <DataArray type=\"Float64\" Name=\"metric\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (size_t v = 0; v < nv; ++v) append_line(out, m.metric[3 * v], m.metric[3 * v + 1], m.metric[3 * v + 2]);
    out += "        </DataArray>\n      </PointData>\n";
  }
  out += "    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return write_file_bytes(path, out);
}

// The mesh's boundary loops: each a closed list of vertices with the domain on the left, the
// label of the edge leaving each vertex, and whether the loop is an outer one (counter-clockwise).
struct Loop {
  std::vector<uint32_t> v;
  std::vector<int32_t> label;
  bool outer = false;
};

std::vector<Loop> boundary_loops(const TriMesh2& m) {
  // Directed boundary edges (a, b) with their triangle on the left: edges of exactly one triangle.
  std::map<std::pair<uint32_t, uint32_t>, int> count;
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.tri[3 * t + size_t(k)], b = m.tri[3 * t + size_t((k + 1) % 3)];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  std::map<std::pair<uint32_t, uint32_t>, int32_t> label_of;
  for (size_t e = 0; e < m.edge_label.size(); ++e)
    label_of[{std::min(m.edges[2 * e], m.edges[2 * e + 1]), std::max(m.edges[2 * e], m.edges[2 * e + 1])}] = m.edge_label[e];
  std::multimap<uint32_t, uint32_t> next;  // a -> b
  for (size_t t = 0; t < m.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.tri[3 * t + size_t(k)], b = m.tri[3 * t + size_t((k + 1) % 3)];
      if (count[{std::min(a, b), std::max(a, b)}] == 1) next.emplace(a, b);
    }
  std::vector<Loop> loops;
  while (!next.empty()) {
    Loop loop;
    auto it = next.begin();
    const uint32_t first = it->first;
    uint32_t cur = first;
    double twice_area = 0;
    while (true) {
      auto found = next.find(cur);
      if (found == next.end()) break;
      const uint32_t b = found->second;
      next.erase(found);
      loop.v.push_back(cur);
      const auto l = label_of.find({std::min(cur, b), std::max(cur, b)});
      loop.label.push_back(l == label_of.end() ? 0 : l->second);
      twice_area += m.xy[2 * size_t(cur)] * m.xy[2 * size_t(b) + 1] - m.xy[2 * size_t(b)] * m.xy[2 * size_t(cur) + 1];
      cur = b;
      if (cur == first) break;
    }
    loop.outer = twice_area > 0;
    loops.push_back(std::move(loop));
  }
  return loops;
}

}  // namespace

std::string mesh2d_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == "mesh" || ext == "msh" || ext == "vtu") return ext;
  const std::string file = std::filesystem::path(path).filename().string();
  if (ext == "14" || file == "fort.14") return "fort14";
  return "";
}

Status write_fort14(const std::string& path, const TriMesh2& m, const Fort14Options& o) {
  if (!o.depth.empty() && o.depth.size() != m.num_vertices())
    return Status(Error::InvalidArgument, "fort.14: one depth per vertex is needed");
  std::string out = o.title + "\n";
  append_line(out, int64_t(m.num_triangles()), int64_t(m.num_vertices()));
  for (size_t v = 0; v < m.num_vertices(); ++v)
    append_line(out, int64_t(v) + 1, m.xy[2 * v], m.xy[2 * v + 1], o.depth.empty() ? 0.0 : o.depth[v]);
  for (size_t t = 0; t < m.num_triangles(); ++t)
    append_line(out, int64_t(t) + 1, int64_t(3), int64_t(m.tri[3 * t]) + 1, int64_t(m.tri[3 * t + 1]) + 1, int64_t(m.tri[3 * t + 2]) + 1);
  // Runs of open and of land edges along each loop.
  struct Run {
    std::vector<uint32_t> nodes;
    int type;
    bool outer;
  };
  std::vector<Run> open, land;
  for (const Loop& loop : boundary_loops(m)) {
    const size_t n = loop.v.size();
    auto is_open = [&](size_t i) { return o.open_labels.count(loop.label[i % n]) > 0; };
    size_t start = 0;
    bool mixed = false;
    for (size_t i = 0; i < n; ++i)
      if (is_open(i) != is_open(0)) mixed = true;
    if (!mixed) {
      Run r{loop.v, is_open(0) ? 0 : (loop.outer ? o.mainland_type : o.island_type), loop.outer};
      r.nodes.push_back(loop.v.front());  // a closed boundary: its first node again
      (is_open(0) ? open : land).push_back(std::move(r));
      continue;
    }
    while (is_open(start) == is_open(start + n - 1)) ++start;  // a run starts here
    for (size_t i = 0; i < n;) {
      const bool kind = is_open(start + i);
      Run r{{}, kind ? 0 : o.mainland_type, loop.outer};
      size_t j = i;
      while (j < n && is_open(start + j) == kind) r.nodes.push_back(loop.v[(start + j) % n]), ++j;
      r.nodes.push_back(loop.v[(start + j) % n]);  // the run's last edge's end
      (kind ? open : land).push_back(std::move(r));
      i = j;
    }
  }
  // ADCIRC lists the boundaries around the outside of the domain before the islands.
  std::stable_sort(land.begin(), land.end(), [](const Run& a, const Run& b) { return a.outer > b.outer; });
  std::stable_sort(open.begin(), open.end(), [](const Run& a, const Run& b) { return a.outer > b.outer; });
  size_t neta = 0, nvel = 0;
  for (const Run& r : open) neta += r.nodes.size();
  for (const Run& r : land) nvel += r.nodes.size();
  out += std::to_string(open.size()) + " = Number of open boundaries\n" + std::to_string(neta) +
         " = Total number of open boundary nodes\n";
  for (size_t i = 0; i < open.size(); ++i) {
    out += std::to_string(open[i].nodes.size()) + " 0 = Number of nodes for open boundary " + std::to_string(i + 1) + "\n";
    for (uint32_t v : open[i].nodes) append_line(out, int64_t(v) + 1);
  }
  out += std::to_string(land.size()) + " = Number of land boundaries\n" + std::to_string(nvel) +
         " = Total number of land boundary nodes\n";
  for (size_t i = 0; i < land.size(); ++i) {
    out += std::to_string(land[i].nodes.size()) + " " + std::to_string(land[i].type) + " = Number of nodes for land boundary " +
           std::to_string(i + 1) + "\n";
    for (uint32_t v : land[i].nodes) append_line(out, int64_t(v) + 1);
  }
  return write_file_bytes(path, out);
}

Status write_mesh2d(const std::string& path, const TriMesh2& mesh, const Fort14Options& fort14) {
  const std::string format = mesh2d_format(path);
  if (format == "mesh") return write_medit(path, mesh);
  if (format == "msh") return write_gmsh(path, mesh);
  if (format == "vtu") return write_vtu(path, mesh);
  if (format == "fort14") return write_fort14(path, mesh, fort14);
  return Status(Error::UnsupportedFormat, path + ": unknown output format (2D meshes: .mesh .msh .vtu, .14 or fort.14)");
}

Status write_sol2d(const std::string& path, const TriMesh2& m) {
  const size_t nv = m.num_vertices();
  if (m.metric.size() != 3 * nv) return Status(Error::InvalidArgument, "the mesh has no per-vertex metric");
  bool iso = true;
  for (size_t v = 0; v < nv && iso; ++v) {
    const double* x = &m.metric[3 * v];
    iso = std::fabs(x[1]) <= 1e-6 * (x[0] + x[2]) && std::fabs(x[0] - x[2]) <= 1e-6 * (x[0] + x[2]);
  }
  std::string out = "MeshVersionFormatted 2\n\nDimension 2\n\nSolAtVertices\n";
  append_int(out, int64_t(nv));
  out += iso ? "\n1 1\n\n" : "\n1 3\n\n";
  for (size_t v = 0; v < nv; ++v) {
    const double* x = &m.metric[3 * v];
    if (iso) append_line(out, 1.0 / std::sqrt(0.5 * (x[0] + x[2])));
    else append_line(out, x[0], x[1], x[2]);
  }
  out += "\nEnd\n";
  return write_file_bytes(path, out);
}

}  // namespace anitet::mesh2d
