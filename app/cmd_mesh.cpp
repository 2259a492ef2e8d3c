#include <iostream>
#include <set>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "io/file_bytes.hpp"
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

std::string join_paths(const std::vector<std::string>& paths) {
  std::string out;
  for (const std::string& p : paths) out += (out.empty() ? "'" : ", '") + p + "'";
  return out;
}

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

int check_output_file(const std::string& command, const std::string& path, bool directory) {
  if (Status s = check_can_create(path, directory); !s.ok()) {
    std::cerr << "anitet " << command << ": " << s.message() << " (checked before any work)\n";
    return kExitReadError;
  }
  return kExitOk;
}

int check_output_paths(const MeshArgs& args) {
  for (const std::string& path : output_paths(args)) {
    if (Status s = check_writable_volume_path(path); !s.ok()) {
      std::cerr << "anitet " << args.command << ": cannot write '" << path << "': " << s.message() << "\n";
      return s.code() == Error::NotImplemented ? kExitNotImplemented : kExitUsage;
    }
  }
  for (const std::string& path : output_paths(args)) {
    const bool directory = volume_format_from_path(path).value() == VolumeFormat::OpenFoam;
    if (const int code = check_output_file(args.command, path, directory); code != kExitOk) return code;
  }
  std::vector<std::string> others = {args.report_html, args.metric.write_metric, args.metric.write_sizing};
  if (args.stop_after == "layers") others.push_back(front_path(args.output));
  for (const std::string& path : others)
    if (!path.empty())
      if (const int code = check_output_file(args.command, path, false); code != kExitOk) return code;
  return kExitOk;
}

std::string front_path(const std::string& output) {
  const size_t slash = output.find_last_of('/');
  const size_t dot = output.find_last_of('.');
  const std::string stem = (dot == std::string::npos || (slash != std::string::npos && dot < slash))
                               ? output
                               : output.substr(0, dot);
  return stem + ".front.off";
}

std::vector<std::string> output_paths(const MeshArgs& args) {
  std::vector<std::string> paths{args.output};
  paths.insert(paths.end(), args.also_write.begin(), args.also_write.end());
  return paths;
}

int write_outputs(const MeshArgs& args, const VolumeMesh& mesh) {
  // Every output is attempted, so that one full disk or bad directory costs only its own file;
  // then the user is told plainly which files are complete.
  std::vector<std::string> written;
  int code = kExitOk;
  for (const std::string& path : output_paths(args)) {
    const Status s = write_volume_mesh(mesh, path, args.patch_names);
    if (s.ok()) {
      written.push_back(path);
      continue;
    }
    // The writers' own check of a mesh anitet made failing is a bug of anitet's, not the user's.
    const bool internal = s.code() == Error::InvalidMesh || s.code() == Error::BadIndex || s.code() == Error::InvalidArgument;
    std::cerr << "anitet " << args.command << ": " << (internal ? "internal error: " : "") << "cannot write '" << path
              << "': " << s.message() << "\n";
    if (code == kExitOk || internal) code = internal ? kExitInternal : kExitReadError;
  }
  if (code != kExitOk) {
    std::cerr << "anitet " << args.command << ": "
              << (written.empty() ? std::string("no output was written")
                                  : "written and complete: " + join_paths(written) + "; the others were not written")
              << "\n";
  }
  return code;
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
  if (args.command == "recover") return run_recover(args, checked);
  std::cerr << "anitet " << args.command << ": not implemented yet; '" << args.output
            << "' was not written\n";
  return kExitNotImplemented;
}

}  // namespace anitet::cli
