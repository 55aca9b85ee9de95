// FrictionDampedSystem::linear_part: the linear part x_L' = A x_L + b(t) + r of each
// discrete mode with the contact coordinates frozen. References: the model's own right-hand side
// and guards (A x + b(t) must reproduce them where the mode is exact - a property of the
// decomposition, not a value it produced), and for the all-stuck structure an independent
// generalized eigenproblem assembled here from MemberShapes values (paper eq 27's mass and
// stiffness matrices).
#include "model/model_test_scenes.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace linear_part_test {

using namespace model_test;
using LP = LinearPart<double>;

constexpr auto Stick = ContactState::Stick;
constexpr auto SlipP = ContactState::SlipPositive;
constexpr auto SlipN = ContactState::SlipNegative;

DamperStates states(ContactState a, ContactState b) {
  DamperStates m(2);
  m[0] = a;
  m[1] = b;
  return m;
}

/// Three harmonic loads: two at 200 rad/s (one with a phase and an offset), one at 310 rad/s
/// with a negative frequency (sin(-w t + phi)), so that grouping and signs are exercised.
std::vector<PointLoad<double>> three_loads(const TScene& s) {
  auto loads = paper_load(s);
  // (bending loads: an axial load on the blade would barely reach its retained bending modes)
  auto second = PointLoad<double>::harmonic(s.blade, 0.12, LoadDirection::GlobalX, 7.0, 200.0, 0.4);
  second.offset = 3.0;
  loads.push_back(second);
  loads.push_back(PointLoad<double>::harmonic(s.blade, 0.15, LoadDirection::Moment, 0.5, -310.0, -1.1));
  return loads;
}

struct Scene {
  TScene t = make_t_frame(6);
  ModelOptions<double> options;
  std::vector<PointDamper<double>> dampers = paper_dampers(t, 12.0);
  std::vector<PointLoad<double>> loads = three_loads(t);
  System make() const { return System(t.frame, t.basis, dampers, loads, options); }
};

/// x_L of a state (the first linear_size() components).
Eigen::VectorXd linear_components(const System& sys, const System::State& x) {
  return x.head(sys.linear_size());
}

/// max_k |a_k - b_k| / scale_k with scale_k = |A| |x| + |b0| + sum |bc| + sum |bs| + |ref|
/// (row k): the size of the terms summed, so that a component that cancels is judged against
/// the round-off of its terms.
double affine_error(const Eigen::VectorXd& terms, const Eigen::VectorXd& value, const Eigen::VectorXd& ref) {
  const Eigen::VectorXd scale = terms + ref.cwiseAbs() + Eigen::VectorXd::Constant(ref.size(), 1e-300);
  return ((value - ref).cwiseAbs().array() / scale.array()).maxCoeff();
}

double rhs_error(System& sys, const DamperStates& mode, double t, const System::State& x, const LP& lp) {
  System::State f;
  sys.rhs(mode, t, x, f);
  const Eigen::VectorXd xl = linear_components(sys, x);
  Eigen::VectorXd b(lp.size());
  lp.load(t, b);
  const Eigen::VectorXd pred = lp.A * xl + b;
  Eigen::VectorXd terms = lp.A.cwiseAbs() * xl.cwiseAbs() + lp.b0.cwiseAbs();
  for (Index k = 0; k < lp.bc.cols(); ++k) terms += lp.bc.col(k).cwiseAbs() + lp.bs.col(k).cwiseAbs();
  return affine_error(terms, pred, f.head(lp.size()));
}

double guard_error(System& sys, const DamperStates& mode, double t, const System::State& x, const LP& lp) {
  System::GuardVector g;
  sys.guards(mode, t, x, g);
  EXPECT_EQ(lp.Gx.rows(), g.size());
  const Eigen::VectorXd xl = linear_components(sys, x);
  Eigen::VectorXd pred = lp.Gx * xl + lp.g0;
  Eigen::VectorXd terms = lp.Gx.cwiseAbs() * xl.cwiseAbs() + lp.g0.cwiseAbs();
  for (Index k = 0; k < lp.gc.cols(); ++k) {
    const auto kk = static_cast<std::size_t>(k);
    pred += std::cos(lp.omega[kk] * t) * lp.gc.col(k) + std::sin(lp.omega[kk] * t) * lp.gs.col(k);
    terms += lp.gc.col(k).cwiseAbs() + lp.gs.col(k).cwiseAbs();
  }
  return affine_error(terms, pred, g);
}

