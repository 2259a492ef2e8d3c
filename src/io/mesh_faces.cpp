#include "io/mesh_faces.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <unordered_set>

namespace anitet {

namespace {

struct FaceKey {
  std::array<uint32_t, 3> v;  // sorted vertex ids
  int64_t face;               // 4t+f
};

std::array<uint32_t, 3> sorted3(uint32_t a, uint32_t b, uint32_t c) {
  std::array<uint32_t, 3> s{a, b, c};
  std::sort(s.begin(), s.end());
  return s;
}

}  // namespace

namespace {

std::string one_based_text(const uint32_t* v, int n) {
  std::string s = "(";
  for (int i = 0; i < n; ++i) s += (i ? ", " : "") + std::to_string(uint64_t{v[i]} + 1);
  return s + ")";
}

// Pairs equal keys (sorted by key, then face): across for pairs, an error for three or more.
template <class Key>
Status pair_faces(std::vector<Key>& keys, std::vector<int64_t>& across, const char* what) {
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    return a.v != b.v ? a.v < b.v : a.face < b.face;
  });
  for (size_t i = 0; i < keys.size();) {
    size_t j = i + 1;
    while (j < keys.size() && keys[j].v == keys[i].v) ++j;
    if (j - i > 2) {
      return Status(Error::InvalidMesh, std::string("the ") + what + " " +
                                            one_based_text(keys[i].v.data(), int(keys[i].v.size())) +
                                            " (1-based vertices) is shared by " + std::to_string(j - i) +
                                            (keys[i].v.size() == 3 ? " tets" : " cells"));
    }
    if (j - i == 2) {
      across[size_t(keys[i].face)] = keys[i + 1].face;
      across[size_t(keys[i + 1].face)] = keys[i].face;
    }
    i = j;
  }
  return Status::success();
}

struct QuadKey {
  std::array<uint32_t, 4> v;  // sorted vertex ids
  int64_t face;
};

}  // namespace

Result<MeshFaces> build_mesh_faces(const VolumeMesh& mesh) {
  const size_t nt = mesh.num_tets(), np = mesh.num_prisms(), ny = mesh.num_pyramids();
  const size_t nb = mesh.num_boundary_triangles();
  std::vector<FaceKey> keys;
  keys.reserve(4 * nt + 2 * np + 4 * ny);
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* v = &mesh.tet[4 * t];
    for (int f = 0; f < 4; ++f) {
      const int* lf = kOutwardFace[f];
      keys.push_back({sorted3(v[lf[0]], v[lf[1]], v[lf[2]]), int64_t(4 * t + f)});
    }
  }
  std::vector<QuadKey> quads;
  quads.reserve(3 * np + ny);
  // Prisms, then pyramids: five faces each, a quad or a triangle.
  for (size_t p = 0; p < np + ny; ++p) {
    const bool prism = p < np;
    const uint32_t* v = prism ? &mesh.prism[6 * p] : &mesh.pyramid[5 * (p - np)];
    const int64_t base = int64_t(4 * nt + 5 * p);
    for (int f = 0; f < 5; ++f) {
      const int* lf = prism ? kPrismFace[f] : kPyramidFace[f];
      if ((prism ? kPrismFaceSize[f] : kPyramidFaceSize[f]) == 4) {
        QuadKey q{{v[lf[0]], v[lf[1]], v[lf[2]], v[lf[3]]}, base + f};
        std::sort(q.v.begin(), q.v.end());
        quads.push_back(q);
      } else {
        keys.push_back({sorted3(v[lf[0]], v[lf[1]], v[lf[2]]), base + f});
      }
    }
  }
  MeshFaces out;
  out.across.assign(4 * nt + 5 * (np + ny), MeshFaces::kNone);
  if (Status st = pair_faces(keys, out.across, "face"); !st.ok()) return st;
  if (Status st = pair_faces(quads, out.across, "quad face"); !st.ok()) return st;
  // With prisms or pyramids, a boundary triangle may be half of a quad: its four corner triangles.
  std::vector<FaceKey> halves;
  for (const QuadKey& q : quads)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<uint32_t, 3> t{};
      for (int i = 0, n = 0; i < 4; ++i)
        if (i != skip) t[size_t(n++)] = q.v[size_t(i)];
      halves.push_back({t, q.face});
    }
  std::sort(halves.begin(), halves.end(), [](const FaceKey& a, const FaceKey& b) {
    return a.v != b.v ? a.v < b.v : a.face < b.face;
  });
  out.bnd_face.assign(nb, MeshFaces::kNone);
  out.bnd_internal.assign(nb, false);
  auto find = [](const std::vector<FaceKey>& list, const FaceKey& probe) {
    auto it = std::lower_bound(list.begin(), list.end(), probe, [](const FaceKey& a, const FaceKey& k) {
      return a.v < k.v;
    });
    return it == list.end() || it->v != probe.v ? MeshFaces::kNone : it->face;
  };
  for (size_t b = 0; b < nb; ++b) {
    const uint32_t* v = &mesh.bnd_tri[3 * b];
    const FaceKey probe{sorted3(v[0], v[1], v[2]), -1};
    int64_t face = find(keys, probe);
    if (face == MeshFaces::kNone && !halves.empty()) face = find(halves, probe);
    if (face == MeshFaces::kNone) continue;
    out.bnd_face[b] = face;
    out.bnd_internal[b] = out.across[size_t(face)] != MeshFaces::kNone;
  }
  return out;
}

