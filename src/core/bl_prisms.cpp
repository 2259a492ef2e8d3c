#include "core/bl_prisms.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <string>

#include "predicates/predicates.hpp"

namespace anitet {

namespace {

constexpr uint32_t kNoVertex = ~uint32_t{0};
using Tri = std::array<uint32_t, 3>;
using Quad = std::array<uint32_t, 4>;

Tri sorted3(uint32_t a, uint32_t b, uint32_t c) {
  Tri s{a, b, c};
  std::sort(s.begin(), s.end());
  return s;
}

// Each vertex's column: the vertex it is pushed from, followed down to one pushed from nothing
// (its root), and the number of steps (its depth).
struct Columns {
  std::vector<uint32_t> root, depth;
};

Result<Columns> follow_columns(const std::vector<uint32_t>& origin) {
  const size_t nv = origin.size();
  Columns c;
  c.root.assign(nv, kNoVertex);
  c.depth.assign(nv, 0);
  std::vector<uint32_t> chain;
  for (size_t v = 0; v < nv; ++v) {
    chain.clear();
    uint32_t u = static_cast<uint32_t>(v);
    while (c.root[u] == kNoVertex && origin[u] != kNoVertex) {
      chain.push_back(u);
      u = origin[u];
      if (u >= nv) return Status(Error::BadIndex, "vertex_origin refers to vertex " + std::to_string(u));
      if (chain.size() > nv) return Status(Error::InvalidArgument, "vertex_origin has a cycle");
    }
    if (c.root[u] == kNoVertex) c.root[u] = u;
    for (size_t i = chain.size(); i-- > 0;) {
      const uint32_t w = chain[i];
      c.root[w] = c.root[origin[w]];
      c.depth[w] = c.depth[origin[w]] + 1;
    }
  }
  return c;
}

// A BL tet and the key of the prism it may belong to: its three columns and its lowest depth.
struct TetKey {
  std::array<uint32_t, 3> roots;
  uint32_t depth;
  uint32_t tet;
  bool operator<(const TetKey& o) const {
    return roots != o.roots ? roots < o.roots : depth != o.depth ? depth < o.depth : tet < o.tet;
  }
  bool same_prism(const TetKey& o) const { return roots == o.roots && depth == o.depth; }
};

// The key of tet t when its vertices lie on exactly three columns, two of them one above the
// other on one column.
std::optional<TetKey> key_of(const VolumeMesh& mesh, const Columns& c, const std::vector<uint32_t>& origin, size_t t) {
  const uint32_t* v = &mesh.tet[4 * t];
  TetKey k{{}, kNoVertex, static_cast<uint32_t>(t)};
  std::array<uint32_t, 4> roots{};
  for (int i = 0; i < 4; ++i) {
    roots[size_t(i)] = c.root[v[i]];
    k.depth = std::min(k.depth, c.depth[v[i]]);
  }
  int pairs = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if (roots[size_t(i)] == roots[size_t(j)]) {
        if (origin[v[i]] != v[j] && origin[v[j]] != v[i]) return std::nullopt;
        ++pairs;
      }
  if (pairs != 1) return std::nullopt;
  std::sort(roots.begin(), roots.end());
  const auto last = std::unique(roots.begin(), roots.end());
  std::copy(roots.begin(), last, k.roots.begin());
  return k;
}

// The prism (VolumeMesh::prism's order) that the three tets form exactly, if they do.
std::optional<std::array<uint32_t, 6>> prism_of(const VolumeMesh& mesh, const std::vector<uint32_t>& origin,
                                                const Columns& c, const std::array<uint32_t, 3>& roots,
                                                const uint32_t tets[3]) {
  // Two vertices per column, the upper pushed from the lower.
  uint32_t lo[3], hi[3];
  for (int i = 0; i < 3; ++i) lo[i] = hi[i] = kNoVertex;
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 4; ++i) {
      const uint32_t v = mesh.tet[4 * size_t(tets[k]) + size_t(i)];
      const int col = int(std::find(roots.begin(), roots.end(), c.root[v]) - roots.begin());
      if (lo[col] == v || hi[col] == v) continue;
      if (lo[col] == kNoVertex) {
        lo[col] = v;
      } else if (hi[col] == kNoVertex) {
        hi[col] = v;
      } else {
        return std::nullopt;
      }
    }
  for (int i = 0; i < 3; ++i) {
    if (hi[i] == kNoVertex) return std::nullopt;
    if (origin[lo[i]] == hi[i]) std::swap(lo[i], hi[i]);
    if (origin[hi[i]] != lo[i]) return std::nullopt;
  }
  // The twelve faces: two shared pairs, then the caps once each and each side twice.
  struct Face {
    Tri key;
    Tri outward;
  };
  std::array<Face, 12> faces;
  for (int k = 0; k < 3; ++k)
    for (int f = 0; f < 4; ++f) {
      const uint32_t* v = &mesh.tet[4 * size_t(tets[k])];
      const Tri out{v[kOutwardFace[f][0]], v[kOutwardFace[f][1]], v[kOutwardFace[f][2]]};
      faces[size_t(4 * k + f)] = {sorted3(out[0], out[1], out[2]), out};
    }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.key < b.key; });
  const Tri bottom = sorted3(lo[0], lo[1], lo[2]), top = sorted3(hi[0], hi[1], hi[2]);
  std::optional<Tri> bottom_out;
  int shared = 0, caps = 0, sides[3] = {0, 0, 0};
  uint32_t missing[3][2] = {};
  for (size_t i = 0; i < faces.size(); ++i) {
    if (i + 1 < faces.size() && faces[i].key == faces[i + 1].key) {
      if (i + 2 < faces.size() && faces[i + 2].key == faces[i].key) return std::nullopt;
      ++shared;
      ++i;
      continue;
    }
    const Tri& key = faces[i].key;
    if (key == bottom || key == top) {
      if (key == bottom) bottom_out = faces[i].outward;
      ++caps;
      continue;
    }
    // A side face: both vertices of one column and one of another; side s is opposite column s.
    int count[3] = {0, 0, 0};
    for (uint32_t v : key) ++count[std::find(roots.begin(), roots.end(), c.root[v]) - roots.begin()];
    const int s = count[0] == 0 ? 0 : count[1] == 0 ? 1 : count[2] == 0 ? 2 : -1;
    if (s < 0 || sides[s] == 2) return std::nullopt;
    // The quad's vertex this triangle leaves out.
    const int a = (s + 1) % 3, b = (s + 2) % 3;
    uint32_t left_out = kNoVertex;
    for (uint32_t v : {lo[a], hi[a], lo[b], hi[b]})
      if (std::find(key.begin(), key.end(), v) == key.end()) left_out = v;
    missing[s][sides[s]++] = left_out;
  }
  if (shared != 2 || caps != 2 || !bottom_out) return std::nullopt;
  for (int s = 0; s < 3; ++s) {
    // The two triangles split the quad along a diagonal: they leave out opposite corners.
    const int a = (s + 1) % 3, b = (s + 2) % 3;
    const uint32_t m0 = missing[s][0], m1 = missing[s][1];
    const bool opposite = (m0 == lo[a] && m1 == hi[b]) || (m0 == hi[b] && m1 == lo[a]) ||
                          (m0 == hi[a] && m1 == lo[b]) || (m0 == lo[b] && m1 == hi[a]);
    if (sides[s] != 2 || !opposite) return std::nullopt;
  }
  // The bottom's outward order is the prism's 0 2 1 (kPrismFace[3]).
  const Tri& b = *bottom_out;
  std::array<uint32_t, 6> p{b[0], b[2], b[1], 0, 0, 0};
  for (int i = 0; i < 3; ++i) p[size_t(3 + i)] = hi[std::find(lo, lo + 3, p[size_t(i)]) - lo];
  return p;
}