/// The energy audit's four rates from rhs() against z^T Q_j z (LinearPart::quadrature_forms,
/// z = (x_L, 1, cos w_k t, sin w_k t)), judged as affine_error against |z|^T |Q_j| |z|.
double quadrature_error(System& sys, const DamperStates& mode, double t, const System::State& x, const LP& lp) {
  System::State f;
  sys.rhs(mode, t, x, f);
  const Index n = lp.size(), K = static_cast<Index>(lp.omega.size());
  Eigen::VectorXd z(n + 1 + 2 * K);
  z.head(n) = x.head(n);
  z[n] = 1.0;
  for (Index k = 0; k < K; ++k) {
    z[n + 1 + 2 * k] = std::cos(lp.omega[static_cast<std::size_t>(k)] * t);
    z[n + 2 + 2 * k] = std::sin(lp.omega[static_cast<std::size_t>(k)] * t);
  }
  EXPECT_EQ(lp.quadrature_forms.size(), 4u);
  Eigen::VectorXd value(4), terms(4);
  for (std::size_t j = 0; j < 4; ++j) {
    const Eigen::MatrixXd& q = lp.quadrature_forms[j];
    value[static_cast<Index>(j)] = z.dot(q * z);
    terms[static_cast<Index>(j)] = z.cwiseAbs().dot(q.cwiseAbs() * z.cwiseAbs());
  }
  return affine_error(terms, value, f.segment(n, 4));
}

/// A random state (random_state: blade-sized amplitudes) and time.
System::State sample(const System& sys, std::mt19937& rng, double& t) {
  std::uniform_real_distribution<double> u(0.0, 0.05);
  t = u(rng);
  return random_state(sys, rng);
}

// Round-off: A x + b(t) and rhs() sum the same terms in different orders, through solves of
// condition ~1e2 (identity plus the dampers' low-rank terms): a few hundred units of 1e-16
// against the size of the terms; 1e-12 leaves a margin of ten and fails on any missing term
// (a missing preload, load or column is of the size of the terms themselves).
constexpr double kRoundOff = 1e-12;

struct ExactCase {
  const char* name;
  bool moving;
  NormalLoad normal;
  DamperStates mode;
};

