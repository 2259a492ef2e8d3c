#include "io/mesh_faces.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <string>

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

Result<MeshFaces> build_mesh_faces(const VolumeMesh& mesh) {
  const size_t nt = mesh.num_tets(), nb = mesh.num_boundary_triangles();
  std::vector<FaceKey> keys;
  keys.reserve(4 * nt);
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* v = &mesh.tet[4 * t];
    for (int f = 0; f < 4; ++f) {
      const int* lf = kOutwardFace[f];
      keys.push_back({sorted3(v[lf[0]], v[lf[1]], v[lf[2]]), int64_t(4 * t + f)});
    }
  }
  std::sort(keys.begin(), keys.end(), [](const FaceKey& a, const FaceKey& b) {
    return a.v != b.v ? a.v < b.v : a.face < b.face;
  });
  MeshFaces out;
  out.across.assign(4 * nt, MeshFaces::kNone);
  for (size_t i = 0; i < keys.size();) {
    size_t j = i + 1;
    while (j < keys.size() && keys[j].v == keys[i].v) ++j;
    if (j - i > 2) {
      return Status(Error::InvalidMesh, "the face (" + std::to_string(keys[i].v[0] + 1) + ", " +
                                            std::to_string(keys[i].v[1] + 1) + ", " +
                                            std::to_string(keys[i].v[2] + 1) + ") (1-based vertices) is shared by " +
                                            std::to_string(j - i) + " tets");
    }
    if (j - i == 2) {
      out.across[size_t(keys[i].face)] = keys[i + 1].face;
      out.across[size_t(keys[i + 1].face)] = keys[i].face;
    }
    i = j;
  }
  out.bnd_face.assign(nb, MeshFaces::kNone);
  out.bnd_internal.assign(nb, false);
  for (size_t b = 0; b < nb; ++b) {
    const uint32_t* v = &mesh.bnd_tri[3 * b];
    const FaceKey probe{sorted3(v[0], v[1], v[2]), -1};
    auto it = std::lower_bound(keys.begin(), keys.end(), probe, [](const FaceKey& a, const FaceKey& k) {
      return a.v < k.v;
    });
    if (it == keys.end() || it->v != probe.v) continue;
    out.bnd_face[b] = it->face;
    out.bnd_internal[b] = out.across[size_t(it->face)] != MeshFaces::kNone;
  }
  return out;
}

std::array<uint32_t, 3> outward_triangle(const VolumeMesh& mesh, const MeshFaces& faces, size_t b) {
  const int64_t face = faces.bnd_face[b];
  if (face == MeshFaces::kNone || faces.bnd_internal[b]) {
    return {mesh.bnd_tri[3 * b], mesh.bnd_tri[3 * b + 1], mesh.bnd_tri[3 * b + 2]};
  }
  const uint32_t* v = &mesh.tet[4 * size_t(face / 4)];
  const int* lf = kOutwardFace[face % 4];
  return {v[lf[0]], v[lf[1]], v[lf[2]]};
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