// A cell made of BL tets: a prism (6 vertices, 3 tets, 3 quad sides) or a pyramid (5 vertices,
// 2 tets, its base the one quad).
struct Candidate {
  std::array<uint32_t, 6> v;
  uint32_t tets[3];
  bool pyramid = false;
  bool kept = true;
  int num_tets() const { return pyramid ? 2 : 3; }
  int num_quads() const { return pyramid ? 1 : 3; }
  Quad sorted_quad(int f) const {
    const int* lf = pyramid ? kPyramidFace[0] : kPrismFace[f];
    Quad q{v[size_t(lf[0])], v[size_t(lf[1])], v[size_t(lf[2])], v[size_t(lf[3])]};
    std::sort(q.begin(), q.end());
    return q;
  }
};

// A candidate's quad side, for finding the candidate on its other side.
struct Side {
  Quad q;
  uint32_t cand;
  bool operator<(const Side& o) const { return q < o.q; }
};

// The pyramid (VolumeMesh::pyramid's order) that tets t1 and t2 form exactly (see
// merge_bl_prisms), if they do.
std::optional<std::array<uint32_t, 5>> pyramid_of(const VolumeMesh& mesh, const std::vector<uint32_t>& origin,
                                                  const Columns& c, uint32_t t1, uint32_t t2) {
  // The face they share: t1's vertices that t2 has.
  const uint32_t* v1 = &mesh.tet[4 * size_t(t1)];
  const uint32_t* v2 = &mesh.tet[4 * size_t(t2)];
  Tri shared{};
  size_t ns = 0;
  for (int i = 0; i < 4; ++i)
    if (std::find(v2, v2 + 4, v1[i]) != v2 + 4) {
      if (ns == 3) return std::nullopt;  // the same tet twice
      shared[ns++] = v1[i];
    }
  if (ns != 3) return std::nullopt;
  std::array<uint32_t, 5> u{shared[0], shared[1], shared[2], kNoVertex, kNoVertex};
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i < 4; ++i) {
      const uint32_t w = mesh.tet[4 * size_t(k == 0 ? t1 : t2) + size_t(i)];
      if (std::find(shared.begin(), shared.end(), w) == shared.end()) u[size_t(3 + k)] = w;
    }
  if (u[3] == kNoVertex || u[4] == kNoVertex || u[3] == u[4]) return std::nullopt;
  // Two columns with two vertices, one pushed from the other, and the apex alone on a third.
  uint32_t apex = kNoVertex;
  std::array<uint32_t, 2> lo{kNoVertex, kNoVertex}, hi{kNoVertex, kNoVertex};
  int pairs = 0;
  for (size_t i = 0; i < 5; ++i) {
    size_t same = 5;
    for (size_t j = 0; j < 5; ++j)
      if (j != i && c.root[u[j]] == c.root[u[i]]) {
        if (same != 5) return std::nullopt;  // three on one column
        same = j;
      }
    if (same == 5) {
      if (apex != kNoVertex) return std::nullopt;
      apex = u[i];
    } else if (same > i) {
      if (pairs == 2) return std::nullopt;
      if (origin[u[same]] == u[i]) {
        lo[size_t(pairs)] = u[i], hi[size_t(pairs)] = u[same];
      } else if (origin[u[i]] == u[same]) {
        lo[size_t(pairs)] = u[same], hi[size_t(pairs)] = u[i];
      } else {
        return std::nullopt;
      }
      ++pairs;
    }
  }
  if (pairs != 2 || apex == kNoVertex || std::find(shared.begin(), shared.end(), apex) == shared.end())
    return std::nullopt;
  // The quad's cycle lo0 lo1 hi1 hi0; the shared face's other two vertices are a diagonal.
  const std::array<uint32_t, 4> cyc{lo[0], lo[1], hi[1], hi[0]};
  auto in_shared = [&](uint32_t w) { return std::find(shared.begin(), shared.end(), w) != shared.end(); };
  if (!((in_shared(cyc[0]) && in_shared(cyc[2])) || (in_shared(cyc[1]) && in_shared(cyc[3])))) return std::nullopt;
  // The base's orientation from t1's face without the apex, which points out of the pyramid.
  Tri out{};
  for (const auto& lf : kOutwardFace) {
    const uint32_t* v = &mesh.tet[4 * size_t(t1)];
    out = {v[lf[0]], v[lf[1]], v[lf[2]]};
    if (std::find(out.begin(), out.end(), apex) == out.end()) break;
  }
  Tri r{};  // the quad's corners in out, in the cycle's order
  size_t n = 0;
  for (uint32_t w : cyc)
    if (std::find(out.begin(), out.end(), w) != out.end() && n < 3) r[n++] = w;
  if (n != 3) return std::nullopt;
  const bool along = out == r || out == Tri{r[1], r[2], r[0]} || out == Tri{r[2], r[0], r[1]};
  // The base runs the other way round from the outward cycle (kPyramidFace[0] is 0 3 2 1).
  std::array<uint32_t, 5> p{};
  for (size_t i = 0; i < 4; ++i) p[i] = along ? cyc[(4 - i) % 4] : cyc[i];
  p[4] = apex;
  for (size_t i = 0; i < 4; ++i)
    if (predicates::orient3d_certified(mesh.point(p[i]), mesh.point(p[(i + 1) % 4]), mesh.point(p[(i + 2) % 4]),
                                       mesh.point(apex)) <= 0)
      return std::nullopt;
  return p;
}

