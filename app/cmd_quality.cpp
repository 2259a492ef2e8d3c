#include <fstream>
#include <iostream>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "io/surface_io.hpp"
#include "io/volume_io.hpp"
#include "quality/quality_report.hpp"

namespace anitet::cli {

int run_quality(const QualityArgs& args) {
  Result<VolumeMesh> mesh = read_volume_mesh(args.mesh);
  if (!mesh.ok()) {
    std::cerr << "anitet quality: cannot read mesh '" << args.mesh << "': " << mesh.status().message()
              << " [" << error_name(mesh.status().code()) << "]\n";
    return kExitReadError;
  }
  SurfaceMesh surface;
  const bool have_surface = !args.surface.empty();
  if (have_surface) {
    Result<SurfaceMesh> read = read_surface(args.surface);
    if (!read.ok()) {
      std::cerr << "anitet quality: cannot read surface '" << args.surface
                << "': " << read.status().message() << " [" << error_name(read.status().code()) << "]\n";
      return kExitReadError;
    }
    surface = std::move(read).value();
  }
  QualityOptions options;
  options.match_tolerance = args.tolerance;
  Result<QualityReport> report = compute_quality_report(mesh.value(), have_surface ? &surface : nullptr, options);
  if (!report.ok()) {
    std::cerr << "anitet quality: cannot measure mesh '" << args.mesh << "': " << report.status().message()
              << " [" << error_name(report.status().code()) << "]\n";
    return kExitInvalidInput;
  }
  const QualityReport& r = report.value();
  if (!args.hist_csv.empty()) {
    std::ofstream out(args.hist_csv, std::ios::binary);
    out << quality_histogram_csv(r);
    out.close();
    if (!out) {
      std::cerr << "anitet quality: cannot write histogram '" << args.hist_csv << "'\n";
      return kExitReadError;
    }
  }
  if (args.json) {
    std::cout << quality_report_json(r) << "\n";
  } else {
    std::cout << "mesh file: " << args.mesh << "\n";
    if (have_surface) std::cout << "surface file: " << args.surface << "\n";
    std::cout << quality_report_text(r);
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

}  // namespace anitet::cli
