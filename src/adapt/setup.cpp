#include "adapt/setup.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "adapt/surface_geometry.hpp"
#include "predicates/predicates.hpp"

namespace anitet::adapt {

namespace {

struct FaceRec {
  std::array<uint32_t, 3> key;
  uint32_t id;  // 4 t + i, or a triangle index
  bool operator<(const FaceRec& o) const { return key != o.key ? key < o.key : id < o.id; }
};

std::array<uint32_t, 3> sorted3(uint32_t a, uint32_t b, uint32_t c) {
  std::array<uint32_t, 3> k = {a, b, c};
  std::sort(k.begin(), k.end());
  return k;
}

std::string tri_name(const std::array<uint32_t, 3>& k) {
  return "(" + std::to_string(k[0] + 1) + ", " + std::to_string(k[1] + 1) + ", " + std::to_string(k[2] + 1) + ")";
}

}  // namespace

Status build_adapt_mesh(const VolumeMesh& in, AdaptMesh& out) {
  const size_t nv = in.num_vertices(), nt = in.num_tets();
  if (nt == 0) return Status(Error::EmptyInput, "the mesh has no tetrahedra");
  for (size_t k = 0; k < in.tet.size(); ++k)
    if (in.tet[k] >= nv)
      return Status(Error::InvalidArgument, "tet " + std::to_string(k / 4 + 1) + " refers to vertex " +
                                                std::to_string(in.tet[k] + 1) + ", beyond the " + std::to_string(nv) +
                                                " vertices");
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* w = &in.tet[4 * t];
    const int o = predicates::orient3d(in.point(w[0]), in.point(w[1]), in.point(w[2]), in.point(w[3]));
    if (o <= 0)
      return Status(Error::InvalidArgument, "tet " + std::to_string(t + 1) + " is " + (o < 0 ? "inverted" : "flat") +
                                                " (vertices " + std::to_string(w[0] + 1) + " " + std::to_string(w[1] + 1) +
                                                " " + std::to_string(w[2] + 1) + " " + std::to_string(w[3] + 1) +
                                                "): adaptation needs a valid mesh, positively oriented");
  }
  out = AdaptMesh();
  out.xyz = in.xyz;
  out.met.assign(6 * nv, 0.0);
  out.mdet.assign(nv, 0.0);
  out.nrm.assign(3 * nv, 0.0);
  out.nrm2.assign(3 * nv, 0.0);
  out.tng.assign(3 * nv, 0.0);
  out.tag.assign(nv, ptag::kRemoved);  // points of no tet stay removed
  out.ptet.assign(nv, kNone);
  out.hint.assign(nv, kNone);
  out.touched.assign(nv, 0);
  out.tv = in.tet;
  out.adj.assign(4 * nt, kNone);
  out.fref.assign(4 * nt, 0);
  out.bnd.assign(nt, 0);
  out.region = in.region.size() == nt ? in.region : std::vector<int32_t>(nt, 0);
  out.qual.assign(nt, 0.0);
  for (uint32_t t = 0; t < nt; ++t)
    for (int i = 0; i < 4; ++i) {
      const uint32_t v = out.tv[4 * size_t(t) + size_t(i)];
      out.tag[v] = 0;
      out.ptet[v] = t;
    }
  // Adjacency: the faces sorted by vertex set, two equal keys a pair.
  std::vector<FaceRec> faces(4 * nt);
  for (uint32_t t = 0; t < nt; ++t)
    for (int i = 0; i < 4; ++i) {
      const uint32_t* w = &out.tv[4 * size_t(t)];
      faces[4 * size_t(t) + size_t(i)] = {sorted3(w[kFaceVertex[i][0]], w[kFaceVertex[i][1]], w[kFaceVertex[i][2]]),
                                          4 * t + uint32_t(i)};
    }
  std::sort(faces.begin(), faces.end());
  for (size_t k = 0; k < faces.size();) {
    size_t e = k + 1;
    while (e < faces.size() && faces[e].key == faces[k].key) ++e;
    if (e - k > 2)
      return Status(Error::InvalidMesh, "the face " + tri_name(faces[k].key) + " is shared by " +
                                            std::to_string(e - k) + " tets");
    if (e - k == 2) {
      out.adj[faces[k].id] = faces[k + 1].id;
      out.adj[faces[k + 1].id] = faces[k].id;
    }
    k = e;
  }
  // Boundary faces: the input's triangles first (a label each), then the hull and region borders.
  std::vector<FaceRec> tris(in.num_boundary_triangles());
  for (uint32_t k = 0; k < tris.size(); ++k) {
    const uint32_t* w = &in.bnd_tri[3 * size_t(k)];
    for (int j = 0; j < 3; ++j)
      if (w[j] >= nv)
        return Status(Error::InvalidArgument, "boundary triangle " + std::to_string(k + 1) + " refers to vertex " +
                                                  std::to_string(w[j] + 1) + ", beyond the " + std::to_string(nv) +
                                                  " vertices");
    tris[k] = {sorted3(w[0], w[1], w[2]), k};
  }
  std::sort(tris.begin(), tris.end());
  std::vector<char> tri_used(tris.size(), 0);
  for (size_t k = 0; k < faces.size(); ++k) {
    const uint32_t hf = faces[k].id, t = hf >> 2;
    const int i = int(hf & 3u);
    auto it = std::lower_bound(tris.begin(), tris.end(), FaceRec{faces[k].key, 0});
    const bool listed = it != tris.end() && it->key == faces[k].key;
    const uint32_t a = out.adj[hf];
    const bool hull = a == kNone;
    const bool border = !hull && out.region[t] != out.region[a >> 2];
    if (!listed && !hull && !border) continue;
    out.bnd[t] |= uint8_t(1u << i);
    out.fref[hf] = listed ? (in.bnd_patch.empty() ? 0 : in.bnd_patch[it->id]) : (hull ? 0 : kUnlisted);
    if (listed) tri_used[size_t(it - tris.begin())] = 1;
  }
  for (size_t k = 0; k < tris.size(); ++k)
    if (!tri_used[k] && !(k > 0 && tris[k].key == tris[k - 1].key))
      return Status(Error::InvalidArgument, "boundary triangle " + std::to_string(tris[k].id + 1) + " " +
                                                tri_name(tris[k].key) + " is no face of the tets");
  out.sync_marks();
  return Status::success();
}

