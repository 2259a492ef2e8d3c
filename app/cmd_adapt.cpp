// `anitet adapt IN -o OUT --metric M [--field F]...`: anisotropic adaptation of a volume mesh to a
// metric (adapt/adapt.hpp), the fields carried to the new mesh (metric/field_transfer.hpp).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "adapt/adapt.hpp"
#include "cli_util.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"
#include "io/file_bytes.hpp"
#include "io/sol_io.hpp"
#include "io/volume_io.hpp"
#include "metric/field_transfer.hpp"
#include "metric/metric_field.hpp"
#include "metric/sol_field.hpp"
#include "quality/html_report.hpp"
#include "quality/quality_report.hpp"

namespace anitet::cli {

namespace {

// Where a carried field goes: beside OUT, "OUTSTEM.FIELDNAME" (p2.meshb and --field sol.solb:
// p2.sol.solb).
std::string field_output(const std::string& out, const std::string& field) {
  const std::filesystem::path o(out);
  return (o.parent_path() / (o.stem().string() + "." + std::filesystem::path(field).filename().string())).string();
}

std::string fixed3(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", x);
  return buf;
}

// The run's figures for the HTML report's "Meshing run" table.
std::vector<std::pair<std::string, std::string>> run_rows(const AdaptStats& s) {
  return {{"input", std::to_string(s.vertices_in) + " vertices, " + std::to_string(s.tets_in) + " tets"},
          {"cycles", std::to_string(s.cycles)},
          {"splits (on the surface)", std::to_string(s.splits) + " (" + std::to_string(s.surface_splits) + ")"},
          {"collapses (on the surface)", std::to_string(s.collapses) + " (" + std::to_string(s.surface_collapses) + ")"},
          {"swaps (on the surface)", std::to_string(s.swaps) + " (" + std::to_string(s.surface_swaps) + ")"},
          {"moves (on the surface)", std::to_string(s.moves) + " (" + std::to_string(s.surface_moves) + ")"},
          {"time", fixed3(s.seconds_total) + " s"}};
}

struct LoadedField {
  std::string path, output;
  VertexFields fields;
};

}  // namespace

int run_adapt(const AdaptArgs& args) {
  const std::string me = "anitet adapt";
  if (Status st = check_writable_volume_path(args.output); !st.ok()) {
    std::cerr << me << ": -o '" << args.output << "': " << st.message() << "\n";
    return st.code() == Error::NotImplemented ? kExitNotImplemented : kExitUsage;
  }
  if (const int code = check_output_file("adapt", args.output); code != kExitOk) return code;
  if (!args.report_html.empty())
    if (const int code = check_output_file("adapt", args.report_html); code != kExitOk) return code;
  if (!args.write_metric.empty()) {
    if (!is_sol_path(args.write_metric)) {
      std::cerr << me << ": --write-metric '" << args.write_metric << "': expected a .sol or .solb file\n";
      return kExitUsage;
    }
    if (const int code = check_output_file("adapt", args.write_metric); code != kExitOk) return code;
  }
  std::vector<LoadedField> fields;
  for (const std::string& f : args.fields) {
    if (!is_sol_path(f)) {
      std::cerr << me << ": --field '" << f << "': expected a .sol or .solb file\n";
      return kExitUsage;
    }
    LoadedField lf;
    lf.path = f;
    lf.output = field_output(args.output, f);
    if (lf.output == f || lf.output == args.output) {
      std::cerr << me << ": --field '" << f << "' would be overwritten by its own output '" << lf.output << "'\n";
      return kExitUsage;
    }
    if (const int code = check_output_file("adapt", lf.output); code != kExitOk) return code;
    fields.push_back(std::move(lf));
  }
  Result<VolumeMesh> in = read_volume_mesh(args.input);
  if (!in.ok()) {
    std::cerr << me << ": cannot read mesh '" << args.input << "': " << in.status().message() << " ["
              << error_name(in.status().code()) << "]\n";
    return in.status().code() == Error::FileNotFound ? kExitReadError : kExitInvalidInput;
  }
  const size_t nv = in.value().num_vertices();
  for (LoadedField& lf : fields) {
    Result<VertexFields> r = read_vertex_fields(lf.path);
    if (!r.ok()) {
      std::cerr << me << ": cannot read field '" << lf.path << "': " << r.status().message() << "\n";
      return r.status().code() == Error::FileNotFound ? kExitReadError : kExitInvalidInput;
    }
    if (r.value().num_vertices() != nv) {
      std::cerr << me << ": field '" << lf.path << "' has " << r.value().num_vertices() << " vertex records but mesh '"
                << args.input << "' has " << nv << " vertices: a field on another mesh\n";
      return kExitInvalidInput;
    }
    lf.fields = std::move(r).value();
  }
  AdaptOptions options;
  options.keep_surface = args.keep_surface;
  options.ridge_angle_deg = args.ridge_angle;
  options.max_cycles = args.max_cycles;
  ProgressLine bar(!args.quiet && !args.json);
  options.progress = [&](const std::string& stage, double fraction) { return bar.update(stage, fraction); };
  if (args.verbose) options.log = [](const std::string& line) { std::cerr << "  " << line << "\n"; };
  Result<AdaptResult> result = Status(Error::Internal, "not run");
  if (is_sol_path(args.metric)) {
    Result<metric::SolField> sol = metric::read_sol(args.metric);
    if (!sol.ok()) {
      std::cerr << me << ": cannot read metric '" << args.metric << "': " << sol.status().message() << "\n";
      return sol.status().code() == Error::FileNotFound ? kExitReadError : kExitInvalidInput;
    }
    if (sol.value().num_vertices() != nv) {
      std::cerr << me << ": metric '" << args.metric << "' has " << sol.value().num_vertices()
                << " vertex values but mesh '" << args.input << "' has " << nv << " vertices\n";
      return kExitInvalidInput;
    }
    result = adapt_mesh(in.value(), sol.value().values, options);
  } else if (lower_extension(args.metric) == "vdb") {
    Result<metric::MetricField> f = metric::read_metric_vdb(args.metric);
    if (!f.ok()) {
      std::cerr << me << ": cannot read metric '" << args.metric << "': " << f.status().message() << "\n";
      return f.status().code() == Error::FileNotFound ? kExitReadError : kExitInvalidInput;
    }
    result = adapt_mesh(in.value(), f.value(), options);
  } else {
    std::cerr << me << ": --metric '" << args.metric << "': expected a .sol, .solb or .vdb file\n";
    return kExitUsage;
  }
  bar.update("done", 1.0);
  if (!result.ok()) {
    const Error e = result.status().code();
    std::cerr << me << ": '" << args.input << "' with metric '" << args.metric << "': " << result.status().message()
              << "\n";
    return e == Error::InvalidArgument || e == Error::InvalidMesh || e == Error::EmptyInput ? kExitInvalidInput
                                                                                              : kExitInternal;
  }
  AdaptResult& r = result.value();
  // Fields carried before anything is written: a field that cannot be carried leaves no file.
  std::vector<VertexFields> carried_fields;
  for (const LoadedField& lf : fields) {
    Result<VertexFields> carried = metric::transfer_fields(in.value(), lf.fields, r.mesh.xyz);
    if (!carried.ok()) {
      std::cerr << me << ": cannot carry field '" << lf.path << "': " << carried.status().message() << "\n";
      return kExitInvalidInput;
    }
    carried_fields.push_back(std::move(carried).value());
  }
  VolumeMesh out = r.mesh;
  out.vertex_metric.clear();  // the mesh file holds no metric
  if (Status st = write_volume_mesh(out, args.output); !st.ok()) {
    std::cerr << me << ": cannot write '" << args.output << "': " << st.message() << "\n";
    return kExitReadError;
  }
  if (!args.write_metric.empty()) {
    if (Status st = write_sol(r.mesh, args.write_metric); !st.ok()) {
      std::cerr << me << ": cannot write '" << args.write_metric << "': " << st.message() << "\n";
      return kExitReadError;
    }
  }
  for (size_t i = 0; i < fields.size(); ++i)
    if (Status st = write_vertex_fields(carried_fields[i], fields[i].output); !st.ok()) {
      std::cerr << me << ": cannot write '" << fields[i].output << "': " << st.message() << "\n";
      return kExitReadError;
    }
  const AdaptStats& s = r.stats;
  // The output measured in the metric carried to its vertices (the UGAWG measures).
  MetricQuality measures;
  if (args.json || !args.quiet || !args.report_html.empty()) {
    QualityReport q;
    if (args.report_html.empty()) {
      Result<QualityReport> qr = compute_quality_report(r.mesh, nullptr);
      if (!qr.ok()) {
        std::cerr << me << ": cannot measure '" << args.output << "': " << qr.status().message() << "\n";
        return kExitInternal;
      }
      q = std::move(qr).value();
    } else {
      HtmlReportOptions html;
      html.title = "anitet adapt: " + std::filesystem::path(args.output).filename().string();
      html.mesh_name = args.output;
      html.run_rows = run_rows(r.stats);
      Result<HtmlReport> h = quality_report_html(r.mesh, nullptr, QualityOptions(), html);
      if (!h.ok()) {
        std::cerr << me << ": cannot measure '" << args.output << "': " << h.status().message() << "\n";
        return kExitInternal;
      }
      if (Status st = write_file_bytes(args.report_html, h.value().html); !st.ok()) {
        std::cerr << me << ": cannot write report '" << args.report_html << "': " << st.message() << "\n";
        return kExitReadError;
      }
      q = std::move(h).value().report;
    }
    measures = q.metric;
  }
  if (args.json) {
    nlohmann::ordered_json fj = nlohmann::ordered_json::array();
    for (const LoadedField& lf : fields) fj.push_back({{"input", lf.path}, {"output", lf.output}});
    nlohmann::ordered_json j = {
        {"ok", true},
        {"input", args.input},
        {"output", args.output},
        {"vertices", s.vertices_out},
        {"tets", s.tets_out},
        {"boundary_triangles", s.boundary_triangles_out},
        {"input_mesh", {{"vertices", s.vertices_in}, {"tets", s.tets_in}, {"boundary_triangles", s.boundary_triangles_in}}},
        {"features", {{"ridge_edges", s.ridge_edges}, {"corners", s.corners}}},
        {"cycles", s.cycles},
        {"operations",
         {{"splits", s.splits}, {"surface_splits", s.surface_splits}, {"splits_in_thirds", s.splits_in_thirds},
          {"collapses", s.collapses}, {"surface_collapses", s.surface_collapses}, {"swaps", s.swaps}, {"surface_swaps", s.surface_swaps},
          {"moves", s.moves}, {"surface_moves", s.surface_moves}, {"splits_refused", s.split_refused},
          {"collapses_refused", s.collapse_refused}}},
        {"seconds",
         {{"total", s.seconds_total}, {"setup", s.seconds_setup}, {"split", s.seconds_split},
          {"collapse", s.seconds_collapse}, {"swap", s.seconds_swap}, {"smooth", s.seconds_smooth},
          {"output", s.seconds_output}}},
        {"metric", nlohmann::ordered_json::parse(metric_quality_json(measures))},
        {"fields", fj}};
    if (!args.report_html.empty()) j["report"] = args.report_html;
    std::cout << j.dump(1) << "\n";
  } else if (!args.quiet) {
    std::cout << me << ": wrote '" << args.output << "': " << s.vertices_out << " vertices, " << s.tets_out << " tets, "
              << s.boundary_triangles_out << " boundary triangles (from " << s.vertices_in << ", " << s.tets_in << ", "
              << s.boundary_triangles_in << ")\n"
              << "  " << s.cycles << " cycles: " << s.splits << " splits (" << s.surface_splits << " on the surface), "
              << s.collapses << " collapses (" << s.surface_collapses << "), " << s.swaps << " swaps ("
              << s.surface_swaps << "), " << s.moves << " moves (" << s.surface_moves << "); " << s.ridge_edges
              << " ridge edges and " << s.corners << " corners in the input\n"
              << "  time: " << format_seconds(s.seconds_total) << " (setup " << fixed3(s.seconds_setup) << " s, split "
              << fixed3(s.seconds_split) << " s, collapse " << fixed3(s.seconds_collapse) << " s, swap "
              << fixed3(s.seconds_swap) << " s, smooth " << fixed3(s.seconds_smooth) << " s, output "
              << fixed3(s.seconds_output) << " s)\n"
              << metric_quality_text(measures, args.verbose);
    for (const LoadedField& lf : fields) std::cout << "  field '" << lf.path << "' carried to '" << lf.output << "'\n";
    if (!args.report_html.empty()) std::cout << "  html report: " << args.report_html << "\n";
  }
  return kExitOk;
}

CLI::App* add_adapt_command(CLI::App& app, AdaptArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "adapt", "Adapt a volume mesh to a metric (anisotropic): split, collapse, swap and move in the metric, the "
               "surface too (on its smooth reconstruction), fields carried over");
  cmd->add_option("input", args.input, "Volume mesh (.mesh .meshb .msh .vtu .su2)")->required();
  cmd->add_option("-o,--output", args.output, "Output mesh (.mesh .meshb .msh .vtu .su2 ...)")->required();
  cmd->add_option("--metric", args.metric,
                  "The metric: a .sol/.solb at the input's vertices (sizes or tensors xx xy yy xz yz zz), or a .vdb")
      ->required();
  cmd->add_option("--field", args.fields,
                  "A .sol/.solb of fields at the input's vertices, carried to the output's (written beside it as "
                  "OUTSTEM.FIELDFILE, e.g. p2.sol.solb); repeatable");
  cmd->add_option("--write-metric", args.write_metric,
                  "Also write the metric at the output's vertices (.sol/.solb; interpolated from --metric)");
  cmd->add_flag("--keep-surface", args.keep_surface,
                "Keep the input's boundary triangles exactly: no point added, moved or removed on the surface");
  cmd->add_option("--ridge-angle", args.ridge_angle,
                  "Boundary edges whose faces meet at a dihedral angle over this (degrees) are ridges")
      ->capture_default_str()
      ->check(in_range(0.0, 180.0));
  cmd->add_option("--max-cycles", args.max_cycles,
                  "Refinement/coarsening cycles at most (each: splits, collapses, swaps, moves); they stop "
                  "earlier when a cycle changes fewer than 0.1% of the tets, or when its splits and collapses "
                  "are over 90% of those five cycles before (they undo each other)")
      ->capture_default_str()
      ->check(in_range(0, 1000));
  cmd->add_option("--report", args.report_html,
                  "Also write the HTML quality report of the output, with the UGAWG measures in the metric");
  cmd->add_flag("-q,--quiet", args.quiet, "Print nothing but errors");
  cmd->add_flag("--json", args.json, "Print the result as JSON");
  cmd->add_flag("-v,--verbose", args.verbose, "Print a line per sweep on stderr (operations, tets, time) and the histograms of the measures");
  cmd->footer(
      "Examples:\n"
      "  anitet adapt in.meshb -o out.meshb --metric in.solb\n"
      "  anitet adapt p1.mesh -o p2.mesh --metric m1.sol --field u1.solb   (writes p2.u1.solb)\n"
      "  anitet adapt in.mesh -o out.mesh --metric m.sol --keep-surface");
  return cmd;
}

}  // namespace anitet::cli
