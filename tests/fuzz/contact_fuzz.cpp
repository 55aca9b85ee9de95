// Fuzz harness: the friction laws (CoulombLaw, StribeckLaw, RegularisedLaw), CoulombContact
// (friction force, guards, decide) in every ContactState including Separated, and the impact laws
// (NewtonImpact, coulomb_impulse, frictional_impact) on extreme inputs. Layout of an input
// (tests/fuzz/fuzz_input.hpp encoding; make_corpus.py writes it): law choice(3), its parameters
// (Coulomb: mu_s, mu_k; Stribeck: mu_s, mu_k, v_s, exponent; regularised: mu, v_eps, shape
// choice(2)), the velocity tolerance, then up to 8 probes, each a kind choice(6) followed by
//   kinds 0-4 (the ContactState of that value): v, N, f_required, watch_lift_off flag;
//   kind 5 (an impact): e, landing_speed, W_nn, W_nt, W_tt, asymmetric flag [W_tn if set], v_n, v_t.
//
// Rules checked besides the exception types: for finite inputs of moderate size (|.| <= 1e150,
// so that products of two stay finite) and friction coefficients <= 1e6, the coefficients, their
// derivative, the friction force and the guards are finite; an exact law's kinetic coefficient lies in [mu_k, mu_s]; a regularised
// coefficient is odd with |c| <= mu and a derivative >= 0; decide() obeys eq. 1 where the rules
// leave no choice (N <= 0 -> lift-off; a stick decision has |f_required| <= mu_s N; a slip
// decision goes with v when |v| exceeds the tolerance, else against f_required beyond capacity);
// a separated contact has no friction force and one Falling guard, its gap.
// Impacts (rules in check_newton / check_coulomb_impulse / check_frictional_impact): refused
// exactly when an argument is outside its documented domain; for well-posed inputs (|v| <= 1e50,
// W's entries <= 1e50, W_nn, W_tt >= 1e-50, det W >= 1e-12 W_nn W_tt) the results are finite, the
// normal impulse is >= 0 and gives Newton's velocity (-e v_n or the landing's 0), the tangential
// impulse lies in the Coulomb cone |L_t| <= mu_s L_n and does not reverse the slip, the velocities
// after are v + W L, the energy loss is -L.v - L^T W L / 2 and, with the directions decoupled
// (W_nt = 0, e <= 1), not negative; frictional_impact with W_nt = 0 equals NewtonImpact::impact
// followed by coulomb_impulse.
#include "fuzz/fuzz_input.hpp"

#include <stickslip/contact.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace contact_fuzz {

using namespace stickslip;
using stickslip_fuzz::require;
using stickslip_fuzz::str;

bool moderate(double v) { return std::isfinite(v) && std::abs(v) <= 1e150; }

/// Friction coefficients up to 1e6 count as physical: beyond, products with forces may overflow.
template <class Law>
bool physical(const Law& law) {
  if constexpr (Law::has_stick_state)
    return law.static_coefficient() <= 1e6;
  else
    return law.mu() <= 1e6;
}

template <class Law>
void probe_law(const Law& law, double v) {
  if (!moderate(v) || !physical(law)) return;
  if constexpr (Law::has_stick_state) {
    const double mu = law.kinetic_coefficient(std::abs(v));
    const double mu_s = law.static_coefficient();
    require(std::isfinite(mu), "kinetic_coefficient(" + str(std::abs(v)) + ") = " + str(mu));
    // mu_k <= mu(s) <= mu_s up to the rounding of mu_k + (mu_s - mu_k) e^-p.
    require(mu <= mu_s * (1 + 4e-16) && mu >= 0,
            "kinetic_coefficient(" + str(std::abs(v)) + ") = " + str(mu) + " outside [0, mu_s]");
  } else {
    const double c = law.coefficient(v), cm = law.coefficient(-v);
    const double d = law.coefficient_derivative(v);
    require(std::isfinite(c) && std::isfinite(d),
            "coefficient(" + str(v) + ") = " + str(c) + ", coefficient_derivative = " + str(d) +
                " (mu = " + str(law.mu()) + ", v_eps = " + str(law.v_eps()) + ")");
    require(c == -cm, "coefficient not odd at v = " + str(v));
    require(std::abs(c) <= law.mu() && d >= 0,
            "coefficient(" + str(v) + ") = " + str(c) + " |c| > mu or derivative " + str(d) + " < 0");
  }
}

