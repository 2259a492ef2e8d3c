// Reading and validating an input surface, shared by check-surface, mesh and recover.
#pragma once

#include <string>

#include "core/surface_mesh.hpp"
#include "io/patch_names.hpp"
#include "validate/validate.hpp"

namespace anitet::cli {

struct CheckedSurface {
  bool read = false;    // the file was read (validation may still have failed)
  SurfaceMesh surface;  // after the safe repairs
  ValidationReport report;
  PatchNames names;     // the patch names the file carries (SU2 markers), else empty
};

// Reads and validates `path`. Returns kExitOk, or exit_code_of_read's code for a file that cannot
// be read (3 when it cannot be opened, 4 when it is malformed), or kExitInvalidInput; on failure
// the reason, naming the file, is printed on stderr (prefixed with `command`), for an invalid
// surface only when print_invalid is set (else see print_invalid_surface).
int load_and_validate(const std::string& command, const std::string& path, CheckedSurface& out,
                      bool print_invalid = true);
// The first error with the file lines of its triangles (when the reader knew them), then every
// error kind's count.
void print_invalid_surface(const std::string& command, const std::string& path, const CheckedSurface& checked);

// A readable report: counts, shells and nesting, repairs, problems with examples.
std::string describe_validation(const std::string& path, const CheckedSurface& checked);

}  // namespace anitet::cli