TEST(LinearPart, ExactModesReproduceTheRightHandSideAndGuards) {
  const std::vector<ExactCase> cases = {
      {"fixed contact, all stuck, inertial N", false, NormalLoad::Inertial, states(Stick, Stick)},
      {"fixed contact, one slipping, inertial N", false, NormalLoad::Inertial, states(SlipP, Stick)},
      {"fixed contact, other slipping back, inertial N", false, NormalLoad::Inertial, states(Stick, SlipN)},
      {"fixed contact, both slipping, inertial N", false, NormalLoad::Inertial, states(SlipN, SlipP)},
      {"fixed contact, one slipping, constant N", false, NormalLoad::Constant, states(SlipP, Stick)},
      {"fixed contact, both slipping, constant N", false, NormalLoad::Constant, states(SlipP, SlipN)},
      {"fixed contact, all stuck, constant N", false, NormalLoad::Constant, states(Stick, Stick)},
      {"moving contact, all stuck, inertial N", true, NormalLoad::Inertial, states(Stick, Stick)},
      {"moving contact, all stuck, constant N", true, NormalLoad::Constant, states(Stick, Stick)},
  };
  std::mt19937 rng(19);  // fixed seed
  for (const ExactCase& c : cases) {
    SCOPED_TRACE(c.name);
    Scene scene;
    scene.options.moving_contact = c.moving;
    scene.options.normal_load = c.normal;
    System sys = scene.make();
    LP lp;
    for (int k = 0; k < 6; ++k) {
      double t = 0;
      const System::State x = sample(sys, rng, t);
      ASSERT_TRUE(sys.linear_part(c.mode, t, x, lp));
      EXPECT_TRUE(lp.exact);
      // every component but the four audit integrals (quadratures) is linear
      ASSERT_EQ(lp.size(), sys.state_size() - 4);
      ASSERT_EQ(lp.omega.size(), 2u);  // 200 and 310 rad/s
      EXPECT_LE(rhs_error(sys, c.mode, t, x, lp), kRoundOff);
      ASSERT_TRUE(lp.has_affine_guards());
      EXPECT_LE(guard_error(sys, c.mode, t, x, lp), kRoundOff);
      // the audit's rates as quadratic forms (closed-form quadratures of ExactLinearStepper)
      EXPECT_LE(quadrature_error(sys, c.mode, t, x, lp), kRoundOff);
      // and at other times with the same decomposition: b(t) carries the loads' time dependence
      for (double t2 : {0.0137, 0.4, 2.5}) {
        EXPECT_LE(rhs_error(sys, c.mode, t2, x, lp), kRoundOff);
        EXPECT_LE(guard_error(sys, c.mode, t2, x, lp), kRoundOff);
        EXPECT_LE(quadrature_error(sys, c.mode, t2, x, lp), kRoundOff);
      }
      if (c.moving) {  // X frozen: its columns are zero
        EXPECT_EQ(lp.A.middleCols(sys.contact_offset(), sys.num_dampers()).cwiseAbs().maxCoeff(), 0.0);
      }
    }
  }
}

/// The remainder r = f - A x_L - b(t) of the linear components.
Eigen::VectorXd remainder(System& sys, const DamperStates& mode, double t, const System::State& x, const LP& lp) {
  System::State f;
  sys.rhs(mode, t, x, f);
  Eigen::VectorXd b(lp.size());
  lp.load(t, b);
  return f.head(lp.size()) - lp.A * linear_components(sys, x) - b;
}

TEST(LinearPart, MovingSlippingContactIsFrozenWithARemainderOfOrderDeltaX) {
  Scene scene;  // moving contact, convective terms, inertial N (the defaults)
  System sys = scene.make();
  const DamperStates mode = states(SlipP, Stick);
  std::mt19937 rng(7);
  double t = 0;
  System::State x = sample(sys, rng, t);
  LP lp;
  ASSERT_TRUE(sys.linear_part(mode, t, x, lp));
  EXPECT_FALSE(lp.exact);
  EXPECT_TRUE(lp.has_affine_guards());  // frozen (FrozenGuardRows... below)
  System::State f;
  sys.rhs(mode, t, x, f);
  // At the freezing state the remainder vanishes (b0 corrected there): round-off of the terms.
  const Eigen::VectorXd r0 = remainder(sys, mode, t, x, lp);
  EXPECT_LE(r0.cwiseAbs().maxCoeff(), kRoundOff * (lp.A.cwiseAbs() * linear_components(sys, x).cwiseAbs() +
                                                   lp.b0.cwiseAbs() + f.head(lp.size()).cwiseAbs())
                                                      .maxCoeff());
  // Moving the slipping contact by dX: r grows like |dX| (first order: halving dX halves r,
  // within the O(dX^2) curvature of the shapes - 5 % at these dX, 1e-5 of a 5 mm element).
  const Index X0 = sys.contact_offset();
  std::vector<double> r;
  for (double dX : {4e-5, 2e-5, 1e-5}) {
    System::State xm = x;
    xm[X0] += dX;
    r.push_back(remainder(sys, mode, t, xm, lp).norm());
  }
  EXPECT_GT(r[2], 1e3 * r0.norm());  // a remainder that is really there
  EXPECT_NEAR(r[0] / r[1], 2.0, 0.1);
  EXPECT_NEAR(r[1] / r[2], 2.0, 0.1);
  // The X' = V row of the slipping damper is x' - q'^T psi_u(X) at the frozen X: exact.
  EXPECT_EQ(lp.A(X0, sys.xd_offset()), 1.0);
}