constexpr double kDenormal = std::numeric_limits<double>::denorm_min();

/// Relative agreement |a - b| <= rel * scale + 1e-300 (scale: the size of the terms that made a, b).
bool near(double a, double b, double rel, double scale) {
  return std::abs(a - b) <= rel * scale + 1e-300;
}

/// One impact probe (kind 5 of the layout): the inputs as read, and whether they are well posed.
struct ImpactInput {
  double e, landing_speed;
  Eigen::Matrix2d W;
  Eigen::Vector2d v;

  explicit ImpactInput(stickslip_fuzz::Input& in) {
    e = in.real(0.0, 1.0);
    landing_speed = in.real(0.0, 1e-2);
    W(0, 0) = in.real(0.0, 10.0);
    W(0, 1) = W(1, 0) = in.real(-3.0, 3.0);
    W(1, 1) = in.real(0.0, 10.0);
    if (in.flag()) W(1, 0) = in.real(-3.0, 3.0);
    v[0] = in.real(-10.0, 10.0);
    v[1] = in.real(-10.0, 10.0);
  }

  /// The size where results are finite: |v| <= 1e50, |W| <= 1e50, W_nn, W_tt >= 1e-50 and
  /// det W >= 1e-12 W_nn W_tt (then |W^-1| <= 1e62 and |L| <= 1e112).
  bool well_posed() const {
    const bool sizes = v.allFinite() && W.allFinite() && v.cwiseAbs().maxCoeff() <= 1e50 &&
                       W.cwiseAbs().maxCoeff() <= 1e50 && W(0, 0) >= 1e-50 && W(1, 1) >= 1e-50;
    return sizes && W(0, 1) == W(1, 0) && W.determinant() >= 1e-12 * W(0, 0) * W(1, 1);
  }
  std::string text() const {
    return " (e = " + str(e) + ", landing_speed = " + str(landing_speed) + ", W = [" +
           str(W(0, 0)) + ", " + str(W(0, 1)) + "; " + str(W(1, 0)) + ", " + str(W(1, 1)) +
           "], v = (" + str(v[0]) + ", " + str(v[1]) + "))";
  }
};

/// NewtonImpact::impact(v_n, W_nn): refused exactly for non-finite v_n or W_nn not finite and
/// > 0; W_nn L = v_after - v_n with v_after = -e v_n (bounce) or max(v_n, 0) (landing, e = 0 or
/// v_n >= -landing_speed); L >= 0; loss = (v_n^2 - v_after^2) / (2 W_nn) >= 0 (e <= 1).
NormalImpact<double> check_newton(const NewtonImpact<double>& newton, const ImpactInput& x) {
  const double v_n = x.v[0], w = x.W(0, 0);
  NormalImpact<double> r;
  try {
    r = newton.impact(v_n, w);
  } catch (const std::invalid_argument&) {
    require(!(std::isfinite(v_n) && std::isfinite(w) && w > 0),
            "NewtonImpact::impact refused a valid input" + x.text());
    throw;
  }
  require(std::isfinite(v_n) && std::isfinite(w) && w > 0,
          "NewtonImpact::impact accepted an invalid input" + x.text());
  const bool lands = x.e == 0 || v_n >= -x.landing_speed;
  require(r.lands == lands, "NewtonImpact: landing rule" + x.text());
  require(r.velocity_after == (lands ? std::max(v_n, 0.0) : -x.e * v_n),
          "NewtonImpact: velocity after " + str(r.velocity_after) + x.text());
  if (!x.well_posed()) return r;
  require(std::isfinite(r.impulse) && std::isfinite(r.energy_loss),
          "NewtonImpact: non-finite impulse or loss" + x.text());
  require(r.impulse >= 0, "NewtonImpact: negative normal impulse " + str(r.impulse) + x.text());
  // Rounding of (v_after - v_n) / W_nn, and its underflow (an impulse below the denormals: W_nn times
  // the denormal spacing).
  require(near(w * r.impulse, r.velocity_after - v_n, 1e-14, std::abs(v_n) + std::abs(r.velocity_after)) ||
              std::abs(w * r.impulse - (r.velocity_after - v_n)) <= 2 * w * kDenormal,
          "NewtonImpact: W L != v_after - v_n" + x.text());
  // e <= 1 and a landing keeps |v_after| <= |v_n| exactly (rounding of e v_n is monotone).
  require(r.energy_loss >= 0, "NewtonImpact: energy created, loss " + str(r.energy_loss) + x.text());
  return r;
}

