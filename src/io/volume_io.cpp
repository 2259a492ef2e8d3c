// Format choice by extension, file access and array checks for tetrahedral meshes.
#include "io/volume_io.hpp"

#include "core/tet_faces.hpp"
#include "io/file_bytes.hpp"
#include "io/gmf_format.hpp"
#include "io/mesh_faces.hpp"

#include <algorithm>

namespace anitet {

namespace {

// "a b c" of three 0-based vertex ids, written 1-based as in the files.
std::string one_based(const uint32_t* v) {
  return std::to_string(uint64_t{v[0]} + 1) + " " + std::to_string(uint64_t{v[1]} + 1) + " " +
         std::to_string(uint64_t{v[2]} + 1);
}

// The formats whose boundary elements a solver reads as its boundary conditions: every boundary
// face of the tets must be one of them.
bool has_markers(VolumeFormat f) {
  return f == VolumeFormat::Su2 || f == VolumeFormat::OpenFoam || f == VolumeFormat::Cgns || f == VolumeFormat::Exodus;
}

// The last component of a path, trailing slashes ignored.
std::string last_component(std::string path) {
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// check_boundary_elements for a mesh with prisms or pyramids: the cell faces matched by
// build_mesh_faces, a quad on the boundary given by two triangles of one patch that split it
// along a diagonal.
Status check_mixed_boundary_elements(const VolumeMesh& mesh, bool cover) {
  Result<MeshFaces> built = build_mesh_faces(mesh);
  if (!built.ok()) return built.status();
  const MeshFaces& faces = built.value();
  const size_t nb = mesh.num_boundary_triangles();
  std::vector<std::vector<uint32_t>> given(faces.across.size());  // boundary triangles per cell face
  for (size_t b = 0; b < nb; ++b) {
    const int64_t face = faces.bnd_face[b];
    if (face == MeshFaces::kNone)
      return Status(Error::InvalidMesh, "boundary triangle " + std::to_string(b + 1) + " (vertices " +
                                            one_based(&mesh.bnd_tri[3 * b]) + ", 1-based) is no face of the cells");
    given[size_t(face)].push_back(static_cast<uint32_t>(b));
    // A shared face is also the other cell's.
    if (faces.across[size_t(face)] != MeshFaces::kNone) given[size_t(faces.across[size_t(face)])].push_back(static_cast<uint32_t>(b));
  }
  for (size_t face = 0; face < faces.across.size(); ++face) {
    uint32_t v[4];
    const int n = face_vertices(mesh, int64_t(face), v);
    const std::vector<uint32_t>& g = given[face];
    auto where = [&] {
      return std::string(n == 4 ? "the quad side " : "the face ") + one_based(v) +
             (n == 4 ? " " + std::to_string(uint64_t{v[3]} + 1) : "") + " (1-based)";
    };
    if (g.empty()) {
      if (cover && faces.across[face] == MeshFaces::kNone)
        return Status(Error::InvalidMesh, "boundary face " + where() + " of the cells is no boundary triangle");
      continue;
    }
    if (n == 3 && g.size() > 1)
      return Status(Error::InvalidMesh, "boundary triangle " + std::to_string(uint64_t{g[1]} + 1) +
                                            " repeats a face an earlier one gives: " + where());
    if (n == 4) {
      // Two triangles of one patch, leaving out opposite corners (0 and 2, or 1 and 3).
      auto left_out = [&](uint32_t b) {
        for (int i = 0; i < 4; ++i)
          if (std::find(&mesh.bnd_tri[3 * size_t(b)], &mesh.bnd_tri[3 * size_t(b)] + 3, v[i]) == &mesh.bnd_tri[3 * size_t(b)] + 3)
            return i;
        return -1;
      };
      const bool split = g.size() == 2 && (left_out(g[0]) + 2) % 4 == left_out(g[1]) &&
                         mesh.bnd_patch[g[0]] == mesh.bnd_patch[g[1]];
      if (!split)
        return Status(Error::InvalidMesh, where() + " is given by " + std::to_string(g.size()) +
                                              " boundary triangles, not by two of one patch split along a diagonal");
    }
  }
  return Status::success();
}

}  // namespace

bool volume_format_writes_prisms(VolumeFormat f) {
  return f == VolumeFormat::OpenFoam || f == VolumeFormat::Vtu;
}

Result<VolumeFormat> volume_format_from_path(const std::string& path) {
  if (last_component(path) == "polyMesh") return VolumeFormat::OpenFoam;
  const std::string ext = lower_extension(path);
  if (ext == "mesh") return VolumeFormat::Medit;
  if (ext == "meshb") return VolumeFormat::MeditBinary;
  if (ext == "msh") return VolumeFormat::Gmsh;
  if (ext == "node" || ext == "ele") return VolumeFormat::TetGen;
  if (ext == "vtu") return VolumeFormat::Vtu;
  if (ext == "su2") return VolumeFormat::Su2;
  if (ext == "cgns") return VolumeFormat::Cgns;
  if (ext == "exo" || ext == "e") return VolumeFormat::Exodus;
  return Status(Error::UnsupportedFormat, path + ": unknown volume mesh format '." + ext +
                                              "' (expected .mesh, .meshb, .msh, .node, .ele, .vtu, .su2, "
                                              ".cgns, .exo, .e or a .../polyMesh directory)");
}

Status check_writable_volume_path(const std::string& path) {
  Result<VolumeFormat> format = volume_format_from_path(path);
  if (!format.ok()) return format.status();
  switch (format.value()) {
    case VolumeFormat::TetGen:
      return Status(Error::UnsupportedFormat, path + ": TetGen .node/.ele is read only; output formats are "
                                                 ".mesh, .meshb, .msh, .vtu, .su2, .cgns, .exo/.e and .../polyMesh");
    case VolumeFormat::Cgns:
      if (!cgns_available()) {
        return Status(Error::NotImplemented, path + ": anitet was not built with CGNS (libcgns-dev)");
      }
      if (const std::string why = cgns_load_error(); !why.empty()) return Status(Error::NotImplemented, path + ": " + why);
      break;
    case VolumeFormat::Exodus:
      if (!exodus_available()) {
        return Status(Error::NotImplemented, path + ": anitet was not built with Exodus II (libexodusii-dev)");
      }
      if (const std::string why = exodus_load_error(); !why.empty()) return Status(Error::NotImplemented, path + ": " + why);
      break;
    default:
      break;
  }
  return Status::success();
}

Result<VolumeMesh> read_volume_mesh(const std::string& path) {
  Result<VolumeFormat> format = volume_format_from_path(path);
  if (!format.ok()) return format.status();
  if (format.value() == VolumeFormat::Su2 || format.value() == VolumeFormat::OpenFoam ||
      format.value() == VolumeFormat::Cgns || format.value() == VolumeFormat::Exodus) {
    return Status(Error::UnsupportedFormat,
                  path + ": anitet writes this format but does not read it as a volume mesh (it reads .mesh, .msh, "
                         ".node/.ele and .vtu" +
                      std::string(format.value() == VolumeFormat::Su2 ? "; an .su2 file's boundary is read as a surface)" : ")"));
  }
  if (format.value() == VolumeFormat::TetGen) {
    const std::string base = path.substr(0, path.size() - lower_extension(path).size() - 1);
    Result<std::string> node = read_file_bytes(base + ".node");
    if (!node.ok()) return node.status();
    Result<std::string> ele = read_file_bytes(base + ".ele");
    if (!ele.ok()) return ele.status();
    Result<std::string> face = read_file_bytes(base + ".face");  // optional
    return read_tetgen(node.value(), ele.value(), face.ok() ? face.value() : std::string(), base);
  }
  Result<std::string> bytes = read_file_bytes(path);
  if (!bytes.ok()) return bytes.status();
  switch (format.value()) {
    case VolumeFormat::Medit:
      return read_medit_volume(bytes.value(), path);
    case VolumeFormat::MeditBinary:
      return read_meshb_volume(bytes.value(), path);
    case VolumeFormat::Gmsh:
      return read_gmsh_volume(bytes.value(), path);
    case VolumeFormat::Vtu:
      return read_vtu(bytes.value(), path);
    default:
      break;
  }
  return Status(Error::UnsupportedFormat, path + ": unknown volume mesh format");
}

Status write_volume_mesh(const VolumeMesh& mesh, const std::string& path,
                         const std::vector<TetScalar>& tet_scalars) {
  return write_volume_mesh(mesh, path, PatchNames(), tet_scalars);
}

Status write_volume_mesh(const VolumeMesh& mesh, const std::string& path, const PatchNames& patch_names,
                         const std::vector<TetScalar>& tet_scalars) {
  return write_volume_mesh(mesh, path, patch_names, PatchTypes(), tet_scalars);
}

Status write_volume_mesh(const VolumeMesh& mesh, const std::string& path, const PatchNames& patch_names,
                         const PatchTypes& patch_types, const std::vector<TetScalar>& tet_scalars) {
  Result<VolumeFormat> format = volume_format_from_path(path);
  if (!format.ok()) {
    return Status(Error::UnsupportedFormat, path + ": cannot write volume mesh format '." + lower_extension(path) +
                                                "' (expected .mesh, .meshb, .msh, .vtu, .su2, .cgns, .exo, .e "
                                                "or a .../polyMesh directory)");
  }
  if (format.value() == VolumeFormat::TetGen) return check_writable_volume_path(path);
  if (mesh.has_mixed_cells() && !volume_format_writes_prisms(format.value()))
    return Status(Error::UnsupportedFormat, path + ": this format is written with tets only, and the mesh has " +
                                                std::to_string(mesh.num_prisms()) + " prisms and " +
                                                std::to_string(mesh.num_pyramids()) +
                                                " pyramids (prism and pyramid cells: " + kPrismFormats + ")");
  // Nothing wrong is written: the boundary elements are checked against the tets first.
  const bool cover = has_markers(format.value()) || !mesh.bnd_tri.empty();
  if (Status st = check_boundary_elements(mesh, cover); !st.ok()) {
    return Status(st.code(), path + ": not written: " + st.message() +
                                 (mesh.bnd_tri.empty() ? " (this format's boundary markers need them)" : ""));
  }
  // The formats without patch types still refuse a type for a label no triangle has.
  if (!patch_types.empty()) {
    if (Result<std::vector<NamedPatch>> named = named_patches(mesh.bnd_patch, patch_names, patch_types); !named.ok())
      return named.status();
  }
  Result<std::string> bytes = std::string();
  switch (format.value()) {
    case VolumeFormat::Medit: return write_medit_volume(mesh, path, patch_names);
    case VolumeFormat::Gmsh: bytes = to_gmsh(mesh, patch_names); break;
    case VolumeFormat::MeditBinary:
    case VolumeFormat::Vtu:
      if (Result<std::vector<NamedPatch>> named = named_patches(mesh.bnd_patch, patch_names, patch_types); !named.ok()) {
        return named.status();  // VTU and .meshb have no names, but a wrong name is still an error
      }
      bytes = format.value() == VolumeFormat::Vtu ? to_vtu(mesh, tet_scalars) : to_meshb(mesh);
      break;
    case VolumeFormat::Su2: bytes = to_su2(mesh, patch_names); break;
    case VolumeFormat::OpenFoam: return write_openfoam(mesh, path, patch_names, patch_types);
    case VolumeFormat::Cgns: return write_cgns(mesh, path, patch_names, patch_types);
    case VolumeFormat::Exodus: return write_exodus(mesh, path, patch_names, patch_types);
    case VolumeFormat::TetGen: break;  // refused above
  }
  if (!bytes.ok()) return bytes.status();
  return write_file_bytes(path, bytes.value());
}

Status check_volume_arrays(const VolumeMesh& mesh) {
  // Regions are given for every cell or for none.
  const bool regions = !mesh.region.empty() || !mesh.prism_region.empty() || !mesh.pyramid_region.empty();
  if (mesh.xyz.size() % 3 != 0 || mesh.tet.size() % 4 != 0 || mesh.bnd_tri.size() % 3 != 0 ||
      mesh.prism.size() % 6 != 0 || mesh.pyramid.size() % 5 != 0 ||
      mesh.bnd_patch.size() != mesh.num_boundary_triangles() ||
      (regions && (mesh.region.size() != mesh.num_tets() || mesh.prism_region.size() != mesh.num_prisms() ||
                   mesh.pyramid_region.size() != mesh.num_pyramids()))) {
    return Status(Error::InvalidArgument, "volume mesh arrays of inconsistent sizes");
  }
  const size_t nv = mesh.num_vertices();
  for (size_t i = 0; i < mesh.tet.size(); ++i) {
    if (mesh.tet[i] >= nv) {
      return Status(Error::BadIndex, "tetrahedron " + std::to_string(i / 4) + " refers to vertex " +
                                         std::to_string(mesh.tet[i]) + " of " + std::to_string(nv));
    }
  }
  for (size_t i = 0; i < mesh.prism.size(); ++i) {
    if (mesh.prism[i] >= nv) {
      return Status(Error::BadIndex, "prism " + std::to_string(i / 6) + " refers to vertex " +
                                         std::to_string(mesh.prism[i]) + " of " + std::to_string(nv));
    }
  }
  for (size_t i = 0; i < mesh.pyramid.size(); ++i) {
    if (mesh.pyramid[i] >= nv) {
      return Status(Error::BadIndex, "pyramid " + std::to_string(i / 5) + " refers to vertex " +
                                         std::to_string(mesh.pyramid[i]) + " of " + std::to_string(nv));
    }
  }
  for (size_t i = 0; i < mesh.bnd_tri.size(); ++i) {
    if (mesh.bnd_tri[i] >= nv) {
      return Status(Error::BadIndex, "boundary triangle " + std::to_string(i / 3) +
                                         " refers to vertex " + std::to_string(mesh.bnd_tri[i]) +
                                         " of " + std::to_string(nv));
    }
  }
  return Status::success();
}

Status check_boundary_elements(const VolumeMesh& mesh, bool cover) {
  if (Status st = check_volume_arrays(mesh); !st.ok()) return st;
  if (mesh.has_mixed_cells()) return check_mixed_boundary_elements(mesh, cover);
  return check_boundary_elements(mesh.tet, mesh.num_vertices(), mesh.bnd_tri, cover);
}

Status check_boundary_elements(const std::vector<uint32_t>& tet, size_t num_vertices, const std::vector<uint32_t>& bnd_tri,
                               bool cover) {
  const FaceCensus faces = census_faces(tet.data(), tet.size() / 4, num_vertices, /*parallel=*/true, bnd_tri.data(),
                                        bnd_tri.size() / 3);
  if (faces.shared_by_more_than_two > 0) {
    return Status(Error::InvalidMesh, std::to_string(faces.shared_by_more_than_two) +
                                          " faces are shared by more than two tetrahedra (overlapping tets)");
  }
  size_t not_faces = 0, first = 0;
  for (size_t b = faces.tets_of_triangle.size(); b-- > 0;) {
    if (faces.tets_of_triangle[b] == 0) {
      ++not_faces;
      first = b;
    }
  }
  if (not_faces > 0) {
    return Status(Error::InvalidMesh, std::to_string(not_faces) + " of " + std::to_string(bnd_tri.size() / 3) +
                                          " boundary triangles are not faces of the tetrahedra; first: triangle " +
                                          std::to_string(first + 1) + " (vertices " + one_based(&bnd_tri[3 * first]) +
                                          ", 1-based)");
  }
  if (!faces.repeated.empty()) {
    const uint32_t b = faces.repeated[0];
    return Status(Error::InvalidMesh, std::to_string(faces.repeated.size()) +
                                          " boundary triangles repeat a face an earlier one gives; first: triangle " +
                                          std::to_string(uint64_t{b} + 1) + " (vertices " + one_based(&bnd_tri[3 * size_t(b)]) +
                                          ", 1-based)");
  }
  const std::vector<uint32_t>& uncovered = bnd_tri.empty() ? faces.boundary : faces.uncovered;
  if (cover && !uncovered.empty()) {
    return Status(Error::InvalidMesh, std::to_string(uncovered.size() / 3) + " of " +
                                          std::to_string(faces.boundary.size() / 3) +
                                          " boundary faces of the tetrahedra are no boundary triangle; first: vertices " +
                                          one_based(uncovered.data()) + " (1-based)");
  }
  return Status::success();
}

}  // namespace anitet
