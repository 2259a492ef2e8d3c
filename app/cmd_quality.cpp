#include <filesystem>
#include <iostream>
#include <sstream>

#include "commands.hpp"
#include "cli_util.hpp"
#include "exit_codes.hpp"
#include "io/surface_io.hpp"
#include "io/volume_io.hpp"
#include "metric/sol_field.hpp"
#include "io/file_bytes.hpp"
#include "quality/html_report.hpp"
#include "quality/quality_report.hpp"

namespace anitet::cli {

int run_quality(const QualityArgs& args) {
  Result<VolumeMesh> mesh = read_volume_mesh(args.mesh);
  if (!mesh.ok()) {
    std::cerr << "anitet quality: cannot read mesh '" << args.mesh << "': " << mesh.status().message()
              << " [" << error_name(mesh.status().code()) << "]\n";
    return exit_code_of_read(mesh.status().code());
  }
  if (!args.metric_sol.empty()) {
    Result<metric::SolField> sol = metric::read_sol(args.metric_sol);
    if (!sol.ok()) {
      std::cerr << "anitet quality: cannot read metric '" << args.metric_sol << "': " << sol.status().message()
                << " [" << error_name(sol.status().code()) << "]\n";
      return exit_code_of_read(sol.status().code());
    }
    if (sol.value().num_vertices() != mesh.value().num_vertices()) {
      std::cerr << "anitet quality: metric '" << args.metric_sol << "' has " << sol.value().num_vertices()
                << " vertex values but mesh '" << args.mesh << "' has " << mesh.value().num_vertices()
                << " vertices\n";
      return kExitInvalidInput;
    }
    mesh.value().vertex_metric = std::move(sol).value().values;
  }
  SurfaceMesh surface;
  const bool have_surface = !args.surface.empty();
  if (have_surface) {
    Result<SurfaceMesh> read = read_surface(args.surface);
    if (!read.ok()) {
      std::cerr << "anitet quality: cannot read surface '" << args.surface
                << "': " << read.status().message() << " [" << error_name(read.status().code()) << "]\n";
      return exit_code_of_read(read.status().code());
    }
    surface = std::move(read).value();
  }
  QualityOptions options;
  options.match_tolerance = args.tolerance;
  QualityReport r;
  std::string report_line;  // what the HTML report holds, printed after the text report
  if (args.report_html.empty()) {
    Result<QualityReport> report = compute_quality_report(mesh.value(), have_surface ? &surface : nullptr, options);
    if (!report.ok()) {
      std::cerr << "anitet quality: cannot measure mesh '" << args.mesh << "': " << report.status().message()
                << " [" << error_name(report.status().code()) << "]\n";
      return kExitInvalidInput;
    }
    r = std::move(report).value();
  } else {
    HtmlReportOptions html_options;
    html_options.title = "anitet quality: " + std::filesystem::path(args.mesh).filename().string();
    html_options.mesh_name = args.mesh;
    html_options.surface_name = args.surface;
    for (size_t k = 0; k < 3 && k < args.cut.size(); ++k) html_options.cut[k] = args.cut[k];
    html_options.max_polygons_per_view = args.cut_max;
    Result<HtmlReport> html = quality_report_html(mesh.value(), have_surface ? &surface : nullptr, options, html_options);
    if (!html.ok()) {
      std::cerr << "anitet quality: cannot measure mesh '" << args.mesh << "': " << html.status().message()
                << " [" << error_name(html.status().code()) << "]\n";
      return kExitInvalidInput;
    }
    if (Status st = write_file_bytes(args.report_html, html.value().html); !st.ok()) {
      std::cerr << "anitet quality: cannot write report '" << args.report_html << "': " << st.message() << "\n";
      return kExitReadError;
    }
    const HtmlReport& h = html.value();
    std::ostringstream line;
    line << "html report: " << args.report_html << " (" << h.html.size() / 1024 << " KiB, " << h.seconds_html
         << " s after " << h.seconds_quality << " s of measures; cut views draw " << h.cut_polygons_drawn[0]
         << "/" << h.cut_polygons_total[0] << ", " << h.cut_polygons_drawn[1] << "/" << h.cut_polygons_total[1]
         << ", " << h.cut_polygons_drawn[2] << "/" << h.cut_polygons_total[2] << " cross-sections)\n";
    report_line = line.str();
    r = std::move(html).value().report;
  }
  if (!args.hist_csv.empty()) {
    if (Status st = write_file_bytes(args.hist_csv, quality_histogram_csv(r)); !st.ok()) {
      std::cerr << "anitet quality: cannot write histogram '" << args.hist_csv << "': " << st.message() << "\n";
      return kExitReadError;
    }
  }
  if (args.json) {
    std::cout << quality_report_json(r) << "\n";
  } else {
    std::cout << "mesh file: " << args.mesh << "\n";
    if (have_surface) std::cout << "surface file: " << args.surface << "\n";
    std::cout << quality_report_text(r) << report_line;
  }
  if (args.strict) {
    if (!r.valid) {
      std::cerr << "anitet quality: mesh '" << args.mesh << "' is invalid (" << r.nonpositive_tets
                << " non-positive tets, " << r.faces_shared_by_more_than_two
                << " faces shared by more than two tets)\n";
      return kExitInvalidInput;
    }
    if (have_surface && !r.surface.boundary_constrained) {
      std::cerr << "anitet quality: mesh '" << args.mesh << "' does not keep the surface '" << args.surface
                << "' (" << r.surface.input_triangles_missing << " input triangles missing, "
                << r.surface.boundary_faces_not_in_input << " extra boundary faces, "
                << r.surface.steiner_points_on_boundary << " Steiner points on the boundary, "
                << r.surface.vertices_on_input_surface << " other vertices on the surface)\n";
      return kExitInvalidInput;
    }
  }
  return kExitOk;
}


int run_report(QualityArgs& args) {
  if (args.report_html.empty()) {  // default: MESH with .html
    const std::filesystem::path p(args.mesh);
    args.report_html = (p.parent_path() / p.stem()).string() + ".html";
  }
  return run_quality(args);
}

CLI::App* add_quality_command(CLI::App& app, QualityArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "quality", "Quality report of a tetrahedral mesh, optionally against its input surface");
  cmd->add_option("MESH", args.mesh, "Mesh file (.mesh .meshb .msh .vtu, TetGen .node/.ele)")->required();
  cmd->add_option("--surface", args.surface,
                          "Input surface: check that the mesh keeps it (boundary constrained)");
  cmd->add_flag("--json", args.json, "Print the report as JSON");
  cmd->add_option("--hist", args.hist_csv, "Write the radius-ratio histogram as CSV here");
  cmd->add_option("--tol", args.tolerance,
                          "Relative tolerance for matching mesh vertices to input vertices "
                          "written with fewer digits (exact matches come first)")
      ->capture_default_str()
      ->check(non_negative());
  cmd->add_flag("--strict", args.strict,
                        "Exit 4 when the mesh is invalid or does not keep the surface");
  CLI::Option* report_opt = cmd->add_option(
      "--report", args.report_html, "Write a self-contained HTML report here (summary, histograms, cut views)");
  cmd->add_option("--cut", args.cut,
                          "Cut planes of the HTML report: x,y,z as fractions of the bounding box")
      ->expected(3)
      ->delimiter(',')
      ->capture_default_str()
      ->check(in_range(0.0, 1.0))
      ->needs(report_opt);
  cmd->add_option("--cut-max", args.cut_max,
                          "Cross-sections drawn per cut view at most (the ones nearest the centre)")
      ->capture_default_str()
      ->check(positive())
      ->needs(report_opt);
  cmd->add_option("--metric", args.metric_sol,
                  "Per-vertex .sol/.solb of MESH (sizes or tensors, as `mesh --write-metric` writes): the "
                  "report adds the UGAWG measures in it (edge lengths, share in [1/sqrt2, sqrt2], mean ratio)");
  cmd->footer(
      "Examples:\n"
      "  anitet quality part.mesh --surface part.stl         # valid? surface kept? shape figures\n"
      "  anitet quality part.mesh --strict --json            # exit 4 when invalid or not kept\n"
      "  anitet quality out.mesh --metric out.sol             # + UGAWG measures in the metric");
  return cmd;
}

