#include "pipeline/bl_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace anitet {

namespace {

double distance(const double* p, const double* q) {
  return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

// The normal (p1 - p0) x (p2 - p0) of the triangle p0 p1 p2 (not unit).
void triangle_normal(const double* p0, const double* p1, const double* p2, double n[3]) {
  const double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
  n[0] = e1[1] * e2[2] - e1[2] * e2[1];
  n[1] = e1[2] * e2[0] - e1[0] * e2[2];
  n[2] = e1[0] * e2[1] - e1[1] * e2[0];
}

// The distance from q to the plane of the triangle p (0 for a degenerate one).
double height_over(const double* const p[3], const double* q) {
  double n[3];
  triangle_normal(p[0], p[1], p[2], n);
  const double w[3] = {q[0] - p[0][0], q[1] - p[0][1], q[2] - p[0][2]};
  const double ln = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  return ln > 0.0 ? std::abs(n[0] * w[0] + n[1] * w[1] + n[2] * w[2]) / ln : 0.0;
}

double mean_edge(const TetMesh& mesh, uint32_t t) {
  double sum = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) sum += distance(mesh.point(mesh.vertex(t, i)), mesh.point(mesh.vertex(t, j)));
  return sum / 6.0;
}

// The transition figures of BoundaryLayerReport from the interior/BL ratios of the faces between them.
void summarize_transition(std::vector<double>& ratios, double edge_ratio_sum, BoundaryLayerReport& r) {
  r.transition_faces = ratios.size();
  r.transition_within_1_5 = 0;
  r.transition_ratio_mean = r.transition_ratio_median = r.transition_ratio_p90 = r.transition_edge_ratio_mean = 0.0;
  if (ratios.empty()) return;
  double sum = 0.0;
  for (double x : ratios) {
    sum += x;
    r.transition_within_1_5 += x >= 1.0 / 1.5 && x <= 1.5;
  }
  r.transition_ratio_mean = sum / double(ratios.size());
  r.transition_edge_ratio_mean = edge_ratio_sum / double(ratios.size());
  std::sort(ratios.begin(), ratios.end());
  r.transition_ratio_median = ratios[ratios.size() / 2];
  r.transition_ratio_p90 = ratios[std::min(ratios.size() - 1, ratios.size() * 9 / 10)];
}

}  // namespace

