#include "quality/quality_report.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include <tbb/parallel_invoke.h>

#include "core/exact_scaling.hpp"
#include "core/tet_faces.hpp"
#include "predicates/predicates.hpp"
#include "quality/parallel_for.hpp"
#include "quality/report_detail.hpp"
#include "quality/tet_measures.hpp"

namespace anitet {

namespace quality_detail {

namespace {

// The statistics of values[i] for the i that keep(i) says, without copying them: a pass for the
// count, extremes and the mean (a Neumaier sum in index order), then the 1st percentile's two
// order statistics from a histogram of the values and a selection among the few in their bins
// (a copy of every value and nth_element over it was most of this; the figures are the same).
template <class Keep>
Stats stats_kept(const std::vector<double>& values, Keep&& keep) {
  Stats s;
  double sum = 0.0, comp = 0.0;
  for (size_t i = 0; i < values.size(); ++i) {
    if (!keep(i)) continue;
    const double x = values[i];
    if (s.count++ == 0) s.min = s.max = x;
    const double t = sum + x;
    comp += std::fabs(sum) >= std::fabs(x) ? (sum - t) + x : (x - t) + sum;
    sum = t;
    s.min = std::min(s.min, x);
    s.max = std::max(s.max, x);
  }
  if (s.count == 0) return s;
  s.mean = (sum + comp) / double(s.count);
  // numpy.percentile's default ("linear"): interpolate between ranks floor(q) and floor(q) + 1.
  const double rank = 0.01 * double(s.count - 1);
  const size_t lo = static_cast<size_t>(std::floor(rank));
  const double frac = rank - double(lo);
  const size_t hi = std::min(lo + 1, s.count - 1);
  // Bins over [min, max]: x <= y gives bin(x) <= bin(y) ((x - min) * scale is monotone).
  constexpr size_t kBins = 4096;
  const double scale = s.max > s.min ? double(kBins) / (s.max - s.min) : 0.0;
  auto bin = [&](double x) {
    const double u = (x - s.min) * scale;
    return u >= double(kBins - 1) ? kBins - 1 : u > 0.0 ? static_cast<size_t>(u) : size_t(0);
  };
  std::vector<size_t> count(kBins, 0);
  for (size_t i = 0; i < values.size(); ++i)
    if (keep(i)) ++count[bin(values[i])];
  size_t below = 0, first = 0;  // values in bins before `first`; first: the bin of rank lo
  while (below + count[first] <= lo) below += count[first++];
  size_t last = first, upto = below + count[first];  // last: the bin of rank hi
  while (upto <= hi) upto += count[++last];
  std::vector<double> near;
  near.reserve(upto - below);
  for (size_t i = 0; i < values.size(); ++i) {
    if (!keep(i)) continue;
    const size_t k = bin(values[i]);
    if (k >= first && k <= last) near.push_back(values[i]);
  }
  const size_t at = lo - below;
  std::nth_element(near.begin(), near.begin() + long(at), near.end());
  const double a = near[at];
  double b = a;
  if (at + 1 < near.size()) b = *std::min_element(near.begin() + long(at) + 1, near.end());
  s.p01 = frac >= 0.5 ? b - (b - a) * (1.0 - frac) : a + (b - a) * frac;
  return s;
}

}  // namespace

Stats make_stats(const std::vector<double>& values) {
  return stats_kept(values, [](size_t) { return true; });
}

Stats make_stats_where(const std::vector<double>& values, const std::vector<uint8_t>& select, uint8_t value) {
  return stats_kept(values, [&](size_t i) { return select[i] == value; });
}

QualitySplit split_quality(const TetData& data, const std::vector<uint8_t>& select, uint8_t value) {
  QualitySplit q;
  double dmin = 180.0;
  size_t good = 0, bad = 0;
  for (size_t t = 0; t < select.size(); ++t) {
    if (select[t] != value) continue;
    const double r = data.radius_ratio[t];
    ++q.tets;
    dmin = std::min(dmin, data.min_dihedral[t]);
    good += r > 0.4;
    bad += r < 0.1;
  }
  if (q.tets == 0) return q;
  q.min_dihedral_deg = dmin;
  q.good_fraction = double(good) / double(q.tets);
  q.bad_fraction = double(bad) / double(q.tets);
  q.radius_ratio = make_stats_where(data.radius_ratio, select, value);
  q.mean_ratio = make_stats_where(data.mean_ratio, select, value);
  return q;
}

}  // namespace quality_detail

namespace {

using quality_detail::for_chunks;
using quality_detail::TetData;

// Every tet index in range and every used coordinate finite; marks the used vertices.
Status check_input(const VolumeMesh& mesh, std::vector<uint8_t>& used) {
  const size_t nv = mesh.num_vertices();
  used.assign(nv, 0);
  if (mesh.xyz.size() % 3 != 0 || mesh.tet.size() % 4 != 0) {
    return Status(Error::InvalidArgument, "mesh arrays are not a whole number of vertices/tets");
  }
  for (size_t i = 0; i < mesh.tet.size(); ++i) {
    const uint32_t v = mesh.tet[i];
    if (v >= nv) {
      std::ostringstream os;
      os << "tet " << i / 4 << " refers to vertex " << v << " but the mesh has " << nv
         << " vertices";
      return Status(Error::BadIndex, os.str());
    }
    used[v] = 1;
  }
  for (size_t v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    const double* p = mesh.point(v);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      std::ostringstream os;
      os << "vertex " << v << " has a non-finite coordinate (" << p[0] << ", " << p[1] << ", "
         << p[2] << ")";
      return Status(Error::NonFiniteCoordinate, os.str());
    }
  }
  return Status::success();
}

TetData measure_tets(const VolumeMesh& mesh, bool parallel) {
  const size_t nt = mesh.num_tets();
  TetData d;
  d.volume.resize(nt);
  d.radius_ratio.resize(nt);
  d.mean_ratio.resize(nt);
  d.min_dihedral.resize(nt);
  d.max_dihedral_key.resize(nt);
  d.orient.resize(nt);
  for_chunks(nt, parallel, [&](size_t begin, size_t end) {
    for (size_t t = begin; t < end; ++t) {
      const uint32_t* v = &mesh.tet[4 * t];
      const double *a = mesh.point(v[0]), *b = mesh.point(v[1]), *c = mesh.point(v[2]),
                   *e = mesh.point(v[3]);
      // A certified sign is the exact one: the exact predicate only for the uncertified.
      const int certified = predicates::orient3d_certified(a, b, c, e);
      const int o = certified != 0 ? certified : predicates::orient3d(a, b, c, e);
      TetMeasures m = tet_measures_keyed(a, b, c, e, d.max_dihedral_key[t]);
      if (o == 0) {  // exactly flat: the float volume is rounding noise
        m.radius_ratio = 0.0;
        m.mean_ratio = 0.0;
      }
      // 2: positive, but a double evaluation of the volume could find it zero or negative.
      d.orient[t] = static_cast<int8_t>(o > 0 && certified <= 0 ? 2 : o);
      d.volume[t] = m.volume;
      d.radius_ratio[t] = m.radius_ratio;
      d.mean_ratio[t] = m.mean_ratio;
      d.min_dihedral[t] = m.min_dihedral_deg;
    }
  });
  return d;
}

}  // namespace

