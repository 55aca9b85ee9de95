// The composed acceleration solve (docs/model.md, all three forms) against two independent
// references: (1) a dense (n + 3D) linear system assembled row by row from the physical equations
// (11)-(14), (19), (25) and solved with a full-pivoting LU; (2) the paper's printed mode-space
// equations (26)-(28) for two dampers with a fixed contact point.
#include "model_test_scenes.hpp"

#include <Eigen/LU>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>

namespace {
using namespace model_test;
using Eigen::MatrixXd;
using Eigen::VectorXd;

const ContactState kStates[] = {ContactState::Stick, ContactState::SlipPositive, ContactState::SlipNegative};

struct Shapes {
  VectorXd a, b, da, dda, db;
};

// Mode values at X from component 3 directly (not through the system).
Shapes shapes_at(const TScene& s, double X) {
  MemberShapes<double> ms(s.frame, s.platform, s.basis);
  auto v = ms.evaluate(X);
  return {v.psi_w, v.psi_u, v.dpsi_w, v.ddpsi_w, v.dpsi_u};
}

// Dense reference: unknowns u = [q'' (n), N (D), f (D), x'' (D)].
template <class Sys>
VectorXd dense_reference(const TScene& s, const Sys& sys, const DamperStates& mode, double t,
                         const typename Sys::State& x, bool inertial, bool moving, bool convective) {
  const Index n = sys.num_modes(), D = sys.num_dampers(), U = n + 3 * D;
  MatrixXd A = MatrixXd::Zero(U, U);
  VectorXd r = VectorXd::Zero(U);
  const VectorXd q = x.head(n), qd = x.segment(n, n);
  // structure: q'' - sum N a + sum f b = F psi - omega^2 q
  A.topLeftCorner(n, n).setIdentity();
  r.head(n) = -sys.omega_squared().cwiseProduct(q);
  const auto& load = sys.loads()[0];
  r.head(n) += load.value(t) * sys.point_shape(load.member, load.coordinate, load.direction);
  for (Index i = 0; i < D; ++i) {
    const auto& d = sys.dampers()[static_cast<std::size_t>(i)];
    const double X = moving ? x[sys.contact_offset() + i] : d.contact_coordinate;
    Shapes sh = shapes_at(s, X);
    // y_i is measured along side * w (PointDamper::side): a, a' and a'' change sign with it.
    sh.a *= d.side;
    sh.da *= d.side;
    sh.dda *= d.side;
    const double m = d.effective_mass(), k = d.effective_stiffness();
    const bool stuck = mode[i] == ContactState::Stick;
    const double V = stuck ? 0.0 : x[sys.xd_offset() + i] - qd.dot(sh.b);
    const Index cN = n + i, cF = n + D + i, cX = n + 2 * D + i;
    A.block(0, cN, n, 1) = -sh.a;
    A.block(0, cF, n, 1) = sh.b;
    // damper along u (eq 11): m x'' - f = -k x
    A(cN, cX) = m;
    A(cN, cF) = -1;
    r[cN] = -k * x[sys.x_offset() + i];
    // normal force (eqs 13, 19): N + m y'' = N0
    const Index rowN = cF;
    A(rowN, cN) = 1;
    r[rowN] = d.preload;
    if (inertial) {
      A.block(rowN, 0, 1, n) += m * sh.a.transpose();
      if (!stuck && convective) {
        const double slope = q.dot(sh.da);
        const double h = 2 * qd.dot(sh.da) * V + q.dot(sh.dda) * V * V;
        const double dd = qd.dot(sh.db) * V;
        // + m slope (x'' - b^T q'' - dd) + m h
        A(rowN, cX) += m * slope;
        A.block(rowN, 0, 1, n) -= m * slope * sh.b.transpose();
        r[rowN] += -m * h + m * slope * dd;
      }
    }
    // friction: slip f = -sign(V) mu_k N; stick x'' - b^T q'' = 0
    const Index rowF = cX;
    if (stuck) {
      A(rowF, cX) = 1;
      A.block(rowF, 0, 1, n) = -sh.b.transpose();
    } else {
      // mu_k(|V|) straight from the damper's law (constant for Coulomb, Stribeck's decay)
      const double mu_k = std::visit(
          [&](const auto& law) {
            if constexpr (std::decay_t<decltype(law)>::has_stick_state)
              return law.kinetic_coefficient(std::abs(V));
            else
              return std::numeric_limits<double>::quiet_NaN();  // (no such law in these scenes)
          },
          d.law);
      const double sgn = mode[i] == ContactState::SlipPositive ? 1.0 : -1.0;
      A(rowF, cF) = 1;
      A(rowF, cN) = sgn * mu_k;
    }
  }
  return A.fullPivLu().solve(r);
}

void check_against_dense(bool inertial, bool moving, bool convective, bool stribeck = false) {
  const TScene s = make_t_frame();
  ModelOptions<double> opt;
  opt.normal_load = inertial ? NormalLoad::Inertial : NormalLoad::Constant;
  opt.moving_contact = moving;
  opt.convective_terms = convective;
  std::vector<PointDamper<double>> dampers = paper_dampers(s, 12.0);
  // Stribeck decay over v_s = 1e-2 m/s, the size of random_state's relative velocities: the slip
  // coefficient varies between 0.25 and 0.35 across the trials.
  if (stribeck)
    for (auto& d : dampers) d.law = StribeckLaw<double>(0.35, 0.25, 1e-2);
  System sys(s.frame, s.basis, dampers, paper_load(s), opt);
  const unsigned seed = 20261122u;
  std::printf("random states with seed %u\n", seed);
  std::mt19937 rng(seed);
  for (ContactState s0 : kStates)
    for (ContactState s1 : kStates) {
      DamperStates mode(2);
      mode[0] = s0;
      mode[1] = s1;
      for (int trial = 0; trial < 3; ++trial) {
        const System::State x = random_state(sys, rng);
        const double t = 0.0123 * (trial + 1);
        const auto& e = sys.evaluate(mode, t, x);
        const VectorXd ref = dense_reference(s, sys, mode, t, x, inertial, moving, opt.convective_terms);
        const Index n = sys.num_modes();
        // Both are direct solves of the same well-conditioned system (condition ~ 1e2 here):
        // agreement to round-off, 1e-10 relative to the largest entry of each block.
        const double qscale = ref.head(n).cwiseAbs().maxCoeff();
        EXPECT_LT((e.qdd - ref.head(n)).cwiseAbs().maxCoeff(), 1e-10 * qscale) << mode.to_string();
        EXPECT_LT((e.N - ref.segment(n, 2)).cwiseAbs().maxCoeff(), 1e-10 * 12.0) << mode.to_string();
        EXPECT_LT((e.f - ref.segment(n + 2, 2)).cwiseAbs().maxCoeff(), 1e-10 * 12.0) << mode.to_string();
        const double xscale = ref.tail(2).cwiseAbs().maxCoeff() + 1e-300;
        EXPECT_LT((e.xdd - ref.tail(2)).cwiseAbs().maxCoeff(), 1e-10 * xscale) << mode.to_string();
      }
    }
}

// Several dampers spread over the platform (every other one pressing from the other face,
// side = -1) in random stick/slip patterns. Which form of the solve a pattern takes depends on n
// and U (docs/model.md); each caller names the forms (mode space?, order of the factorised
// matrix) its patterns must reach, so every path of the solve is checked against the reference:
// 6 modes, 8 dampers: the fixed 6 x 6 mode-space form; 12 modes, 8 dampers: the exact-size
// mode-space form (U >= 13) and the fixed 8 x 8 capacitance form; 24 modes, 8 dampers: the
// exact-size capacitance form; 24 modes, 3 dampers: the 4 x 4 and 6 x 6 capacitance forms
// (padded with identity rows for U = 3, 5); 7 modes, 8 dampers: the mode-space form padded to
// 8 x 8. The 2-damper checks above cover the 2 x 2 and 4 x 4 forms.
// Sys is System or its form with the number of modes fixed at compile time (Modes = modes).
using Form = std::pair<bool, Index>;
template <class Sys = System>
void check_many_dampers_against_dense(int modes, int num_dampers, bool inertial,
                                      const std::set<Form>& must_reach) {
  const TScene s = make_t_frame(modes, 20, 8);
  ModelOptions<double> opt;
  opt.normal_load = inertial ? NormalLoad::Inertial : NormalLoad::Constant;
  std::vector<PointDamper<double>> dampers;
  const double m = 12.0 / (0.5 * 0.46 * 50.0 * 50.0);
  for (int i = 0; i < num_dampers; ++i) {
    dampers.emplace_back(s.platform, 0.032 * (i + 1) / num_dampers, m, 1e4, 12.0,
                         CoulombLaw<double>(0.35, 0.3), 0.5);
    if (i % 2 == 1) dampers.back().side = -1.0;
  }
  Sys sys(s.frame, s.basis, dampers, paper_load(s), opt);
  std::set<Form> reached;
  const unsigned seed = 20261123u;
  std::printf("random states and patterns with seed %u\n", seed);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, 2);
  const Index n = sys.num_modes(), D = sys.num_dampers();
  int pivoted = 0;
  for (int trial = 0; trial < 24; ++trial) {
    DamperStates mode(D);
    for (Index i = 0; i < D; ++i) mode[i] = kStates[pick(rng)];
    if (trial == 0)
      for (Index i = 0; i < D; ++i) mode[i] = ContactState::Stick;  // the largest system, U = 2D
    if (trial == 1)
      for (Index i = 0; i < D; ++i) mode[i] = ContactState::SlipNegative;  // the smallest, U = D
    const typename Sys::State x = random_state(sys, rng);
    const double t = 0.0071 * (trial + 1);
    const auto& e = sys.evaluate(mode, t, x);
    if (sys.last_solve().unknowns > 0)
      reached.insert({sys.last_solve().mode_space, sys.last_solve().system_size});
    pivoted += sys.last_solve().pivoted;
    const VectorXd ref = dense_reference(s, sys, mode, t, x, inertial, true, opt.convective_terms);
    // Same bounds as above: both are direct solves of one well-conditioned linear system.
    const double qscale = ref.head(n).cwiseAbs().maxCoeff();
    EXPECT_LT((e.qdd - ref.head(n)).cwiseAbs().maxCoeff(), 1e-10 * qscale) << mode.to_string();
    EXPECT_LT((e.N - ref.segment(n, D)).cwiseAbs().maxCoeff(), 1e-10 * 12.0) << mode.to_string();
    EXPECT_LT((e.f - ref.segment(n + D, D)).cwiseAbs().maxCoeff(), 1e-10 * 12.0) << mode.to_string();
    const double xscale = ref.tail(D).cwiseAbs().maxCoeff() + 1e-300;
    EXPECT_LT((e.xdd - ref.tail(D)).cwiseAbs().maxCoeff(), 1e-10 * xscale) << mode.to_string();
  }
  std::string seen;
  for (const Form& f : reached)
    seen += " (" + std::string(f.first ? "mode space" : "capacitance") + ", " + std::to_string(f.second) + ")";
  for (const Form& f : must_reach)
    EXPECT_EQ(reached.count(f), 1u) << "form not reached: mode_space = " << f.first
                                    << ", order " << f.second << "; reached:" << seen;
  // These matrices (identity plus rank-one terms of damper mass times mode values, condition
  // ~1e2) pass the block elimination's backward-error check: the pivoted LU is the exception,
  // not the path taken (a check that always failed would still give correct numbers above).
  EXPECT_EQ(pivoted, 0);
}