size_t cell_of_face(const VolumeMesh& mesh, int64_t face) {
  const size_t nt = mesh.num_tets(), f = size_t(face);
  return f < 4 * nt ? f / 4 : nt + (f - 4 * nt) / 5;
}

int face_vertices(const VolumeMesh& mesh, int64_t face, uint32_t out[4]) {
  const size_t nt = mesh.num_tets(), f = size_t(face);
  if (f < 4 * nt) {
    const uint32_t* v = &mesh.tet[4 * (f / 4)];
    for (int k = 0; k < 3; ++k) out[k] = v[kOutwardFace[f % 4][k]];
    return 3;
  }
  const size_t cell = (f - 4 * nt) / 5, lf = (f - 4 * nt) % 5, np = mesh.num_prisms();
  const bool prism = cell < np;
  const uint32_t* v = prism ? &mesh.prism[6 * cell] : &mesh.pyramid[5 * (cell - np)];
  const int n = prism ? kPrismFaceSize[lf] : kPyramidFaceSize[lf];
  for (int k = 0; k < n; ++k) out[k] = v[prism ? kPrismFace[lf][k] : kPyramidFace[lf][k]];
  return n;
}

BoundaryElements boundary_elements(const VolumeMesh& mesh, const MeshFaces& faces, const std::vector<uint32_t>& tris) {
  BoundaryElements out;
  std::unordered_set<int64_t> quads_done;
  for (uint32_t b : tris) {
    const int64_t face = faces.bnd_face[b];
    uint32_t v[4];
    if (face != MeshFaces::kNone && face_vertices(mesh, face, v) == 4) {
      if (!quads_done.insert(face).second) continue;
      out.vertices.insert(out.vertices.end(), v, v + 4);
      out.size.push_back(4);
      continue;
    }
    const std::array<uint32_t, 3> t = outward_triangle(mesh, faces, b);
    out.vertices.insert(out.vertices.end(), t.begin(), t.end());
    out.size.push_back(3);
  }
  return out;
}

std::array<uint32_t, 3> outward_triangle(const VolumeMesh& mesh, const MeshFaces& faces, size_t b) {
  const int64_t face = faces.bnd_face[b];
  if (face == MeshFaces::kNone || faces.bnd_internal[b]) {
    return {mesh.bnd_tri[3 * b], mesh.bnd_tri[3 * b + 1], mesh.bnd_tri[3 * b + 2]};
  }
  uint32_t v[4];
  if (face_vertices(mesh, face, v) == 3) return {v[0], v[1], v[2]};
  // Half of a quad side: its corners in the quad's (outward) cyclic order.
  std::array<uint32_t, 3> t{};
  for (int i = 0, n = 0; i < 4; ++i)
    if (std::find(&mesh.bnd_tri[3 * b], &mesh.bnd_tri[3 * b] + 3, v[i]) != &mesh.bnd_tri[3 * b] + 3) t[size_t(n++)] = v[i];
  return t;
}

Result<std::vector<PatchTriangles>> patch_triangles(const VolumeMesh& mesh, const PatchNames& names,
                                                    const PatchTypes& types) {
  Result<std::vector<NamedPatch>> patches = named_patches(mesh.bnd_patch, names, types);
  if (!patches.ok()) return patches.status();
  std::vector<PatchTriangles> out;
  std::map<int32_t, size_t> index;
  for (NamedPatch& p : patches.value()) {
    index[p.label] = out.size();
    out.push_back({std::move(p), {}});
  }
  for (size_t b = 0; b < mesh.num_boundary_triangles(); ++b) {
    out[index.at(mesh.bnd_patch[b])].tris.push_back(static_cast<uint32_t>(b));
  }
  return out;
}

}  // namespace anitet
