// Stages 3b/3c in parts (distributed/): the parts of a round cover the mesh once, merging
// unrefined parts gives the mesh back, the messages round-trip, and the whole pipeline run in two
// and three parts (one thread per part here, with the bytes the MPI ranks would send) gives a
// valid, boundary-constrained mesh whose quality is within 2% of the serial run's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/tet_mesh.hpp"
#include "distributed/parts.hpp"
#include "distributed/rank_mesh.hpp"
#include "io/surface_io.hpp"
#include "pipeline/mesher.hpp"
#include "quality/quality_report.hpp"
#include "refine/edges.hpp"

using namespace anitet;
using namespace anitet::distributed;

namespace {

SurfaceMesh knight() {
  Result<SurfaceMesh> s = read_surface(std::string(ANITET_SURFACES_DIR) + "/decimated-knight.off");
  EXPECT_TRUE(s.ok()) << s.status().message();
  return s.ok() ? s.value() : SurfaceMesh();
}

// The coupled mesh of the knight (stages 1, 2 and the coupling), caught by the stage-3 hook.
TetMesh coupled_knight() {
  TetMesh caught;
  MesherOptions options;
  options.stage3 = [&](TetMesh& mesh, const SizingField&, RefineStats&, OptimizeStats& o) {
    caught = mesh;
    o.after = summarize_quality(mesh);
    return Status::success();
  };
  Result<MesherResult> r = Mesher(options).run(knight());
  EXPECT_TRUE(r.ok()) << r.status().message();
  return caught;
}

// Ranks as threads: gather and broadcast through one mailbox, each call a barrier.
class Mailbox {
 public:
  explicit Mailbox(int ranks) : ranks_(ranks), slots_(size_t(ranks)) {}
  // Rank r puts its bytes in; once all have, each takes what `take` gives it.
  template <class Take>
  auto exchange(int rank, std::vector<uint8_t> bytes, Take take) {
    std::unique_lock<std::mutex> lock(m_);
    const long round = round_;
    slots_[size_t(rank)] = std::move(bytes);
    if (++arrived_ == ranks_) {
      snapshot_ = slots_;
      arrived_ = 0;
      ++round_;
      cv_.notify_all();
    } else {
      cv_.wait(lock, [&] { return round_ != round; });
    }
    return take(snapshot_);
  }

 private:
  int ranks_;
  std::vector<std::vector<uint8_t>> slots_, snapshot_;
  int arrived_ = 0;
  long round_ = 0;
  std::mutex m_;
  std::condition_variable cv_;
};

class ThreadExchange final : public Exchange {
 public:
  ThreadExchange(Mailbox& box, int rank, int ranks) : box_(box), rank_(rank), ranks_(ranks) {}
  int rank() const override { return rank_; }
  int ranks() const override { return ranks_; }
  Result<std::vector<std::vector<uint8_t>>> gather(const std::vector<uint8_t>& mine) override {
    return box_.exchange(rank_, mine, [&](const std::vector<std::vector<uint8_t>>& all) {
      return rank_ == 0 ? all : std::vector<std::vector<uint8_t>>();
    });
  }
  Result<std::vector<uint8_t>> broadcast(const std::vector<uint8_t>& root_bytes) override {
    return box_.exchange(rank_, rank_ == 0 ? root_bytes : std::vector<uint8_t>(),
                         [](const std::vector<std::vector<uint8_t>>& all) { return all[0]; });
  }

