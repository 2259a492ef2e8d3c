#include "mesh2d/mesher2.hpp"

#include <chrono>
#include <memory>

#include "mesh2d/conforming.hpp"
#include "mesh2d/domain.hpp"

namespace anitet::mesh2d {

namespace {

using Clock = std::chrono::steady_clock;

// With points allowed on segments: at each input point whose angle between two segments (on the
// domain's side) is below 60 degrees, the segments there are split at one distance from it (half
// the shortest of them, at most the size there), so that the triangle in the corner is isosceles
// and the mesh around it can be good (the corner's own angle cannot be improved).
size_t split_at_small_angles(Triangulation& m, const Pslg& p, VertexMetrics& vm, std::vector<uint8_t>& fixed) {
  Kernel kernel(m);
  std::vector<uint32_t> fan;
  size_t splits = 0;
  for (uint32_t v = 0; v < p.num_points(); ++v) {
    if (m.vtri[v] == kNone) continue;
    m.star(v, fan);
    // The constrained edges at v, in the fan's order, and the angle between consecutive ones.
    std::vector<uint32_t> ends;
    for (uint32_t t : fan) {
      const int i = m.index_of(t, v);
      if (m.constrained(t, (i + 2) % 3)) ends.push_back(m.v(t, (i + 1) % 3));
    }
    if (!fan.empty()) {
      const uint32_t t = fan.back();
      const int i = m.index_of(t, v);
      if (m.constrained(t, (i + 1) % 3)) ends.push_back(m.v(t, (i + 2) % 3));
    }
    if (ends.size() < 2) continue;
    const double* o = m.point(v);
    double smallest = M_PI, shortest = 1e300;
    for (size_t k = 0; k < ends.size(); ++k) {
      const double* a = m.point(ends[k]);
      shortest = std::min(shortest, std::hypot(a[0] - o[0], a[1] - o[1]));
      const double* b = m.point(ends[(k + 1) % ends.size()]);
      const double ang = std::atan2((a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]),
                                    (a[0] - o[0]) * (b[0] - o[0]) + (a[1] - o[1]) * (b[1] - o[1]));
      if (ang > 0) smallest = std::min(smallest, ang);
    }
    if (smallest >= M_PI / 3) continue;
    const double h = 1.0 / std::sqrt(std::max(vm.at[v].xx, vm.at[v].yy));
    const double d = std::min(0.5 * shortest, h);
    for (uint32_t e : ends) {
      const double* a = m.point(e);
      const double len = std::hypot(a[0] - o[0], a[1] - o[1]);
      if (len < 1.5 * d) continue;
      uint32_t t;
      int k;
      if (!m.find_edge(v, e, t, k) && !m.find_edge(e, v, t, k)) continue;
      const double q[2] = {o[0] + d / len * (a[0] - o[0]), o[1] + d / len * (a[1] - o[1])};
      Location loc;
      loc.t = t, loc.kind = Location::OnEdge, loc.k = k;
      const Metric2 mq = metric_at(vm.field, q[0], q[1]);
      if (kernel.insert(q, loc, vm.anisotropic ? &mq : nullptr, true) == kNone) continue;
      vm.at.push_back(mq);
      fixed.push_back(1);  // the corner's shell stays put
      ++splits;
    }
  }
  return splits;
}

// The output: vertices in no triangle (collapsed) dropped, the input's points first; each
// triangle's attribute from its face in the input's classification.
TriMesh2 extract(const Triangulation& m, const Pslg& p, const Domain& d, const VertexMetrics& vm) {
  TriMesh2 out;
  out.input_points = p.num_points();
  std::vector<uint32_t> id(m.num_vertices(), kNone);
  for (uint32_t v = 0; v < m.num_vertices(); ++v)
    if (v < p.num_points() || m.vtri[v] != kNone) {
      id[v] = uint32_t(out.xy.size() / 2);
      out.xy.insert(out.xy.end(), {m.xy[2 * size_t(v)], m.xy[2 * size_t(v) + 1]});
      out.metric.insert(out.metric.end(), {vm.at[v].xx, vm.at[v].xy, vm.at[v].yy});
    }
  std::vector<uint32_t> face;
  const uint32_t faces = label_faces(m, face);
  std::vector<double> attribute(faces, 0.0);
  std::vector<uint8_t> known(faces, 0);
  uint32_t hint = kNone;
  for (uint32_t t = 0; t < m.num_slots(); ++t) {
    if (!m.alive(t)) continue;
    const uint32_t f = face[t];
    if (!known[f]) {
      known[f] = 1;
      const double* a = m.point(m.v(t, 0));
      const double* b = m.point(m.v(t, 1));
      const double* c = m.point(m.v(t, 2));
      const double q[2] = {(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0};
      const uint32_t df = d.face_at(q, hint);
      attribute[f] = df == kNone ? 0.0 : d.face_attribute[df];
    }
    out.tri.insert(out.tri.end(), {id[m.v(t, 0)], id[m.v(t, 1)], id[m.v(t, 2)]});
    out.attribute.push_back(attribute[f]);
    for (int k = 0; k < 3; ++k) {
      const uint32_t n = m.across(t, k);
      if (!m.constrained(t, k) || (n != kNone && n < t)) continue;
      const int32_t s = m.edge_tag(t, k);
      out.edges.insert(out.edges.end(), {id[m.edge_a(t, k)], id[m.edge_b(t, k)]});
      out.edge_segment.push_back(uint32_t(s));
      out.edge_label.push_back(p.label[size_t(s)]);
    }
  }
  return out;
}

}  // namespace

namespace {
Result<TriMesh2> run(const Pslg& p, const Mesh2dOptions& o, Mesh2dStats& st);
}  // namespace

Result<TriMesh2> mesh_pslg(const Pslg& p, const Mesh2dOptions& o, Mesh2dStats* stats) {
  Mesh2dStats local;
  Mesh2dStats& st = stats ? *stats : local;
  Result<TriMesh2> out = run(p, o, st);
  if (!out.ok() && !st.stage_seconds.empty()) st.failed_stage = st.stage_seconds.back().first;
  return out;
}

namespace {

Result<TriMesh2> run(const Pslg& p, const Mesh2dOptions& o, Mesh2dStats& st) {
  const Clock::time_point start = Clock::now();
  Clock::time_point last = start;
  auto stage = [&](double fraction, const char* name) {
    const Clock::time_point now = Clock::now();
    if (!st.stage_seconds.empty()) st.stage_seconds.back().second = std::chrono::duration<double>(now - last).count();
    last = now;
    st.stage_seconds.emplace_back(name, 0.0);
    return !o.progress || o.progress(fraction, name);
  };
  const Status cancelled(Error::Cancelled, "cancelled by the progress callback");
  if (o.layers < 1 || o.layers > 20) return Status(Error::InvalidArgument, "layers must be in 1..20");
  if (!stage(0.0, "validate")) return cancelled;
  Result<Domain> domain = analyse_domain(p);
  if (!domain.ok()) return domain.status();
  if (!stage(0.1, "sizing")) return cancelled;
  Result<std::unique_ptr<SizingField>> field = build_sizing2(p, domain.value(), o.sizing, &st.sizing);
  if (!field.ok()) return field.status();
  const bool anisotropic = !field.value()->isotropic();
  if (!stage(0.2, "front")) return cancelled;
  FrontOptions fo;
  fo.layers = o.layers;
  fo.field = field.value().get();
  Result<Triangulation> mesh = boundary_constrained_triangulation(p, domain.value(), fo, &st.stages);
  if (!mesh.ok()) return mesh.status();
  Triangulation& m = mesh.value();
  std::vector<uint8_t> fixed(m.num_vertices(), 0);
  std::fill(fixed.begin(), fixed.begin() + long(p.num_points()), uint8_t(1));
  VertexMetrics vm(*field.value(), anisotropic);
  vm.update(m);
  if (o.split_segments) st.refine.segment_splits += split_at_small_angles(m, p, vm, fixed);
  RefineOptions2 ro;
  ro.split_segments = o.split_segments;
  const int cycles = 1 + (anisotropic ? std::max(o.anisotropic_cycles, 0) : 0);
  for (int cycle = 0; cycle < cycles; ++cycle) {
    if (o.refine) {
      if (!stage(0.4 + 0.5 * cycle / cycles, "refine")) return cancelled;
      if (Status s = refine2(m, fixed, vm, ro, &st.refine); !s.ok()) return s;
    }
    if (o.optimize) {
      if (!stage(0.4 + 0.5 * (cycle + 0.5) / cycles, "optimize")) return cancelled;
      OptimizeOptions2 oo = o.optimize_options;
      oo.cleanup = oo.cleanup && cycle + 1 == cycles && !anisotropic;
      oo.split_segments = o.split_segments;
      if (Status s = optimize2(m, fixed, vm, oo, &st.optimize); !s.ok()) return s;
    }
  }
  if (Status s = check_triangulation(m); !s.ok()) return Status(Error::Internal, "the final mesh: " + s.message());
  st.in_range = share_in_range(m, vm);
  if (!stage(1.0, "done")) return cancelled;
  TriMesh2 out = extract(m, p, domain.value(), vm);
  st.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return out;
}

}  // namespace

}  // namespace anitet::mesh2d