void measure_boundary_layer(const SurfaceMesh& surface, const BoundaryLayerOptions& bl, int layers,
                            const std::vector<uint32_t>& vertex_origin, const std::vector<double>& t1_xyz,
                            const TetMesh& mesh, int32_t first_bl_region, BoundaryLayerReport& r) {
  r.layers = layers;
  r.column_xyz.clear();
  r.column_layers.clear();
  r.column_first.clear();
  r.column_total.clear();
  r.column_normal_share.clear();
  std::vector<uint32_t> top(surface.num_vertices(), TetMesh::kNone);  // a wall vertex's column top
  std::vector<size_t> column(surface.num_vertices(), 0);              // its index in the columns
  r.columns_reaching.assign(size_t(std::max(layers, 0)) + 1, 0);
  const size_t nv = vertex_origin.size();
  std::vector<std::vector<uint32_t>> children(nv);
  for (uint32_t v = 0; v < nv; ++v)
    if (vertex_origin[v] != TetMesh::kNone && vertex_origin[v] < nv) children[vertex_origin[v]].push_back(v);
  std::vector<uint8_t> in_bl_tet(nv, 0);
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t)
    if (!mesh.is_deleted(t) && !mesh.is_ghost(t) && mesh.tet_region[t] >= first_bl_region)
      for (int i = 0; i < 4; ++i)
        if (mesh.vertex(t, i) < nv) in_bl_tet[mesh.vertex(t, i)] = 1;
  std::vector<uint8_t> wall(surface.num_vertices(), 0);
  for (size_t t = 0; t < surface.num_triangles(); ++t)
    if (std::find(bl.wall_patches.begin(), bl.wall_patches.end(), surface.patch[t]) != bl.wall_patches.end())
      for (int k = 0; k < 3; ++k) wall[surface.tri[3 * t + k]] = 1;
  double first_sum = 0.0, growth_sum = 0.0;
  r.first_height_min = HUGE_VAL;
  const size_t n = size_t(std::max(layers, 0));
  r.layer_height_min.assign(n, HUGE_VAL);
  r.layer_height_mean.assign(n, 0.0);
  r.layer_height_max.assign(n, 0.0);
  std::vector<size_t> reaching(n, 0);
  for (uint32_t v = 0; v < surface.num_vertices(); ++v) {
    if (!wall[v]) continue;
    ++r.wall_vertices;
    uint32_t at = v;
    double worst = 0.0, first = 0.0, last = 0.0, total = 0.0;
    int reached = 0;
    for (int i = 0; i < layers; ++i) {
      if (at >= nv || children[at].empty() || !in_bl_tet[children[at].back()]) break;
      ++reached;
      const uint32_t next = children[at].back();
      const double h = distance(mesh.point(at), mesh.point(next));
      if (i == 0) first = h;
      total += h;
      if (i > 0 && h > 0.0 && last > 0.0) r.max_neighbour_growth = std::max({r.max_neighbour_growth, h / last, last / h});
      last = h;
      r.layer_height_min[size_t(i)] = std::min(r.layer_height_min[size_t(i)], h);
      r.layer_height_max[size_t(i)] = std::max(r.layer_height_max[size_t(i)], h);
      r.layer_height_mean[size_t(i)] += h;
      ++reaching[size_t(i)];
      worst = std::max(worst, std::abs(h / (bl.first_height * std::pow(bl.growth, i)) - 1.0));
      at = next;
    }
    ++r.columns_reaching[size_t(reached)];
    r.column_xyz.insert(r.column_xyz.end(), mesh.point(v), mesh.point(v) + 3);
    r.column_layers.push_back(reached);
    r.column_first.push_back(first);
    r.column_total.push_back(total);
    top[v] = at;
    column[v] = r.column_layers.size() - 1;
    if (reached < layers || layers == 0) continue;
    ++r.full_columns;
    first_sum += first;
    r.first_height_min = std::min(r.first_height_min, first);
    r.first_height_max = std::max(r.first_height_max, first);
    growth_sum += layers > 1 && first > 0.0 ? std::pow(last / first, 1.0 / (layers - 1)) : 1.0;
    if (worst <= 0.1) {
      ++r.nominal_columns;
      r.max_height_error = std::max(r.max_height_error, worst);
    }
  }
  // The normal shares: each wall triangle's fluid-side normal (the triangles face into the body)
  // against the columns of its corners.
  r.column_normal_share.assign(r.column_layers.size(), 1.0);
  for (size_t t = 0; t < surface.num_triangles(); ++t) {
    const uint32_t* c = &surface.tri[3 * t];
    if (std::find(bl.wall_patches.begin(), bl.wall_patches.end(), surface.patch[t]) == bl.wall_patches.end()) continue;
    double nrm[3];
    triangle_normal(surface.point(c[0]), surface.point(c[2]), surface.point(c[1]), nrm);  // reversed: into the fluid
    const double ln = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = c[k];
      if (top[v] == TetMesh::kNone || top[v] == v || !(ln > 0.0)) continue;
      const double* p = mesh.point(v);
      const double* q = mesh.point(top[v]);
      const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
      const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      if (!(lu > 0.0)) continue;
      double& share = r.column_normal_share[column[v]];
      share = std::min(share, (u[0] * nrm[0] + u[1] * nrm[1] + u[2] * nrm[2]) / (lu * ln));
    }
  }
  for (size_t i = 0; i < n; ++i) {
    r.layer_height_mean[i] = reaching[i] ? r.layer_height_mean[i] / double(reaching[i]) : 0.0;
    if (!reaching[i]) r.layer_height_min[i] = 0.0;
  }
  if (r.full_columns) {
    r.first_height_mean = first_sum / double(r.full_columns);
    r.growth_mean = growth_sum / double(r.full_columns);
  } else {
    r.first_height_min = 0.0;
  }
  for (uint32_t v = 0; v < nv && 3 * size_t(v) + 2 < t1_xyz.size(); ++v)
    if (mesh.vflags[v] & vflag::kBoundaryLayer)
      r.max_displacement = std::max(r.max_displacement, distance(mesh.point(v), &t1_xyz[3 * size_t(v)]));
}

