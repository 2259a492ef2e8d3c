// Surface validation: decides whether a triangulated surface bounds a volume the mesher can fill,
// applies the repairs that are safe, and reports every defect with its own error code.
//
// Checks, in order (each problem kind is counted in full; the first few instances are kept with
// element ids and coordinates):
//   invalid_argument, empty_input, bad_index - stop here: nothing else can be checked
//   (repair: merge duplicate vertices)
//   non_finite_coordinate              - geometric checks are skipped when present
//   degenerate_triangle                - repeated vertex, or three exactly collinear points
//   duplicate_triangle                 - same vertex set as a triangle with a smaller id
//   open_boundary / non_manifold_edge  - an edge with one / more than two triangles
//   inconsistent_orientation           - an edge used twice in the same direction (this includes
//                                        every non-manifold edge with 3+ triangles); also a
//                                        closed shell facing the wrong way when orient_shells
//                                        is off
//   non_manifold_vertex                - the corners around a vertex form more than one fan
//   self_intersection                  - two triangles of one shell meet beyond their shared
//                                        corners or edge (exact predicates; corners with equal
//                                        coordinates are shared; degenerate triangles and
//                                        duplicates are left out of this test)
//   intersecting_shells                - the same for two triangles of different shells
// Warnings: unreferenced vertices (kept: vertex ids stay stable).
//
// Repairs (applied to the surface in place, listed in the report):
//   - vertices with exactly equal coordinates are merged (the first one is kept, the others are
//     removed and the remaining ids compacted; report.vertex_map maps old ids to new ones);
//   - shells whose edges all have two triangles but whose neighbours disagree on orientation
//     are made consistent when they are orientable (the fewer triangles flipped; a
//     non-orientable shell is an error, non_orientable_shell, naming an edge);
//   - closed, consistently oriented shells are flipped to the expected orientation.
//
// Orientation rule. Shells are the connected components of triangles across edges. Every shell is
// oriented outward from the material it bounds: a shell contained in an even number of other
// closed shells (depth 0, 2, ...) bounds a body from outside and has positive signed volume; a
// shell at odd depth bounds a cavity and faces into the cavity (negative signed volume). Each
// body (even-depth shell) is a region; a cavity belongs to its parent's region.
//
// All element ids in the report refer to the surface after the repairs; the problems' messages
// number triangles and vertices from 1 (the examples' arrays are 0-based like every array).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/status.hpp"
#include "core/surface_mesh.hpp"

namespace anitet {

struct ValidationOptions {
  bool merge_duplicate_vertices = true;  // repair: merge vertices with exactly equal coordinates
  bool orient_triangles = true;          // repair: make orientable shells consistent (polygon soups)
  bool orient_shells = true;             // repair: flip closed shells oriented against the rule
  bool check_self_intersections = true;  // the (most expensive) exact intersection search
  size_t max_examples = 5;               // instances kept per problem kind
  int num_threads = 0;                   // 0: TBB's default; the report never depends on it
};

enum class Severity : uint8_t { Error, Warning };

// One instance of a problem: the elements involved and their coordinates.
struct ProblemExample {
  std::vector<uint32_t> triangles;
  std::vector<uint32_t> vertices;
  std::vector<std::array<double, 3>> points;  // coordinates of `vertices`, in the same order
};

struct Problem {
  Error code = Error::Ok;  // the error code; Error::Ok for warnings
  std::string kind;        // stable name: error_name(code), or e.g. "unreferenced_vertex"
  Severity severity = Severity::Error;
  size_t count = 0;        // total number of instances (edges, vertices, triangles or pairs)
  std::string message;     // human summary naming the first instance
  std::vector<ProblemExample> examples;
};

struct Repair {
  std::string kind;  // "merged_duplicate_vertices", "reoriented_triangles" or "flipped_shell"
  size_t count = 0;  // vertices removed, or triangles flipped
  std::string message;
};

struct ShellInfo {
  uint32_t first_triangle = 0;  // smallest triangle id of the shell (shells are numbered by it)
  size_t num_triangles = 0;
  bool closed = false;          // every edge has two triangles, oriented consistently
  bool flipped = false;         // reoriented by the repair
  int32_t parent = -1;          // innermost closed shell containing this one (-1: none)
  int32_t depth = 0;            // closed shells containing this one; odd = cavity boundary
  int32_t region = -1;          // region id (closed shells only)
  double signed_volume = 0.0;   // after the repair; floating point, for information
};

struct ValidationReport {
  std::vector<Problem> problems;  // errors then warnings, in check order; only kinds found
  std::vector<Repair> repairs;
  std::vector<ShellInfo> shells;
  size_t num_regions = 0;
  // Every intersecting triangle pair (i < j), sorted: self-intersections and shell crossings.
  std::vector<std::pair<uint32_t, uint32_t>> intersecting_pairs;
  std::vector<uint32_t> vertex_map;  // old -> new vertex id when vertices were merged, else empty

  bool ok() const;           // no error (warnings and repairs allowed)
  Status status() const;     // the first error, or success
  const Problem* find(const std::string& kind) const;
  size_t count(Error code) const;  // instances of an error kind (0 when absent)
  std::string summary() const;     // several lines for people
};

// Validates `surface` and applies the safe repairs to it.
ValidationReport validate_surface(SurfaceMesh& surface, const ValidationOptions& options = {});

// The report as JSON (machine-readable; stable keys).
std::string report_to_json(const ValidationReport& report, int indent = 2);

}  // namespace anitet
