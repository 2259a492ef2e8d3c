// Format choice by extension, file access and array checks for surfaces.
#include "io/surface_io.hpp"

#include "io/file_bytes.hpp"

namespace anitet {

Result<SurfaceFormat> surface_format_from_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == "off") return SurfaceFormat::Off;
  if (ext == "obj") return SurfaceFormat::Obj;
  if (ext == "stl") return SurfaceFormat::Stl;
  if (ext == "ply") return SurfaceFormat::Ply;
  if (ext == "mesh") return SurfaceFormat::Medit;
  if (ext == "msh") return SurfaceFormat::Gmsh;
  if (ext == "su2") return SurfaceFormat::Su2;
  return Status(Error::UnsupportedFormat, path + ": unknown surface format '." + ext +
                                              "' (expected .off, .obj, .stl, .ply, .mesh, .msh or .su2)");
}

Result<SurfaceMesh> read_surface(std::string_view data, SurfaceFormat format,
                                 const std::string& name) {
  switch (format) {
    case SurfaceFormat::Off:
      return read_off(data, name);
    case SurfaceFormat::Obj:
      return read_obj(data, name);
    case SurfaceFormat::Stl:
      return read_stl(data, name);
    case SurfaceFormat::Ply:
      return read_ply(data, name);
    case SurfaceFormat::Medit:
      return read_medit_surface(data, name);
    case SurfaceFormat::Gmsh:
      return read_gmsh_surface(data, name);
    case SurfaceFormat::Su2:
      return read_su2_surface(data, name);
  }
  return Status(Error::UnsupportedFormat, name + ": unknown surface format");
}

Result<SurfaceMesh> read_surface(const std::string& path, PatchNames* names) {
  Result<SurfaceFormat> format = surface_format_from_path(path);
  if (!format.ok()) return format.status();
  Result<std::string> bytes = read_file_bytes(path);
  if (!bytes.ok()) return bytes.status();
  if (format.value() == SurfaceFormat::Su2) return read_su2_surface(bytes.value(), path, names);
  return read_surface(bytes.value(), format.value(), path);
}

Status write_surface(const SurfaceMesh& mesh, const std::string& path) {
  const std::string ext = lower_extension(path);
  Result<std::string> bytes =
      Status(Error::UnsupportedFormat, path + ": cannot write surface format '." + ext +
                                           "' (expected .off, .obj, .stl or .mesh)");
  if (ext == "off") {
    bytes = to_off(mesh);
  } else if (ext == "obj") {
    bytes = to_obj(mesh);
  } else if (ext == "stl") {
    bytes = to_stl_binary(mesh);
  } else if (ext == "mesh") {
    bytes = to_medit(mesh);
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
