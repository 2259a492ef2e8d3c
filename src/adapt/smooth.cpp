// Vertex moves. For each tet of v's ball, the ideal place of v is the apex of the regular tet (in
// v's metric) on the opposite face, at the height sqrt(2/3) times that face's mean edge length;
// v is tried at the mean of those points, then half and a quarter of the way there. A surface
// point moves in its tangent plane and lands on the PN triangle of the boundary face it crosses
// into; a ridge point moves along the ridge curve. A move is made when every tet of the ball
// stays positive (exact orient3d), the worst quality of the ball does not fall and the sum
// rises (or the worst rises), and on the surface no boundary face turns by more than kSurfaceTurn
// or fits the smooth surface worse than it did (surface_fit).
// When that finds no move, v is tried where its edges come nearer unit length (balance: each
// neighbour wants v at unit metric length on the line through them): made when the sum of
// squared log lengths of v's edges falls by 5% and no tet of the ball falls below
// min(its worst, kBalanceQuality). The mean ratio (the worst over the corners' metrics) sees
// the metric's turn over a tet only in part; the lengths see it along each edge: on a curved
// wall with a strong normal metric (the sphere case, h_r = 0.001 at R = 0.5) a tangential edge
// of length l has a normal part l^2/2R at its ends, so the lengths in range span a factor 1.4
// in l, not 2, and the quality moves left the tangential spacing uneven (misses short and long
// side by side).
#include <algorithm>
#include <cmath>

#include "adapt/remesher.hpp"
#include "adapt/surface_geometry.hpp"
#include "predicates/predicates.hpp"

