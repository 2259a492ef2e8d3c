// Reading and validating an input surface, shared by check-surface, mesh and recover.
#pragma once

#include <string>

#include "core/surface_mesh.hpp"
#include "io/patch_names.hpp"
#include "validate/validate.hpp"

namespace anitet::cli {

struct CheckedSurface {
  SurfaceMesh surface;  // after the safe repairs
  ValidationReport report;
  PatchNames names;     // the patch names the file carries (SU2 markers), else empty
};

// Reads and validates `path`. Returns kExitOk, kExitReadError or kExitInvalidInput; on failure
// the reason, naming the file, is printed on stderr (prefixed with `command`), for an invalid
// surface only when print_invalid is set (else see print_invalid_surface).
int load_and_validate(const std::string& command, const std::string& path, CheckedSurface& out,
                      bool print_invalid = true);
void print_invalid_surface(const std::string& command, const std::string& path,
                           const ValidationReport& report);

// A readable report: counts, shells and nesting, repairs, problems with examples.
std::string describe_validation(const std::string& path, const CheckedSurface& checked);

}  // namespace anitet::cli
