// `anitet merge PARTS.pvtu -o OUT`: the pieces anitet-mpi wrote, joined into one mesh (their
// shared vertices by GlobalNodeIds), checked to fit, written in any format anitet writes.
#include <iostream>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "io/pvtu_format.hpp"
#include "io/volume_io.hpp"

namespace anitet::cli {

CLI::App* add_merge_command(CLI::App& app, MergeArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "merge", "Join the pieces of a .pvtu written by anitet-mpi into one mesh file (holds the whole mesh)");
  cmd->add_option("input", args.input, "The .pvtu index (its pieces are read from beside it)")->required();
  cmd->add_option("-o,--output", args.output, "The mesh file: .mesh .meshb .msh .vtu .su2 .cgns .exo, or a polyMesh directory")
      ->required();
  cmd->footer("Example:\n  mpirun -np 4 anitet-mpi mesh part.stl -o parts.pvtu && anitet merge parts.pvtu -o part.mesh");
  return cmd;
}

int run_merge(const MergeArgs& args) {
  Result<std::vector<std::string>> paths = read_pvtu_index(args.input);
  if (!paths.ok()) {
    std::cerr << "anitet merge: " << paths.status().message() << "\n";
    return kExitReadError;
  }
  std::vector<VtuPiece> pieces;
  for (const std::string& path : paths.value()) {
    Result<VtuPiece> piece = read_vtu_piece(path);
    if (!piece.ok()) {
      std::cerr << "anitet merge: " << piece.status().message() << "\n";
      return kExitReadError;
    }
    pieces.push_back(std::move(piece).value());
  }
  Result<VolumeMesh> mesh = join_pieces(pieces);
  pieces.clear();
  Status st = mesh.ok() ? check_joined(mesh.value()) : mesh.status();
  if (!st.ok()) {
    std::cerr << "anitet merge: " << args.input << ": " << st.message() << "\n";
    return kExitInvalidInput;
  }
  if (Status w = write_volume_mesh(mesh.value(), args.output); !w.ok()) {
    std::cerr << "anitet merge: cannot write '" << args.output << "': " << w.message() << "\n";
    return w.code() == Error::InvalidArgument ? kExitUsage : kExitReadError;
  }
  std::cout << "anitet merge: " << paths->size() << " pieces, " << mesh->num_vertices() << " vertices, "
            << mesh->num_tets() << " tets, " << mesh->num_boundary_triangles() << " boundary triangles -> "
            << args.output << "\n";
  return kExitOk;
}

}  // namespace anitet::cli