 private:
  Mailbox& box_;
  int rank_, ranks_;
};

// The pipeline with stages 3b/3c in `parts` parts, one thread each.
Result<MesherResult> mesh_in_parts(const SurfaceMesh& surface, int parts, size_t* tets_after_hook = nullptr,
                                   const SizingField* sizing = nullptr, const PartsOptions& parts_options = {}) {
  MesherOptions options;
  options.sizing = sizing;
  options.stage3 = [&](TetMesh& mesh, const SizingField& field, RefineStats& refine, OptimizeStats& optimize) {
    Mailbox box(parts);
    std::vector<TetMesh> copies(size_t(parts) - 1, mesh);
    std::vector<Status> status(size_t(parts), Status::success());
    std::vector<std::thread> others;
    for (int r = 1; r < parts; ++r)
      others.emplace_back([&, r] {
        ThreadExchange ex(box, r, parts);
        RefineStats rs;
        OptimizeStats os;
        PartsOptions own = parts_options;
        own.cycles_run = nullptr;  // rank 0's count only
        status[size_t(r)] = run_in_parts(copies[size_t(r) - 1], field, options.refine, options.optimize, own, ex, rs,
                                         os);
      });
    ThreadExchange ex(box, 0, parts);
    status[0] = run_in_parts(mesh, field, options.refine, options.optimize, parts_options, ex, refine, optimize);
    for (std::thread& t : others) t.join();
    for (const Status& st : status)
      if (!st.ok()) return st;
    // Every rank ends with the same mesh.
    for (const TetMesh& c : copies)
      if (c.tet_v != mesh.tet_v || c.xyz != mesh.xyz) return Status(Error::Internal, "ranks disagree");
    if (tets_after_hook) *tets_after_hook = mesh.num_live_tets();
    return Status::success();
  };
  return Mesher(options).run(surface);
}

void expect_valid_and_constrained(const SurfaceMesh& surface, const MesherResult& r, const std::string& what) {
  Result<QualityReport> q = compute_quality_report(r.mesh, &surface);
  ASSERT_TRUE(q.ok()) << what << ": " << q.status().message();
  EXPECT_TRUE(q->valid) << what;
  EXPECT_TRUE(q->surface.boundary_constrained) << what;
  EXPECT_EQ(q->surface.steiner_points_on_boundary, 0u) << what;
  EXPECT_LT(q->surface.volume_rel_error, 1e-9) << what;
  EXPECT_EQ(q->unused_vertices, 0u) << what;
  TetMesh tm = TetMesh::from_volume_mesh(r.mesh);
  ASSERT_TRUE(tm.build_adjacency().ok()) << what;
  Status st = check_mesh(tm, {});
  EXPECT_TRUE(st.ok()) << what << ": " << st.message();
}

}  // namespace

TEST(Parts, EveryTetInOnePartAndBalanced) {
  const TetMesh m = coupled_knight();
  ASSERT_GT(m.num_live_tets(), 1000u);
  for (int parts : {1, 2, 3}) {
    const std::vector<int32_t> p = hilbert_parts(m, parts);
    std::vector<size_t> count(size_t(parts), 0);
    for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
      if (m.is_deleted(t)) {
        EXPECT_EQ(p[t], -1);
        continue;
      }
      ASSERT_GE(p[t], 0);
      ASSERT_LT(p[t], parts);
      ++count[size_t(p[t])];
    }
    for (size_t c : count) EXPECT_LE(c, m.num_live_tets() / size_t(parts) + 1) << parts << " parts";
  }
}

