#pragma once
/// \file pitchfork_half_period.hpp
/// \brief SymmetricBranches' classification (the part shared with and without a half-period
/// shift), and under a half-period shift: the classification by the half-period map's
/// eigenvalues (-1: pitchfork, +1: fold) and the pitchfork located by a secant on det(H + I).

#include <stickslip/steady_state/pitchfork.hpp>

#include <array>
#include <deque>
#include <string>

namespace stickslip {

template <class System>
template <class Crossing>
SymmetryBreakingPoint<System> SymmetricBranches<System>::classified(const ContinuationPoint<System>& a,
                                                                    const ContinuationPoint<System>& b,
                                                                    std::array<Scalar, 2> gm, std::array<Scalar, 2> gp,
                                                                    const std::string& none_m,
                                                                    const std::string& none_p,
                                                                    Crossing&& crossing) const {
  SymmetryBreakingPoint<System> c;
  std::array<Scalar, 2> g{};
  if (gm[0] * gm[1] <= 0) {
    c.kind = BifurcationKind::Pitchfork;
    g = gm;
  } else if (gp[0] * gp[1] <= 0) {
    c.kind = BifurcationKind::Fold;
    g = gp;
  } else {
    c.message = none_m + detail::format_value(gm[0]) + ", " + detail::format_value(gm[1]) + none_p +
                detail::format_value(gp[0]) + ", " + detail::format_value(gp[1]) + ")";
    return c;
  }
  c.ok = true;
  c.parameter = g[0] != g[1] ? a.parameter + (b.parameter - a.parameter) * g[0] / (g[0] - g[1])
                             : (a.parameter + b.parameter) / 2;
  // The orbit nearer the crossing (the smaller |g|) that has a real multiplier there.
  int k = std::abs(g[0]) <= std::abs(g[1]) ? 0 : 1;
  c.multiplier = crossing(k, c.kind, &c.eigenvector);
  if (!detail::is_finite(c.multiplier)) {
    k = 1 - k;
    c.multiplier = crossing(k, c.kind, &c.eigenvector);
  }
  c.orbit = (k == 0 ? a : b).orbit;
  c.tangent = detail::branch_secant(a, b, shooting_);
  return c;
}

template <class System>
SymmetryBreakingPoint<System> SymmetricBranches<System>::classify_half(const ContinuationPoint<System>& a,
                                                                       const ContinuationPoint<System>& b) const {
  SymmetryBreakingPoint<System> c;
  const ContinuationPoint<System>* pts[2] = {&a, &b};
  detail::HalfPeriodMap<System> h[2];
  for (int k = 0; k < 2; ++k) {
    h[k] = half_map(*pts[k], true);
    const std::string at = "the orbit at p = " + detail::format_value(pts[k]->parameter);
    if (!h[k].ok) {
      c.message = at + ": " + h[k].message;
      return c;
    }
    Scalar m = 0;
    for (const auto i : shooting_.periodic_indices(pts[k]->orbit.x0.size())) m = std::max(m, std::abs(pts[k]->orbit.x0[i]));
    if (!(h[k].asymmetry <= sym_tol_ * std::max(Scalar(1), m))) {
      c.message = at + " is not symmetric (max |x(t0 + T/2) - S x(t0)| = " + detail::format_value(h[k].asymmetry) +
                  "): the branch must be a symmetric one";
      return c;
    }
  }
  return classified(
      a, b, {detail::det_shifted(h[0].H, Scalar(-1)), detail::det_shifted(h[1].H, Scalar(-1))},
      {detail::det_shifted(h[0].H, Scalar(1)), detail::det_shifted(h[1].H, Scalar(1))},
      "no real eigenvalue of the half-period map crosses -1 or +1 between the points (det(H + I) ", "; det(H - I) ",
      [&](int k, BifurcationKind kind, Vector* v) {
        const Scalar eig = detail::nearest_real_eigenvalue(h[k].H, Scalar(kind == BifurcationKind::Pitchfork ? -1 : 1),
                                                           shooting_.multiplier_tolerance, v);
        return eig * eig;  // M = H^2 (NaN stays NaN)
      });
}

template <class System>
SymmetryBreakingPoint<System> SymmetricBranches<System>::locate_half(SymmetryBreakingPoint<System> c,
                                                                     const ContinuationPoint<System>& a,
                                                                     const ContinuationPoint<System>& b,
                                                                     Scalar tolerance) {
  Shooting<System> shooting(sys_, shooting_);
  using End = detail::SecantEnd<System>;
  const Scalar tol = shooting_.multiplier_tolerance;
  // The half-period maps of the orbits met, by parameter (the secant asks for each twice).
  std::deque<std::pair<Scalar, Matrix>> maps;  // stable addresses
  const auto map_of = [&](Scalar p, const PeriodicOrbit<System>& orbit, std::string& why) -> const Matrix* {
    for (const auto& m : maps)
      if (m.first == p) return &m.second;
    ContinuationPoint<System> pt;
    pt.parameter = p;
    pt.orbit = orbit;
    auto h = half_map(pt, true);
    if (!h.ok) {
      why = "the orbit at p = " + detail::format_value(p) + ": " + h.message;
      return nullptr;
    }
    maps.emplace_back(p, std::move(h.H));
    return &maps.back().second;
  };
  std::string why;
  End lo{a.parameter, 0, a.orbit}, hi{b.parameter, 0, b.orbit};
  for (End* e : {&lo, &hi}) {
    const Matrix* H = map_of(e->p, e->orbit, why);
    if (!H) {
      c.ok = false;
      c.message = why;
      return c;
    }
    e->g = detail::det_shifted(*H, Scalar(-1));
  }
  // The secant on g = det(H + I), each orbit shot at fixed p from the bracket's nearer orbit.
  const auto shoot = [&](Scalar p, const End& from, End& e, std::string& why_not) {
    set_(sys_, p);
    e.p = p;
    e.orbit = shooting.forced(from.orbit.mode, from.orbit.t0, from.orbit.x0, period_(p));
    if (!e.orbit.ok()) {
      why_not = "the orbit at p = " + detail::format_value(p) + " failed: " + e.orbit.message;
      return false;
    }
    const Matrix* H = map_of(p, e.orbit, why_not);
    if (!H) return false;
    e.g = detail::det_shifted(*H, Scalar(-1));
    return true;
  };
  const auto done = [&](const End& e) {
    std::string ignored;
    const Matrix* H = map_of(e.p, e.orbit, ignored);
    if (!H) return false;
    const Scalar h = detail::nearest_real_eigenvalue(*H, Scalar(-1), tol, static_cast<Vector*>(nullptr));
    return std::abs(h * h - 1) <= tolerance;
  };
  End found;
  if (!detail::illinois_secant(lo, hi, shoot, done, found, c.message)) {
    c.ok = false;
    return c;
  }
  const Matrix* H = map_of(found.p, found.orbit, why);
  c.located = true;
  c.parameter = found.p;
  c.orbit = found.orbit;
  const Scalar h = detail::nearest_real_eigenvalue(*H, Scalar(-1), tol, &c.eigenvector);
  c.multiplier = h * h;
  return c;
}

}  // namespace stickslip