TEST(AccelerationSolve, EightDampersOnSixModesFixedModeSpaceFormMatchesDenseReference) {
  check_many_dampers_against_dense(6, 8, true, {{true, 6}});
}
TEST(AccelerationSolve, EightDampersExactModeSpaceFormMatchesDenseReference) {
  check_many_dampers_against_dense(12, 8, true, {{true, 12}, {false, 8}});
}
TEST(AccelerationSolve, EightDampersCapacitanceFormMatchesDenseReference) {
  check_many_dampers_against_dense(24, 8, true, {{false, 16}});
}
TEST(AccelerationSolve, ThreeDampersPaddedCapacitanceFormsMatchDenseReference) {
  check_many_dampers_against_dense(24, 3, true, {{false, 4}, {false, 6}});
}
TEST(AccelerationSolve, EightDampersOnSevenModesPaddedModeSpaceFormMatchesDenseReference) {
  check_many_dampers_against_dense(7, 8, true, {{true, 8}});
}

// The number of modes fixed at compile time: the same reference and the same forms, through the
// fixed-size views of the solve (Modes = 6 and 7: fixed mode-space systems; Modes = 12: the
// dynamic mode-space LU, the exact-size capacitance LU and, with three dampers, the 4 x 4 and
// 6 x 6 capacitance forms, all with fixed-row products). Three numbers of modes only: each is a
// full instantiation of the system, and the test build's time is dominated by them.
template <int M>
using FixedSystem = FrictionDampedSystem<double, FrictionLawVariant<double>, M>;
TEST(AccelerationSolve, FixedModesMatchDenseReferenceInEveryForm) {
  check_many_dampers_against_dense<FixedSystem<6>>(6, 8, true, {{true, 6}});
  check_many_dampers_against_dense<FixedSystem<7>>(7, 8, true, {{true, 8}});
  check_many_dampers_against_dense<FixedSystem<12>>(12, 8, true, {{true, 12}, {false, 8}, {false, 10}});
  check_many_dampers_against_dense<FixedSystem<12>>(12, 3, true, {{false, 4}, {false, 6}});
  check_many_dampers_against_dense<FixedSystem<6>>(6, 8, false, {{false, 4}, {true, 6}});
}