// A method that does not use the frozen guards of an inexact mode (want_inexact_guards = false:
// ExactLinearStepper without long slipping steps) gets none, and the same A_m and b_m bit for bit
// (the guards' probes run after those of A_m and restore the frozen solve's state); an exact mode
// gives its guards regardless.
TEST(LinearPart, InexactModeSkipsItsFrozenGuardsWhenTheMethodDoesNotWantThem) {
  Scene scene;  // moving contact, inertial N
  System sys = scene.make();
  std::mt19937 rng(13);
  double t = 0;
  const System::State x = sample(sys, rng, t);
  LP with, without;
  without.want_inexact_guards = false;
  const DamperStates slipping = states(SlipP, Stick);
  ASSERT_TRUE(sys.linear_part(slipping, t, x, with));
  System other = scene.make();  // a fresh system: nothing kept from the first call
  ASSERT_TRUE(other.linear_part(slipping, t, x, without));
  EXPECT_FALSE(without.exact);
  EXPECT_TRUE(with.has_affine_guards());
  EXPECT_FALSE(without.has_affine_guards());
  EXPECT_EQ(with.A, without.A);
  EXPECT_EQ(with.b0, without.b0);
  EXPECT_EQ(with.bc, without.bc);
  EXPECT_EQ(with.bs, without.bs);
  LP stuck;
  stuck.want_inexact_guards = false;
  ASSERT_TRUE(other.linear_part(states(Stick, Stick), t, x, stuck));
  EXPECT_TRUE(stuck.exact);
  EXPECT_TRUE(stuck.has_affine_guards());
}

// Frozen affine guards of an inexact mode (slipping moving contact next to a stuck one): equal
// to guards() at the freezing state (g0 is corrected there: round-off of the terms, kRoundOff);
// the slipping damper's guard V = x' - q'^T psi_u(X) is linear in (q', x') at a fixed X, so its
// row must reproduce guards() at states that differ in q' and x' only - an independent check of
// the probed columns (round-off of the terms); a member-end guard is the row of the contact
// coordinate (+1 for X, -1 for L - X, nothing else).
TEST(LinearPart, FrozenGuardRowsOfAnInexactModeMatchTheGuardsAtTheFreezingState) {
  Scene scene;  // moving contact, inertial N
  System sys = scene.make();
  const DamperStates mode = states(SlipP, Stick);
  std::mt19937 rng(11);
  double t = 0;
  const System::State x = sample(sys, rng, t);
  LP lp;
  ASSERT_TRUE(sys.linear_part(mode, t, x, lp));
  ASSERT_FALSE(lp.exact);
  ASSERT_TRUE(lp.has_affine_guards());
  EXPECT_LE(guard_error(sys, mode, t, x, lp), kRoundOff);
  System::State xv = x;
  std::normal_distribution<double> n01(0.0, 1.0);
  for (Index k = 0; k < sys.num_modes(); ++k) xv[sys.num_modes() + k] *= 1.0 + 0.5 * n01(rng);
  xv[sys.xd_offset()] += 0.1 * n01(rng);
  System::GuardVector g;
  sys.guards(mode, t, xv, g);
  const Eigen::VectorXd xl = linear_components(sys, xv);
  Eigen::VectorXd pred = lp.Gx * xl + lp.g0;
  for (Index k = 0; k < lp.gc.cols(); ++k) {
    const auto kk = static_cast<std::size_t>(k);
    pred += std::cos(lp.omega[kk] * t) * lp.gc.col(k) + std::sin(lp.omega[kk] * t) * lp.gs.col(k);
  }
  const double scale = (lp.Gx.row(0).cwiseAbs() * xl.cwiseAbs())(0) + std::abs(lp.g0[0]) + std::abs(g[0]);
  EXPECT_LE(std::abs(pred[0] - g[0]), kRoundOff * scale) << "slip guard V of damper 0";
  const Index X0 = sys.contact_offset();
  int end_rows = 0;
  for (Index k = 0; k < lp.Gx.rows(); ++k) {
    if (lp.Gx(k, X0) == 0.0) continue;
    ++end_rows;
    EXPECT_EQ(std::abs(lp.Gx(k, X0)), 1.0);
    EXPECT_EQ(lp.Gx.row(k).cwiseAbs().sum(), 1.0) << "row " << k;
  }
  EXPECT_EQ(end_rows % 2, 0);
}