CLI::App* add_report_command(CLI::App& app, QualityArgs& args) {
    CLI::App* cmd = app.add_subcommand(
      "report", "Write the self-contained HTML quality report of a mesh (histograms, cut views) and print the text report");
  cmd->add_option("MESH", args.mesh, "Mesh file (.mesh .meshb .msh .vtu, TetGen .node/.ele)")->required();
  cmd->add_option("--surface", args.surface, "Input surface: check that the mesh keeps it");
  cmd->add_option("-o,--output", args.report_html, "The HTML page (default: MESH with .html)");
  cmd->add_option("--cut", args.cut, "Cut planes: x,y,z as fractions of the bounding box")
      ->expected(3)
      ->delimiter(',')
      ->capture_default_str()
      ->check(in_range(0.0, 1.0));
  cmd->add_option("--cut-max", args.cut_max, "Cross-sections drawn per cut view at most")
      ->capture_default_str()
      ->check(positive());
  cmd->add_option("--metric", args.metric_sol,
                  "Per-vertex .sol/.solb of MESH: edge lengths in it, and the UGAWG measures");
  cmd->footer(
      "Examples:\n"
      "  anitet report part.mesh --surface part.stl          # writes part.html\n"
      "  anitet report part.mesh -o view.html --cut 0.5,0.3,0.5");
  return cmd;
}

}  // namespace anitet::cli