// A fixed Modes must match the basis: a clear error naming it, not a wrong-sized view.
TEST(AccelerationSolve, FixedModesRejectsBasisOfOtherSize) {
  const TScene s = make_t_frame(7, 20, 8);
  try {
    FixedSystem<6> sys(s.frame, s.basis, paper_dampers(s, 12.0), paper_load(s));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("Modes = 6"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("basis"), std::string::npos) << e.what();
  }
}
TEST(AccelerationSolve, EightDampersConstantNormalLoadMatchesDenseReference) {
  check_many_dampers_against_dense(24, 8, false, {{false, 8}});
}

// A slipping damper's normal-force row has the diagonal A_jj = 1 - s_j mu_j (slope s_j, signed
// slip coefficient mu_j). The solve divides a row with |A_jj| >= 1/2 by A_jj and uses the
// mode-space form only when every row was so normalised; a row with |A_jj| < 1/2 (down to 0 and
// below) sends it to the capacitance form. Here q is scaled so that damper 0's slope gives a chosen
// A_00 (absurdly steep slopes, 1 to 10 rad: a test of the algebra, not of a physical state); every
// call must match the dense reference, and the form must follow the rule, with A_jj computed here
// from component 3's slope, independently of the system.
TEST(AccelerationSolve, SteepSlopesSwitchToCapacitanceFormAndMatchDenseReference) {
  const TScene s = make_t_frame(6, 20, 8);
  std::vector<PointDamper<double>> dampers;
  const double m = 12.0 / (0.5 * 0.46 * 50.0 * 50.0);
  for (int i = 0; i < 8; ++i) dampers.emplace_back(s.platform, 0.004 * (i + 1), m, 1e4, 12.0, CoulombLaw<double>(0.35, 0.3), 0.5);
  System sys(s.frame, s.basis, dampers, paper_load(s), ModelOptions<double>{});
  const Index n = sys.num_modes(), D = sys.num_dampers();
  std::mt19937 rng(20261123u);
  bool reached[2] = {false, false};
  for (double A0 : {0.9, 0.7, 0.51, -0.51, -3.0, 0.49, 0.2, 0.0, -0.3}) {
    for (ContactState s0 : {ContactState::SlipPositive, ContactState::SlipNegative}) {
      DamperStates mode(D);
      for (Index i = 0; i < D; ++i) mode[i] = i % 2 == 0 ? ContactState::SlipPositive : ContactState::SlipNegative;
      mode[0] = s0;
      System::State x = random_state(sys, rng);
      auto slope = [&](Index i) {
        return x.head(n).dot(shapes_at(s, x[sys.contact_offset() + i]).da);  // side = +1
      };
      auto mu = [&](Index i) { return mode[i] == ContactState::SlipPositive ? 0.3 : -0.3; };
      x.head(n) *= (1.0 - A0) / mu(0) / slope(0);  // slope_0 = (1 - A0) / mu_0
      bool all_normalised = true;
      for (Index i = 0; i < D; ++i) all_normalised = all_normalised && std::abs(1.0 - slope(i) * mu(i)) >= 0.5;
      const auto& e = sys.evaluate(mode, 0.01, x);
      EXPECT_NEAR(1.0 - slope(0) * mu(0), A0, 1e-12);
      EXPECT_EQ(sys.last_solve().mode_space, all_normalised) << "A_00 = " << A0;
      reached[sys.last_solve().mode_space ? 1 : 0] = true;
      const VectorXd ref = dense_reference(s, sys, mode, 0.01, x, true, true, true);
      // As above: direct solves of one linear system; its condition number grows as A_00 -> 0
      // (1e3-1e4 here), hence 1e-9 instead of 1e-10.
      const double qscale = ref.head(n).cwiseAbs().maxCoeff();
      EXPECT_LT((e.qdd - ref.head(n)).cwiseAbs().maxCoeff(), 1e-9 * qscale) << "A_00 = " << A0;
      const double Nscale = ref.segment(n, D).cwiseAbs().maxCoeff();
      EXPECT_LT((e.N - ref.segment(n, D)).cwiseAbs().maxCoeff(), 1e-9 * Nscale) << "A_00 = " << A0;
      EXPECT_LT((e.f - ref.segment(n + D, D)).cwiseAbs().maxCoeff(), 1e-9 * Nscale) << "A_00 = " << A0;
    }
  }
  EXPECT_TRUE(reached[0]) << "capacitance form not reached";
  EXPECT_TRUE(reached[1]) << "mode-space form not reached";
}