namespace {

struct BFace {
  uint32_t v[3];
  int32_t label;
  double n[3];
};

// The boundary faces once each (a hull face oriented out of the mesh).
std::vector<BFace> boundary_faces(const AdaptMesh& mesh) {
  std::vector<BFace> out;
  for (uint32_t t = 0; t < mesh.num_slots(); ++t) {
    if (mesh.dead(t) || !mesh.bnd[t]) continue;
    for (int i = 0; i < 4; ++i) {
      if (!mesh.is_bnd_face(t, i)) continue;
      const uint32_t a = mesh.adj[4 * size_t(t) + i];
      if (a != kNone && adj_tet(a) < t) continue;
      const uint32_t* w = mesh.verts(t);
      BFace f;
      // kFaceVertex turns the normal into the tet: reversed, out of it.
      f.v[0] = w[kFaceVertex[i][0]], f.v[1] = w[kFaceVertex[i][2]], f.v[2] = w[kFaceVertex[i][1]];
      f.label = mesh.fref[4 * size_t(t) + i];
      geom::triangle_normal(mesh.p(f.v[0]), mesh.p(f.v[1]), mesh.p(f.v[2]), f.n);
      out.push_back(f);
    }
  }
  return out;
}

struct EdgeUse {
  uint64_t key;
  uint32_t face;
  bool forward;  // the face runs the edge from its smaller vertex to its larger
  bool operator<(const EdgeUse& o) const { return key != o.key ? key < o.key : face < o.face; }
};

int find_root(std::vector<uint32_t>& parent, uint32_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return int(x);
}

// Marks the ridges; returns their count.
size_t find_ridges(AdaptMesh& mesh, const std::vector<BFace>& faces, double cos_ridge, std::vector<int>& degree) {
  std::vector<EdgeUse> uses;
  uses.reserve(3 * faces.size());
  for (uint32_t f = 0; f < faces.size(); ++f)
    for (int j = 0; j < 3; ++j) {
      const uint32_t a = faces[f].v[j], b = faces[f].v[(j + 1) % 3];
      uses.push_back({edge_key(a, b), f, a < b});
    }
  std::sort(uses.begin(), uses.end());
  size_t ridges = 0;
  for (size_t k = 0; k < uses.size();) {
    size_t e = k + 1;
    while (e < uses.size() && uses[e].key == uses[k].key) ++e;
    bool ridge = e - k != 2;
    if (!ridge) {
      const BFace &f1 = faces[uses[k].face], &f2 = faces[uses[k + 1].face];
      // Consistently oriented faces run their common edge in opposite directions.
      const double s = uses[k].forward != uses[k + 1].forward ? 1.0 : -1.0;
      ridge = f1.label != f2.label || s * geom::dot(f1.n, f2.n) < cos_ridge;
    }
    if (ridge) {
      const auto a = uint32_t(uses[k].key >> 32), b = uint32_t(uses[k].key & 0xffffffffu);
      mesh.set_ridge(a, b, true);
      ++degree[a], ++degree[b];
      ++ridges;
    }
    k = e;
  }
  return ridges;
}

// The angle-weighted mean normal of `fs` (faces at v), their signs made to agree with the first.
void mean_normal(const AdaptMesh& mesh, const std::vector<BFace>& faces, uint32_t v, const std::vector<uint32_t>& fs,
                 double n[3]) {
  n[0] = n[1] = n[2] = 0.0;
  const double* ref = faces[fs[0]].n;
  for (uint32_t f : fs) {
    const BFace& face = faces[f];
    int j = face.v[0] == v ? 0 : face.v[1] == v ? 1 : 2;
    double e1[3], e2[3];
    geom::sub(mesh.p(face.v[(j + 1) % 3]), mesh.p(v), e1);
    geom::sub(mesh.p(face.v[(j + 2) % 3]), mesh.p(v), e2);
    const double c = geom::dot(e1, e2) / (geom::norm(e1) * geom::norm(e2));
    const double angle = std::acos(std::max(-1.0, std::min(1.0, c)));
    const double s = geom::dot(face.n, ref) < 0 ? -angle : angle;
    for (int k = 0; k < 3; ++k) n[k] += s * face.n[k];
  }
  if (!geom::normalize(n)) n[0] = ref[0], n[1] = ref[1], n[2] = ref[2];
}

// Solves the 5x5 system a x = b (a symmetric positive definite, row-major) by Cholesky; false
// when it is singular to rounding.
bool solve5(double a[25], double b[5], double x[5]) {
  double l[25] = {};
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j <= i; ++j) {
      double sum = a[5 * i + j];
      for (int k = 0; k < j; ++k) sum -= l[5 * i + k] * l[5 * j + k];
      if (i == j) {
        if (!(sum > 1e-12 * std::max(1.0, a[0] + a[6] + a[12]))) return false;
        l[5 * i + i] = std::sqrt(sum);
      } else {
        l[5 * i + j] = sum / l[5 * j + j];
      }
    }
  double y[5];
  for (int i = 0; i < 5; ++i) {
    double sum = b[i];
    for (int k = 0; k < i; ++k) sum -= l[5 * i + k] * y[k];
    y[i] = sum / l[5 * i + i];
  }
  for (int i = 4; i >= 0; --i) {
    double sum = y[i];
    for (int k = i + 1; k < 5; ++k) sum -= l[5 * k + i] * x[k];
    x[i] = sum / l[5 * i + i];
  }
  return true;
}

