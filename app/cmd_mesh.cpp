#include <iostream>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "io/volume_io.hpp"
#include "surface_check.hpp"

namespace anitet::cli {

int run_mesh(const MeshArgs& args) {
  // A bad output name is a usage error, found before any work.
  Result<VolumeFormat> format = volume_format_from_path(args.output);
  if (!format.ok()) {
    std::cerr << "anitet " << args.command << ": cannot write '" << args.output
              << "': " << format.status().message() << "\n";
    return kExitUsage;
  }
  if (format.value() == VolumeFormat::TetGen) {
    std::cerr << "anitet " << args.command << ": cannot write '" << args.output
              << "': output formats are .mesh, .msh and .vtu\n";
    return kExitUsage;
  }
  CheckedSurface checked;
  if (const int code = load_and_validate(args.command, args.input, checked); code != kExitOk) return code;
  if (!args.quiet) {
    std::cout << "anitet " << args.command << ": '" << args.input << "' is a valid surface ("
              << checked.surface.num_vertices() << " vertices, " << checked.surface.num_triangles()
              << " triangles, " << checked.report.shells.size() << " shells)\n";
    for (const Repair& rep : checked.report.repairs) std::cout << "  repaired: " << rep.message << "\n";
  }
  std::cerr << "anitet " << args.command << ": not implemented yet; '" << args.output
            << "' was not written\n";
  return kExitNotImplemented;
}

}  // namespace anitet::cli
