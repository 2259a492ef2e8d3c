// Writers for solver formats that need no library: SU2 native (.su2) and OpenFOAM polyMesh.
// (CGNS and Exodus II are in cgns_format.cpp and exodus_format.cpp.)
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <system_error>
#include <vector>

#include "io/file_bytes.hpp"
#include "io/mesh_faces.hpp"
#include "io/number_text.hpp"
#include "io/volume_io.hpp"

namespace anitet {

namespace {

constexpr int kSu2Triangle = 5;
constexpr int kSu2Tetra = 10;

// Every triangle's unit normal within 1e-8 of the first's (either way), and every corner within
// 1e-10 of the patch's size of its plane.
bool triangles_coplanar(const VolumeMesh& mesh, const std::vector<uint32_t>& tris) {
  if (tris.empty()) return false;
  auto normal = [&](uint32_t b, double n[3]) {
    const double* p = mesh.point(mesh.bnd_tri[3 * size_t(b)]);
    const double* q = mesh.point(mesh.bnd_tri[3 * size_t(b) + 1]);
    const double* r = mesh.point(mesh.bnd_tri[3 * size_t(b) + 2]);
    const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k) n[k] = len > 0 ? n[k] / len : 0.0;
  };
  double n0[3], lo[3], hi[3];
  normal(tris[0], n0);
  const double* origin = mesh.point(mesh.bnd_tri[3 * size_t(tris[0])]);
  for (int k = 0; k < 3; ++k) lo[k] = hi[k] = origin[k];
  for (uint32_t b : tris)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], mesh.point(mesh.bnd_tri[3 * size_t(b) + j])[k]);
        hi[k] = std::max(hi[k], mesh.point(mesh.bnd_tri[3 * size_t(b) + j])[k]);
      }
  const double size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  for (uint32_t b : tris) {
    double n[3];
    normal(b, n);
    if (std::abs(std::abs(n[0] * n0[0] + n[1] * n0[1] + n[2] * n0[2]) - 1.0) > 1e-8) return false;
    for (int j = 0; j < 3; ++j) {
      const double* x = mesh.point(mesh.bnd_tri[3 * size_t(b) + j]);
      const double d = (x[0] - origin[0]) * n0[0] + (x[1] - origin[1]) * n0[1] + (x[2] - origin[2]) * n0[2];
      if (std::abs(d) > 1e-10 * size) return false;
    }
  }
  return true;
}

// OpenFOAM's type for a patch: a symmetry patch is a symmetryPlane when its faces are coplanar
// (OpenFOAM refuses a symmetryPlane that is not), else the general `symmetry`.
const char* openfoam_type(PatchKind kind, const VolumeMesh& mesh, const std::vector<uint32_t>& tris) {
  switch (kind) {
    case PatchKind::Wall: return "wall";
    case PatchKind::Symmetry: return triangles_coplanar(mesh, tris) ? "symmetryPlane" : "symmetry";
    case PatchKind::Inlet:
    case PatchKind::Outlet:
    case PatchKind::Farfield:
    case PatchKind::Patch: break;
  }
  return "patch";
}

void append_foam_header(std::string& out, const char* cls, const char* object, const std::string& note = "") {
  out += "/*--- written by anitet ---*/\nFoamFile\n{\n    version     2.0;\n    format      ascii;\n";
  out += "    class       ";
  out += cls;
  out += ";\n";
  if (!note.empty()) out += "    note        \"" + note + "\";\n";
  out += "    location    \"constant/polyMesh\";\n    object      ";
  out += object;
  out += ";\n}\n\n";
}

void append_label_list(std::string& out, const std::vector<uint32_t>& values) {
  append_line(out, uint64_t{values.size()});
  out += "(\n";
  for (uint32_t v : values) append_line(out, v);
  out += ")\n";
}

}  // namespace

Result<std::string> to_su2(const VolumeMesh& mesh, const PatchNames& patch_names) {
  if (Status s = check_volume_arrays(mesh); !s.ok()) return s;
  Result<std::vector<PatchTriangles>> patches = patch_triangles(mesh, patch_names);
  if (!patches.ok()) return patches.status();
  Result<MeshFaces> faces = build_mesh_faces(mesh);
  if (!faces.ok()) return faces.status();
  const size_t nv = mesh.num_vertices(), nt = mesh.num_tets();
  std::string out = "% written by anitet: ";
  out += std::to_string(nv) + " points, " + std::to_string(nt) + " tetrahedra, " +
         std::to_string(patches.value().size()) + " markers\nNDIME= 3\nNELEM= " + std::to_string(nt) + "\n";
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t* v = &mesh.tet[4 * t];
    append_line(out, int32_t{kSu2Tetra}, v[0], v[1], v[2], v[3], uint64_t{t});
  }
  out += "NPOIN= " + std::to_string(nv) + "\n";
  for (size_t v = 0; v < nv; ++v) append_line(out, mesh.xyz[3 * v], mesh.xyz[3 * v + 1], mesh.xyz[3 * v + 2], uint64_t{v});
  out += "NMARK= " + std::to_string(patches.value().size()) + "\n";
  for (const PatchTriangles& p : patches.value()) {
    out += "MARKER_TAG= " + p.patch.name + "\nMARKER_ELEMS= " + std::to_string(p.tris.size()) + "\n";
    for (uint32_t b : p.tris) {
      const std::array<uint32_t, 3> tri = outward_triangle(mesh, faces.value(), b);
      append_line(out, int32_t{kSu2Triangle}, tri[0], tri[1], tri[2]);
    }
  }
  return out;
}