/// coulomb_impulse(law, v_t, W_tt, L_n) with L_n from NewtonImpact: |L_t| <= mu_s L_n (the
/// Coulomb cone); stick: v_t after = 0 and L_t = -v_t / W_tt; slip: no reversal,
/// v_t after = v_t + W_tt L_t; 0 <= loss <= v_t^2 / (2 W_tt).
template <class Law>
TangentialImpact<double> check_coulomb_impulse(const Law& law, const ImpactInput& x, double L_n) {
  const double v_t = x.v[1], w = x.W(1, 1);
  const auto r = coulomb_impulse(law, v_t, w, L_n);  // well posed (probe_impact): not refused
  const std::string at = " (L_n = " + str(L_n) + ")" + x.text();
  const double scale = std::abs(v_t);
  require(std::abs(r.impulse) <= law.static_coefficient() * L_n * (1 + 1e-15),
          "coulomb_impulse outside the Coulomb cone: L_t = " + str(r.impulse) + at);
  if (r.state == ContactState::Stick) {
    require(r.velocity_after == 0 && r.impulse == -v_t / w, "coulomb_impulse: stick not at rest" + at);
  } else {
    // v_t + W_tt L_t keeps the sign of v_t since |W_tt L_t| < |v_t| (mu_k <= mu_s), up to an ulp.
    require(is_slipping(r.state) && slip_sign(r.state) * v_t > 0 &&
                slip_sign(r.state) * r.velocity_after >= -4e-16 * scale,
            std::string("coulomb_impulse: slip state ") + to_string(r.state) + " reversed or against v_t" + at);
    require(near(r.velocity_after, v_t + w * r.impulse, 1e-15, scale),
            "coulomb_impulse: velocity after != v_t + W_tt L_t" + at);
  }
  require(r.energy_loss >= 0 && r.energy_loss <= v_t * v_t / (2 * w) * (1 + 1e-15),
          "coulomb_impulse: loss " + str(r.energy_loss) + " outside [0, v_t^2 / (2 W_tt)]" + at);
  return r;
}

