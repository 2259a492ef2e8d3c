// Per-vertex solution files by extension (.sol ASCII, .solb binary), and the vertex metric of a
// volume mesh written as one.
#include "io/sol_io.hpp"

#include "io/file_bytes.hpp"
#include "io/volume_io.hpp"

namespace anitet {

namespace {

// The vertex metric as one field: sizes (1 per vertex) or tensors (6 per vertex).
Result<VertexFields> metric_fields(const VolumeMesh& mesh) {
  const size_t nv = mesh.num_vertices();
  const size_t per_vertex = nv == 0 ? 0 : mesh.vertex_metric.size() / nv;
  if (nv == 0 || (per_vertex != 1 && per_vertex != 6) || per_vertex * nv != mesh.vertex_metric.size()) {
    return Status(Error::InvalidArgument, "a .sol needs 1 or 6 metric values per vertex; the mesh has " +
                                              std::to_string(mesh.vertex_metric.size()) + " values for " +
                                              std::to_string(nv) + " vertices");
  }
  return VertexFields::single(per_vertex == 1 ? FieldKind::Scalar : FieldKind::SymTensor, mesh.vertex_metric);
}

}  // namespace

bool is_sol_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == "sol" || ext == "solb";
}

Result<VertexFields> read_vertex_fields(const std::string& path, GmfFileInfo* info) {
  const std::string ext = lower_extension(path);
  if (ext != "sol" && ext != "solb") {
    return Status(Error::UnsupportedFormat, path + ": unknown solution format '." + ext + "' (expected .sol or .solb)");
  }
  Result<std::string> bytes = read_file_bytes(path);
  if (!bytes.ok()) return bytes.status();
  if (ext == "solb") return read_solb(bytes.value(), path, info);
  Result<VertexFields> fields = read_medit_sol(bytes.value(), path);
  if (fields.ok() && fields.value().dimension != 3) {
    return Status(Error::UnsupportedFormat, path + ": a Dimension 2 .sol is for `anitet mesh2d`, not a 3D mesh");
  }
  return fields;
}

Status write_vertex_fields(const VertexFields& fields, const std::string& path, int gmf_version) {
  const std::string ext = lower_extension(path);
  Result<std::string> bytes =
      ext == "solb" ? to_solb(fields, gmf_version)
      : ext == "sol"
          ? to_sol(fields)
          : Result<std::string>(Status(Error::UnsupportedFormat,
                                       path + ": cannot write solution format '." + ext + "' (expected .sol or .solb)"));
  if (!bytes.ok()) return bytes.status();
  return write_file_bytes(path, bytes.value());
}

Result<std::string> to_sol(const VolumeMesh& mesh) {
  Result<VertexFields> fields = metric_fields(mesh);
  if (!fields.ok()) return fields.status();
  return to_sol(fields.value());
}

Status write_sol(const VolumeMesh& mesh, const std::string& path) {
  Result<VertexFields> fields = metric_fields(mesh);
  if (!fields.ok()) return fields.status();
  // (Any other extension than .solb gets the ASCII text, as before .solb was written.)
  Result<std::string> bytes = lower_extension(path) == "solb" ? to_solb(fields.value()) : to_sol(fields.value());
  if (!bytes.ok()) return bytes.status();
  return write_file_bytes(path, bytes.value());
}

}  // namespace anitet
