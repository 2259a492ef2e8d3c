// `anitet recover IN -o OUT`: the conforming Delaunay tetrahedralization of the surface (stage 2
// alone); the boundary triangles written are the recovered surface S2 with the input's patch
// labels.
#include <iostream>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "optimize/optimize.hpp"
#include "recovery/recovery.hpp"
#include "surface_check.hpp"

namespace anitet::cli {

namespace {

int recover_checked(const MeshArgs& args, const CheckedSurface& checked) {
  Result<RecoveryOutput> r = recover_boundary(checked.surface, recovery_options(args));
  if (!r.ok()) {
    std::cerr << "anitet recover: '" << args.input << "': " << r.status().message() << "\n";
    return kExitInternal;
  }
  RecoveryOutput& out = r.value();
  // Tets flat to rounding are valid for the exact predicates, but a solver or checker computing
  // volumes in doubles may find them inverted: flips remove them (no vertex of S can move).
  const FlatTetFlips flat = flip_flat_tets(out.mesh);
  const VolumeMesh vm = out.mesh.to_volume_mesh(/*drop_unused_vertices=*/true, out.s2_tri, out.s2_patch);
  if (const int code = write_outputs(args, vm); code != kExitOk) return code;
  if (!args.quiet) {
    const RecoveryStats& st = out.stats;
    std::cout << "anitet recover: wrote '" << args.output << "': " << vm.num_vertices() << " vertices, "
              << vm.num_tets() << " tets, " << vm.num_boundary_triangles() << " boundary triangles, "
              << st.regions << " regions\n"
              << "  steiner points: " << st.steiner_on_edges + st.steiner_on_faces << " ("
              << st.steiner_on_edges << " on edges, " << st.steiner_on_faces << " on faces; "
              << st.walk_splits << " placed by a walk, " << st.edge_crossing_splits << " of them where it crosses a mesh edge), " << st.flips << " flips, " << st.passes << " passes, "
              << st.blocked_insertions << " insertions refused (" << st.early_refusals
              << " before their cavity grew), strategy: " << recovery_strategy_name(st.strategy)
              << "\n"
              << "  tets flat to rounding: " << flat.found << " found, " << flat.flips << " flips, " << flat.left
              << " left\n"
              << "  time: " << st.seconds_total << " s (delaunay " << st.seconds_delaunay
              << " s, recovery " << st.seconds_recovery << " s, carving " << st.seconds_carve << " s)\n";
  }
  return kExitOk;
}

}  // namespace

int run_recover(MeshArgs& args) {
  // A bad output name is a usage error, found before any work.
  if (const int code = check_output_paths(args); code != kExitOk) return code;
  CheckedSurface checked;
  if (const int code = load_and_validate(args.command, args.input, checked); code != kExitOk) return code;
  if (const int code = check_patch_names(args, checked); code != kExitOk) return code;
  if (!args.quiet) {
    std::cout << "anitet " << args.command << ": '" << args.input << "' is a valid surface ("
              << checked.surface.num_vertices() << " vertices, " << checked.surface.num_triangles()
              << " triangles, " << checked.report.shells.size() << " shells)\n";
    for (const Repair& rep : checked.report.repairs) std::cout << "  repaired: " << rep.message << "\n";
  }
  return recover_checked(args, checked);
}


CLI::App* add_recover_command(CLI::App& app, MeshArgs& args) {
  args.command = "recover";
  CLI::App* cmd = app.add_subcommand(
      "recover", "The Delaunay tetrahedra of the surface's points with the surface recovered conformingly "
                 "(Steiner points added on it): stage 2 of mesh alone, for tests and comparisons");
  add_mesh_io_options(cmd, args);
  cmd->footer(
      "Examples:\n"
      "  anitet recover part.stl -o part.mesh       # the Delaunay tets of the surface's points\n"
      "  anitet recover part.stl -o part.vtu --recovery split");
  return cmd;
}

}  // namespace anitet::cli