// A tet's face and an id: the tet, or the candidate the tet is in (kNoVertex: none).
struct FaceOf {
  Tri key;
  uint32_t id;
  bool operator<(const FaceOf& o) const { return key != o.key ? key < o.key : id < o.id; }
};

// Whether a triangle of quad q (any three of its corners) is a face of a tet that is not in
// candidate `own` (faces sorted): a cell across the quad that has it as triangles.
bool quad_on_other_faces(const Quad& q, uint32_t own, const std::vector<FaceOf>& faces) {
  for (int skip = 0; skip < 4; ++skip) {
    Tri t{};
    for (int i = 0, n = 0; i < 4; ++i)
      if (i != skip) t[size_t(n++)] = q[size_t(i)];
    for (auto it = std::lower_bound(faces.begin(), faces.end(), FaceOf{t, 0}); it != faces.end() && it->key == t; ++it)
      if (it->id != own) return true;
  }
  return false;
}

// The pyramids (pyramid_of) of two BL tets in no prism candidate that share a face, each tet in
// one at most.
std::vector<Candidate> find_pyramids(const VolumeMesh& mesh, const std::vector<uint32_t>& origin, const Columns& c,
                                     const std::vector<uint8_t>& free_tet) {
  std::vector<FaceOf> faces;  // id: the tet
  for (size_t t = 0; t < mesh.num_tets(); ++t)
    if (free_tet[t])
      for (const auto& lf : kOutwardFace) {
        const uint32_t* v = &mesh.tet[4 * t];
        faces.push_back({sorted3(v[lf[0]], v[lf[1]], v[lf[2]]), uint32_t(t)});
      }
  std::sort(faces.begin(), faces.end());
  std::vector<uint8_t> used(mesh.num_tets(), 0);
  std::vector<Candidate> out;
  for (size_t i = 0; i + 1 < faces.size(); ++i) {
    if (faces[i + 1].key != faces[i].key) continue;
    const uint32_t t1 = faces[i].id, t2 = faces[i + 1].id;
    ++i;
    if (used[t1] || used[t2]) continue;
    if (!mesh.region.empty() && mesh.region[t1] != mesh.region[t2]) continue;
    if (auto p = pyramid_of(mesh, origin, c, t1, t2)) {
      used[t1] = used[t2] = 1;
      Candidate cand{{(*p)[0], (*p)[1], (*p)[2], (*p)[3], (*p)[4], kNoVertex}, {t1, t2, kNoVertex}};
      cand.pyramid = true;
      out.push_back(cand);
    }
  }
  return out;
}

