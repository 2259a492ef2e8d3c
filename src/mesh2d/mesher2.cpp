#include "mesh2d/mesher2.hpp"

#include <chrono>
#include <memory>

#include "mesh2d/conforming.hpp"
#include "mesh2d/corners.hpp"
#include "mesh2d/domain.hpp"

namespace anitet::mesh2d {

namespace {

using Clock = std::chrono::steady_clock;


// The output: vertices in no triangle (collapsed) dropped, the input's points first; each
// triangle's attribute from its face in the input's classification.
TriMesh2 extract(const Triangulation& m, const Pslg& p, const Domain& d, const VertexMetrics& vm) {
  TriMesh2 out;
  out.input_points = p.num_points();
  std::vector<uint32_t> id(m.num_vertices(), kNone);
  for (const auto& [copy, original] : m.copies) id[copy] = original;  // mapped below
  for (uint32_t v = 0; v < m.num_vertices(); ++v)
    if (id[v] != kNone) {
      id[v] = id[id[v]];  // a pinched vertex's copy: the original's output vertex
    } else if (v < p.num_points() || m.vtri[v] != kNone) {
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
  for (const auto& copy : m.copies) fixed[copy.first] = 1;
  VertexMetrics vm(*field.value(), anisotropic);
  vm.update(m);
  if (o.split_segments) st.refine.segment_splits += split_sharp_corners(m, vm, fixed, uint32_t(p.num_points()));
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