TEST(Parts, MovedInterfacesLieInsideOnePart) {
  const TetMesh m = coupled_knight();
  const std::vector<int32_t> p = hilbert_parts(m, 2);
  const std::vector<int32_t> q = move_interfaces(m, p, 2, 0);
  // Every vertex where the first parts met now has all its tets in one part.
  std::map<uint32_t, std::pair<int32_t, int32_t>> first, second;  // vertex -> (min, max) part
  auto range = [&](const std::vector<int32_t>& part, std::map<uint32_t, std::pair<int32_t, int32_t>>& out) {
    for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
      if (part[t] < 0) continue;
      for (int i = 0; i < 4; ++i) {
        auto it = out.try_emplace(m.vertex(t, i), part[t], part[t]).first;
        it->second.first = std::min(it->second.first, part[t]);
        it->second.second = std::max(it->second.second, part[t]);
      }
    }
  };
  range(p, first);
  range(q, second);
  size_t interface = 0;
  for (const auto& [v, r] : first) {
    if (r.first == r.second) continue;
    ++interface;
    EXPECT_EQ(second[v].first, second[v].second) << "vertex " << v;
  }
  EXPECT_GT(interface, 0u);
  // With a zone of one ring, the tets away from the old interfaces are kept (their old part read
  // back from the label), the ones at an interface vertex are not.
  const std::vector<int32_t> z = move_interfaces(m, p, 2, 1);
  size_t kept_tets = 0;
  for (uint32_t t = 0; t < m.num_tet_slots(); ++t) {
    if (z[t] == -1) continue;
    bool at_interface = false;
    for (int i = 0; i < 4; ++i) {
      const auto& r = first[m.vertex(t, i)];
      at_interface |= r.first != r.second;
    }
    if (z[t] <= -2) {
      ++kept_tets;
      EXPECT_FALSE(at_interface);
      EXPECT_EQ(part_of_label(z[t]), p[t]);
    } else if (at_interface) {
      EXPECT_EQ(z[t], q[t]);
    }
  }
  EXPECT_GT(kept_tets, 0u);
  // Parts with kept tets merge back to the mesh too.
  std::vector<MeshPart> parts;
  for (int32_t k = 0; k < 2; ++k) parts.push_back(extract_part(m, z, k).value());
  Result<TetMesh> merged = merge_parts(m, z, parts, count_boundary_facets(m), nullptr);
  ASSERT_TRUE(merged.ok()) << merged.status().message();
  EXPECT_EQ(merged->num_live_tets(), m.num_live_tets());
  EXPECT_TRUE(check_mesh(merged.value(), {}).ok());
}

TEST(Parts, UnrefinedPartsMergeBackAndMessagesRoundTrip) {
  const TetMesh m = coupled_knight();
  const std::vector<int32_t> p = hilbert_parts(m, 3);
  std::vector<MeshPart> parts;
  size_t own = 0;
  for (int32_t k = 0; k < 3; ++k) {
    Result<MeshPart> part = extract_part(m, p, k);
    ASSERT_TRUE(part.ok()) << part.status().message();
    ASSERT_TRUE(check_mesh(part->mesh, {}).ok());
    for (uint32_t t = 0; t < part->mesh.num_tet_slots(); ++t) own += part->mesh.tet_region[t] >= 0 ? 1 : 0;
    EXPECT_FALSE(part->interface_facets.empty());
    Result<MeshPart> back = deserialize_part(serialize_part(part.value()));
    ASSERT_TRUE(back.ok()) << back.status().message();
    EXPECT_EQ(back->mesh.tet_v, part->mesh.tet_v);
    EXPECT_EQ(back->mesh.tet_flags, part->mesh.tet_flags);
    EXPECT_EQ(back->global_of, part->global_of);
    EXPECT_EQ(back->interface_facets, part->interface_facets);
    parts.push_back(std::move(back).value());
  }
  EXPECT_EQ(own, m.num_live_tets());
  std::vector<int32_t> tet_part;
  Result<TetMesh> merged = merge_parts(m, p, parts, count_boundary_facets(m), &tet_part);
  ASSERT_TRUE(merged.ok()) << merged.status().message();
  ASSERT_TRUE(check_mesh(merged.value(), {}).ok());
  EXPECT_EQ(merged->num_live_tets(), m.num_live_tets());
  EXPECT_EQ(merged->xyz, m.xyz);
  // The same protected facets as before the cut (the interface ones unprotected again).
  auto protected_count = [](const TetMesh& x) {
    size_t n = 0;
    for (uint32_t t = 0; t < x.num_tet_slots(); ++t)
      if (!x.is_deleted(t))
        for (int i = 0; i < 4; ++i) n += x.facet_protected(t, i) ? 1 : 0;
    return n;
  };
  EXPECT_EQ(protected_count(merged.value()), protected_count(m));
  std::vector<int32_t> parts_back;
  Result<TetMesh> sent = deserialize_mesh(serialize_mesh(merged.value(), tet_part), parts_back, true);
  ASSERT_TRUE(sent.ok()) << sent.status().message();
  EXPECT_EQ(sent->tet_v, merged->tet_v);
  EXPECT_EQ(parts_back, tet_part);
  // A truncated message is refused, not read past its end.
  std::vector<uint8_t> bytes = serialize_part(parts[0]);
  bytes.resize(bytes.size() / 2);
  EXPECT_FALSE(deserialize_part(bytes).ok());
}