TEST(AccelerationSolve, MatchesDenseReferenceFullModel) { check_against_dense(true, true, true); }
TEST(AccelerationSolve, MatchesDenseReferenceWithoutConvectiveTerms) { check_against_dense(true, true, false); }
TEST(AccelerationSolve, MatchesDenseReferenceFixedContact) { check_against_dense(true, false, false); }
TEST(AccelerationSolve, MatchesDenseReferenceConstantNormalLoad) { check_against_dense(false, true, true); }
TEST(AccelerationSolve, MatchesDenseReferenceStribeckLaw) { check_against_dense(true, true, true, true); }
TEST(AccelerationSolve, MatchesDenseReferenceStribeckLawConstantNormalLoad) {
  check_against_dense(false, true, true, true);
}

// The paper's eqs 26-28 (two dampers, m_1 = m_2, contact point fixed so that X' = X'' = 0),
// written with the effective mass m = share * mass (the paper's m/2) and spring k (the paper's k/2).
class PaperEquations : public ::testing::Test {
 protected:
  void SetUp() override {
    ModelOptions<double> opt;
    opt.moving_contact = false;
    sys_ = std::make_unique<System>(s_.frame, s_.basis, paper_dampers(s_, 12.0), paper_load(s_), opt);
    std::mt19937 rng(7u);
    x_ = random_state(*sys_, rng);
    const auto& d = sys_->dampers()[0];
    m_ = d.effective_mass();
    k_ = d.effective_stiffness();
    N0_ = d.preload;
    sh_[0] = shapes_at(s_, 0.01);
    sh_[1] = shapes_at(s_, 0.03);
    const Index n = sys_->num_modes();
    const auto& load = sys_->loads()[0];
    r0_ = load.value(t_) * sys_->point_shape(load.member, load.coordinate, load.direction) -
          sys_->omega_squared().cwiseProduct(x_.head(n));
  }
  // g(X) = psi_w - mu_k sgn(X'_paper) psi_u with X'_paper = u' - x' = -V.
  VectorXd g(int i, ContactState s) const {
    const double sgnV = s == ContactState::SlipPositive ? 1.0 : -1.0;
    return sh_[i].a + 0.3 * sgnV * sh_[i].b;
  }
  TScene s_ = make_t_frame();
  std::unique_ptr<System> sys_;
  System::State x_;
  double m_ = 0, k_ = 0, N0_ = 0, t_ = 0.031;
  Shapes sh_[2];
  VectorXd r0_;
};

