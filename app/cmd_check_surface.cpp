#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "exit_codes.hpp"
#include "io/surface_io.hpp"
#include "surface_check.hpp"

namespace anitet::cli {

namespace {

std::string coords(const std::array<double, 3>& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.10g, %.10g, %.10g)", p[0], p[1], p[2]);
  return buf;
}

// An example for people: elements numbered from 1, with the file line of each triangle when the
// reader knew it.
std::string describe_example(const ProblemExample& e, const SurfaceMesh& s) {
  std::ostringstream os;
  if (!e.triangles.empty()) {
    os << "triangles";
    for (size_t i = 0; i < e.triangles.size(); ++i) {
      os << (i ? ", " : " ") << uint64_t{e.triangles[i]} + 1;
      if (e.triangles[i] < s.line.size()) os << " (line " << s.line[e.triangles[i]] << ")";
    }
  }
  if (!e.vertices.empty()) {
    os << (e.triangles.empty() ? "" : "; ") << "vertices";
    for (size_t i = 0; i < e.vertices.size(); ++i) {
      os << (i ? ", " : " ") << uint64_t{e.vertices[i]} + 1;
      if (i < e.points.size()) os << " " << coords(e.points[i]);
    }
  }
  return os.str();
}

// Line `line` (1-based) of the file, without its end; empty when it cannot be read.
std::string file_line(const std::string& path, uint32_t line) {
  std::ifstream in(path, std::ios::binary);
  std::string text;
  for (uint32_t n = 1; n <= line && std::getline(in, text); ++n) {
  }
  while (!text.empty() && (text.back() == '\r' || text.back() == ' ')) text.pop_back();
  return in ? text : std::string();
}

struct PatchCount {
  int32_t label = 0;
  size_t triangles = 0;
};

// The patch labels the triangles carry, in increasing order, with their triangle counts.
std::vector<PatchCount> patch_counts(const SurfaceMesh& s) {
  std::map<int32_t, size_t> count;
  for (int32_t p : s.patch) ++count[p];
  std::vector<PatchCount> out;
  for (const auto& [label, n] : count) out.push_back({label, n});
  return out;
}

}  // namespace

int load_and_validate(const std::string& command, const std::string& path, CheckedSurface& out,
                      bool print_invalid) {
  out.names.clear();
  Result<SurfaceMesh> read = read_surface(path, &out.names);
  if (!read.ok()) {
    std::cerr << "anitet " << command << ": cannot read surface '" << path << "': "
              << read.status().message() << " [" << error_name(read.status().code()) << "]\n";
    return exit_code_of_read(read.status().code());
  }
  out.read = true;
  out.surface = std::move(read).value();
  out.report = validate_surface(out.surface);
  if (!out.report.ok()) {
    if (print_invalid) print_invalid_surface(command, path, out);
    return kExitInvalidInput;
  }
  return kExitOk;
}

void print_invalid_surface(const std::string& command, const std::string& path, const CheckedSurface& checked) {
  const ValidationReport& report = checked.report;
  const Status st = report.status();
  std::cerr << "anitet " << command << ": invalid surface '" << path << "': " << st.message() << " ["
            << error_name(st.code()) << "]\n";
  // The first error's triangles where they are in the file: PATH:LINE: triangle K: the line.
  for (const Problem& p : report.problems) {
    if (p.severity != Severity::Error) continue;
    std::vector<uint32_t> shown;
    for (const ProblemExample& e : p.examples)
      for (uint32_t t : e.triangles) {
        if (t >= checked.surface.line.size() || shown.size() == 4) continue;
        if (std::find(shown.begin(), shown.end(), t) != shown.end()) continue;
        shown.push_back(t);
        const uint32_t line = checked.surface.line[t];
        std::cerr << "  " << path << ":" << line << ": triangle " << uint64_t{t} + 1 << ": " << file_line(path, line)
                  << "\n";
      }
    break;
  }
  for (const Problem& p : report.problems) {
    if (p.severity == Severity::Error) std::cerr << "  " << p.kind << ": " << p.count << "\n";
  }
}