TEST(Parts, AChangedHaloIsCaughtAtTheMerge) {
  const TetMesh m = coupled_knight();
  const std::vector<int32_t> p = hilbert_parts(m, 2);
  std::vector<MeshPart> parts;
  for (int32_t k = 0; k < 2; ++k) parts.push_back(extract_part(m, p, k).value());
  // Part 0 "forgets" one of its own tets: a hole the merge must see.
  MeshPart& a = parts[0];
  for (uint32_t t = 0; t < a.mesh.num_tet_slots(); ++t)
    if (a.mesh.tet_region[t] >= 0) {
      a.mesh.delete_tet(t);
      break;
    }
  EXPECT_FALSE(merge_parts(m, p, parts, count_boundary_facets(m), nullptr).ok());
}

TEST(Parts, PipelineInPartsIsValidConstrainedAndAsGoodAsSerial) {
  const SurfaceMesh s = knight();
  Result<MesherResult> serial = Mesher(MesherOptions()).run(s);
  ASSERT_TRUE(serial.ok()) << serial.status().message();
  for (int parts : {2, 3}) {
    const std::string what = std::to_string(parts) + " parts";
    Result<MesherResult> r = mesh_in_parts(s, parts);
    ASSERT_TRUE(r.ok()) << what << ": " << r.status().message();
    expect_valid_and_constrained(s, r.value(), what);
    const double mean = r->optimize.after.mean, serial_mean = serial->optimize.after.mean;
    EXPECT_GT(mean, 0.98 * serial_mean) << what << ": mean radius ratio " << mean << " against " << serial_mean;
    EXPECT_GT(r->refine.splits, 0u) << what;
    EXPECT_GT(r->refine.length_in_range, serial->refine.length_in_range - 0.02) << what;
    std::printf("%s: radius ratio mean %.4f (serial %.4f), min %.4f (serial %.4f), lengths in range %.4f (serial %.4f), tets %zu (serial %zu)\n",
                what.c_str(), mean, serial_mean, r->optimize.after.min, serial->optimize.after.min,
                r->refine.length_in_range, serial->refine.length_in_range, r->mesh.num_tets(), serial->mesh.num_tets());
    // The same run twice gives the same mesh (no dependence on the threads' timing).
    Result<MesherResult> again = mesh_in_parts(s, parts);
    ASSERT_TRUE(again.ok());
    EXPECT_EQ(again->mesh.tet, r->mesh.tet) << what;
    EXPECT_EQ(again->mesh.xyz, r->mesh.xyz) << what;
  }
}

// split_coarse_for_parts, as run_rank_parts calls it for 4 ranks, on the knight meshed 4 times
// finer (size scale 0.25): the largest coarse tet's prediction falls (337 -> 127 final tets; the
// tets whose edges lie on the surface are not split), the mesh stays valid with its boundary, and
// two runs give the same mesh (every rank splits its own copy).
TEST(Parts, SplittingTheCoarseMeshCapsItsLargestTetsTheSameEveryTime) {
  MesherOptions options;
  options.stage3 = [&](TetMesh& mesh, const SizingField& field, RefineStats&, OptimizeStats& o) {
    auto largest = [&](const TetMesh& m) {
      const std::vector<double> w = estimate_refined_tets_per_tet(m, field, 0.25);
      return *std::max_element(w.begin(), w.end());
    };
    const double before = largest(mesh);
    const size_t boundary = count_boundary_facets(mesh);
    TetMesh again = mesh;
    RefineOptions fine;
    fine.size_scale = 0.25;
    Result<size_t> splits = split_coarse_for_parts(mesh, field, fine, 4, 2000);
    EXPECT_TRUE(splits.ok()) << splits.status().message();
    Result<size_t> splits_again = split_coarse_for_parts(again, field, fine, 4, 2000);
    EXPECT_TRUE(splits_again.ok());
    EXPECT_GT(splits.value(), 0u);
    EXPECT_EQ(splits.value(), splits_again.value());
    EXPECT_EQ(mesh.tet_v, again.tet_v);
    EXPECT_EQ(mesh.xyz, again.xyz);
    EXPECT_TRUE(check_mesh(mesh, {}).ok());
    EXPECT_EQ(count_boundary_facets(mesh), boundary);
    const double after = largest(mesh);
    std::printf("largest coarse tet: %.0f -> %.0f final tets, %zu splits\n", before, after, splits.value());
    EXPECT_LT(after, before / 2);
    o.after = summarize_quality(mesh);
    return Status::success();
  };
  Result<MesherResult> r = Mesher(options).run(knight());
  ASSERT_TRUE(r.ok()) << r.status().message();
}