/// frictional_impact(newton, law, W, v): refused exactly for non-finite v or W, asymmetric W or
/// W not positive definite; for well-posed inputs the rules of the file comment.
template <class Law>
void check_frictional_impact(const NewtonImpact<double>& newton, const Law& law, const ImpactInput& x) {
  const Eigen::Matrix2d& W = x.W;
  const Eigen::Vector2d& v = x.v;
  const bool valid = v.allFinite() && W.allFinite() && W(0, 1) == W(1, 0) && W(0, 0) > 0 &&
                     W.determinant() > 0;
  FrictionalImpact<double> r;
  try {
    r = frictional_impact(newton, law, W, v);
  } catch (const std::invalid_argument&) {
    require(!valid, "frictional_impact refused a valid input" + x.text());
    return;
  }
  require(valid, "frictional_impact accepted an invalid input" + x.text());
  if (!x.well_posed() || !physical(law)) return;
  const std::string at = " (state " + std::string(to_string(r.state)) + ", L = (" + str(r.impulse[0]) +
                         ", " + str(r.impulse[1]) + "))" + x.text();
  require(r.impulse.allFinite() && r.velocity_after.allFinite() && std::isfinite(r.energy_loss),
          "frictional_impact: non-finite result" + at);
  require(r.lands == newton.lands(v[0]), "frictional_impact: landing rule" + at);
  if (!(v[0] < 0)) {
    require(r.impulse.isZero(0) && r.velocity_after == v, "frictional_impact: impulse without approach" + at);
    return;
  }
  if (!r.resolved) return;  // documented: no stick or slip solution (reported, not a violation)
  const double L_n = r.impulse[0], L_t = r.impulse[1];
  require(L_n >= 0, "frictional_impact: negative normal impulse" + at);
  require(std::abs(L_t) <= law.static_coefficient() * L_n * (1 + 1e-12),
          "frictional_impact outside the Coulomb cone" + at);
  require(r.velocity_after[0] == (r.lands ? 0.0 : -x.e * v[0]),
          "frictional_impact: normal velocity after is not Newton's" + at);
  // Round-off bounds: the stick solve goes through W^-1, whose cofactor formula loses up to
  // kappa = |W|_F^2 / det W >= cond(W) ulps; a slip solve divides by W_nn - s mu W_nt, which
  // loses up to (W_nn + mu |W_nt|) / W_nn <= 1 + mu_s kappa ulps relative to the terms of size
  // S = |v|_1 + (1 + mu_s) max|W_ij| |L|_1. So residuals are checked to 1e-13 kappa (1 + mu_s) S
  // (~500 ulps of margin over the bound), and the energy identity to that times |L|_1.
  const double mu_s = law.static_coefficient();
  const double kappa = W.squaredNorm() / W.determinant();
  const double rel = 1e-13 * kappa * (1 + mu_s);
  const double S = v.lpNorm<1>() + (1 + mu_s) * W.cwiseAbs().maxCoeff() * r.impulse.lpNorm<1>();
  const Eigen::Vector2d WL = W * r.impulse;
  const double underflow = 4 * W.cwiseAbs().maxCoeff() * kDenormal;  // impulses below the denormals
  require(((v + WL) - r.velocity_after).lpNorm<Eigen::Infinity>() <= rel * S + underflow,
          "frictional_impact: velocity after != v + W L" + at);
  if (r.state == ContactState::Stick)
    require(r.velocity_after[1] == 0, "frictional_impact: stick with a sliding velocity" + at);
  else
    require(is_slipping(r.state) && slip_sign(r.state) * r.velocity_after[1] >= -rel * S,
            "frictional_impact: the slip reversed" + at);
  // The kinetic energy change of v -> v + W L through the metric W^-1: -L.v - L^T W L / 2.
  const double work = -r.impulse.dot(v) - r.impulse.dot(WL) / 2;
  require(near(r.energy_loss, work, rel, S * r.impulse.lpNorm<1>()),
          "frictional_impact: energy loss " + str(r.energy_loss) + " != -L.v - L^T W L / 2 = " + str(work) + at);
  if (W(0, 1) != 0) return;  // coupled: Newton + Coulomb may create energy (Stronge 2000, ch. 4)
  require(r.energy_loss >= -rel * S * r.impulse.lpNorm<1>(), "frictional_impact: energy created" + at);
  // Decoupled: NewtonImpact::impact followed by coulomb_impulse (the documented equivalence).
  const auto n = check_newton(newton, x);
  const auto t = check_coulomb_impulse(law, x, n.impulse);
  const bool stick_at_the_cone = std::abs(std::abs(v[1] / W(1, 1)) - law.static_coefficient() * n.impulse) <=
                                 1e-12 * std::abs(v[1] / W(1, 1));
  require(near(L_n, n.impulse, 1e-14, n.impulse) &&
              (stick_at_the_cone || (t.state == r.state && near(L_t, t.impulse, 1e-13, std::abs(t.impulse)))),
          "frictional_impact with W_nt = 0 differs from NewtonImpact + coulomb_impulse: (" + str(n.impulse) +
              ", " + str(t.impulse) + ", " + to_string(t.state) + ")" + at);
}

/// An impact probe: NewtonImpact (every law), coulomb_impulse and frictional_impact (exact laws).
template <class Law>
void probe_impact(stickslip_fuzz::Input& in, const Law& law) {
  const ImpactInput x(in);
  const bool valid_law = std::isfinite(x.e) && x.e >= 0 && x.e <= 1 && std::isfinite(x.landing_speed) &&
                         x.landing_speed >= 0;
  std::optional<NewtonImpact<double>> newton;
  try {
    newton.emplace(x.e, x.landing_speed);
  } catch (const std::invalid_argument&) {
    require(!valid_law, "NewtonImpact refused a valid e or landing speed" + x.text());
    return;
  }
  require(valid_law, "NewtonImpact accepted an invalid e or landing speed" + x.text());
  NormalImpact<double> n;
  try {
    n = check_newton(*newton, x);
  } catch (const std::invalid_argument&) {
    return;  // checked in check_newton: v_n or W_nn invalid
  }
  if constexpr (Law::has_stick_state) {
    if (x.well_posed() && physical(law)) check_coulomb_impulse(law, x, n.impulse);
    check_frictional_impact(*newton, law, x);
  }
}