TEST_F(PaperEquations, Eq27BothStuck) {
  DamperStates mode(2, ContactState::Stick);
  const Index n = sys_->num_modes();
  MatrixXd M = MatrixXd::Identity(n, n);
  VectorXd rhs = r0_;
  for (int i = 0; i < 2; ++i) {
    M += m_ * (sh_[i].b * sh_[i].b.transpose() + sh_[i].a * sh_[i].a.transpose());
    rhs += N0_ * sh_[i].a - k_ * x_[sys_->x_offset() + i] * sh_[i].b;  // -k/2 psi_u (psi_u^T q - c)
  }
  const VectorXd qdd = M.lu().solve(rhs);
  EXPECT_LT((sys_->evaluate(mode, t_, x_).qdd - qdd).norm(), 1e-10 * qdd.norm());
}

TEST_F(PaperEquations, Eq26BothSlipping) {
  for (ContactState s0 : {ContactState::SlipPositive, ContactState::SlipNegative})
    for (ContactState s1 : {ContactState::SlipPositive, ContactState::SlipNegative}) {
      DamperStates mode(2);
      mode[0] = s0;
      mode[1] = s1;
      const Index n = sys_->num_modes();
      MatrixXd M = MatrixXd::Identity(n, n);
      VectorXd rhs = r0_;
      const ContactState st[2] = {s0, s1};
      for (int i = 0; i < 2; ++i) {
        M += m_ * g(i, st[i]) * sh_[i].a.transpose();
        rhs += N0_ * g(i, st[i]);
      }
      const VectorXd qdd = M.lu().solve(rhs);
      EXPECT_LT((sys_->evaluate(mode, t_, x_).qdd - qdd).norm(), 1e-10 * qdd.norm()) << mode.to_string();
    }
}