// The normal of the quadratic height field z = a x + b y + c x^2 + d xy + e y^2 fitted (least
// squares) to the points `nb` around v, in the frame of the first estimate n (a degree-2 jet,
// as CGAL's jet fitting): on the icosphere of the curved case its error is 6e-5 rad against the
// angle-weighted mean's 7e-3, and the surface points placed from the normals are that much
// closer to the sphere. Kept only when it is within kJetTurn of n (a fit over too few or too
// curved neighbours is not trusted).
void jet_normal(const AdaptMesh& mesh, uint32_t v, const std::vector<uint32_t>& nb, double n[3]) {
  const double kJetTurn = std::cos(20.0 * M_PI / 180.0);
  if (nb.size() < 5) return;
  double t1[3], t2[3];
  const double ax[3] = {1, 0, 0}, ay[3] = {0, 1, 0};
  geom::cross(n, std::fabs(n[0]) < 0.9 ? ax : ay, t1);
  geom::normalize(t1);
  geom::cross(n, t1, t2);
  double ata[25] = {}, atz[5] = {};
  double scale = 0.0;
  for (uint32_t w : nb) {
    double d[3];
    geom::sub(mesh.p(w), mesh.p(v), d);
    scale = std::max(scale, geom::norm(d));
  }
  if (!(scale > 0.0)) return;
  for (uint32_t w : nb) {
    double d[3];
    geom::sub(mesh.p(w), mesh.p(v), d);
    const double x = geom::dot(d, t1) / scale, y = geom::dot(d, t2) / scale, z = geom::dot(d, n) / scale;
    const double row[5] = {x, y, x * x, x * y, y * y};
    for (int i = 0; i < 5; ++i) {
      atz[i] += row[i] * z;
      for (int j = 0; j < 5; ++j) ata[5 * i + j] += row[i] * row[j];
    }
  }
  double c[5];
  if (!solve5(ata, atz, c)) return;
  double m[3];
  for (int k = 0; k < 3; ++k) m[k] = n[k] - c[0] * t1[k] - c[1] * t2[k];
  if (!geom::normalize(m) || geom::dot(m, n) < kJetTurn) return;
  n[0] = m[0], n[1] = m[1], n[2] = m[2];
}

}  // namespace