TEST(LinearPart, SpeedDependentLawsAndUserTimeFunctionsAreNotExact) {
  std::mt19937 rng(11);
  {
    SCOPED_TRACE("regularised law slipping at a fixed contact");
    Scene scene;
    scene.options.moving_contact = false;
    scene.dampers[0].law = RegularisedLaw<double>(0.3, 1e-4);
    System sys = scene.make();
    const DamperStates mode = states(SlipP, Stick);  // a regularised damper is always "slipping"
    double t = 0;
    const System::State x = sample(sys, rng, t);
    LP lp;
    ASSERT_TRUE(sys.linear_part(mode, t, x, lp));
    EXPECT_FALSE(lp.exact);
    EXPECT_LE(remainder(sys, mode, t, x, lp).cwiseAbs().maxCoeff(), 1e-9);  // (q'' ~ 1e3: round-off)
  }
  {
    SCOPED_TRACE("a user time function load");
    Scene scene;
    scene.options.moving_contact = false;
    scene.loads[1].time_function = [](double tt) { return 4.0 * tt * tt; };
    System sys = scene.make();
    const DamperStates mode = states(Stick, Stick);
    double t = 0;
    const System::State x = sample(sys, rng, t);
    LP lp;
    ASSERT_TRUE(sys.linear_part(mode, t, x, lp));
    EXPECT_FALSE(lp.exact);
    EXPECT_LE(remainder(sys, mode, t, x, lp).cwiseAbs().maxCoeff(), 1e-9);
    // the remainder is the time function's load, 4 t^2, minus its value frozen at t: at 2t it is
    // nonzero
    EXPECT_GT(remainder(sys, mode, 2 * t + 0.01, x, lp).cwiseAbs().maxCoeff(), 1e-6);
  }
}

TEST(LinearPart, VersionChangesExactlyWhenTheDecompositionDoes) {
  Scene scene;  // moving contact
  System sys = scene.make();
  std::mt19937 rng(3);
  const DamperStates stuck = states(Stick, Stick);
  System::State x = sys.initial_state();
  LP lp;
  ASSERT_TRUE(sys.linear_part(stuck, 0.0, x, lp));
  const auto v0 = lp.version;
  const Eigen::MatrixXd A0 = lp.A;
  // other q, q', x_d, x_d' and t at the same X: same version, same A
  for (int k = 0; k < 3; ++k) {
    System::State y = random_state(sys, rng);
    y.segment(sys.contact_offset(), 2) = x.segment(sys.contact_offset(), 2);
    ASSERT_TRUE(sys.linear_part(stuck, 0.01 * k, y, lp));
    EXPECT_EQ(lp.version, v0);
    EXPECT_EQ(lp.A, A0);
  }
  // a damper slips: new version
  ASSERT_TRUE(sys.linear_part(states(SlipP, Stick), 0.0, x, lp));
  const auto v1 = lp.version;
  EXPECT_NE(v1, v0);
  // the slip sign reverses: new version
  ASSERT_TRUE(sys.linear_part(states(SlipN, Stick), 0.0, x, lp));
  EXPECT_NE(lp.version, v1);
  // back to stick at the same X: a version different from the slipping ones; and X moved: new
  ASSERT_TRUE(sys.linear_part(stuck, 0.0, x, lp));
  const auto v2 = lp.version;
  EXPECT_NE(v2, v1);
  EXPECT_EQ(lp.A, A0);
  x[sys.contact_offset() + 1] += 1e-3;
  ASSERT_TRUE(sys.linear_part(stuck, 0.0, x, lp));
  EXPECT_NE(lp.version, v2);
  EXPECT_NE(lp.A, A0);
}