Result<QualityReport> compute_quality_report(const VolumeMesh& mesh,
                                             const SurfaceMesh* input_surface,
                                             const QualityOptions& options) {
  quality_detail::TetData data;
  std::vector<uint32_t> boundary;
  return quality_detail::compute_quality_report_keep(mesh, input_surface, options, data, boundary);
}

namespace {

// The report of a mesh (and surface) whose coordinates lie outside the range the measures are
// computed in (exact_scaling.hpp): measured scaled by 2^k (every shape measure and exact test
// the same), the volumes and the matching tolerance scaled back.
Result<QualityReport> report_scaled(const VolumeMesh& mesh, const SurfaceMesh* surface, const QualityOptions& options,
                                    quality_detail::TetData& data, std::vector<uint32_t>& boundary, int k) {
  VolumeMesh m = mesh;
  for (double& x : m.xyz) x = std::ldexp(x, k);
  // Metric lengths stay the same: sizes scaled with the coordinates, tensors by the inverse square.
  const bool sizes = m.vertex_metric.size() == m.num_vertices();
  for (double& x : m.vertex_metric) x = std::ldexp(x, sizes ? k : -2 * k);
  SurfaceMesh s;
  if (surface) {
    s = *surface;
    for (double& x : s.xyz) x = std::ldexp(x, k);
  }
  Result<QualityReport> r = quality_detail::compute_quality_report_keep(m, surface ? &s : nullptr, options, data, boundary);
  if (!r.ok()) return r;
  r->volume = std::ldexp(r->volume, -3 * k);
  r->surface.surface_volume = std::ldexp(r->surface.surface_volume, -3 * k);
  r->surface.tolerance_abs = std::ldexp(r->surface.tolerance_abs, -k);
  for (double& v : data.volume) v = std::ldexp(v, -3 * k);
  return r;
}

}  // namespace