SurfaceFeatures analyse_surface(AdaptMesh& mesh, double ridge_angle_deg, bool keep_surface) {
  SurfaceFeatures out;
  const double cos_ridge = std::cos(ridge_angle_deg * M_PI / 180.0);
  const std::vector<BFace> faces = boundary_faces(mesh);
  const size_t np = mesh.num_points();
  std::vector<int> degree(np, 0);
  out.ridge_edges = find_ridges(mesh, faces, cos_ridge, degree);
  // Faces per point (CSR).
  std::vector<uint32_t> start(np + 1, 0), list(3 * faces.size());
  for (const BFace& f : faces)
    for (uint32_t v : f.v) ++start[v + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (uint32_t f = 0; f < faces.size(); ++f)
      for (uint32_t v : faces[f].v) list[fill[v]++] = f;
  }
  std::vector<uint32_t> parent, sector_faces;
  for (uint32_t v = 0; v < np; ++v) {
    if (start[v + 1] == start[v]) continue;
    ++out.boundary_points;
    mesh.tag[v] |= ptag::kBoundary;
    if (keep_surface) mesh.tag[v] |= ptag::kRequired;
    // Sectors: the faces at v joined across their non-ridge edges through v.
    const uint32_t n = start[v + 1] - start[v];
    parent.resize(n);
    std::iota(parent.begin(), parent.end(), 0u);
    for (uint32_t x = 0; x < n; ++x)
      for (uint32_t y = x + 1; y < n; ++y) {
        const BFace &fx = faces[list[start[v] + x]], &fy = faces[list[start[v] + y]];
        for (uint32_t w : fx.v) {
          if (w == v || mesh.is_ridge(v, w)) continue;
          if (fy.v[0] == w || fy.v[1] == w || fy.v[2] == w)
            parent[size_t(find_root(parent, x))] = uint32_t(find_root(parent, y));
        }
      }
    std::vector<int> roots;
    for (uint32_t x = 0; x < n; ++x) {
      const int r = find_root(parent, x);
      if (std::find(roots.begin(), roots.end(), r) == roots.end()) roots.push_back(r);
    }
    const int deg = degree[v];
    bool corner = (deg != 0 && deg != 2) || (deg == 0 && roots.size() != 1) || (deg == 2 && roots.size() > 2);
    uint32_t ends[2] = {kNone, kNone};
    if (deg == 2 && !corner) {
      // The ridge's two other ends: among the face vertices joined to v by a ridge.
      int found = 0;
      for (uint32_t k = start[v]; k < start[v + 1] && found < 2; ++k)
        for (uint32_t w : faces[list[k]].v)
          if (w != v && w != ends[0] && found < 2 && mesh.is_ridge(v, w)) ends[found++] = w;
      double d1[3], d2[3];
      geom::sub(mesh.p(v), mesh.p(ends[0]), d1);
      geom::sub(mesh.p(ends[1]), mesh.p(v), d2);
      geom::normalize(d1);
      geom::normalize(d2);
      corner = found != 2 || geom::dot(d1, d2) < cos_ridge;
      if (!corner) {
        double* t = &mesh.tng[3 * size_t(v)];
        for (int k = 0; k < 3; ++k) t[k] = d1[k] + d2[k];
        if (!geom::normalize(t)) corner = true;
      }
    }
    if (corner) {
      mesh.tag[v] |= ptag::kCorner;
      ++out.corners;
      continue;
    }
    for (size_t s = 0; s < roots.size(); ++s) {
      sector_faces.clear();
      for (uint32_t x = 0; x < n; ++x)
        if (find_root(parent, x) == roots[s]) sector_faces.push_back(list[start[v] + x]);
      mean_normal(mesh, faces, v, sector_faces, s == 0 ? &mesh.nrm[3 * size_t(v)] : &mesh.nrm2[3 * size_t(v)]);
    }
    if (deg == 0) {
      // A smooth point: the jet normal over the points of its faces (and, when fewer than 6,
      // those of its smooth neighbours' faces: never across a ridge, where the fit would bend a
      // flat face's normal towards the next face's).
      std::vector<uint32_t> nb;
      for (uint32_t k = start[v]; k < start[v + 1]; ++k)
        for (uint32_t w : faces[list[k]].v)
          if (w != v && std::find(nb.begin(), nb.end(), w) == nb.end()) nb.push_back(w);
      if (nb.size() < 6) {
        const size_t ring1 = nb.size();
        for (size_t i = 0; i < ring1; ++i)
          if (degree[nb[i]] == 0)
            for (uint32_t k = start[nb[i]]; k < start[nb[i] + 1]; ++k)
            for (uint32_t w : faces[list[k]].v)
              if (w != v && std::find(nb.begin(), nb.end(), w) == nb.end()) nb.push_back(w);
      }
      jet_normal(mesh, v, nb, &mesh.nrm[3 * size_t(v)]);
    }
    if (deg == 2) {
      mesh.tag[v] |= ptag::kRidge;
      if (roots.size() == 1)  // a border between two labels on a smooth surface
        for (int k = 0; k < 3; ++k) mesh.nrm2[3 * size_t(v) + size_t(k)] = mesh.nrm[3 * size_t(v) + size_t(k)];
    }
  }
  return out;
}

