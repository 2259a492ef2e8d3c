// What `mesh` and `recover` share: their output paths checked before any work, the meshes written
// to every output, the patch names checked, and the recovery options.
#include <iostream>
#include <set>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "io/file_bytes.hpp"
#include "io/volume_io.hpp"
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
    if (is_pvtu_path(path)) {
      if (distributed_run() && path == args.output && args.stop_after.empty()) continue;
      std::cerr << "anitet " << args.command << ": cannot write '" << path
                << "': a .pvtu (one piece per rank) is written by anitet-mpi as its -o output; "
                   "`anitet merge` joins the pieces into any other format\n";
      return kExitUsage;
    }
    if (Status s = check_writable_volume_path(path); !s.ok()) {
      std::cerr << "anitet " << args.command << ": cannot write '" << path << "': " << s.message() << "\n";
      return s.code() == Error::NotImplemented ? kExitNotImplemented : kExitUsage;
    }
  }
  for (const std::string& path : output_paths(args)) {
    const bool directory = !is_pvtu_path(path) && volume_format_from_path(path).value() == VolumeFormat::OpenFoam;
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
    const Status s = write_volume_mesh(mesh, path, args.patch_names, args.patch_types);
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
  std::set<int32_t> labels(input.surface.patch.begin(), input.surface.patch.end());
  labels.insert(extra_labels.begin(), extra_labels.end());
  if (!args.patch_types_spec.empty()) {
    Result<PatchTypes> types = parse_patch_types(args.patch_types_spec);
    if (!types.ok()) {
      std::cerr << cmd << ": --patch-types: " << types.status().message() << "\n";
      return kExitUsage;
    }
    for (const auto& [label, kind] : types.value())
      if (!labels.count(label)) {
        std::cerr << cmd << ": --patch-types: no triangle of '" << args.input << "' has the patch label " << label
                  << " (given the type " << patch_kind_name(kind) << ")\n";
        return kExitUsage;
      }
    args.patch_types = std::move(types).value();
  }
  if (args.patch_names_spec.empty()) return kExitOk;
  Result<PatchNames> names = parse_patch_names(args.patch_names_spec);
  if (!names.ok()) {
    std::cerr << cmd << ": --patch-names: " << names.status().message() << "\n";
    return kExitUsage;
  }
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

void add_mesh_io_options(CLI::App* cmd, MeshArgs& args) {
  const char* io = "Input and output";
  cmd->add_option("IN", args.input,
                  "Closed surface (.off .obj .stl .ply .mesh .meshb .msh .su2), or a volume mesh whose "
                  "boundary triangles are the surface (.mesh .meshb .msh .vtu .su2 .node/.ele)")
      ->required();
  cmd->add_option("-o,--output", args.output,
                  "Output mesh: .mesh .meshb .msh .vtu, or for solvers .su2 (SU2), .cgns (CGNS), .exo/.e "
                  "(Exodus II), or a directory path ending in polyMesh (OpenFOAM: CASE/constant/polyMesh)")
      ->required()
      ->group(io);
  cmd->add_option("--also-write", args.also_write,
                  "Also write the same mesh to this file, any output format; repeat for more (-o case.cgns "
                  "--also-write case.su2)")
      ->group(io);
  cmd->add_option("--patch-names", args.patch_names_spec,
                  "Names of the input's patch labels, LABEL=NAME,... (1=wall,2=farfield); unnamed labels "
                  "are patch<label>. A name: 1-32 letters, digits or '_', starting with a letter. Used as "
                  "SU2 markers, OpenFOAM patches, CGNS and Exodus names, Gmsh physical names. The name "
                  "implies the patch's type unless --patch-types gives it")
      ->group(io);
  cmd->add_option("--patch-types", args.patch_types_spec,
                  "Types of the patch labels, LABEL=TYPE,... (2=inlet,3=outlet): wall, inlet, outlet, farfield, "
                  "symmetry or patch. OpenFOAM gets wall, patch (inlet, outlet, farfield, patch) or "
                  "symmetryPlane; CGNS BCWall, BCInflow, BCOutflow, BCFarfield, BCSymmetryPlane, BCGeneral; "
                  "Exodus a side-set property of that name. Unlisted labels: from the name ('inlet', "
                  "'inflow', 'outlet', 'outflow', 'farfield', 'symmetry' in it, any case), else wall")
      ->group(io);
  cmd->add_flag("-q,--quiet", args.quiet, "Print nothing but errors")->group(io);
  cmd->add_option("--recovery", args.recovery,
                  "Stage 2 recovery strategies: all (split constraints, then the fuzzy-face ones when it "
                  "fails), split (split constraints only: fast, every decision combinatorial) or fuzzy")
      ->capture_default_str()
      ->check(CLI::IsMember({"all", "split", "fuzzy"}))
      ->group("Stages");
}

}  // namespace anitet::cli
