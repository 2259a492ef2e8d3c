// Per-vertex solution files: Medit .sol (ASCII) and GMF .solb (binary, gmf_format.hpp), each a
// SolAtVertices block of any number of fields (scalar 1, vector 2, symmetric tensor 3).
#pragma once

#include <string>
#include <string_view>

#include "core/status.hpp"
#include "core/vertex_fields.hpp"
#include "io/gmf_format.hpp"

namespace anitet {

// ASCII Medit .sol: "MeshVersionFormatted v", "Dimension 3", "SolAtVertices / n / k t1 .. tk /
// n lines of values", "End", or Dimension 2 (VertexFields::dimension 2, the 2D mesher's fields);
// '#' comments; other keywords skipped up to the next keyword.
// Error::Parse naming the line for malformed or truncated input, Error::UnsupportedFormat for
// another dimension, a full-matrix field (type 4) or binary bytes, Error::EmptyInput without
// SolAtVertices.
Result<VertexFields> read_medit_sol(std::string_view data, const std::string& name);
// The same text: MeshVersionFormatted 2, Dimension 3, SolAtVertices (one line per vertex, every
// double written so that it reads back to the same bits), End. Error::InvalidArgument for no
// field or values that are not a whole number of records.
Result<std::string> to_sol(const VertexFields& fields);

// By extension: .sol (ASCII) or .solb (binary; `info` receives its version and byte order), 3D
// only. Error::UnsupportedFormat for another extension or a 2D file, Error::FileNotFound when it
// cannot be read.
Result<VertexFields> read_vertex_fields(const std::string& path, GmfFileInfo* info = nullptr);
// By extension: .sol, or .solb in `gmf_version` (0: automatic, see to_gmf_mesh).
Status write_vertex_fields(const VertexFields& fields, const std::string& path, int gmf_version = 0);

// True for a path ending in .sol or .solb (case-insensitive).
bool is_sol_path(const std::string& path);

}  // namespace anitet