Result<QualityReport> quality_detail::compute_quality_report_keep(const VolumeMesh& mesh,
                                                                  const SurfaceMesh* input_surface,
                                                                  const QualityOptions& options,
                                                                  TetData& data,
                                                                  std::vector<uint32_t>& boundary) {
  const auto clock_start = std::chrono::steady_clock::now();
  // (Non-finite coordinates fit no scaling: check_input reports them below.)
  const Result<int> k = exact_power_of_two_scaling(
      {{mesh.xyz.data(), mesh.num_vertices()},
       {input_surface ? input_surface->xyz.data() : nullptr, input_surface ? input_surface->num_vertices() : 0}});
  if (k.ok() && k.value() != 0) return report_scaled(mesh, input_surface, options, data, boundary, k.value());
  QualityReport r;
  std::vector<uint8_t> used;
  if (Status s = check_input(mesh, used); !s.ok()) return s;
  if (options.histogram_bins < 1) return Status(Error::InvalidArgument, "histogram_bins must be >= 1");

  r.vertices = mesh.num_vertices();
  r.tets = mesh.num_tets();
  r.unused_vertices = size_t(std::count(used.begin(), used.end(), uint8_t(0)));

  // The faces first: the census's working memory (32 bytes per tet) is gone before the per-tet
  // measures (41 bytes per tet) are made, not held beside them (issue 49).
  {
    FaceCensus faces = census_faces(mesh.tet.data(), mesh.num_tets(), mesh.num_vertices(), options.parallel);
    boundary = std::move(faces.boundary);
    r.faces_shared_by_more_than_two = faces.shared_by_more_than_two;
    r.boundary_faces = boundary.size() / 3;
  }
  data = measure_tets(mesh, options.parallel);
  const TetData& d = data;
  double vol = 0.0, comp = 0.0;  // Neumaier sum of the signed volumes
  r.rr_histogram.assign(size_t(options.histogram_bins), 0);
  const double bins = double(options.histogram_bins);
  size_t good = 0, bad = 0;
  for (size_t t = 0; t < r.tets; ++t) {
    if (d.orient[t] <= 0) {
      ++r.nonpositive_tets;
      r.inverted_tets += d.orient[t] < 0;
      r.flat_tets += d.orient[t] == 0;
      if (r.nonpositive_examples.size() < options.max_listed) r.nonpositive_examples.push_back(uint32_t(t));
    }
    r.rounding_flat_tets += d.orient[t] == 2;
    const double x = d.volume[t], sum = vol + x;
    comp += std::fabs(vol) >= std::fabs(x) ? (vol - sum) + x : (x - sum) + vol;
    vol = sum;
    const double rr = d.radius_ratio[t];
    good += rr > 0.4;
    bad += rr < 0.1;
    r.tets_dihedral_lt_5deg += d.min_dihedral[t] < 5.0;
    r.tets_dihedral_lt_10deg += d.min_dihedral[t] < 10.0;
    // Bin edges i/bins; a value on an edge goes up, 1.0 (and rounding just above it) in the last.
    long bin = static_cast<long>(std::clamp(rr, 0.0, 1.0) * bins);
    if (bin > 0 && rr < double(bin) / bins) --bin;
    if (bin + 1 < options.histogram_bins && rr >= double(bin + 1) / bins) ++bin;
    r.rr_histogram[size_t(std::min<long>(bin, options.histogram_bins - 1))] += 1;
  }
  r.volume = vol + comp;
  if (r.tets > 0) {
    r.good_fraction = double(good) / double(r.tets);
    r.bad_fraction = double(bad) / double(r.tets);
    Stats dmin;
    auto stats_of = [](const std::vector<double>& values, Stats& into) { into = quality_detail::make_stats(values); };
    if (options.parallel) {
      tbb::parallel_invoke([&] { stats_of(d.radius_ratio, r.radius_ratio); },
                           [&] { stats_of(d.mean_ratio, r.mean_ratio); }, [&] { stats_of(d.min_dihedral, dmin); });
    } else {
      stats_of(d.radius_ratio, r.radius_ratio);
      stats_of(d.mean_ratio, r.mean_ratio);
      stats_of(d.min_dihedral, dmin);
    }
    r.min_dihedral_deg = dmin.min;
    r.dihedral_p01_deg = dmin.p01;
    r.max_dihedral_deg = max_dihedral_from_key(*std::max_element(d.max_dihedral_key.begin(), d.max_dihedral_key.end()));
  }

  if (mesh.region.size() == r.tets && r.tets > 0) {
    // The distinct ids: a scan against the few seen so far (sorting every tet's id took longer
    // than the rest of this loop), a sort when there are many.
    std::vector<int32_t> ids;
    int32_t last = mesh.region[0];
    ids.push_back(last);
    for (int32_t id : mesh.region) {
      if (id == last) continue;
      last = id;
      if (std::find(ids.begin(), ids.end(), id) != ids.end()) continue;
      ids.push_back(id);
      if (ids.size() > 64) {
        ids = mesh.region;
        break;
      }
    }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    if (ids.size() > 1) {
      std::vector<uint8_t> select(r.tets);
      for (int32_t id : ids) {
        for (size_t t = 0; t < r.tets; ++t) select[t] = mesh.region[t] == id;
        r.by_region.push_back({id, quality_detail::split_quality(d, select, 1)});
      }
    }
  }

  r.valid = r.nonpositive_tets == 0 && r.faces_shared_by_more_than_two == 0;

  if (input_surface != nullptr) {
    quality_detail::match_surface(mesh, *input_surface, boundary, used, d, options, r);
  }
  if (Status s = quality_detail::measure_metric(mesh, options.histogram_bins, options.parallel, r.metric); !s.ok())
    return s;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return r;
}

}  // namespace anitet
