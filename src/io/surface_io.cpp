// Format choice by extension, file access and array checks for surfaces.
#include "io/surface_io.hpp"

#include <functional>
#include <set>

#include "io/file_bytes.hpp"
#include "io/mesh_faces.hpp"
#include "io/volume_io.hpp"
#include "io/gmf_format.hpp"

namespace anitet {

Result<SurfaceFormat> surface_format_from_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == "off") return SurfaceFormat::Off;
  if (ext == "obj") return SurfaceFormat::Obj;
  if (ext == "stl") return SurfaceFormat::Stl;
  if (ext == "ply") return SurfaceFormat::Ply;
  if (ext == "mesh") return SurfaceFormat::Medit;
  if (ext == "meshb") return SurfaceFormat::MeditBinary;
  if (ext == "msh") return SurfaceFormat::Gmsh;
  if (ext == "su2") return SurfaceFormat::Su2;
  if (ext == "vtu") return SurfaceFormat::Vtu;
  if (ext == "node" || ext == "ele") return SurfaceFormat::TetGen;
  return Status(Error::UnsupportedFormat, path + ": unknown surface format '." + ext +
                                              "' (expected .off, .obj, .stl, .ply, .mesh, .meshb, .msh, .su2, "
                                              ".vtu, .node or .ele)");
}

Result<SurfaceMesh> surface_of_volume(const VolumeMesh& mesh) {
  SurfaceMesh s;
  s.xyz = mesh.xyz;
  if (!mesh.bnd_tri.empty()) {
    s.tri = mesh.bnd_tri;
    s.patch = mesh.bnd_patch;
    return s;
  }
  Result<MeshFaces> faces = build_mesh_faces(mesh);
  if (!faces.ok()) return faces.status();
  for (size_t face = 0; face < faces->across.size(); ++face) {
    if (faces->across[face] != MeshFaces::kNone) continue;
    const uint32_t* v = &mesh.tet[4 * (face / 4)];
    const int* lf = kOutwardFace[face % 4];
    s.add_triangle(v[lf[0]], v[lf[1]], v[lf[2]], 0);
  }
  return s;
}

namespace {

// A file of a format that holds volume meshes but no triangle: its tets' boundary.
Result<SurfaceMesh> surface_or_volume_boundary(Result<SurfaceMesh> surface,
                                               const std::function<Result<VolumeMesh>()>& read_volume) {
  if (surface.ok() || surface.status().code() != Error::EmptyInput) return surface;
  Result<VolumeMesh> volume = read_volume();
  if (!volume.ok()) return volume.status().code() == Error::EmptyInput ? surface : Result<SurfaceMesh>(volume.status());
  return surface_of_volume(volume.value());
}

// The file's names of the labels its triangles have, checked as patch names, into `names`.
Result<SurfaceMesh> with_names(SurfaceMesh s, const PatchNames& found, const std::string& name, PatchNames* names) {
  const std::set<int32_t> labels(s.patch.begin(), s.patch.end());
  for (const auto& [label, text] : found) {
    if (!labels.count(label)) continue;
    if (Status st = check_patch_name(text); !st.ok())
      return Status(Error::InvalidArgument, name + ": patch " + std::to_string(label) + " is named '" + text +
                                                "', which cannot name a patch in every output format: " + st.message());
    (*names)[label] = text;
  }
  return s;
}

}  // namespace

Result<SurfaceMesh> read_surface(std::string_view data, SurfaceFormat format, const std::string& name,
                                 PatchNames* names) {
  switch (format) {
    case SurfaceFormat::Off:
      return read_off(data, name);
    case SurfaceFormat::Obj:
      return read_obj(data, name);
    case SurfaceFormat::Stl:
      return read_stl(data, name, names);
    case SurfaceFormat::Ply:
      return read_ply(data, name);
    case SurfaceFormat::Medit: {
      Result<SurfaceMesh> s = surface_or_volume_boundary(read_medit_surface(data, name),
                                                         [&] { return read_medit_volume(data, name); });
      if (s.ok() && names) return with_names(std::move(s).value(), medit_patch_names(data), name, names);
      return s;
    }
    case SurfaceFormat::Gmsh: {
      Result<SurfaceMesh> s = surface_or_volume_boundary(read_gmsh_surface(data, name),
                                                         [&] { return read_gmsh_volume(data, name); });
      if (!s.ok() || !names) return s;
      Result<PatchNames> found = gmsh_surface_names(data, name);
      if (!found.ok()) return found.status();
      return with_names(std::move(s).value(), found.value(), name, names);
    }
    case SurfaceFormat::MeditBinary:
      return surface_or_volume_boundary(read_meshb_surface(data, name),
                                        [&] { return read_meshb_volume(data, name); });
    case SurfaceFormat::Su2:
      return read_su2_surface(data, name, names);
    case SurfaceFormat::Vtu: {
      Result<VolumeMesh> volume = read_vtu(data, name);
      if (!volume.ok()) return volume.status();
      return surface_of_volume(volume.value());
    }
    case SurfaceFormat::TetGen:
      return Status(Error::UnsupportedFormat, name + ": a TetGen mesh is read from its files (give the .node or .ele path)");
  }
  return Status(Error::UnsupportedFormat, name + ": unknown surface format");
}

Result<SurfaceMesh> read_surface(const std::string& path, PatchNames* names) {
  Result<SurfaceFormat> format = surface_format_from_path(path);
  if (!format.ok()) return format.status();
  if (format.value() == SurfaceFormat::TetGen) {
    Result<VolumeMesh> volume = read_volume_mesh(path);
    if (!volume.ok()) return volume.status();
    return surface_of_volume(volume.value());
  }
  Result<std::string> bytes = read_file_bytes(path);
  if (!bytes.ok()) return bytes.status();
  return read_surface(bytes.value(), format.value(), path, names);
}

Status write_surface(const SurfaceMesh& mesh, const std::string& path) {
  const std::string ext = lower_extension(path);
  Result<std::string> bytes =
      Status(Error::UnsupportedFormat, path + ": cannot write surface format '." + ext +
                                           "' (expected .off, .obj, .stl, .mesh or .meshb)");
  if (ext == "off") {
    bytes = to_off(mesh);
  } else if (ext == "obj") {
    bytes = to_obj(mesh);
  } else if (ext == "stl") {
    bytes = to_stl_binary(mesh);
  } else if (ext == "mesh") {
    bytes = to_medit(mesh);
  } else if (ext == "meshb") {
    bytes = to_meshb(mesh);
  }
  if (!bytes.ok()) return bytes.status();
  return write_file_bytes(path, bytes.value());
}

Status check_surface_arrays(const SurfaceMesh& mesh) {
  if (mesh.xyz.size() % 3 != 0 || mesh.tri.size() % 3 != 0 ||
      mesh.patch.size() != mesh.tri.size() / 3) {
    return Status(Error::InvalidArgument, "surface arrays of inconsistent sizes");
  }
  const size_t nv = mesh.num_vertices();
  for (size_t i = 0; i < mesh.tri.size(); ++i) {
    if (mesh.tri[i] >= nv) {
      return Status(Error::BadIndex, "triangle " + std::to_string(i / 3) + " refers to vertex " +
                                         std::to_string(mesh.tri[i]) + " of " + std::to_string(nv));
    }
  }
  return Status::success();
}

}  // namespace anitet
