#include "fuzz_entry.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <set>
#include <string>

#include "anitet.h"
#include "io/gmf_format.hpp"
#include "io/surface_io.hpp"
#include "io/volume_io.hpp"
#include "mesh2d/domain.hpp"
#include "mesh2d/pslg_io.hpp"
#include "mesh2d/stages.hpp"
#include "metric/sol_field.hpp"
#include "validate/validate.hpp"

namespace anitet::fuzz {
namespace {

// The `name` given to the readers; every error message must contain it.
constexpr const char* kName = "fuzz-input";

// Surfaces larger than this are read but not validated: the fuzzer's time goes to the readers.
constexpr size_t kMaxValidatedTriangles = 256;

[[noreturn]] void broken(const char* target, const std::string& what) {
  std::fprintf(stderr, "fuzz target %s: contract broken: %s\n", target, what.c_str());
  std::fflush(stderr);
  std::abort();
}

std::string_view text(const uint8_t* data, size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

bool one_of(Error code, std::initializer_list<Error> codes) {
  return std::find(codes.begin(), codes.end(), code) != codes.end();
}

// A reader's error: a code of its header's list, and a message naming the input.
void check_read_error(const char* target, const Status& s) {
  // OutOfMemory: catch_bad_alloc's answer to an allocation failure (reader_util.hpp).
  if (!one_of(s.code(), {Error::Parse, Error::BadIndex, Error::EmptyInput,
                         Error::UnsupportedFormat, Error::OutOfMemory})) {
    broken(target, std::string("undocumented error ") + error_name(s.code()) + ": " + s.message());
  }
  if (s.message().find(kName) == std::string::npos) {
    broken(target, "the message does not name the input: " + s.message());
  }
}

// What validation may answer (validate.hpp: one code per defect kind).
bool validation_code(Error code) {
  return code == Error::Ok || code == Error::EmptyInput ||
         (int32_t(code) <= int32_t(Error::NonFiniteCoordinate) && int32_t(code) >= int32_t(Error::BadIndex));
}

// A surface reader's result, then the validation and repairs the CLI runs next on it.
void check_surface(const char* target, Result<SurfaceMesh> read) {
  if (!read.ok()) return check_read_error(target, read.status());
  SurfaceMesh mesh = std::move(read).value();
  if (Status s = check_surface_arrays(mesh); !s.ok()) broken(target, "read surface: " + s.message());
  if (mesh.num_triangles() == 0) broken(target, "a surface without triangles, not EmptyInput");
  if (mesh.num_triangles() > kMaxValidatedTriangles) return;
  ValidationOptions options;
  options.num_threads = 1;
  const ValidationReport report = validate_surface(mesh, options);
  const Status status = report.status();
  if (!validation_code(status.code())) {
    broken(target, std::string("validation answered ") + error_name(status.code()));
  }
  if (!status.ok() && status.message().empty()) broken(target, "validation error without message");
  if (Status s = check_surface_arrays(mesh); !s.ok()) broken(target, "repaired surface: " + s.message());
  (void)report_to_json(report);
}

void check_volume(const char* target, const Result<VolumeMesh>& read) {
  if (!read.ok()) return check_read_error(target, read.status());
  const VolumeMesh& mesh = read.value();
  if (Status s = check_volume_arrays(mesh); !s.ok()) broken(target, "read mesh: " + s.message());
  if (mesh.num_tets() == 0) broken(target, "a mesh without tets, not EmptyInput");
}

// TetGen's three files in one input: .node, .ele and .face separated by NUL bytes (a missing
// part is empty; the .face part keeps any further NULs).
void tetgen(const uint8_t* data, size_t size) {
  std::string_view parts[3];
  std::string_view rest = text(data, size);
  for (int i = 0; i < 2; ++i) {
    const size_t nul = rest.find('\0');
    parts[i] = rest.substr(0, nul);
    rest = nul == std::string_view::npos ? std::string_view() : rest.substr(nul + 1);
  }
  parts[2] = rest;
  check_volume("tetgen", read_tetgen(parts[0], parts[1], parts[2], kName));
}

void sol(const uint8_t* data, size_t size) {
  const Result<metric::SolField> read = metric::parse_sol(text(data, size), kName);
  if (!read.ok()) {
    // EmptyInput: no SolAtVertices (sol_io.hpp); OutOfMemory: catch_bad_alloc (reader_util.hpp).
    if (!one_of(read.status().code(), {Error::Parse, Error::UnsupportedFormat, Error::EmptyInput, Error::OutOfMemory}) ||
        read.status().message().find(kName) == std::string::npos) {
      broken("sol", std::string(error_name(read.status().code())) + ": " + read.status().message());
    }
    return;
  }
  const metric::SolField& f = read.value();
  // Sizes (1) or tensors: 6 in 3D, 3 in 2D (the 2D mesher's xx xy yy).
  const int tensor = f.dimension == 2 ? 3 : 6;
  if ((f.dimension != 2 && f.dimension != 3) || (f.components != 1 && f.components != tensor))
    broken("sol", "dimension " + std::to_string(f.dimension) + ", components " + std::to_string(f.components));
  if (f.values.size() % size_t(f.components) != 0) broken("sol", "values not a multiple of components");
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

// Binary Medit (.meshb and .solb share the format): the volume, surface and solution readers on
// each input; what reads is written again in the version read and must read back the same.
void gmf(const uint8_t* data, size_t size) {
  const std::string_view bytes = text(data, size);
  check_volume("gmf", read_meshb_volume(bytes, kName));
  check_surface("gmf", read_meshb_surface(bytes, kName));
  GmfFileInfo info;
  const Result<GmfMesh> mesh = read_gmf_mesh(bytes, kName, &info);
  if (!mesh.ok()) {
    check_read_error("gmf", mesh.status());
  } else {
    const Result<std::string> again = to_gmf_mesh(mesh.value(), info.version);
    if (!again.ok()) broken("gmf", "a mesh read cannot be written: " + again.status().message());
    const Result<GmfMesh> back = read_gmf_mesh(again.value(), kName);
    if (!back.ok() || back->tet != mesh->tet || back->tri != mesh->tri || back->tet_ref != mesh->tet_ref ||
        !same_bits(back->xyz, mesh->xyz)) {
      broken("gmf", "a mesh written again does not read back the same");
    }
  }
  const Result<VertexFields> sol = read_solb(bytes, kName, &info);
  if (!sol.ok()) return check_read_error("gmf", sol.status());
  if (sol->record_size() == 0 || sol->values.size() % sol->record_size() != 0) broken("gmf", "fields of no whole records");
  const Result<std::string> again = to_solb(sol.value(), info.version);
  const Result<VertexFields> back = again.ok() ? read_solb(again.value(), kName) : again.status();
  if (!back.ok() || back->kinds != sol->kinds || !same_bits(back->values, sol->values)) {
    broken("gmf", "fields written again do not read back the same");
  }
}

// ------------------------------------------------------------------------------------------------
// The C ABI's surface input: the bytes decoded into caller arrays for anitet_surface_create, then
// anitet_surface_validate and the queries, each answer checked against include/anitet.h.

class Bytes {
 public:
  Bytes(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  template <class T>
  T raw() {
    uint8_t b[sizeof(T)];
    for (uint8_t& x : b) x = byte();
    T v;
    std::memcpy(&v, b, sizeof v);
    return v;
  }

 private:
  const uint8_t* data_;
  size_t size_, pos_ = 0;
};

// Mostly small grid values (coincident points, coplanar and degenerate triangles), sometimes
// non-finite, huge, tiny or arbitrary ones.
double coordinate(Bytes& in) {
  const uint8_t c = in.byte();
  if (c < 0xe0) return double(int(c % 9) - 4) * (c < 0x70 ? 1.0 : 0.25);
  switch (c) {
    case 0xe0: return std::numeric_limits<double>::quiet_NaN();
    case 0xe1: return std::numeric_limits<double>::infinity();
    case 0xe2: return -std::numeric_limits<double>::infinity();
    case 0xe3: return std::numeric_limits<double>::max();
    case 0xe4: return -std::numeric_limits<double>::max();
    case 0xe5: return std::numeric_limits<double>::denorm_min();
    case 0xe6: return 1e300;
    case 0xe7: return -1e-300;
    default: break;
  }
  if (c < 0xf0) return in.raw<double>();
  return 1e-12 * double(int(c) - 0xf7);  // next to 0: near-duplicate points
}

// Mostly indices near [base, base + n) (one below and one above it included), sometimes the
// extremes of int32_t or arbitrary values.
int32_t index(Bytes& in, int64_t n, int32_t base) {
  const uint8_t c = in.byte();
  if (c < 0xf8) return int32_t(int64_t(c) % (n + 2) - 1 + base);
  switch (c) {
    case 0xf8: return std::numeric_limits<int32_t>::max();
    case 0xf9: return std::numeric_limits<int32_t>::min();
    case 0xfa: return -1;
    default: return in.raw<int32_t>();
  }
}

[[noreturn]] void capi_broken(const std::string& what, int code) {
  broken("capi_surface", what + " (code " + std::to_string(code) + " " +
                             anitet_error_name(code) + ": " + anitet_last_error_message() + ")");
}

void expect_ok(const char* call, int code) {
  if (code != ANITET_OK) capi_broken(std::string(call) + " failed", code);
}

void capi_surface(const uint8_t* data, size_t size) {
  Bytes in(data, size);
  const uint8_t flags = in.byte();
  const uint8_t more = in.byte();
  int32_t base = flags & 1;
  if (flags & 0x80) base = int8_t(in.byte());  // mostly not 0 or 1: INVALID_ARGUMENT
  const bool with_patch = flags & 2;
  const bool null_xyz = flags & 4, null_tri = flags & 8, negative = flags & 16;

  const int64_t np = in.byte() % 48, nt = in.byte() % 96;
  std::vector<double> xyz(size_t(3 * np));
  for (double& x : xyz) x = coordinate(in);
  std::vector<int32_t> tri(size_t(3 * nt));
  for (int32_t& v : tri) v = index(in, np, base);
  std::vector<int32_t> patch(static_cast<size_t>(nt));
  for (int32_t& p : patch) p = int8_t(in.byte());

  // The answer the header promises for these arguments.
  const bool indices_in_range = std::all_of(tri.begin(), tri.end(), [&](int32_t v) {
    return int64_t(v) - base >= 0 && int64_t(v) - base < np;
  });
  int expected = ANITET_OK;
  if (base != 0 && base != 1) expected = ANITET_ERR_INVALID_ARGUMENT;
  else if (negative && (np > 0 || nt > 0)) expected = ANITET_ERR_INVALID_ARGUMENT;
  else if (np == 0 || nt == 0) expected = ANITET_ERR_EMPTY_INPUT;
  else if (null_xyz || null_tri) expected = ANITET_ERR_INVALID_ARGUMENT;
  else if (!indices_in_range) expected = ANITET_ERR_BAD_INDEX;

  // docs/c-api.md: the handle is set to NULL on failure, so start from something else.
  static char not_a_surface;
  anitet_surface* surface = reinterpret_cast<anitet_surface*>(&not_a_surface);
  const int created =
      anitet_surface_create(null_xyz ? nullptr : xyz.data(), negative ? -np : np,
                            null_tri ? nullptr : tri.data(), negative ? -nt : nt,
                            with_patch ? patch.data() : nullptr, base, &surface);
  if (created != expected) capi_broken("anitet_surface_create: expected " + std::to_string(expected), created);
  if (created != ANITET_OK) {
    if (surface != nullptr) capi_broken("anitet_surface_create failed but set *out", created);
    if (*anitet_last_error_message() == '\0') capi_broken("an error without message", created);
    anitet_surface_destroy(surface);  // NULL is accepted
    return;
  }

  // The copy is exact.
  int64_t cp = -1, ct = -1;
  expect_ok("anitet_surface_get_counts", anitet_surface_get_counts(surface, &cp, &ct));
  if (cp != np || ct != nt) capi_broken("counts differ from the input", ANITET_OK);
  std::vector<double> xyz_out(xyz.size());
  expect_ok("anitet_surface_get_points",
            anitet_surface_get_points(surface, xyz_out.data(), int64_t(xyz_out.size())));
  if (std::memcmp(xyz.data(), xyz_out.data(), xyz.size() * sizeof(double)) != 0) {
    capi_broken("points differ from the input", ANITET_OK);
  }
  std::vector<int32_t> tri_out(tri.size());
  expect_ok("anitet_surface_get_triangles",
            anitet_surface_get_triangles(surface, tri_out.data(), int64_t(tri_out.size()), base));
  if (tri_out != tri) capi_broken("triangles differ from the input", ANITET_OK);
  const int short_buffer = anitet_surface_get_triangles(surface, tri_out.data(), int64_t(tri.size()) - 1, 0);
  if (short_buffer != ANITET_ERR_BUFFER_TOO_SMALL) capi_broken("short triangle buffer", short_buffer);

  // Validation (one thread: the report must not depend on it, and the fuzzer runs many).
  anitet_options options = ANITET_OPTIONS_INIT;
  options.num_threads = 1;
  options.merge_duplicate_vertices = more & 1;
  options.orient_shells = (more >> 1) & 1;
  options.check_self_intersections = (more >> 2) & 1;
  const int validated = anitet_surface_validate(surface, &options);
  if (validated != ANITET_OK && !(validated <= ANITET_ERR_NON_FINITE_COORDINATE &&
                                  validated >= ANITET_ERR_BAD_INDEX)) {
    capi_broken("anitet_surface_validate answered an undocumented code", validated);
  }
  if (validated != ANITET_OK) {
    if (*anitet_last_error_message() == '\0') capi_broken("an error without message", validated);
    int64_t count = 0;
    expect_ok("anitet_surface_problem_count", anitet_surface_problem_count(surface, validated, &count));
    if (count < 1) capi_broken("the error's problem count is 0", validated);
  }

  // After the repairs: indices still name vertices.
  expect_ok("anitet_surface_get_counts", anitet_surface_get_counts(surface, &cp, &ct));
  tri_out.assign(size_t(3 * ct), 0);
  expect_ok("anitet_surface_get_triangles",
            anitet_surface_get_triangles(surface, tri_out.data(), int64_t(tri_out.size()), 1));
  for (int32_t v : tri_out) {
    if (v < 1 || v > cp) capi_broken("a repaired triangle refers to vertex " + std::to_string(v), ANITET_OK);
  }

  int64_t needed = 0;
  expect_ok("anitet_surface_validation_json", anitet_surface_validation_json(surface, nullptr, 0, &needed));
  std::string json(size_t(needed), '\x7f');
  expect_ok("anitet_surface_validation_json",
            anitet_surface_validation_json(surface, json.data(), needed, &needed));
  if (needed < 1 || std::strlen(json.c_str()) + 1 != size_t(needed)) {
    capi_broken("the JSON report's size", ANITET_OK);
  }
  anitet_surface_destroy(surface);
}

// A 2D reader's result (mesh2d/pslg_io.hpp); then, for small inputs, the input's checks and
// stages 1-2 with the coupling: either a documented refusal naming the file, or a valid
// triangulation in which every segment is an edge.
void check_pslg(const char* target, Result<mesh2d::Pslg> read) {
  if (!read.ok()) {
    const Status& s = read.status();
    if (!one_of(s.code(), {Error::Parse, Error::BadIndex, Error::EmptyInput, Error::UnsupportedFormat,
                           Error::InvalidArgument, Error::OutOfMemory}))
      broken(target, std::string("undocumented error ") + error_name(s.code()) + ": " + s.message());
    if (s.message().find(kName) == std::string::npos) broken(target, "the message does not name the input: " + s.message());
    return;
  }
  const mesh2d::Pslg& p = read.value();
  if (p.label.size() != p.num_segments()) broken(target, "one label per segment");
  for (uint32_t v : p.seg)
    if (v >= p.num_points()) broken(target, "a segment refers to a missing point");
  if (p.num_segments() > 64) return;
  Result<mesh2d::Domain> d = mesh2d::analyse_domain(p);
  if (!d.ok()) {
    const Status& s = d.status();
    if (!one_of(s.code(), {Error::NonFiniteCoordinate, Error::BadIndex, Error::InvalidArgument, Error::DuplicatePoint,
                           Error::OpenBoundary, Error::SelfIntersection, Error::EmptyInput, Error::RecoveryFailed}))
      broken(target, std::string("the checks answered ") + error_name(s.code()) + ": " + s.message());
    if (s.message().find(kName) == std::string::npos) broken(target, "the check does not name the input: " + s.message());
    return;
  }
  mesh2d::StageStats stats;
  Result<mesh2d::Triangulation> m = mesh2d::boundary_constrained_triangulation(p, d.value(), mesh2d::FrontOptions{}, &stats);
  if (!m.ok()) {
    // The one refusal past the checks: a domain narrower beside a segment than stage 1's precision.
    const Status& s = m.status();
    if (s.code() == Error::InvalidArgument && s.message().find("the precision stage 1 needs") != std::string::npos &&
        s.message().find(kName) != std::string::npos)
      return;
    broken(target, "stages 1-2 failed on a checked input: " + s.message());
  }
  if (Status s = mesh2d::check_triangulation(m.value()); !s.ok()) broken(target, "stages 1-2: " + s.message());
  for (size_t i = 0; i < p.num_segments(); ++i) {
    uint32_t t;
    int k;
    if (!mesh2d::find_edge_of_points(m.value(), p.seg[2 * i], p.seg[2 * i + 1], t, k))
      broken(target, "segment " + std::to_string(i) + " is no edge after stages 1-2");
  }
}

}  // namespace

const std::vector<Target>& targets() {
  // Readers of the same format share a target (one corpus): medit and gmsh run the surface and
  // the volume reader on each input.
  static const std::vector<Target> all = {
      {"off", [](const uint8_t* d, size_t n) { check_surface("off", read_off(text(d, n), kName)); }},
      {"obj", [](const uint8_t* d, size_t n) { check_surface("obj", read_obj(text(d, n), kName)); }},
      {"stl",
       [](const uint8_t* d, size_t n) {
         PatchNames names;
         Result<SurfaceMesh> mesh = read_stl(text(d, n), kName, &names);
         check_surface("stl", mesh);
         // The solid names made patch names: valid, unique, each for a label the triangles have.
         std::set<std::string> seen;
         for (const auto& [label, name] : names) {
           if (Status s = check_patch_name(name); !s.ok()) broken("stl", "solid " + name + ": " + s.message());
           if (!seen.insert(name).second) broken("stl", "two labels named " + name);
           if (!mesh.ok() || std::find(mesh->patch.begin(), mesh->patch.end(), label) == mesh->patch.end()) {
             broken("stl", "name " + name + " for label " + std::to_string(label) + ", which no triangle has");
           }
         }
       }},
      {"ply", [](const uint8_t* d, size_t n) { check_surface("ply", read_ply(text(d, n), kName)); }},
      {"medit",
       [](const uint8_t* d, size_t n) {
         check_surface("medit", read_medit_surface(text(d, n), kName));
         check_volume("medit", read_medit_volume(text(d, n), kName));
       }},
      {"gmsh",
       [](const uint8_t* d, size_t n) {
         check_surface("gmsh", read_gmsh_surface(text(d, n), kName));
         check_volume("gmsh", read_gmsh_volume(text(d, n), kName));
       }},
      {"su2",
       [](const uint8_t* d, size_t n) {
         PatchNames names;
         check_surface("su2", read_su2_surface(text(d, n), kName, &names));
         for (const auto& entry : names) {
           if (Status s = check_patch_name(entry.second); !s.ok()) {
             broken("su2", "marker " + entry.second + ": " + s.message());
           }
         }
       }},
      {"tetgen", tetgen},
      {"vtu", [](const uint8_t* d, size_t n) { check_volume("vtu", read_vtu(text(d, n), kName)); }},
      {"sol", sol},
      {"gmf", gmf},
      {"capi_surface", capi_surface},
      {"poly", [](const uint8_t* d, size_t n) { check_pslg("poly", mesh2d::parse_poly(text(d, n), kName)); }},
      {"geojson", [](const uint8_t* d, size_t n) { check_pslg("geojson", mesh2d::parse_geojson(text(d, n), kName)); }},
      {"medit2d", [](const uint8_t* d, size_t n) { check_pslg("medit2d", mesh2d::parse_medit2d_pslg(text(d, n), kName)); }},
  };
  return all;
}

const Target* find_target(std::string_view name) {
  for (const Target& t : targets()) {
    if (name == t.name) return &t;
  }
  return nullptr;
}

}  // namespace anitet::fuzz
