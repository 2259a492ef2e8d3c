// The subcommands of the `anitet` tool. Each returns the process exit code (exit_codes.hpp),
// prints results on stdout and errors (naming the file) on stderr, and never throws.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/sizing.hpp"
#include "core/surface_mesh.hpp"
#include "core/tet_mesh.hpp"
#include "core/volume_mesh.hpp"
#include "io/patch_names.hpp"
#include "adapt/adapt.hpp"
#include "layers/layers.hpp"
#include "optimize/optimize.hpp"
#include "refine/refine.hpp"
#include "recovery/recovery.hpp"
#include "metric_options.hpp"
#include "surface_check.hpp"

namespace anitet::cli {

// The whole tool: parses the arguments, runs a subcommand, returns the exit code; never throws.
int cli_main(int argc, char** argv);

// Each command registers its subcommand and options on `app` (filling `args`, which must outlive
// the parse) in the file that runs it: cmd_check_surface.cpp, cmd_quality.cpp (quality and
// report), cmd_mesh.cpp, cmd_recover.cpp; the options mesh and recover share are outputs.cpp's.

// Set by the MPI driver (mpi/main_mpi.cpp) before cli_main: `anitet mesh` then runs stages 3b/3c
// through `stage3` (one part per rank), and only rank 0 writes the mesh and prints the report.
// With a `.pvtu` output, `stage3_parts` runs instead: no rank ever holds the whole mesh, each
// writes its piece of `output` (the boundary triangles from `surface`), and the coarse mesh is
// left with no tet; rank 0 prints a short report.
// The pipeline's anisotropic cycles (MesherOptions::anisotropic_cycles, _cycle_gain and
// _cycle_optimizer_gain), which the rounds in parts run too; `run` gets the cycles that ran.
struct CycleOptions {
  int cycles = 0;
  double gain = 0.0, optimizer_gain = 0.0;
  int* run = nullptr;
};
struct DistributedRun {
  int rank = 0, ranks = 1;
  std::function<Status(TetMesh& mesh, const SizingField& field, const RefineOptions& refine_options,
                       const OptimizeOptions& optimize_options, const CycleOptions& cycles, RefineStats& refine,
                       OptimizeStats& optimize)>
      stage3;
  std::function<Status(TetMesh& mesh, const SizingField& field, const RefineOptions& refine_options,
                       const OptimizeOptions& optimize_options, const CycleOptions& cycles, const SurfaceMesh& surface,
                       const std::string& output, RefineStats& refine, OptimizeStats& optimize)>
      stage3_parts;
};
// Whether an output path names a .pvtu index (the pieces' output of anitet-mpi).
bool is_pvtu_path(const std::string& path);
void set_distributed_run(const DistributedRun* run);
const DistributedRun* distributed_run();  // null in the serial tool

struct CheckSurfaceArgs {
  std::string input;
  std::string output;  // -o: the repaired surface (.off .obj .stl .mesh); empty: none
  bool json = false;
};
CLI::App* add_check_surface_command(CLI::App& app, CheckSurfaceArgs& args);
int run_check_surface(const CheckSurfaceArgs& args);

struct QualityArgs {
  std::string mesh;
  std::string surface;    // empty: no input surface
  std::string hist_csv;   // empty: no histogram file
  double tolerance = 1e-9;
  bool json = false;
  bool strict = false;    // exit 4 when the mesh is invalid or not boundary constrained
  std::string report_html;            // empty: no HTML report
  std::vector<double> cut{0.5, 0.5, 0.5};  // cut planes of the HTML report (bounding-box fractions)
  size_t cut_max = 25000;             // cross-sections drawn per cut view at most
  std::string metric_sol;             // per-vertex .sol of MESH: edge lengths of the report in it
};
CLI::App* add_quality_command(CLI::App& app, QualityArgs& args);
CLI::App* add_report_command(CLI::App& app, QualityArgs& args);
int run_quality(const QualityArgs& args);
// `report`: run_quality with the HTML page at MESH with .html unless -o names it.
int run_report(QualityArgs& args);

// `adapt` (cmd_adapt.cpp): a volume mesh adapted to a metric, fields carried over.
struct AdaptArgs {
  std::string input, output, metric;
  std::vector<std::string> fields;  // --field: carried to OUTSTEM.FIELDFILE
  std::string write_metric;         // --write-metric: the metric at OUT's vertices (.sol/.solb)
  std::string report_html;          // --report: the HTML quality report of OUT
  bool keep_surface = false;
  double ridge_angle = 45.0;
  int max_cycles = AdaptOptions().max_cycles;
  bool quiet = false, json = false, verbose = false;
};
CLI::App* add_adapt_command(CLI::App& app, AdaptArgs& args);
int run_adapt(const AdaptArgs& args);

// `mesh` and `recover` (recover uses the input, output and recovery options only).
struct MergeArgs {
  std::string input;   // the .pvtu index
  std::string output;  // -o: any volume format
};
CLI::App* add_merge_command(CLI::App& app, MergeArgs& args);
int run_merge(const MergeArgs& args);

struct MeshArgs {
  std::string command;  // "mesh" or "recover", for messages
  std::string input;
  std::string output;
  std::vector<std::string> also_write;  // --also-write: more outputs of the same mesh (any format)
  std::string report_html;              // --report (mesh): the HTML quality report, with the run's figures
  std::vector<double> report_cut{0.5, 0.5, 0.5};  // its cut planes
  bool quiet = false;
  bool json = false;
  std::string stop_after;               // "" (the whole pipeline) or "layers"
  int layers = 1;                       // --front-layers: stage 1 layer count
  int deprecated_layers = 0;            // --layers, the old name of --front-layers (0: not given)
  bool verbose = false;                 // -v: every stage's figures and the full quality report
  double max_tets = -1;                 // --max-tets (-1: from free memory; 0: no limit)
  double attempts_seconds = 240;        // MesherOptions::attempts_seconds
  bool no_layer_retries = false;        // !MesherOptions::retry_layer_counts
  std::string layer_scheme = "push";    // "push" (prism layers) or "faces" (the paper's)
  size_t push_tasks_min_vertices = LayersOptions().push_tasks_min_vertices;
  std::vector<int> bl_patches;          // boundary-layer walls (patch labels); empty: none
  std::vector<int> bl_slide_patches;    // patches the walls may meet, re-triangulated (labels)
  double bl_first_height = 0.0;         // h0 (given, or from --bl-yplus)
  double bl_yplus = 0.0;                // y+ of the first layer (0: not given)
  double bl_reynolds = 0.0;             // Reynolds number on bl_ref_length, for bl_yplus
  double bl_ref_length = 0.0;           // reference length of bl_reynolds
  double bl_growth = 1.2;               // r
  int bl_layers = 10;                   // n
  std::string bl_cells = "tets";         // how BL prisms are written: "tets" (3 each) or "prisms"
  std::string bl_columns;                // --bl-columns: the BL columns as CSV (empty: none)
  bool bl_mitre = false;                 // --bl-mitre (BoundaryLayerOptions::mitre)
  double bl_sizing_growth = 0.0;        // MesherOptions::boundary_layer_sizing_growth
  bool bl_sizing = false;               // interior sizes continue the BL (MesherOptions::boundary_layer_sizing)
  double size = 1.0;                    // global scale of the sizing field (2: twice as coarse)
  bool no_refine = false;               // skip refinement/coarsening (stage 3b)
  bool no_optimize = false;             // skip CVT, flips and sliver removal (stage 3c)
  int anisotropic_cycles = 2;           // MesherOptions::anisotropic_cycles
  MetricCliOptions metric;              // --metric, --hmin/--hmax/--hgrad, --geodetic, ... (mesh)
  std::string recovery = "all";         // stage 2 strategies: all (split, then fuzzy), split, fuzzy
  std::string patch_names_spec;         // --patch-names "1=wall,2=farfield"
  PatchNames patch_names;               // parsed by check_output_options
  std::string patch_types_spec;         // --patch-types "2=inlet,3=outlet"
  PatchTypes patch_types;               // parsed by check_patch_names
  int threads = 0;                      // --threads (0: all cores)
};
CLI::App* add_mesh_command(CLI::App& app, MeshArgs& args);
CLI::App* add_recover_command(CLI::App& app, MeshArgs& args);
// -o, --also-write, -q, --recovery, --patch-names: registered on both.
void add_mesh_io_options(CLI::App* cmd, MeshArgs& args);
// `mesh`: the options that need the parse (combinations, --bl-yplus), then the pipeline or
// --stop-after layers.
int run_mesh(const CLI::App& cmd, MeshArgs& args);
// `recover`: read, validate, stage 2 alone, write.
int run_recover(MeshArgs& args);
// The recovery options --recovery asks for.
RecoveryOptions recovery_options(const MeshArgs& args);
// Before any work: every file the command will write (-o, --also-write, --report,
// --write-metric, --write-sizing, the front of --stop-after layers) has a format that can be
// written and can be created (io's check_can_create). Returns kExitOk, or after printing the
// reason kExitUsage for a format that cannot be written, kExitNotImplemented for .cgns/.exo in a
// build without the library, kExitReadError for a file that cannot be created.
int check_output_paths(const MeshArgs& args);
// Before any work, for any command: `path` (a file, or a directory a writer creates) can be
// created: kExitOk, else the reason printed and kExitReadError.
int check_output_file(const std::string& command, const std::string& path, bool directory = false);
// The front surface `mesh --stop-after layers` writes beside OUT: "out/t1.mesh" -> "out/t1.front.off".
std::string front_path(const std::string& output);
// -o and every --also-write, in that order.
std::vector<std::string> output_paths(const MeshArgs& args);
// Writes mesh to every output path; kExitOk, or kExitReadError after printing which failed.
int write_outputs(const MeshArgs& args, const VolumeMesh& mesh);
// After reading the surface: args.patch_names gets the names the file carries (SU2 markers),
// then those of --patch-names, which may name only labels the surface has (or one of
// `extra_labels`, e.g. the S1 patch of --stop-after layers); no two labels may share a name.
// --patch-types is parsed there too (labels the surface has).
// Returns kExitOk, or kExitUsage after printing the reason.
int check_patch_names(MeshArgs& args, const CheckedSurface& input, const std::vector<int32_t>& extra_labels = {});
// `mesh`: the whole pipeline (cmd_mesh.cpp).
int run_mesh_pipeline(MeshArgs& args);
// `mesh --stop-after layers`: stage 1 alone (cmd_layers.cpp).
int run_mesh_layers(MeshArgs& args);

}  // namespace anitet::cli