// Keeps as tets the candidates (prisms, pyramids) with a quad on triangles of another cell: first
// those beside a BL cell that is neither (a partial push; without pyramids, the two tets on each
// triangle around a column that stopped in the layer) or beside a pyramid's side triangles, then,
// one after the other, those beside a candidate kept as tets (its tets split the quad they share),
// which spreads through the layer. Every quad left is then another candidate's or on the boundary.
void drop_unmatched_sides(const VolumeMesh& mesh, std::vector<Candidate>& cands, PrismMergeStats& stats) {
  const size_t nt = mesh.num_tets();
  std::vector<uint32_t> cand_of(nt, kNoVertex);
  std::vector<Side> sides;
  for (size_t i = 0; i < cands.size(); ++i) {
    for (int k = 0; k < cands[i].num_tets(); ++k) cand_of[cands[i].tets[k]] = uint32_t(i);
    for (int f = 0; f < cands[i].num_quads(); ++f) sides.push_back({cands[i].sorted_quad(f), uint32_t(i)});
  }
  std::sort(sides.begin(), sides.end());
  // Every tet's faces: a quad side of one candidate only is on the boundary unless a half of it
  // is a face of another cell's tet (a tet kept, or a pyramid's side triangle).
  std::vector<FaceOf> tet_faces;
  tet_faces.reserve(4 * nt);
  for (size_t t = 0; t < nt; ++t)
    for (const auto& lf : kOutwardFace) {
      const uint32_t* v = &mesh.tet[4 * t];
      tet_faces.push_back({sorted3(v[lf[0]], v[lf[1]], v[lf[2]]), cand_of[t]});
    }
  std::sort(tet_faces.begin(), tet_faces.end());
  std::vector<uint32_t> dropped;
  for (size_t i = 0; i < sides.size();) {
    size_t j = i + 1;
    while (j < sides.size() && sides[j].q == sides[i].q) ++j;
    Candidate& c = cands[sides[i].cand];
    if (j - i == 1 && c.kept && quad_on_other_faces(sides[i].q, sides[i].cand, tet_faces)) {
      c.kept = false;
      ++stats.beside_other_cells;
      dropped.push_back(sides[i].cand);
    }
    i = j;
  }
  while (!dropped.empty()) {
    const uint32_t d = dropped.back();
    dropped.pop_back();
    for (int f = 0; f < cands[d].num_quads(); ++f) {
      const auto range = std::equal_range(sides.begin(), sides.end(), Side{cands[d].sorted_quad(f), 0});
      for (auto it = range.first; it != range.second; ++it)
        if (cands[it->cand].kept) {
          cands[it->cand].kept = false;
          ++stats.beside_kept;
          dropped.push_back(it->cand);
        }
    }
  }
}

}  // namespace

