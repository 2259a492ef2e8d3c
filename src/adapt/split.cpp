// Edge split: the shell of ab, each tet (a b x y) cut into (a m x y) and (m b x y) at the point m
// where the edge's two halves have equal metric lengths (the size taken to vary linearly along
// the edge); on the surface, m is on the surface edge's curve, on a ridge on the ridge curve.
#include <algorithm>
#include <cmath>

#include "adapt/remesher.hpp"
#include "adapt/surface_geometry.hpp"
#include "predicates/predicates.hpp"

namespace anitet::adapt {

namespace {

// A split point closer than this (metric length) to a point made earlier in the same sweep is
// put off to the next: splitting every long edge of a stretched tet at once crowded points that
// the collapses then removed (pass 2 of the UGAWG linear loop went to 70k tets and back to 43k).
constexpr double kSpacing = 0.7;

// The parameter of the metric midpoint of ab (la, lb: its length in the metrics at a and b).
double metric_midpoint(double la, double lb) {
  if (!(la > 0.0) || !(lb > 0.0)) return 0.5;
  const double sa = std::sqrt(la), sb = std::sqrt(lb);
  return std::clamp(sb / (sa + sb), 0.2, 0.8);
}

}  // namespace

bool Remesher::split_edge(uint32_t a, uint32_t b, uint32_t t0) {
  Shell& s = shell_;
  if (!mesh_.shell(a, b, t0, s, 256)) return false;
  const bool surface = s.num_boundary > 0;
  // An edge from a kept surface point into the volume: its length cannot follow the metric (the
  // kept faces are as coarse as given), and splitting it crowds points against the kept faces
  // (UGAWG linear, --keep-surface: inner points at 1e-4 from them, 44% of the edges within 0.01
  // of a face out of range). The inner edges beside it are split instead.
  if (opt_.keep_surface && ((mesh_.tag[a] ^ mesh_.tag[b]) & ptag::kRequired)) return false;
  if (surface && (opt_.keep_surface || ((mesh_.tag[a] & ptag::kRequired) && (mesh_.tag[b] & ptag::kRequired))))
    return false;
  const double *pa = mesh_.p(a), *pb = mesh_.p(b);
  double ab[3];
  geom::sub(pb, pa, ab);
  const double tpar = metric_midpoint(std::sqrt(quad_form(mesh_.m(a), ab)), std::sqrt(quad_form(mesh_.m(b), ab)));
  double pos[3], n1[3] = {0, 0, 0}, n2[3] = {0, 0, 0}, tg[3] = {0, 0, 0};
  uint8_t tag = 0;
  if (!surface) {
    for (int k = 0; k < 3; ++k) pos[k] = pa[k] + tpar * ab[k];
    double met[6];
    uint32_t hint = mesh_.hint[a];
    metric_.eval(pos, hint, met);
    return insert_on_inner_edge(s, pos, met, hint);
  } else {
    tag = ptag::kBoundary;
    // The boundary faces through ab (the first two): their normals choose the ends' sides.
    double fn[2][3];
    for (int f = 0; f < 2; ++f) {
      const uint32_t r = s.ring[std::min<size_t>(s.bnd_ring[size_t(std::min(f, s.num_boundary - 1))], s.ring.size() - 1)];
      geom::triangle_normal(pa, pb, mesh_.p(r), fn[f]);
    }
    const bool ridge = s.num_boundary != 2 || mesh_.is_ridge(a, b);
    if (ridge) {
      tag |= ptag::kRidge;
      double ta[3], tb[3], chord[3] = {ab[0], ab[1], ab[2]};
      geom::normalize(chord);
      for (int k = 0; k < 3; ++k) {
        ta[k] = (mesh_.tag[a] & (ptag::kRidge)) && !(mesh_.tag[a] & ptag::kFrozen) ? mesh_.tng[3 * size_t(a) + size_t(k)] : chord[k];
        tb[k] = (mesh_.tag[b] & (ptag::kRidge)) && !(mesh_.tag[b] & ptag::kFrozen) ? mesh_.tng[3 * size_t(b) + size_t(k)] : chord[k];
      }
      geom::ridge_point(pa, ta, pb, tb, tpar, pos, tg);
      geom::surface_edge_normal(pa, side_normal(a, fn[0]), pb, side_normal(b, fn[0]), tpar, n1);
      geom::surface_edge_normal(pa, side_normal(a, fn[1]), pb, side_normal(b, fn[1]), tpar, n2);
    } else {
      const double *na = side_normal(a, fn[0]), *nb = side_normal(b, fn[0]);
      geom::surface_edge_point(pa, na, pb, nb, tpar, pos);
      geom::surface_edge_normal(pa, na, pb, nb, tpar, n1);
    }
  }
  // Put off when a point this sweep made is near (the split of a neighbouring edge).
  for (uint32_t r : s.ring) {
    double d[3];
    geom::sub(mesh_.p(r), pos, d);
    if (std::sqrt(std::sqrt(quad_form(mesh_.m(a), d) * quad_form(mesh_.m(b), d))) < (r >= first_new_ ? kSpacing : 0.0)) {
      ++stats_.split_refused;
      return false;
    }
  }
  // Every new tet positive.
  const size_t k = s.tets.size();
  for (size_t i = 0; i < k; ++i) {
    const double *x = mesh_.p(s.ring_at(i)), *y = mesh_.p(s.ring_at(i + 1));
    if (predicates::orient3d(pa, pos, x, y) <= 0 || predicates::orient3d(pos, pb, x, y) <= 0) {
      ++stats_.split_refused;
      return false;
    }
  }
  // The halves of the boundary faces through ab fit the smooth surface as well as they did.
  const PointGeometry g{uint32_t(mesh_.num_points()), tag, n1, (tag & ptag::kRidge) ? n2 : nullptr};
  for (const uint32_t t : s.tets) {
    if (!mesh_.bnd[t]) continue;
    const uint32_t* w = mesh_.verts(t);
    for (int f = 0; f < 4; ++f) {
      if (!mesh_.is_bnd_face(t, f) || w[f] == a || w[f] == b) continue;  // faces through ab only
      uint32_t fv[3] = {w[kFaceVertex[f][0]], w[kFaceVertex[f][1]], w[kFaceVertex[f][2]]};
      const bool hull = mesh_.adj[4 * size_t(t) + f] == kNone;
      double n[3];
      geom::triangle_normal(mesh_.p(fv[0]), mesh_.p(fv[1]), mesh_.p(fv[2]), n);
      for (double& c : n) c = -c;  // out of the tet
      const double before = std::min(surface_fit(fv, n, hull), kSurfaceFit);
      for (uint32_t end : {a, b}) {
        uint32_t half[3] = {fv[0], fv[1], fv[2]};
        const double* x[3];
        for (int j = 0; j < 3; ++j) {
          if (half[j] == end) half[j] = g.id;
          x[j] = half[j] == g.id ? pos : mesh_.p(half[j]);
        }
        geom::triangle_normal(x[0], x[1], x[2], n);
        for (double& c : n) c = -c;
        if (surface_fit(half, n, hull, &g) < before) {
          ++stats_.split_refused;
          return false;
        }
      }
    }
  }
  double met[6];
  uint32_t hint = mesh_.hint[a];
  metric_.eval(pos, hint, met);
  const uint32_t mid = mesh_.add_point(pos, met, tag, hint);
  for (int c = 0; c < 3; ++c) {
    mesh_.nrm[3 * size_t(mid) + size_t(c)] = n1[c];
    mesh_.nrm2[3 * size_t(mid) + size_t(c)] = n2[c];
    mesh_.tng[3 * size_t(mid) + size_t(c)] = tg[c];
  }
  mesh_.sync_marks();
  created_.resize(k);
  for (size_t i = 0; i < k; ++i) {
    const uint32_t t = s.tets[i];
    const int ia = mesh_.local(t, a), ib = mesh_.local(t, b);
    uint32_t w[4];
    std::copy(mesh_.verts(t), mesh_.verts(t) + 4, w);
    w[ia] = mid;
    const uint32_t t2 = mesh_.new_tet(w[0], w[1], w[2], w[3], mesh_.region[t]);
    mesh_.bnd[t2] = mesh_.bnd[t];
    for (int j = 0; j < 4; ++j) mesh_.fref[4 * size_t(t2) + j] = mesh_.fref[4 * size_t(t) + j];
    // t2 takes t's face opposite a; t and t2 meet across (m x y).
    const uint32_t across_a = mesh_.adj[4 * size_t(t) + ia];
    mesh_.adj[4 * size_t(t2) + ia] = across_a;
    if (across_a != kNone) mesh_.adj[across_a] = 4 * t2 + uint32_t(ia);
    mesh_.adj[4 * size_t(t) + ia] = 4 * t2 + uint32_t(ib);
    mesh_.adj[4 * size_t(t2) + ib] = 4 * t + uint32_t(ia);
    mesh_.bnd[t] &= uint8_t(~(1u << ia));
    mesh_.bnd[t2] &= uint8_t(~(1u << ib));
    mesh_.tv[4 * size_t(t) + size_t(ib)] = mid;
    created_[i] = t2;
  }
  // The halves t2 around the edge (m b): as the tets around ab were.
  for (size_t i = 0; i < k; ++i) {
    if (i + 1 == k && s.open) break;
    const size_t j = (i + 1) % k;
    const int lx = mesh_.local(s.tets[i], s.ring_at(i));
    const int ly = mesh_.local(s.tets[j], s.ring_at(j + 1));
    mesh_.adj[4 * size_t(created_[i]) + lx] = 4 * created_[j] + uint32_t(ly);
    mesh_.adj[4 * size_t(created_[j]) + ly] = 4 * created_[i] + uint32_t(lx);
  }
  mesh_.ptet[mid] = s.tets[0];
  mesh_.ptet[b] = created_[0];
  for (size_t i = 0; i < k; ++i) {
    update_quality(s.tets[i]);
    update_quality(created_[i]);
    mesh_.touch_tet(s.tets[i]);
    mesh_.touch_tet(created_[i]);
  }
  if (tag & ptag::kRidge) {
    mesh_.set_ridge(a, b, false);
    mesh_.set_ridge(a, mid, true);
    mesh_.set_ridge(mid, b, true);
  }
  ++stats_.splits;
  if (surface) ++stats_.surface_splits;
  return true;
}

size_t Remesher::split_sweep() {
  first_new_ = uint32_t(mesh_.num_points());
  collect_edges(-1.0, opt_.split_length, edges_);
  std::sort(edges_.begin(), edges_.end(), [](const EdgeRec& x, const EdgeRec& y) { return x.length > y.length; });
  size_t made = 0;
  for (const EdgeRec& e : edges_) {
    uint32_t t = e.t;
    if (mesh_.dead(t) || mesh_.local(t, e.a) < 0 || mesh_.local(t, e.b) < 0) t = mesh_.edge_tet(e.a, e.b, ball_);
    if (t == kNone) continue;
    made += split_edge(e.a, e.b, t);
  }
  return made;
}

}  // namespace anitet::adapt
