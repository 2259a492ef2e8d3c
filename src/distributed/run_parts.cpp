// run_in_parts: the rounds of extract, refine and optimize, gather, merge and broadcast.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

#include "distributed/parts.hpp"
#include "refine/edges.hpp"
#include "refine/mesh_ops.hpp"

namespace anitet::distributed {

namespace {

// A message: 1 and the payload, or 0, a failure's code (4 bytes) and its text.
std::vector<uint8_t> ok_message(std::vector<uint8_t> payload) {
  payload.insert(payload.begin(), uint8_t(1));
  return payload;
}

std::vector<uint8_t> failure_message(const Status& st) {
  const auto code = static_cast<int32_t>(st.code());
  const std::string& text = st.message();
  std::vector<uint8_t> m(1 + sizeof(code) + text.size(), 0);
  std::memcpy(m.data() + 1, &code, sizeof(code));
  std::copy(text.begin(), text.end(), m.begin() + 1 + sizeof(code));
  return m;
}

// The payload of an ok message, or the failure it carries.
Result<std::vector<uint8_t>> payload_of(std::vector<uint8_t> m, int from) {
  if (m.empty()) return Status(Error::Internal, "distributed: an empty message from rank " + std::to_string(from));
  if (m[0] == 1) {
    m.erase(m.begin());
    return m;
  }
  int32_t code = static_cast<int32_t>(Error::Internal);
  if (m.size() >= 1 + sizeof(code)) std::memcpy(&code, m.data() + 1, sizeof(code));
  const std::string text = m.size() > 1 + sizeof(code) ? std::string(m.begin() + 1 + sizeof(code), m.end()) : "failed";
  return Status(static_cast<Error>(code), "rank " + std::to_string(from) + ": " + text);
}

// This rank's part of a round, meshed, as a message; its counts added to `refine` and `optimize`
// when asked.
std::vector<uint8_t> mesh_my_part(const TetMesh& mesh, const std::vector<int32_t>& part_of, int rank, Step step,
                                  const SizingField& field, const RefineOptions& refine_options,
                                  const OptimizeOptions& optimize_options, RefineStats* refine,
                                  OptimizeStats* optimize) {
  Result<MeshPart> part = extract_part(mesh, part_of, rank);
  if (!part.ok()) return failure_message(part.status());
  if (Status st = mesh_part(part.value(), step, field, refine_options, optimize_options); !st.ok())
    return failure_message(st);
  if (refine && optimize) add_counts(part.value(), *refine, *optimize);
  return ok_message(serialize_part(part.value()));
}

// Rank 0: the parts merged, as the message every rank gets.
std::vector<uint8_t> merge_messages(const TetMesh& mesh, const std::vector<int32_t>& part_of, size_t boundary_facets,
                                    std::vector<std::vector<uint8_t>> messages, RefineStats& refine,
                                    OptimizeStats& optimize) {
  std::vector<MeshPart> parts;
  for (size_t r = 0; r < messages.size(); ++r) {
    Result<std::vector<uint8_t>> payload = payload_of(std::move(messages[r]), int(r));
    if (!payload.ok()) return failure_message(payload.status());
    Result<MeshPart> part = deserialize_part(payload.value());
    if (!part.ok()) return failure_message(part.status());
    add_counts(part.value(), refine, optimize);
    parts.push_back(std::move(part).value());
  }
  std::vector<int32_t> tet_part;
  Result<TetMesh> merged = merge_parts(mesh, part_of, parts, boundary_facets, &tet_part);
  if (!merged.ok()) return failure_message(merged.status());
  return ok_message(serialize_mesh(merged.value(), tet_part));
}

// The field's metrics at the vertices, scaled as refinement scales them.
std::vector<double> scaled_metrics(const TetMesh& mesh, const SizingField& field, const RefineOptions& options) {
  return vertex_metrics(mesh, field, options.size_scale > 0.0 ? options.size_scale : 1.0);
}

// Whether the optimizer will measure in the metric (an anisotropic metric at some vertex of a
// tet), as optimize_mesh decides it on the whole mesh.
bool anisotropic_somewhere(const TetMesh& mesh, const SizingField& field, const RefineOptions& options) {
  const ScaledSizing scaled(field, options.size_scale > 0.0 ? options.size_scale : 1.0);
  std::vector<uint8_t> used(mesh.num_vertices(), 0);
  for (uint32_t t = 0; t < mesh.num_tet_slots(); ++t)
    if (!mesh.is_deleted(t) && !mesh.is_ghost(t))
      for (int i = 0; i < 4; ++i) used[mesh.vertex(t, i)] = 1;
  double m[6];
  for (uint32_t v = 0; v < mesh.num_vertices(); ++v) {
    if (!used[v]) continue;
    scaled.metric(mesh.point(v), m);
    if (!meshops::MetricMap::of(m).identity) return true;
  }
  return false;
}

}  // namespace

Status run_in_parts(TetMesh& mesh, const SizingField& field, const RefineOptions& refine_options,
                    const OptimizeOptions& optimize_options, const PartsOptions& options, Exchange& exchange,
                    RefineStats& refine, OptimizeStats& optimize) {
  if (Status s = check_meshable_in_parts(mesh); !s.ok()) return s;
  refine = RefineStats();
  optimize = OptimizeStats();
  std::vector<int32_t> part_of;
  // Every rank starts from rank 0's mesh: the ranks' coupled meshes are the same unless a
  // wall-time budget ran out on one rank only.
  {
    Result<std::vector<uint8_t>> sent = exchange.broadcast(exchange.rank() == 0 ? serialize_mesh(mesh, {}) : std::vector<uint8_t>());
    if (!sent.ok()) return sent.status();
    std::vector<int32_t> none;
    Result<TetMesh> first = deserialize_mesh(sent.value(), none, true);
    if (!first.ok()) return first.status();
    mesh = std::move(first).value();
  }
  const size_t boundary_facets = count_boundary_facets(mesh);
  refine.vertices_before = refine_detail::live_vertex_count(mesh);
  refine.tets_before = mesh.num_live_tets();
  optimize.before = summarize_quality(mesh);
  int round = 0;
  // One round: every rank meshes its part; rank 0 merges and sends the mesh to all.
  auto run_round = [&](Step step) -> Status {
    ++round;
    // Rank 0 sums everyone's counts from the messages; the others keep their own.
    const bool own_counts = exchange.rank() != 0;
    std::vector<uint8_t> mine = mesh_my_part(mesh, part_of, exchange.rank(), step, field, refine_options,
                                             optimize_options, own_counts ? &refine : nullptr,
                                             own_counts ? &optimize : nullptr);
    Result<std::vector<std::vector<uint8_t>>> gathered = exchange.gather(mine);
    if (!gathered.ok()) return gathered.status();
    std::vector<uint8_t> merged;
    if (exchange.rank() == 0) merged = merge_messages(mesh, part_of, boundary_facets, std::move(gathered).value(), refine, optimize);
    Result<std::vector<uint8_t>> sent = exchange.broadcast(merged);
    if (!sent.ok()) return sent.status();
    Result<std::vector<uint8_t>> payload = payload_of(std::move(sent).value(), 0);
    if (!payload.ok())
      return Status(payload.status().code(), "round " + std::to_string(round) + ": " + payload.status().message());
    Result<TetMesh> next = deserialize_mesh(payload.value(), part_of, false);
    if (!next.ok()) return next.status();
    mesh = std::move(next).value();
    return Status::success();
  };
  // Refinement, then optimization: each on Hilbert parts, then around their interfaces.
  auto two_rounds = [&](Step step) -> Status {
    // Optimization cuts half a part along the curve from where refinement cut, so that what
    // refinement's second round inserted beside the first one's interfaces lies inside a part.
    part_of = hilbert_parts(mesh, exchange.ranks(), step == Step::kOptimize ? 0.5 : 0.0);
    if (Status st = run_round(step); !st.ok()) return st;
    part_of = move_interfaces(mesh, part_of, options.rings, options.zone);
    return run_round(step);
  };
  // With an anisotropic field the optimizer reports the share of edges in [1/sqrt2, sqrt2] before
  // and after it (OptimizeStats::length_in_range_*), and the cycles' gates read them and
  // refinement's share: measured on the whole mesh, not summed from the parts.
  const bool anisotropic = anisotropic_somewhere(mesh, field, refine_options);
  double unused_mean = 0.0, refined_in_range = 0.0;
  auto rounds = [&](Step step) -> Status {
    if (Status st = two_rounds(step); !st.ok()) return st;
    if (!anisotropic) return Status::success();
    const std::vector<double> metrics = scaled_metrics(mesh, field, refine_options);
    if (step == Step::kRefine) {
      refine_detail::summarize_edge_lengths(mesh, metrics, refine_options.collapse_length, refine_options.split_length,
                                            unused_mean, refined_in_range);
    }
    refine_detail::summarize_edge_lengths(
        mesh, metrics, kUnitRangeMin, kUnitRangeMax, unused_mean,
        step == Step::kRefine ? optimize.length_in_range_before : optimize.length_in_range_after);
    return Status::success();
  };
  if (Status st = run_steps_and_cycles(options, anisotropic, refined_in_range, optimize, rounds); !st.ok()) return st;
  // The rounds' meshes travel without their adjacency; the caller gets it.
  if (Status st = mesh.build_adjacency(); !st.ok()) return st;
  refine_detail::summarize_edge_lengths(mesh, scaled_metrics(mesh, field, refine_options),
                                        refine_options.collapse_length, refine_options.split_length,
                                        refine.length_mean, refine.length_in_range);
  refine.vertices_after = refine_detail::live_vertex_count(mesh);
  refine.tets_after = mesh.num_live_tets();
  optimize.after = summarize_quality(mesh);
  return Status::success();
}

}  // namespace anitet::distributed