template <class Law>
void probe_contact(stickslip_fuzz::Input& in, const Law& law) {
  const CoulombContact<Law> contact(law, in.real(0.0, 1e-6));
  const double tol = contact.velocity_tolerance();
  for (int k = 0; k < 8 && !in.empty(); ++k) {
    const unsigned kind = in.choice(6);
    if (kind == 5) {
      probe_impact(in, law);
      continue;
    }
    const auto s = static_cast<ContactState>(kind);
    const double v = in.real(-1.0, 1.0), N = in.real(-1.0, 100.0), f = in.real(-100.0, 100.0);
    const bool watch = in.flag();
    probe_law(law, v);
    const bool inputs_moderate = moderate(v) && moderate(N) && moderate(f) && physical(law);
    const double force = contact.friction_force(s, v, N, f);
    if (inputs_moderate) require(std::isfinite(force), "friction_force non-finite: " + str(force));
    double g[CoulombContact<Law>::max_guards];
    const Eigen::Index ng = CoulombContact<Law>::num_guards(s, watch);
    require(ng >= 0 && ng <= CoulombContact<Law>::max_guards, "num_guards out of range");
    if (s == ContactState::Separated) {
      // Flight: no friction, one guard, the gap (here N's value), falling at the impact.
      require(force == 0 && ng == 1, "separated: friction force " + str(force) + ", " +
                                         std::to_string(ng) + " guards");
      CoulombContact<Law>::gap_guard(N, g);
      require(g[0] == N || (std::isnan(N) && std::isnan(g[0])), "separated: gap guard != gap");
      require(CoulombContact<Law>::guard_direction(s, 0, watch) == CrossingDirection::Falling,
              "separated: the gap guard is not Falling");
    } else {
      contact.guards(s, v, N, f, watch, g);
    }
    for (Eigen::Index i = 0; i < ng; ++i) {
      if (inputs_moderate) require(std::isfinite(g[i]), "guard " + std::to_string(i) + " non-finite");
      static_cast<void>(CoulombContact<Law>::guard_direction(s, i, watch));
    }
    ContactState to;
    try {
      to = contact.decide(s, v, N, f);
    } catch (const std::invalid_argument&) {
      require(!(std::isfinite(v) && std::isfinite(N) && std::isfinite(f)),
              "decide threw on finite inputs");
      continue;
    }
    require(std::isfinite(v) && std::isfinite(N) && std::isfinite(f),
            "decide accepted a non-finite input");
    const std::string at = " (v = " + str(v) + ", N = " + str(N) + ", f_required = " + str(f) +
                           ", tol = " + str(tol) + ")";
    if (!(N > 0)) {
      require(to == ContactState::LiftOff, std::string("N <= 0 not lift-off: ") + to_string(to) + at);
      continue;
    }
    require(to != ContactState::LiftOff, "lift-off with N > 0" + at);
    const int with_v = v > 0 ? 1 : -1, against_f = f > 0 ? -1 : 1;
    if constexpr (Law::has_stick_state) {
      const double capacity = law.static_coefficient() * N;
      if (to == ContactState::Stick)
        require(std::abs(f) <= capacity, "stick beyond capacity" + at);
      else if (std::abs(v) <= tol)
        require(slip_sign(to) == against_f && std::abs(f) > capacity,
                std::string("slip from rest not against f_required beyond capacity: ") +
                    to_string(to) + at);
      else
        require(slip_sign(to) == with_v || (slip_sign(to) == against_f && std::abs(f) > capacity),
                std::string("slip in neither the direction of v nor against f_required: ") +
                    to_string(to) + at);
    } else if (is_slipping(to)) {
      require(std::abs(v) > tol && slip_sign(to) == with_v,
              std::string("regularised law slip state against v: ") + to_string(to) + at);
    }
  }
}

void run(stickslip_fuzz::Input& in) {
  switch (in.choice(3)) {
    case 0: {
      const double mu_s = in.real(0.0, 1.0), mu_k = in.real(0.0, 1.0);
      probe_contact(in, CoulombLaw<double>(mu_s, mu_k));
      break;
    }
    case 1: {
      const double mu_s = in.real(0.0, 1.0), mu_k = in.real(0.0, 1.0);
      const double v_s = in.real(1e-6, 1.0), exponent = in.real(0.1, 4.0);
      probe_contact(in, StribeckLaw<double>(mu_s, mu_k, v_s, exponent));
      break;
    }
    default: {
      const double mu = in.real(0.0, 1.0), v_eps = in.real(1e-9, 1e-2);
      const auto shape = in.flag() ? RegularisedShape::LinearSaturated : RegularisedShape::Tanh;
      probe_contact(in, RegularisedLaw<double>(mu, v_eps, shape));
      break;
    }
  }
}

}  // namespace contact_fuzz

STICKSLIP_FUZZ_ENTRY(contact, contact_fuzz::run)