Result<PrismMergeStats> merge_bl_prisms(VolumeMesh& mesh, const std::vector<uint32_t>& vertex_origin,
                                        int32_t first_bl_region, std::vector<int32_t>* tet_prism,
                                        bool make_pyramids, std::vector<int32_t>* tet_pyramid) {
  const size_t nv = mesh.num_vertices(), nt = mesh.num_tets();
  if (vertex_origin.size() != nv)
    return Status(Error::InvalidArgument, "merge_bl_prisms: vertex_origin needs one entry per vertex");
  if (!mesh.region.empty() && mesh.region.size() != nt)
    return Status(Error::InvalidArgument, "merge_bl_prisms: region needs one entry per tet");
  if (mesh.has_mixed_cells())
    return Status(Error::InvalidArgument, "merge_bl_prisms: the mesh has prisms or pyramids already");
  for (uint32_t v : mesh.tet)
    if (v >= nv) return Status(Error::BadIndex, "merge_bl_prisms: a tet refers to vertex " + std::to_string(v));
  Result<Columns> columns = follow_columns(vertex_origin);
  if (!columns.ok()) return Status(columns.status().code(), "merge_bl_prisms: " + columns.status().message());
  const Columns& c = columns.value();
  auto region = [&](size_t t) { return mesh.region.empty() ? 0 : mesh.region[t]; };

  PrismMergeStats stats;
  std::vector<TetKey> keys;
  for (size_t t = 0; t < nt; ++t) {
    if (region(t) < first_bl_region) continue;
    ++stats.bl_tets;
    if (std::optional<TetKey> k = key_of(mesh, c, vertex_origin, t)) keys.push_back(*k);
  }
  std::sort(keys.begin(), keys.end());
  std::vector<Candidate> cands;
  for (size_t i = 0; i < keys.size();) {
    size_t j = i + 1;
    while (j < keys.size() && keys[j].same_prism(keys[i])) ++j;
    if (j - i == 3) {
      const uint32_t tets[3] = {keys[i].tet, keys[i + 1].tet, keys[i + 2].tet};
      const bool one_region = region(tets[0]) == region(tets[1]) && region(tets[0]) == region(tets[2]);
      if (one_region)
        if (auto p = prism_of(mesh, vertex_origin, c, keys[i].roots, tets)) cands.push_back({*p, {tets[0], tets[1], tets[2]}});
    }
    i = j;
  }
  stats.exact_prisms = cands.size();
  if (make_pyramids) {
    std::vector<uint8_t> free_bl_tet(nt, 0);
    for (size_t t = 0; t < nt; ++t) free_bl_tet[t] = region(t) >= first_bl_region;
    for (const Candidate& cand : cands)
      for (uint32_t t : cand.tets) free_bl_tet[t] = 0;
    const std::vector<Candidate> pyramids = find_pyramids(mesh, vertex_origin, c, free_bl_tet);
    stats.exact_pyramids = pyramids.size();
    cands.insert(cands.end(), pyramids.begin(), pyramids.end());
  }
  drop_unmatched_sides(mesh, cands, stats);

  std::vector<uint8_t> merged(nt, 0);
  if (tet_prism) tet_prism->assign(nt, -1);
  if (tet_pyramid) tet_pyramid->assign(nt, -1);
  for (const Candidate& cand : cands) {
    if (!cand.kept) continue;
    std::vector<int32_t>* tet_cell = cand.pyramid ? tet_pyramid : tet_prism;
    for (int k = 0; k < cand.num_tets(); ++k) {
      merged[cand.tets[k]] = 1;
      if (tet_cell) (*tet_cell)[cand.tets[k]] = int32_t(cand.pyramid ? stats.pyramids : stats.prisms);
    }
    const int32_t label = mesh.region.empty() ? 0 : mesh.region[cand.tets[0]];
    if (cand.pyramid) {
      mesh.pyramid.insert(mesh.pyramid.end(), cand.v.begin(), cand.v.begin() + 5);
      if (!mesh.region.empty()) mesh.pyramid_region.push_back(label);
      ++stats.pyramids;
    } else {
      mesh.prism.insert(mesh.prism.end(), cand.v.begin(), cand.v.end());
      if (!mesh.region.empty()) mesh.prism_region.push_back(label);
      ++stats.prisms;
    }
  }
  size_t out = 0;
  for (size_t t = 0; t < nt; ++t) {
    if (merged[t]) continue;
    std::copy_n(&mesh.tet[4 * t], 4, &mesh.tet[4 * out]);
    if (!mesh.region.empty()) mesh.region[out] = mesh.region[t];
    ++out;
  }
  mesh.tet.resize(4 * out);
  if (!mesh.region.empty()) mesh.region.resize(out);
  stats.kept_tets = stats.bl_tets - 3 * stats.prisms - 2 * stats.pyramids;
  return stats;
}

}  // namespace anitet