Result<PolyMesh> to_polymesh(const VolumeMesh& mesh, const PatchNames& patch_names, const PatchTypes& patch_types) {
  if (Status s = check_volume_arrays(mesh); !s.ok()) return s;
  Result<std::vector<PatchTriangles>> patches = patch_triangles(mesh, patch_names, patch_types);
  if (!patches.ok()) return patches.status();
  Result<MeshFaces> built = build_mesh_faces(mesh);
  if (!built.ok()) return built.status();
  const MeshFaces& faces = built.value();
  const size_t nt = mesh.num_tets();

  const size_t np = mesh.num_prisms(), ny = mesh.num_pyramids(), num_cells = nt + np + ny;
  auto first_face = [&](size_t c) { return c < nt ? 4 * c : 4 * nt + 5 * (c - nt); };
  auto num_faces = [&](size_t c) { return c < nt ? 4 : 5; };

  // The patch of every boundary face of the cells, by index into `patches`.
  constexpr uint32_t kUnset = ~uint32_t{0};
  std::vector<uint32_t> face_patch(faces.across.size(), kUnset);
  for (size_t p = 0; p < patches.value().size(); ++p) {
    for (uint32_t b : patches.value()[p].tris) {
      const int64_t face = faces.bnd_face[b];
      if (face == MeshFaces::kNone) {
        return Status(Error::InvalidArgument, "boundary triangle " + std::to_string(b) +
                                                  " is not a face of any cell: an OpenFOAM patch face must be");
      }
      if (faces.bnd_internal[b]) {
        return Status(Error::InvalidArgument, "boundary triangle " + std::to_string(b) + " (patch '" +
                                                  patches.value()[p].patch.name +
                                                  "') is an internal face between two cells: OpenFOAM "
                                                  "patches hold boundary faces only");
      }
      // A quad is given by two triangles of one patch (check_boundary_elements).
      uint32_t v[4];
      const bool quad = face_vertices(mesh, face, v) == 4;
      if (face_patch[size_t(face)] != kUnset && !(quad && face_patch[size_t(face)] == p)) {
        return Status(Error::InvalidArgument, "boundary triangle " + std::to_string(b) +
                                                  " is listed twice (the same face as another boundary triangle)");
      }
      face_patch[size_t(face)] = static_cast<uint32_t>(p);
    }
  }

  PolyMesh pm;
  auto push_face = [&](size_t face) {
    uint32_t v[4];
    const int n = face_vertices(mesh, int64_t(face), v);
    pm.face.insert(pm.face.end(), v, v + n);
    pm.face_size.push_back(static_cast<uint8_t>(n));
    pm.owner.push_back(static_cast<uint32_t>(cell_of_face(mesh, int64_t(face))));
  };
  // Internal faces: each once, owned by the lower cell, by owner then neighbour.
  for (size_t c = 0; c < num_cells; ++c) {
    std::array<std::pair<uint32_t, size_t>, 5> upper;
    int count = 0;
    for (size_t face = first_face(c); face < first_face(c) + num_faces(c); ++face) {
      const int64_t other = faces.across[face];
      if (other == MeshFaces::kNone) {
        if (face_patch[face] == kUnset) {
          return Status(Error::InvalidArgument,
                        "face " + std::to_string(face - first_face(c)) + " of cell " + std::to_string(c) +
                            " is on the mesh boundary but is no boundary triangle: every OpenFOAM "
                            "boundary face must be in a patch");
        }
        continue;
      }
      const size_t u = cell_of_face(mesh, other);
      if (u == c) return Status(Error::InvalidMesh, "cell " + std::to_string(c) + " has two equal faces");
      if (u > c) upper[size_t(count++)] = {static_cast<uint32_t>(u), face};
    }
    // By neighbour; at most 5 items (insertion sort: std::sort on this small array trips GCC 12's
    // -Warray-bounds under the sanitizers).
    for (int i = 1; i < count; ++i) {
      for (int j = i; j > 0 && upper[size_t(j)] < upper[size_t(j - 1)]; --j) std::swap(upper[size_t(j)], upper[size_t(j - 1)]);
    }
    for (int i = 0; i < count; ++i) {
      push_face(upper[size_t(i)].second);
      pm.neighbour.push_back(upper[size_t(i)].first);
    }
  }
  // Boundary faces, patch by patch, each patch's faces by cell.
  std::vector<std::vector<size_t>> by_patch(patches.value().size());
  for (size_t face = 0; face < face_patch.size(); ++face) {
    if (face_patch[face] != kUnset) by_patch[face_patch[face]].push_back(face);
  }
  for (size_t p = 0; p < patches.value().size(); ++p) {
    const NamedPatch& named = patches.value()[p].patch;
    PolyMeshPatch patch{named.name, openfoam_type(named.kind, mesh, patches.value()[p].tris), pm.owner.size(), 0};
    for (size_t face : by_patch[p]) push_face(face);
    patch.size = pm.owner.size() - patch.start;
    pm.patches.push_back(std::move(patch));
  }
  if (!mesh.region.empty() || !mesh.prism_region.empty() || !mesh.pyramid_region.empty()) {
    std::map<int32_t, std::vector<uint32_t>> zones;
    for (size_t t = 0; t < nt; ++t) zones[mesh.region[t]].push_back(static_cast<uint32_t>(t));
    for (size_t p = 0; p < np; ++p) zones[mesh.prism_region[p]].push_back(static_cast<uint32_t>(nt + p));
    for (size_t y = 0; y < ny; ++y) zones[mesh.pyramid_region[y]].push_back(static_cast<uint32_t>(nt + np + y));
    for (auto& [label, cells] : zones) pm.cell_zones.emplace_back(region_name(label), std::move(cells));
  }
  return pm;
}