void measure_boundary_layer_cells(const TetMesh& mesh, int32_t first_bl_region, BoundaryLayerReport& r) {
  const double kPi = 3.14159265358979323846;
  auto centroid = [&](uint32_t t, double c[3]) {
    for (int k = 0; k < 3; ++k) c[k] = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) c[k] += 0.25 * mesh.point(mesh.vertex(t, i))[k];
  };
  auto bl = [&](uint32_t t) { return !mesh.is_deleted(t) && !mesh.is_ghost(t) && mesh.tet_region[t] >= first_bl_region; };
  double angle_sum = 0.0, edge_ratio_sum = 0.0;
  std::vector<double> transition;
  r.dual_faces = 0;
  r.non_orthogonality_max = r.skewness_max = 0.0;
  r.non_orthogonal_faces = r.skew_faces = 0;
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t) {
    if (!bl(t)) continue;
    for (int f = 0; f < 4; ++f) {
      if (mesh.tet_adj[4 * size_t(t) + f] == TetMesh::kNoNeighbour) continue;
      const uint32_t u = mesh.neighbour(t, f);
      if (mesh.is_deleted(u) || mesh.is_ghost(u) || (bl(u) && u < t)) continue;  // each face once
      const double* p[3] = {mesh.point(mesh.vertex(t, kFacetVertex[f][0])), mesh.point(mesh.vertex(t, kFacetVertex[f][1])),
                            mesh.point(mesh.vertex(t, kFacetVertex[f][2]))};
      double ct[3], cu[3], fc[3], d[3], e1[3], e2[3], s[3];
      centroid(t, ct);
      centroid(u, cu);
      for (int k = 0; k < 3; ++k) {
        fc[k] = (p[0][k] + p[1][k] + p[2][k]) / 3.0;
        d[k] = cu[k] - ct[k];
        e1[k] = p[1][k] - p[0][k];
        e2[k] = p[2][k] - p[0][k];
      }
      s[0] = e1[1] * e2[2] - e1[2] * e2[1];
      s[1] = e1[2] * e2[0] - e1[0] * e2[2];
      s[2] = e1[0] * e2[1] - e1[1] * e2[0];
      // Oriented out of t: away from its vertex opposite the face.
      const double* opposite = mesh.point(mesh.vertex(t, f));
      if (!bl(u)) {
        const double own = height_over(p, opposite);
        const double across = height_over(p, mesh.point(mesh.vertex(u, mesh.neighbour_facet(t, f))));
        if (own > 0.0) {
          transition.push_back(across / own);
          edge_ratio_sum += mean_edge(mesh, u) / own;
        }
      }
      if (s[0] * (opposite[0] - p[0][0]) + s[1] * (opposite[1] - p[0][1]) + s[2] * (opposite[2] - p[0][2]) > 0.0)
        for (double& x : s) x = -x;
      const double sd = s[0] * d[0] + s[1] * d[1] + s[2] * d[2];
      const double ls = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
      const double ld = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (!(ls > 0.0 && ld > 0.0)) continue;
      // Towards u's centre when the dual edge is sound (below 90 deg).
      const double angle = std::acos(std::clamp(sd / (ls * ld), -1.0, 1.0)) * 180.0 / kPi;
      // Skewness: where the centres' line crosses the face's plane, against the face's centroid.
      const double at = sd != 0.0 ? (s[0] * (fc[0] - ct[0]) + s[1] * (fc[1] - ct[1]) + s[2] * (fc[2] - ct[2])) / sd : 0.0;
      double sv[3], lsv = 0.0;
      for (int k = 0; k < 3; ++k) {
        sv[k] = fc[k] - (ct[k] + at * d[k]);
        lsv += sv[k] * sv[k];
      }
      lsv = std::sqrt(lsv);
      double reach = 0.2 * ld;
      if (lsv > 0.0)
        for (const double* q : p)
          reach = std::max(reach, std::abs((q[0] - fc[0]) * sv[0] + (q[1] - fc[1]) * sv[1] + (q[2] - fc[2]) * sv[2]) / lsv);
      const double skew = lsv / reach;
      ++r.dual_faces;
      angle_sum += angle;
      r.non_orthogonality_max = std::max(r.non_orthogonality_max, angle);
      r.skewness_max = std::max(r.skewness_max, skew);
      r.non_orthogonal_faces += angle > 70.0;
      r.skew_faces += skew > 4.0;
    }
  }
  r.non_orthogonality_mean = r.dual_faces ? angle_sum / double(r.dual_faces) : 0.0;
  summarize_transition(transition, edge_ratio_sum, r);
}

std::string bl_columns_csv(const BoundaryLayerReport& r, const SurfaceMesh& surface, const std::vector<int32_t>& walls) {
  std::vector<std::vector<int32_t>> labels(surface.num_vertices());
  for (size_t t = 0; t < surface.num_triangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      std::vector<int32_t>& l = labels[surface.tri[3 * t + k]];
      if (std::find(l.begin(), l.end(), surface.patch[t]) == l.end()) l.push_back(surface.patch[t]);
    }
  const auto is_wall = [&](int32_t p) { return std::find(walls.begin(), walls.end(), p) != walls.end(); };
  std::string out = "x,y,z,layers,first_height,total_height,normal_share,patches\n";
  char line[160];
  size_t c = 0;
  for (uint32_t v = 0; v < surface.num_vertices() && c < r.column_layers.size(); ++v) {
    std::vector<int32_t>& l = labels[v];
    if (std::none_of(l.begin(), l.end(), is_wall)) continue;
    std::sort(l.begin(), l.end());
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%d,%.9g,%.9g,%.6f,", r.column_xyz[3 * c], r.column_xyz[3 * c + 1],
                  r.column_xyz[3 * c + 2], r.column_layers[c], r.column_first[c], r.column_total[c],
                  r.column_normal_share[c]);
    out += line;
    for (size_t i = 0; i < l.size(); ++i) out += (i ? " " : "") + std::to_string(l[i]);
    out += "\n";
    ++c;
  }
  return out;
}

}  // namespace anitet