VolumeMesh export_mesh(const AdaptMesh& mesh) {
  VolumeMesh out;
  std::vector<uint32_t> id(mesh.num_points(), kNone);
  uint32_t next = 0;
  out.tet.reserve(4 * mesh.num_tets());
  out.region.reserve(mesh.num_tets());
  for (uint32_t t = 0; t < mesh.num_slots(); ++t) {
    if (mesh.dead(t)) continue;
    for (int i = 0; i < 4; ++i) {
      const uint32_t v = mesh.verts(t)[i];
      if (id[v] == kNone) id[v] = next++;
      out.tet.push_back(id[v]);
    }
    out.region.push_back(mesh.region[t]);
  }
  out.xyz.resize(3 * size_t(next));
  out.vertex_metric.resize(6 * size_t(next));
  for (uint32_t v = 0; v < mesh.num_points(); ++v) {
    if (id[v] == kNone) continue;
    for (int k = 0; k < 3; ++k) out.xyz[3 * size_t(id[v]) + size_t(k)] = mesh.xyz[3 * size_t(v) + size_t(k)];
    for (int k = 0; k < 6; ++k) out.vertex_metric[6 * size_t(id[v]) + size_t(k)] = mesh.met[6 * size_t(v) + size_t(k)];
  }
  for (uint32_t t = 0; t < mesh.num_slots(); ++t) {
    if (mesh.dead(t) || !mesh.bnd[t]) continue;
    for (int i = 0; i < 4; ++i) {
      if (!mesh.is_bnd_face(t, i) || mesh.fref[4 * size_t(t) + i] == kUnlisted) continue;
      const uint32_t a = mesh.adj[4 * size_t(t) + i];
      if (a != kNone && adj_tet(a) < t) continue;
      const uint32_t* w = mesh.verts(t);
      out.bnd_tri.push_back(id[w[kFaceVertex[i][0]]]);
      out.bnd_tri.push_back(id[w[kFaceVertex[i][2]]]);
      out.bnd_tri.push_back(id[w[kFaceVertex[i][1]]]);
      out.bnd_patch.push_back(mesh.fref[4 * size_t(t) + i]);
    }
  }
  return out;
}

}  // namespace anitet::adapt