std::string describe_validation(const std::string& path, const CheckedSurface& checked) {
  const ValidationReport& r = checked.report;
  std::ostringstream os;
  os << "surface: " << path << "\n";
  os << "  " << checked.surface.num_vertices() << " vertices, " << checked.surface.num_triangles()
     << " triangles\n";
  size_t closed = 0;
  for (const ShellInfo& s : r.shells) closed += s.closed;
  os << "  shells: " << r.shells.size() << " (" << closed << " closed), regions: " << r.num_regions
     << "\n";
  constexpr size_t kMaxShells = 10;
  for (size_t i = 0; i < r.shells.size() && i < kMaxShells; ++i) {
    const ShellInfo& s = r.shells[i];
    os << "    shell " << i << ": " << s.num_triangles << " triangles from triangle " << s.first_triangle
       << ", " << (s.closed ? "closed" : "open");
    if (s.closed) {
      os << ", depth " << s.depth << (s.depth % 2 ? " (cavity)" : " (body)");
      if (s.parent >= 0) os << " inside shell " << s.parent;
      os << ", region " << s.region << ", signed volume " << s.signed_volume;
    }
    if (s.flipped) os << ", reoriented";
    os << "\n";
  }
  if (r.shells.size() > kMaxShells) os << "    ... " << r.shells.size() - kMaxShells << " more shells\n";
  if (r.repairs.empty()) {
    os << "  repairs: none\n";
  } else {
    os << "  repairs:\n";
    for (const Repair& rep : r.repairs) {
      os << "    " << (rep.message.empty() ? rep.kind + " (" + std::to_string(rep.count) + ")" : rep.message)
         << "\n";
    }
  }
  if (r.problems.empty()) {
    os << "  problems: none\n";
  } else {
    os << "  problems:\n";
    for (const Problem& p : r.problems) {
      os << "    " << p.kind << (p.severity == Severity::Error ? " (error)" : " (warning)") << ": "
         << p.count << " in total";
      if (!p.message.empty()) os << " - " << p.message;
      os << "\n";
      for (size_t i = 0; i < p.examples.size(); ++i) {
        os << "      #" << i + 1 << " " << describe_example(p.examples[i], checked.surface) << "\n";
      }
      if (p.count > p.examples.size()) os << "      ... " << p.count - p.examples.size() << " more\n";
    }
  }
  os << "  result: " << (r.ok() ? "OK" : "INVALID") << "\n";
  return os.str();
}

int run_check_surface(const CheckSurfaceArgs& args) {
  if (!args.output.empty()) {
    if (Result<SurfaceFormat> f = surface_format_from_path(args.output);
        !f.ok() || !(f.value() == SurfaceFormat::Off || f.value() == SurfaceFormat::Obj ||
                     f.value() == SurfaceFormat::Stl || f.value() == SurfaceFormat::Medit)) {
      std::cerr << "anitet check-surface: cannot write '" << args.output
                << "': the repaired surface is written as .off, .obj, .stl or .mesh\n";
      return kExitUsage;
    }
    if (const int code = check_output_file("check-surface", args.output); code != kExitOk) return code;
  }
  CheckedSurface checked;
  const int code = load_and_validate("check-surface", args.input, checked, false);
  if (!checked.read) return code;
  const std::vector<PatchCount> patches = patch_counts(checked.surface);
  bool written = false;
  if (!args.output.empty() && code == kExitOk) {
    if (Status st = write_surface(checked.surface, args.output); !st.ok()) {
      std::cerr << "anitet check-surface: " << st.message() << "\n";
      return kExitReadError;
    }
    written = true;
  }
  if (args.json) {
    nlohmann::json j = nlohmann::json::parse(report_to_json(checked.report), nullptr, false);
    if (j.is_discarded() || !j.is_object()) j = nlohmann::json::object();
    j["file"] = args.input;
    j["vertices"] = checked.surface.num_vertices();
    j["triangles"] = checked.surface.num_triangles();
    nlohmann::json list = nlohmann::json::array();
    for (const PatchCount& p : patches)
      list.push_back({{"label", p.label}, {"name", patch_name(checked.names, p.label)}, {"named", checked.names.count(p.label) > 0}, {"triangles", p.triangles}});
    j["patches"] = list;
    j["written"] = written ? nlohmann::json(args.output) : nlohmann::json(nullptr);
    j["ok"] = checked.report.ok();
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << describe_validation(args.input, checked);
    std::cout << "  patches:";
    for (const PatchCount& p : patches) {
      const auto named = checked.names.find(p.label);
      std::cout << " " << p.label << (named != checked.names.end() ? " '" + named->second + "'" : std::string()) << " ("
                << p.triangles << " triangles)" << (&p == &patches.back() ? "" : ",");
    }
    std::cout << "\n";
    if (written) std::cout << "  repaired surface written: " << args.output << "\n";
  }
  std::cout.flush();  // the report first, then the verdict on stderr
  if (code == kExitInvalidInput) {
    print_invalid_surface("check-surface", args.input, checked);
    if (!args.output.empty()) std::cerr << "anitet check-surface: '" << args.output << "' not written: the surface is invalid\n";
  }
  return code;
}


CLI::App* add_check_surface_command(CLI::App& app, CheckSurfaceArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "check-surface", "Read and validate a triangulated surface; report problems and safe repairs");
  cmd->add_option("IN", args.input,
                  "Surface (.off .obj .stl .ply .mesh .meshb .msh .su2), or a volume mesh whose boundary "
                  "triangles are the surface (.mesh .meshb .msh .vtu .su2 .node/.ele)")
      ->required();
  cmd->add_option("-o,--output", args.output,
                        "Write the surface after the safe repairs (merged vertices, reoriented triangles and "
                        "shells) here when it is valid: .off, .obj, .stl (float: lossy) or .mesh (keeps patch labels)");
  cmd->add_flag("--json", args.json, "Print the report as JSON");
  cmd->footer(
      "Examples:\n"
      "  anitet check-surface part.stl                     # what is wrong, with element numbers\n"
      "  anitet check-surface soup.stl -o repaired.mesh    # the repaired surface, patches kept");
  return cmd;
}

}  // namespace anitet::cli