namespace anitet::adapt {

namespace {

const double kSurfaceTurn = std::cos(20.0 * M_PI / 180.0);
// The quality a balancing move may lower a tet to. Sphere case, pass 2 in range: 81.0% at 0.3,
// 82.3% at 0.2, 83.5% at 0.15; at 0.1 UGAWG linear's mean ratio min fell to 0.31 (0.55 at 0.15;
// issue 46 asks >= 0.4).
constexpr double kBalanceQuality = 0.15;
constexpr double kBalanceGain = 0.95;

bool sym_inverse(const double m[6], double inv[6]) {
  const double a = m[0], b = m[1], c = m[2], d = m[3], e = m[4], f = m[5];
  const double A = c * f - e * e, B = d * e - b * f, C = b * e - c * d;
  const double det = a * A + b * B + d * C;
  if (!(det > 0.0)) return false;
  inv[0] = A / det;
  inv[1] = B / det;
  inv[2] = (a * f - d * d) / det;
  inv[3] = C / det;
  inv[4] = (b * d - a * e) / det;
  inv[5] = (a * c - b * b) / det;
  return true;
}

void sym_apply(const double m[6], const double x[3], double y[3]) {
  y[0] = m[0] * x[0] + m[1] * x[1] + m[3] * x[2];
  y[1] = m[1] * x[0] + m[2] * x[1] + m[4] * x[2];
  y[2] = m[3] * x[0] + m[4] * x[1] + m[5] * x[2];
}

}  // namespace

bool Remesher::ideal_point(uint32_t t, int i, const double m[6], double out[3]) const {
  const uint32_t* w = mesh_.verts(t);
  const double *f0 = mesh_.p(w[kFaceVertex[i][0]]), *f1 = mesh_.p(w[kFaceVertex[i][1]]),
               *f2 = mesh_.p(w[kFaceVertex[i][2]]);
  double e1[3], e2[3], e3[3], n[3];
  geom::sub(f1, f0, e1);
  geom::sub(f2, f0, e2);
  geom::sub(f2, f1, e3);
  geom::cross(e1, e2, n);  // towards vertex i
  double inv[6], d[3];
  if (!sym_inverse(m, inv)) return false;
  sym_apply(inv, n, d);
  const double dn = geom::dot(d, n);
  if (!(dn > 0.0)) return false;
  const double e = (std::sqrt(quad_form(m, e1)) + std::sqrt(quad_form(m, e2)) + std::sqrt(quad_form(m, e3))) / 3.0;
  const double s = e * std::sqrt(2.0 / 3.0) / std::sqrt(dn);
  for (int k = 0; k < 3; ++k) out[k] = (f0[k] + f1[k] + f2[k]) / 3.0 + s * d[k];
  return true;
}

void Remesher::neighbours(uint32_t v, const std::vector<uint32_t>& ball, std::vector<uint32_t>& out) {
  out.clear();
  mesh_.next_stamp();
  mesh_.mark_point(v);
  for (uint32_t t : ball)
    for (int i = 0; i < 4; ++i) {
      const uint32_t y = mesh_.verts(t)[i];
      if (!mesh_.point_marked(y)) mesh_.mark_point(y), out.push_back(y);
    }
}

double Remesher::length_energy(const std::vector<uint32_t>& nb, const double pos[3], const double met[6]) const {
  double e = 0.0;
  for (uint32_t y : nb) {
    const double l = ugawg_edge_length(pos, mesh_.p(y), met, mesh_.m(y));
    if (!(l > 0.0)) return HUGE_VAL;
    e += std::log(l) * std::log(l);
  }
  return e;
}

bool Remesher::balance_target(uint32_t v, const std::vector<uint32_t>& ball, double out[3]) {
  neighbours(v, ball, nb_);
  if (nb_.empty()) return false;
  nb_energy_ = length_energy(nb_, mesh_.p(v), mesh_.m(v));
  const double* p = mesh_.p(v);
  out[0] = out[1] = out[2] = 0.0;
  for (uint32_t y : nb_) {
    const double l = length(v, y);
    if (!(l > 0.0)) return false;
    const double* py = mesh_.p(y);
    for (int k = 0; k < 3; ++k) out[k] += py[k] + (p[k] - py[k]) / l;
  }
  for (int k = 0; k < 3; ++k) out[k] /= double(nb_.size());
  return true;
}

bool Remesher::try_move(uint32_t v, const std::vector<uint32_t>& ball, const double pos[3], const double* nrm,
                        const double* nrm2, const double* tng, bool surface, bool balance) {
  double met[6];
  uint32_t hint = mesh_.hint[v];
  metric_.eval(pos, hint, met);
  const double det = metric_det(met);
  if (balance && !(length_energy(nb_, pos, met) < kBalanceGain * nb_energy_))
    return false;
  double old_min = 1.0, old_sum = 0.0, new_min = 1.0, new_sum = 0.0;
  newq_.resize(ball.size());
  for (size_t k = 0; k < ball.size(); ++k) {
    const uint32_t t = ball[k];
    old_min = std::min(old_min, mesh_.qual[t]);
    old_sum += mesh_.qual[t];
    const double q = quality(mesh_.verts(t), v, pos, met, det);
    if (!(q > 0.0)) return false;
    newq_[k] = q;
    new_min = std::min(new_min, q);
    new_sum += q;
  }
  const bool better = balance ? new_min >= std::min(old_min, kBalanceQuality)
                              : (new_min > old_min + 1e-6 && new_sum > old_sum - 1e-3) ||
                                    (new_min >= old_min && new_sum > old_sum + 1e-6 * double(ball.size()));
  if (!better) return false;
  for (uint32_t t : ball) {
    const uint32_t* w = mesh_.verts(t);
    const double* x[4];
    for (int i = 0; i < 4; ++i) x[i] = w[i] == v ? pos : mesh_.p(w[i]);
    if (predicates::orient3d(x[0], x[1], x[2], x[3]) <= 0) return false;
  }
  if (surface) {
    for (uint32_t t : ball) {
      if (!mesh_.bnd[t]) continue;
      const uint32_t* w = mesh_.verts(t);
      const int iv = mesh_.local(t, v);
      for (int i = 0; i < 4; ++i) {
        if (i == iv || !mesh_.is_bnd_face(t, i)) continue;
        const double* x[3];
        const uint32_t fv[3] = {w[kFaceVertex[i][0]], w[kFaceVertex[i][1]], w[kFaceVertex[i][2]]};
        for (int j = 0; j < 3; ++j) x[j] = mesh_.p(fv[j]);
        double before[3], after[3];
        geom::triangle_normal(x[0], x[1], x[2], before);
        for (int j = 0; j < 3; ++j)
          if (fv[j] == v) x[j] = pos;
        geom::triangle_normal(x[0], x[1], x[2], after);
        if (geom::dot(before, after) < kSurfaceTurn) return false;
        // Out of the tet (kFaceVertex turns it in): no fold against the surface normals.
        const bool hull = mesh_.adj[4 * size_t(t) + i] == kNone;
        for (double& c : before) c = -c;
        for (double& c : after) c = -c;
        const PointGeometry g{v, mesh_.tag[v], nrm ? nrm : &mesh_.nrm[3 * size_t(v)],
                              nrm2 ? nrm2 : &mesh_.nrm2[3 * size_t(v)]};
        if (surface_fit(fv, after, hull, &g) < std::min(surface_fit(fv, before, hull), kSurfaceFit)) return false;
      }
    }
  }
  for (int k = 0; k < 3; ++k) mesh_.xyz[3 * size_t(v) + size_t(k)] = pos[k];
  mesh_.set_metric(v, met);
  mesh_.hint[v] = hint;
  for (int k = 0; k < 3; ++k) {
    if (nrm) mesh_.nrm[3 * size_t(v) + size_t(k)] = nrm[k];
    if (nrm2) mesh_.nrm2[3 * size_t(v) + size_t(k)] = nrm2[k];
    if (tng) mesh_.tng[3 * size_t(v) + size_t(k)] = tng[k];
  }
  for (size_t k = 0; k < ball.size(); ++k) mesh_.qual[ball[k]] = newq_[k];
  mesh_.touch(v);
  ++stats_.moves;
  if (surface) ++stats_.surface_moves;
  return true;
}

namespace {

// The mean of v's ideal points over its ball; false when one cannot be had.
template <class Ideal>
bool ideal_mean(const AdaptMesh& mesh, uint32_t v, const std::vector<uint32_t>& ball, Ideal&& ideal, double out[3]) {
  out[0] = out[1] = out[2] = 0.0;
  for (uint32_t t : ball) {
    double x[3];
    if (!ideal(t, mesh.local(t, v), x)) return false;
    for (int k = 0; k < 3; ++k) out[k] += x[k];
  }
  for (int k = 0; k < 3; ++k) out[k] /= double(ball.size());
  return true;
}

}  // namespace

bool Remesher::move_interior(uint32_t v, const std::vector<uint32_t>& ball) {
  double target[3];
  const double* m = mesh_.m(v);
  if (!ideal_mean(mesh_, v, ball, [&](uint32_t t, int i, double* x) { return ideal_point(t, i, m, x); }, target))
    return false;
  if (move_interior_towards(v, ball, target, false)) return true;
  return balance_target(v, ball, target) && move_interior_towards(v, ball, target, true);
}

bool Remesher::move_interior_towards(uint32_t v, const std::vector<uint32_t>& ball, const double target[3],
                                     bool balance) {
  const double* p = mesh_.p(v);
  for (double w : {1.0, 0.5, 0.25}) {
    const double pos[3] = {p[0] + w * (target[0] - p[0]), p[1] + w * (target[1] - p[1]), p[2] + w * (target[2] - p[2])};
    if (try_move(v, ball, pos, nullptr, nullptr, nullptr, false, balance)) return true;
  }
  return false;
}

bool Remesher::move_surface(uint32_t v, const std::vector<uint32_t>& ball) {
  double target[3];
  const double* m = mesh_.m(v);
  if (!ideal_mean(mesh_, v, ball, [&](uint32_t t, int i, double* x) { return ideal_point(t, i, m, x); }, target))
    return false;
  if (move_surface_towards(v, ball, target, false)) return true;
  return balance_target(v, ball, target) && move_surface_towards(v, ball, target, true);
}

bool Remesher::move_surface_towards(uint32_t v, const std::vector<uint32_t>& ball, const double target[3],
                                    bool balance) {
  const double* p = mesh_.p(v);
  const double* n = &mesh_.nrm[3 * size_t(v)];
  double delta[3];
  geom::sub(target, p, delta);
  const double dn = geom::dot(delta, n);
  for (int k = 0; k < 3; ++k) delta[k] -= dn * n[k];
  for (double w : {1.0, 0.5, 0.25}) {
    const double c[3] = {p[0] + w * delta[0], p[1] + w * delta[1], p[2] + w * delta[2]};
    // The boundary face at v that c falls in (its largest smallest barycentric coordinate).
    double best = -0.05, bary[3] = {0, 0, 0};
    uint32_t fv[3] = {kNone, kNone, kNone};
    for (uint32_t t : ball) {
      if (!mesh_.bnd[t]) continue;
      const uint32_t* w4 = mesh_.verts(t);
      const int iv = mesh_.local(t, v);
      for (int i = 0; i < 4; ++i) {
        if (i == iv || !mesh_.is_bnd_face(t, i)) continue;
        const uint32_t x[3] = {w4[kFaceVertex[i][0]], w4[kFaceVertex[i][1]], w4[kFaceVertex[i][2]]};
        double fn[3];
        geom::triangle_normal(mesh_.p(x[0]), mesh_.p(x[1]), mesh_.p(x[2]), fn);
        double lam[3], sum = 0.0;
        for (int j = 0; j < 3; ++j) {
          // Signed area of (c, x[j+1], x[j+2]) along fn.
          double e1[3], e2[3], cr[3];
          geom::sub(mesh_.p(x[(j + 1) % 3]), c, e1);
          geom::sub(mesh_.p(x[(j + 2) % 3]), c, e2);
          geom::cross(e1, e2, cr);
          lam[j] = geom::dot(cr, fn);
          sum += lam[j];
        }
        if (!(sum > 0.0)) continue;
        const double lo = std::min({lam[0], lam[1], lam[2]}) / sum;
        if (lo > best) {
          best = lo;
          for (int j = 0; j < 3; ++j) bary[j] = lam[j] / sum, fv[j] = x[j];
        }
      }
    }
    if (fv[0] == kNone) continue;
    for (double& b : bary) b = std::max(b, 0.0);
    const double bs = bary[0] + bary[1] + bary[2];
    for (double& b : bary) b /= bs;
    double fn[3];
    geom::triangle_normal(mesh_.p(fv[0]), mesh_.p(fv[1]), mesh_.p(fv[2]), fn);
    const double* pts[3] = {mesh_.p(fv[0]), mesh_.p(fv[1]), mesh_.p(fv[2])};
    const double* nrms[3] = {side_normal(fv[0], fn), side_normal(fv[1], fn), side_normal(fv[2], fn)};
    double pos[3], nn[3];
    geom::pn_triangle(pts, nrms, bary, pos, nn);
    if (geom::dot(nn, n) < 0) nn[0] = -nn[0], nn[1] = -nn[1], nn[2] = -nn[2];
    if (try_move(v, ball, pos, nn, nullptr, nullptr, true, balance)) return true;
  }
  return false;
}

bool Remesher::move_ridge(uint32_t v, const std::vector<uint32_t>& ball) {
  uint32_t nb[2] = {kNone, kNone};
  int found = 0;
  for (uint32_t t : ball)
    for (int i = 0; i < 4; ++i) {
      const uint32_t x = mesh_.verts(t)[i];
      if (x == v || x == nb[0] || x == nb[1] || !mesh_.is_ridge(v, x)) continue;
      if (found == 2) return false;  // not a simple ridge point any more
      nb[found++] = x;
    }
  if (found != 2) return false;
  double target[3];
  const double* m = mesh_.m(v);
  if (!ideal_mean(mesh_, v, ball, [&](uint32_t t, int i, double* x) { return ideal_point(t, i, m, x); }, target))
    return false;
  const double* p = mesh_.p(v);
  const double* tv = &mesh_.tng[3 * size_t(v)];
  double d[3];
  geom::sub(target, p, d);
  const double s = geom::dot(d, tv);
  if (s == 0.0) return false;
  uint32_t w = kNone;
  for (uint32_t x : nb) {
    double e[3];
    geom::sub(mesh_.p(x), p, e);
    if (geom::dot(e, tv) * s > 0) w = x;
  }
  if (w == kNone) return false;
  double e[3], chord[3];
  geom::sub(mesh_.p(w), p, e);
  const double len = geom::norm(e);
  for (int k = 0; k < 3; ++k) chord[k] = e[k] / len;
  const double* tw = (mesh_.tag[w] & ptag::kRidge) && !(mesh_.tag[w] & ptag::kFrozen) ? &mesh_.tng[3 * size_t(w)] : chord;
  const double* n1 = &mesh_.nrm[3 * size_t(v)];
  const double* n2 = &mesh_.nrm2[3 * size_t(v)];
  for (double om : {1.0, 0.5, 0.25}) {
    const double t = std::min(om * std::fabs(s) / len, 0.4);
    double pos[3], tan[3], nn1[3], nn2[3];
    geom::ridge_point(p, tv, mesh_.p(w), tw, t, pos, tan);
    if (geom::dot(tan, tv) < 0) tan[0] = -tan[0], tan[1] = -tan[1], tan[2] = -tan[2];
    geom::surface_edge_normal(p, n1, mesh_.p(w), side_normal(w, n1), t, nn1);
    geom::surface_edge_normal(p, n2, mesh_.p(w), side_normal(w, n2), t, nn2);
    if (geom::dot(nn1, n1) < 0) nn1[0] = -nn1[0], nn1[1] = -nn1[1], nn1[2] = -nn1[2];
    if (geom::dot(nn2, n2) < 0) nn2[0] = -nn2[0], nn2[1] = -nn2[1], nn2[2] = -nn2[2];
    if (try_move(v, ball, pos, nn1, nn2, tan, true)) return true;
  }
  return false;
}

bool Remesher::move_point(uint32_t v) {
  const uint8_t tag = mesh_.tag[v];
  if (tag & (ptag::kFrozen | ptag::kRemoved)) return false;
  std::vector<uint32_t>& ball = ball2_;
  mesh_.ball(v, ball);
  if (ball.empty()) return false;
  if (!(tag & ptag::kBoundary)) return move_interior(v, ball);
  if (tag & ptag::kRidge) return move_ridge(v, ball);
  return move_surface(v, ball);
}

size_t Remesher::smooth_sweep(bool all_points) {
  size_t made = 0;
  for (uint32_t v = 0; v < mesh_.num_points(); ++v)
    if (all_points || mesh_.active(v)) made += move_point(v);
  return made;
}

}  // namespace anitet::adapt