Status write_openfoam(const VolumeMesh& mesh, const std::string& dir, const PatchNames& patch_names,
                      const PatchTypes& patch_types) {
  Result<PolyMesh> built = to_polymesh(mesh, patch_names, patch_types);
  if (!built.ok()) return built.status();
  const PolyMesh& pm = built.value();
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return Status(Error::FileNotFound, "cannot create the directory '" + dir + "': " + ec.message());
  const std::string base = dir.empty() || dir.back() == '/' ? dir : dir + "/";
  const size_t nv = mesh.num_vertices(), nf = pm.owner.size();

  std::string out;
  append_foam_header(out, "vectorField", "points");
  append_line(out, uint64_t{nv});
  out += "(\n";
  for (size_t v = 0; v < nv; ++v) {
    out += '(';
    append_double(out, mesh.xyz[3 * v]);
    out += ' ';
    append_double(out, mesh.xyz[3 * v + 1]);
    out += ' ';
    append_double(out, mesh.xyz[3 * v + 2]);
    out += ")\n";
  }
  out += ")\n";
  if (Status s = write_file_bytes(base + "points", out); !s.ok()) return s;

  out.clear();
  append_foam_header(out, "faceList", "faces");
  append_line(out, uint64_t{nf});
  out += "(\n";
  for (size_t f = 0, at = 0; f < nf; at += pm.face_size[f++]) {
    out += pm.face_size[f] == 4 ? "4(" : "3(";
    for (size_t k = 0; k < pm.face_size[f]; ++k) {
      if (k) out += ' ';
      append_int(out, pm.face[at + k]);
    }
    out += ")\n";
  }
  out += ")\n";
  if (Status s = write_file_bytes(base + "faces", out); !s.ok()) return s;

  const size_t num_cells = mesh.num_tets() + mesh.num_prisms() + mesh.num_pyramids();
  const std::string note = "nPoints:" + std::to_string(nv) + "  nCells:" + std::to_string(num_cells) +
                           "  nFaces:" + std::to_string(nf) +
                           "  nInternalFaces:" + std::to_string(pm.num_internal_faces());
  out.clear();
  append_foam_header(out, "labelList", "owner", note);
  append_label_list(out, pm.owner);
  if (Status s = write_file_bytes(base + "owner", out); !s.ok()) return s;

  out.clear();
  append_foam_header(out, "labelList", "neighbour", note);
  append_label_list(out, pm.neighbour);
  if (Status s = write_file_bytes(base + "neighbour", out); !s.ok()) return s;

  out.clear();
  append_foam_header(out, "polyBoundaryMesh", "boundary");
  append_line(out, uint64_t{pm.patches.size()});
  out += "(\n";
  for (const PolyMeshPatch& p : pm.patches) {
    out += "    " + p.name + "\n    {\n        type            " + p.type + ";\n";
    if (p.type != "patch") out += "        inGroups        List<word> 1(" + p.type + ");\n";
    out += "        nFaces          " + std::to_string(p.size) + ";\n        startFace       " +
           std::to_string(p.start) + ";\n    }\n";
  }
  out += ")\n";
  if (Status s = write_file_bytes(base + "boundary", out); !s.ok()) return s;

  const std::string zones_path = base + "cellZones";
  if (pm.cell_zones.empty()) {
    std::filesystem::remove(zones_path, ec);  // a stale one from an earlier mesh
    return Status::success();
  }
  out.clear();
  append_foam_header(out, "regIOobject", "cellZones");
  append_line(out, uint64_t{pm.cell_zones.size()});
  out += "(\n";
  for (const auto& [name, cells] : pm.cell_zones) {
    out += name + "\n{\n    type cellZone;\n    cellLabels List<label>\n";
    append_label_list(out, cells);
    out += ";\n}\n";
  }
  out += ")\n";
  return write_file_bytes(zones_path, out);
}

}  // namespace anitet