TEST_F(PaperEquations, Eq28LeftSlipsRightSticks) {
  DamperStates mode(2);
  mode[0] = ContactState::SlipNegative;
  mode[1] = ContactState::Stick;
  const Index n = sys_->num_modes();
  MatrixXd M = MatrixXd::Identity(n, n) + m_ * g(0, mode[0]) * sh_[0].a.transpose() +
               m_ * (sh_[1].b * sh_[1].b.transpose() + sh_[1].a * sh_[1].a.transpose());
  const VectorXd rhs = r0_ + N0_ * (g(0, mode[0]) + sh_[1].a) - k_ * x_[sys_->x_offset() + 1] * sh_[1].b;
  const VectorXd qdd = M.lu().solve(rhs);
  EXPECT_LT((sys_->evaluate(mode, t_, x_).qdd - qdd).norm(), 1e-10 * qdd.norm());
  // Slip friction is exactly the kinetic value with the sign opposing V (eq 15).
  const auto& e = sys_->evaluate(mode, t_, x_);
  EXPECT_NEAR(e.f[0], 0.3 * e.N[0], 1e-12 * std::abs(e.N[0]));
}

}  // namespace

namespace {
// The solve keeps its factorisation while the matrix's inputs (per unknown: column, X, mu,
// slope) are unchanged. Each call below is checked against the dense reference, which has no
// memory. The sequence takes every branch of the key: a genuine reuse (all stuck, new q, q', x,
// x', same X), and refactorisations forced by each key component alone - a moved contact point
// (X), the same slipping damper reversing its slip direction at the same state (mu), the same
// pattern at a new q with the same X (the slope s_i of a slipping damper) - each of these three
// fails the test when left out of the key - then another pattern with the same number of unknowns
// (other columns, though here X and mu differ too) and a return to an earlier point. A stale
// factorisation or right-hand side shows as an O(1) relative error; the bound is the one of the
// checks above (direct solves of a well-conditioned system, round-off ~1e-13).
void check_factorisation_reuse(int modes, int num_dampers) {
  const TScene s = make_t_frame(modes, 20, 8);
  ModelOptions<double> opt;
  std::vector<PointDamper<double>> dampers;
  const double m = 12.0 / (0.5 * 0.46 * 50.0 * 50.0);
  for (int i = 0; i < num_dampers; ++i)
    dampers.emplace_back(s.platform, 0.032 * (i + 1) / num_dampers, m, 1e4, 12.0,
                         CoulombLaw<double>(0.35, 0.3), 0.5);
  System sys(s.frame, s.basis, dampers, paper_load(s), opt);
  const Index n = sys.num_modes(), D = sys.num_dampers();
  std::mt19937 rng(20261124u);
  std::printf("random states with seed %u\n", 20261124u);

  // C: all stuck. A / A': damper 0 slips + / -, the others stick. B: damper 1 slips -, the others
  // stick (the same number of unknowns as A, other columns).
  DamperStates A(D), Am(D), B(D), C(D);
  for (Index i = 0; i < D; ++i) A[i] = Am[i] = B[i] = C[i] = ContactState::Stick;
  A[0] = ContactState::SlipPositive;
  Am[0] = ContactState::SlipNegative;
  B[1] = ContactState::SlipNegative;
  const Index xo = sys.contact_offset();
  const System::State x1 = random_state(sys, rng);
  System::State x2 = random_state(sys, rng);  // new q, q', x, x' ...
  x2.segment(xo, D) = x1.segment(xo, D);      // ... same X
  System::State x3 = x2;
  x3[xo + D - 1] += 1e-3;  // one stuck damper's contact point moved by 1 mm
  System::State x4 = random_state(sys, rng);  // new q (so a new slope s_0) ...
  x4.segment(xo, D) = x3.segment(xo, D);      // ... same X

  struct Call {
    const DamperStates* mode;
    const System::State* x;
    const char* what;
    bool reused;  // the solve must keep the previous factorisation (SolveInfo::reused)
  };
  const Call calls[] = {{&C, &x1, "all stuck", false},
                        {&C, &x2, "reuse: all stuck, same X, new q", true},
                        {&C, &x3, "refactorise: X moved", false},
                        {&A, &x3, "damper 0 slips +", false},
                        {&Am, &x3, "refactorise: mu changed sign", false},
                        {&Am, &x4, "refactorise: slope changed", false},
                        {&B, &x4, "refactorise: pattern B", false},
                        {&C, &x1, "first point again", false}};
  double t = 0.003;
  for (const Call& c : calls) {
    t += 0.0011;
    const auto& e = sys.evaluate(*c.mode, t, *c.x);
    EXPECT_EQ(sys.last_solve().reused, c.reused) << c.what;
    const VectorXd ref = dense_reference(s, sys, *c.mode, t, *c.x, true, true, opt.convective_terms);
    const double qscale = ref.head(n).cwiseAbs().maxCoeff();
    EXPECT_LT((e.qdd - ref.head(n)).cwiseAbs().maxCoeff(), 1e-10 * qscale) << c.what;
    EXPECT_LT((e.N - ref.segment(n, D)).cwiseAbs().maxCoeff(), 1e-10 * 12.0) << c.what;
    EXPECT_LT((e.f - ref.segment(n + D, D)).cwiseAbs().maxCoeff(), 1e-10 * 12.0) << c.what;
  }
}
}  // namespace

