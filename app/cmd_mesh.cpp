#include <iostream>
#include <set>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "io/volume_io.hpp"
#include "optimize/optimize.hpp"
#include "recovery/recovery.hpp"
#include "surface_check.hpp"

namespace anitet::cli {

RecoveryOptions recovery_options(const MeshArgs& args) {
  RecoveryOptions o;
  o.split_constraints = args.recovery != "fuzzy";
  o.fuzzy_faces = args.recovery != "split";
  return o;
}

namespace {

// `anitet recover`: the conforming Delaunay tetrahedralization of the surface (stage 2 alone);
// the boundary triangles written are the recovered surface S2 with the input's patch labels.
int run_recover(const MeshArgs& args, const CheckedSurface& checked) {
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

int check_output_path(const MeshArgs& args) {
  for (const std::string& path : output_paths(args)) {
    if (Status s = check_writable_volume_path(path); !s.ok()) {
      std::cerr << "anitet " << args.command << ": cannot write '" << path << "': " << s.message() << "\n";
      return s.code() == Error::NotImplemented ? kExitNotImplemented : kExitUsage;
    }
  }
  return kExitOk;
}

std::vector<std::string> output_paths(const MeshArgs& args) {
  std::vector<std::string> paths{args.output};
  paths.insert(paths.end(), args.also_write.begin(), args.also_write.end());
  return paths;
}

int write_outputs(const MeshArgs& args, const VolumeMesh& mesh) {
  for (const std::string& path : output_paths(args)) {
    if (Status s = write_volume_mesh(mesh, path, args.patch_names); !s.ok()) {
      std::cerr << "anitet " << args.command << ": cannot write '" << path << "': " << s.message() << "\n";
      return kExitReadError;
    }
  }
  return kExitOk;
}

int check_patch_names(MeshArgs& args, const CheckedSurface& input, const std::vector<int32_t>& extra_labels) {
  const std::string cmd = "anitet " + args.command;
  // The file's own names (SU2 markers) first; --patch-names renames on top of them.
  args.patch_names = input.names;
  if (args.patch_names_spec.empty()) return kExitOk;
  Result<PatchNames> names = parse_patch_names(args.patch_names_spec);
  if (!names.ok()) {
    std::cerr << cmd << ": --patch-names: " << names.status().message() << "\n";
    return kExitUsage;
  }
  std::set<int32_t> labels(input.surface.patch.begin(), input.surface.patch.end());
  labels.insert(extra_labels.begin(), extra_labels.end());
  for (const auto& [label, name] : names.value()) {
    if (!labels.count(label)) {
      std::cerr << cmd << ": --patch-names: no triangle of '" << args.input << "' has the patch label " << label
                << " (named '" << name << "')\n";
      return kExitUsage;
    }
    args.patch_names[label] = name;
  }
  // No two labels with one name once the file's names and the given ones are merged.
  if (Result<std::vector<NamedPatch>> named = named_patches(std::vector<int32_t>(labels.begin(), labels.end()), args.patch_names);
      !named.ok()) {
    std::cerr << cmd << ": --patch-names: " << named.status().message() << "\n";
    return kExitUsage;
  }
  return kExitOk;
}

int run_mesh(MeshArgs& args) {
  // A bad output name is a usage error, found before any work.
  if (const int code = check_output_path(args); code != kExitOk) return code;
  CheckedSurface checked;
  if (const int code = load_and_validate(args.command, args.input, checked); code != kExitOk) return code;
  if (const int code = check_patch_names(args, checked); code != kExitOk) return code;
  if (!args.quiet) {
    std::cout << "anitet " << args.command << ": '" << args.input << "' is a valid surface ("
              << checked.surface.num_vertices() << " vertices, " << checked.surface.num_triangles()
              << " triangles, " << checked.report.shells.size() << " shells)\n";
    for (const Repair& rep : checked.report.repairs) std::cout << "  repaired: " << rep.message << "\n";
  }
  if (args.command == "recover") return run_recover(args, checked);
  std::cerr << "anitet " << args.command << ": not implemented yet; '" << args.output
            << "' was not written\n";
  return kExitNotImplemented;
}

}  // namespace anitet::cli