TEST(LinearPart, AllStuckFrequenciesMatchAnIndependentEigenproblem) {
  // Paper eq 27 (both dampers stuck), generalised: with x_i = b_i^T q + const and N_i = N0 -
  // m_i a_i^T q'', the structure's mass and stiffness are
  //   M = I + sum_i m_i (a_i a_i^T + b_i b_i^T),   K = Omega^2 + sum_i k_i b_i b_i^T,
  // a_i = psi_w(X_i) (pressing face +w), b_i = psi_u(X_i), from MemberShapes (component 3).
  Scene scene;
  scene.options.moving_contact = false;
  System sys = scene.make();
  const MemberShapes<double> shapes(scene.t.frame, scene.t.platform, scene.t.basis);
  const Index n = sys.num_modes();
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(n, n), K = Eigen::MatrixXd::Zero(n, n);
  K.diagonal() = scene.t.basis.omega().array().square().matrix();
  for (const auto& d : scene.dampers) {
    const auto v = shapes.evaluate(d.contact_coordinate);
    const double m = d.effective_mass(), k = d.effective_stiffness();
    M += m * (v.psi_w * v.psi_w.transpose() + v.psi_u * v.psi_u.transpose());
    K += k * v.psi_u * v.psi_u.transpose();
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ref(K, M);
  Eigen::VectorXd w_ref = ref.eigenvalues().cwiseSqrt();
  // The dampers' terms matter far above the tolerance below: the stuck structure's frequencies
  // differ from the free structure's (sorted omega_j) by much more than 1e-10.
  Eigen::VectorXd w_free = scene.t.basis.omega();
  std::sort(w_free.data(), w_free.data() + n);
  EXPECT_GT(((w_ref - w_free).array() / w_free.array()).abs().maxCoeff(), 1e-4);

  LP lp;
  ASSERT_TRUE(sys.linear_part(states(Stick, Stick), 0.0, sys.initial_state(), lp));
  // Balance by an exact similarity (powers of two): displacements scaled by 2^-p ~ 1 / w_max,
  // so that the q'' rows (entries ~ w_max^2) and the velocity rows (1) are of the same size.
  // Unbalanced, the eigensolver's error ~ eps w_max^2 / w_j is 4e-9 of the lowest frequencies.
  const double alpha = std::ldexp(1.0, -static_cast<int>(std::round(std::log2(w_ref[n - 1]))));
  Eigen::VectorXd T = Eigen::VectorXd::Ones(lp.size());
  T.head(n).setConstant(alpha);                                    // q
  T.segment(sys.x_offset(), sys.num_dampers()).setConstant(alpha);  // x_d
  const Eigen::MatrixXd A = T.cwiseInverse().asDiagonal() * lp.A * T.asDiagonal();
  Eigen::EigenSolver<Eigen::MatrixXd> es(A, false);
  // Eigenvalues: +-i w_j (n pairs) and 2D zeros (the dampers' drift x - b^T q, which the stick
  // constraint keeps constant: a double zero each). Take the n with the largest positive
  // imaginary parts.
  std::vector<double> w;
  for (Index j = 0; j < es.eigenvalues().size(); ++j)
    if (es.eigenvalues()[j].imag() > 1.0) w.push_back(es.eigenvalues()[j].imag());
  ASSERT_EQ(static_cast<Index>(w.size()), n);
  std::sort(w.begin(), w.end());
  for (Index j = 0; j < n; ++j) {
    // Balanced, the eigenvalue error is ~ eps w_max / w_j times its condition (w_max / w_1 ~ 1e2
    // here): 1e-10 relative leaves a margin of 1e3-1e4 and is 1e5 below the effect of a
    // damper's mass or spring term (m_i |b|^2 ~ 1e-3 .. 1e-2 of the modal mass).
    EXPECT_NEAR(w[static_cast<std::size_t>(j)] / w_ref[j], 1.0, 1e-10) << "mode " << j;
    // the real parts vanish (no damping in this basis)
  }
  for (Index j = 0; j < es.eigenvalues().size(); ++j)
    EXPECT_LE(std::abs(es.eigenvalues()[j].real()), 1e-6 * w_ref[n - 1]);
}

}  // namespace linear_part_test