TEST(AccelerationSolve, FactorisationReuseFixedFourByFour) { check_factorisation_reuse(6, 2); }
TEST(AccelerationSolve, FactorisationReuseModeSpaceForm) { check_factorisation_reuse(6, 8); }
TEST(AccelerationSolve, FactorisationReuseCapacitanceForm) { check_factorisation_reuse(24, 8); }

namespace {
// Iterative refinement from a stale factorisation (ModelOptions::refine_stale_factorisation):
// a slipping pattern is solved at a state, then at states whose contacts moved by a stage's step
// (X + 1e-7 m, q and q' changed by 1e-3 relative, as between integrator stages). Each refined
// solve must (a) be a refinement (SolveInfo::refinements > 0, not a reuse), (b) match the dense
// reference (1e-10, as above), and (c) match a direct solve of the same state by a system with the
// option off to 1e-12 relative: refinement stops when a correction is below 16 eps relative, and
// the direct LU solve's own error is about cond * eps with cond ~ 1e1-1e2 for these matrices, so
// the two agree to ~1e-14; 1e-12 leaves two orders for the condition number. A large change -
// every slip direction reversed at the same state, a matrix far from the stored one - must
// abandon refinement and refactorise (refinements == 0), still matching the reference. With the
// option off the result is a function of the state alone: bitwise equal to a fresh system's.
void check_refinement(int modes, int num_dampers, bool all_slip, bool expect_mode_space) {
  const TScene s = make_t_frame(modes, 20, 8);
  std::vector<PointDamper<double>> dampers;
  const double m = 12.0 / (0.5 * 0.46 * 50.0 * 50.0);
  for (int i = 0; i < num_dampers; ++i) {
    dampers.emplace_back(s.platform, 0.032 * (i + 1) / (num_dampers + 1), m, 1e4, 12.0, CoulombLaw<double>(0.35, 0.3), 0.5);
    if (i % 2 == 1) dampers.back().side = -1.0;
  }
  ModelOptions<double> on, off;
  off.refine_stale_factorisation = false;
  System sys(s.frame, s.basis, dampers, paper_load(s), on);
  System direct(s.frame, s.basis, dampers, paper_load(s), off);
  const Index n = sys.num_modes(), D = sys.num_dampers(), xo = sys.contact_offset();
  std::mt19937 rng(20261125u);
  DamperStates mode(D), reversed(D);
  for (Index i = 0; i < D; ++i) {
    const bool slip = all_slip || i % 2 == 0;
    mode[i] = slip ? (i % 4 == 0 ? ContactState::SlipPositive : ContactState::SlipNegative) : ContactState::Stick;
    reversed[i] = mode[i] == ContactState::SlipPositive ? ContactState::SlipNegative
                  : mode[i] == ContactState::SlipNegative ? ContactState::SlipPositive : ContactState::Stick;
  }
  System::State x = random_state(sys, rng);
  double t = 0.002;
  auto check = [&](const DamperStates& md, const System::State& xs, const char* what, bool refined) {
    t += 1e-5;
    const auto& e = sys.evaluate(md, t, xs);
    const System::SolveInfo info = sys.last_solve();
    EXPECT_EQ(info.mode_space, expect_mode_space) << what;
    EXPECT_FALSE(info.reused) << what;
    EXPECT_EQ(info.refinements > 0, refined) << what << " (" << info.refinements << " corrections)";
    const VectorXd ref = dense_reference(s, sys, md, t, xs, true, true, true);
    const double qscale = ref.head(n).cwiseAbs().maxCoeff();
    EXPECT_LT((e.qdd - ref.head(n)).cwiseAbs().maxCoeff(), 1e-10 * qscale) << what;
    EXPECT_LT((e.N - ref.segment(n, D)).cwiseAbs().maxCoeff(), 1e-10 * 12.0) << what;
    const auto& d = direct.evaluate(md, t, xs);
    EXPECT_EQ(direct.last_solve().refinements, 0) << what;
    EXPECT_LT((e.qdd - d.qdd).cwiseAbs().maxCoeff(), 1e-12 * d.qdd.cwiseAbs().maxCoeff()) << what;
    EXPECT_LT((e.N - d.N).cwiseAbs().maxCoeff(), 1e-12 * d.N.cwiseAbs().maxCoeff()) << what;
    EXPECT_LT((e.f - d.f).cwiseAbs().maxCoeff(), 1e-12 * d.N.cwiseAbs().maxCoeff()) << what;
    return info.refinements;
  };
  check(mode, x, "first solve: direct", false);
  int corrections = 0;
  for (int stage = 0; stage < 6; ++stage) {
    x.head(2 * n) *= 1.0 + 1e-3;
    x.segment(xo, D).array() += 1e-7;
    corrections = std::max(corrections, check(mode, x, "stage: refined", true));
  }
  std::printf("at most %d corrections per refined solve\n", corrections);
  check(reversed, x, "slip directions reversed: refactorised", false);

  // Option off: bitwise a function of the state (a fresh system gives the same bits).
  System fresh(s.frame, s.basis, dampers, paper_load(s), off);
  const auto& a = direct.evaluate(mode, t, x);
  const VectorXd qa = a.qdd;
  const auto& b = fresh.evaluate(mode, t, x);
  EXPECT_EQ(qa, b.qdd);
}
}  // namespace

TEST(AccelerationSolve, RefinementFromStaleFactorisationModeSpaceForm) { check_refinement(12, 16, true, true); }
TEST(AccelerationSolve, RefinementFromStaleFactorisationCapacitanceForm) { check_refinement(24, 8, false, false); }
