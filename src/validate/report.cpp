// ValidationReport accessors, the text summary and the JSON form.
#include <cmath>
#include <nlohmann/json.hpp>

#include "validate/validate.hpp"

namespace anitet {

bool ValidationReport::ok() const {
  for (const Problem& p : problems) {
    if (p.severity == Severity::Error) return false;
  }
  return true;
}

Status ValidationReport::status() const {
  for (const Problem& p : problems) {
    if (p.severity == Severity::Error) return Status(p.code, p.message);
  }
  return Status::success();
}

const Problem* ValidationReport::find(const std::string& kind) const {
  for (const Problem& p : problems) {
    if (p.kind == kind) return &p;
  }
  return nullptr;
}

size_t ValidationReport::count(Error code) const {
  size_t n = 0;
  for (const Problem& p : problems) {
    if (p.severity == Severity::Error && p.code == code) n += p.count;
  }
  return n;
}

std::string ValidationReport::summary() const {
  std::string out = ok() ? "surface is valid" : "surface is NOT valid";
  size_t closed = 0;
  for (const ShellInfo& sh : shells) closed += sh.closed ? 1 : 0;
  out += ": " + std::to_string(shells.size()) + " shells (" + std::to_string(closed) +
         " closed), " + std::to_string(num_regions) + " regions\n";
  for (const Problem& p : problems) {
    out += p.severity == Severity::Error ? "  error " : "  warning ";
    out += p.kind + ": " + p.message + "\n";
  }
  for (const Repair& r : repairs) out += "  repaired " + r.kind + ": " + r.message + "\n";
  for (size_t i = 0; i < shells.size(); ++i) {
    const ShellInfo& sh = shells[i];
    if (!sh.closed || sh.depth == 0) continue;
    out += "  shell " + std::to_string(i) + " lies inside shell " + std::to_string(sh.parent) +
           (sh.depth % 2 ? " (bounds a cavity)" : " (a body inside a cavity)") + "\n";
  }
  return out;
}

namespace {

nlohmann::json number(double x) {
  if (std::isfinite(x)) return x;
  return nullptr;  // JSON has no NaN/Inf
}

}  // namespace

std::string report_to_json(const ValidationReport& report, int indent) {
  using nlohmann::json;
  json j;
  j["ok"] = report.ok();
  const Status st = report.status();
  j["status"] = {{"code", static_cast<int>(st.code())},
                 {"name", error_name(st.code())},
                 {"message", st.message()}};
  j["problems"] = json::array();
  for (const Problem& p : report.problems) {
    json jp = {{"kind", p.kind},
               {"code", static_cast<int>(p.code)},
               {"severity", p.severity == Severity::Error ? "error" : "warning"},
               {"count", p.count},
               {"message", p.message}};
    jp["examples"] = json::array();
    for (const ProblemExample& ex : p.examples) {
      json points = json::array();
      for (const auto& q : ex.points) points.push_back({number(q[0]), number(q[1]), number(q[2])});
      jp["examples"].push_back(
          {{"triangles", ex.triangles}, {"vertices", ex.vertices}, {"points", points}});
    }
    j["problems"].push_back(jp);
  }
  j["repairs"] = json::array();
  for (const Repair& r : report.repairs) {
    j["repairs"].push_back({{"kind", r.kind}, {"count", r.count}, {"message", r.message}});
  }
  j["shells"] = json::array();
  for (const ShellInfo& sh : report.shells) {
    j["shells"].push_back({{"first_triangle", sh.first_triangle},
                           {"num_triangles", sh.num_triangles},
                           {"closed", sh.closed},
                           {"flipped", sh.flipped},
                           {"parent", sh.parent},
                           {"depth", sh.depth},
                           {"region", sh.region},
                           {"signed_volume", number(sh.signed_volume)}});
  }
  j["num_regions"] = report.num_regions;
  j["intersecting_pairs"] = json::array();
  for (const auto& pr : report.intersecting_pairs) {
    j["intersecting_pairs"].push_back({pr.first, pr.second});
  }
  j["vertices_merged"] = !report.vertex_map.empty();
  return j.dump(indent);
}

}  // namespace anitet