// An anisotropic field (sizes a third as long along z as along x and y) meshed in 2 parts: the
// rounds run refinement's metric kernel and flips and the optimizer's metric measures with the
// interfaces frozen, and the pipeline's extra cycles under the same gates (as many as one
// process runs); valid, boundary constrained, and the metric measures as one process's.
TEST(Parts, AnisotropicFieldMeshesInPartsAsInOneProcess) {
  const SurfaceMesh s = knight();
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (size_t v = 0; v < s.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], s.xyz[3 * v + size_t(k)]);
      hi[k] = std::max(hi[k], s.xyz[3 * v + size_t(k)]);
    }
  struct Stretched final : SizingField {
    double h = 1.0;
    void metric(const double*, double m[6]) const override {
      const double v[6] = {1.0 / (h * h), 0.0, 1.0 / (h * h), 0.0, 0.0, 9.0 / (h * h)};
      std::copy(v, v + 6, m);
    }
  } field;
  field.h = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}) / 10.0;
  MesherOptions serial_options;
  serial_options.sizing = &field;
  Result<MesherResult> serial = Mesher(serial_options).run(s);
  ASSERT_TRUE(serial.ok()) << serial.status().message();
  ASSERT_TRUE(serial->optimize.anisotropic);
  PartsOptions parts_options;
  int cycles_run = -1;
  parts_options.anisotropic_cycles = serial_options.anisotropic_cycles;
  parts_options.cycle_gain = serial_options.anisotropic_cycle_gain;
  parts_options.cycle_optimizer_gain = serial_options.anisotropic_cycle_optimizer_gain;
  parts_options.cycles_run = &cycles_run;
  Result<MesherResult> r = mesh_in_parts(s, 2, nullptr, &field, parts_options);
  ASSERT_TRUE(r.ok()) << r.status().message();
  expect_valid_and_constrained(s, r.value(), "anisotropic, 2 parts");
  EXPECT_TRUE(r->optimize.anisotropic);
  EXPECT_GT(r->metric_quality.tets, 0u);
  // The share of the final mesh's edges in [1/sqrt2, sqrt2] (all edges, the same measure for both).
  auto in_range = [&](const MesherResult& m) {
    TetMesh tm = TetMesh::from_volume_mesh(m.mesh);
    std::vector<double> metrics(6 * tm.num_vertices());
    for (uint32_t v = 0; v < tm.num_vertices(); ++v) field.metric(tm.point(v), &metrics[6 * size_t(v)]);
    double mean = 0.0, share = 0.0;
    refine_detail::summarize_edge_lengths(tm, metrics, 1.0 / std::sqrt(2.0), std::sqrt(2.0), mean, share);
    return share;
  };
  const double share = in_range(r.value()), serial_share = in_range(serial.value());
  std::printf("anisotropic, 2 parts: edges in range %.4f (one process %.4f), metric radius ratio mean %.4f (%.4f), "
              "tets %zu (%zu), extra cycles %d (%d)\n",
              share, serial_share, r->metric_quality.mean, serial->metric_quality.mean, r->mesh.num_tets(),
              serial->mesh.num_tets(), cycles_run, serial->anisotropic_cycles);
  EXPECT_EQ(cycles_run, serial->anisotropic_cycles);
  EXPECT_GT(share, serial_share - 0.02);
  EXPECT_GT(r->metric_quality.mean, 0.97 * serial->metric_quality.mean);
}
