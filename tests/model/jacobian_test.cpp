// FrictionDampedSystem::jacobian (the variational equations of shooting): df/dx from
// the mode's exact linear part where there is one (stick; slip at a fixed contact), central
// differences elsewhere. Reference: Richardson-extrapolated central differences of rhs()
// computed here with steps scaled to each component (an independent computation of the same
// derivative, ~1e-12 accurate), so a wrong or missing term of A_m, of the audit rows or of the
// contact-coordinate columns shows at the size of the terms.
#include "model/model_test_scenes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace jacobian_test {

using namespace model_test;

DamperStates both(ContactState a, ContactState b) {
  DamperStates m(2);
  m[0] = a;
  m[1] = b;
  return m;
}

/// Richardson-extrapolated central differences of rhs, (4 D(h/2) - D(h)) / 3 with
/// h_j = 1e-3 s_j, s_j the scale of component j in random_state (q 1e-4, q' 1e-2, x_d 1e-5,
/// x_d' 1e-2, the audit integrals 1): truncation O((h/s)^4) ~ 1e-12, round-off ~eps |f| / h
/// ~ 1e-13 of a row's scale |f| / s. The contact coordinates X get h = 1e-7: the shapes are
/// piecewise (1 cm elements), and a wider step crosses an element end next to X (seen: X 1e-6
/// from one, where h = 1e-5 gave 6e-4 off the derivative of X's own element).
Eigen::MatrixXd reference_jacobian(System& sys, const DamperStates& mode, double t, const System::State& x) {
  const Index N = x.size(), n = sys.num_modes();
  Eigen::VectorXd s = Eigen::VectorXd::Ones(N);
  s.head(n).setConstant(1e-4);
  s.segment(n, n).setConstant(1e-2);
  s.segment(sys.x_offset(), sys.num_dampers()).setConstant(1e-5);
  s.segment(sys.xd_offset(), sys.num_dampers()).setConstant(1e-2);
  if (sys.contact_offset() >= 0) s.segment(sys.contact_offset(), sys.num_dampers()).setConstant(1e-4);
  Eigen::MatrixXd J(N, N);
  System::State xp = x, fp, fm;
  const auto central = [&](Index j, double h) {
    xp[j] = x[j] + h;
    sys.rhs(mode, t, xp, fp);
    xp[j] = x[j] - h;
    sys.rhs(mode, t, xp, fm);
    xp[j] = x[j];
    return Eigen::VectorXd((fp - fm) / (2 * h));
  };
  for (Index j = 0; j < N; ++j) {
    const double h = 1e-3 * s[j];
    J.col(j) = (4 * central(j, h / 2) - central(j, h)) / 3;
  }
  return J;
}

/// The worst entry of J - R, each row judged against its own scale max_j |R_ij| (the rows mix
/// q' ~ q, q'' ~ omega^2 q and the audit's power rates).
struct RowError {
  double value = 0;
  Index row = -1, col = -1;
  double got = 0, want = 0;
};
RowError row_error(const Eigen::MatrixXd& J, const Eigen::MatrixXd& R) {
  RowError worst;
  for (Index i = 0; i < R.rows(); ++i) {
    const double scale = std::max(R.row(i).cwiseAbs().maxCoeff(), 1e-300);
    for (Index j = 0; j < R.cols(); ++j) {
      const double e = std::abs(J(i, j) - R(i, j)) / scale;
      if (e > worst.value) worst = {e, i, j, J(i, j), R(i, j)};
    }
  }
  return worst;
}

struct JacobianCase {
  const char* name;
  bool moving;
  NormalLoad normal;
  DamperStates mode;
  double tolerance;  // of each row's scale (see the cases)
  bool convective = true;
  bool regularised = false;  // tanh law (mu varies with V): the difference branch
  bool mixed = false;        // damper 1 at a fixed contact point (ContactPoint::Fixed)
  bool function_load = false;  // the load as a time_function: the mode is inexact (the tangent)
};

/// The paper's load, given as a time_function (the same F(t)): a mode with it is not exact, so
/// jacobian() takes the tangent of the solve even at a fixed contact.
std::vector<PointLoad<double>> function_load(const TScene& t) {
  std::vector<PointLoad<double>> loads = paper_load(t);
  const double a = loads[0].amplitude, w = loads[0].omega;
  loads[0].amplitude = 0;
  loads[0].time_function = [a, w](double time) { return a * std::sin(w * time); };
  return loads;
}

TEST(Jacobian, MatchesCentralDifferencesInExactAndInexactModes) {
  // Exact modes and slip at a moving contact, 1e-10: A_m and the audit forms (exact modes), the
  // tangent of the solve (moving slip) and the contact columns X in closed form (both) are exact
  // up to round-off; the reference's own error (~1e-12 of a row) sets the floor (measured: at
  // most 2e-11 over the 21 states). The X columns were central differences at h = 1e-6 before
  // (4e-9 off); dropping psi_w''' from dh/dX gives 1e-9, the stuck friction row's m b'^T q''
  // 2e-5. The difference branch (a slip coefficient that varies with V), 1e-4: the
  // model's steps h = 1e-6 max(1, |x_j|) are 1 % of q ~ 1e-4, and the moving contact makes f
  // nonlinear in (q, q', X) (slope q^T psi'(X) times V times N): truncation (h/q)^2 ~ 1e-4
  // times those terms' share (measured 1e-6 to 1e-5) - the same steps as VariationalSystem's
  // own differences. A wrong or missing term is of the size of its row (error ~1).
  const std::vector<JacobianCase> cases = {
      {"moving contact, all stuck (A_m, X columns in closed form, audit rows)", true, NormalLoad::Inertial,
       both(ContactState::Stick, ContactState::Stick), 1e-10},
      {"fixed contact, one slipping, constant N (exact slip)", false, NormalLoad::Constant,
       both(ContactState::SlipPositive, ContactState::Stick), 1e-10},
      {"fixed contact, both slipping, inertial N (exact slip)", false, NormalLoad::Inertial,
       both(ContactState::SlipNegative, ContactState::SlipPositive), 1e-10},
      {"moving contact, one slipping (tangent of the solve)", true, NormalLoad::Inertial,
       both(ContactState::SlipPositive, ContactState::Stick), 1e-10},
      {"moving contact, both slipping, inertial N (tangent)", true, NormalLoad::Inertial,
       both(ContactState::SlipNegative, ContactState::SlipPositive), 1e-10},
      {"moving contact, both slipping, constant N (tangent)", true, NormalLoad::Constant,
       both(ContactState::SlipPositive, ContactState::SlipPositive), 1e-10},
      {"moving contact, one slipping, no convective terms (tangent)", true, NormalLoad::Inertial,
       both(ContactState::Stick, ContactState::SlipNegative), 1e-10, false},
      {"moving contact, regularised law (differences)", true, NormalLoad::Inertial,
       both(ContactState::SlipPositive, ContactState::SlipPositive), 1e-4, true, true},
      {"one moving and one fixed contact, both slipping (tangent)", true, NormalLoad::Inertial,
       both(ContactState::SlipNegative, ContactState::SlipPositive), 1e-10, true, false, true},
      // no contact coordinates in the state (contact_offset() = -1): the tangent must not write
      // an X column (a write at column -1 lands outside J)
      {"fixed contacts, one slipping, time_function load (tangent, no X columns)", false,
       NormalLoad::Inertial, both(ContactState::SlipPositive, ContactState::Stick), 1e-10, true, false, false,
       true},
      {"fixed contacts, both slipping, time_function load (tangent, no X columns)", false,
       NormalLoad::Inertial, both(ContactState::SlipNegative, ContactState::SlipPositive), 1e-10, true, false,
       false, true},
  };
  std::mt19937 rng(21);  // fixed seed
  for (const JacobianCase& c : cases) {
    SCOPED_TRACE(c.name);
    TScene t = make_t_frame(6);
    ModelOptions<double> options;  // energy audit on (the default): four quadrature rows
    options.moving_contact = c.moving;
    options.normal_load = c.normal;
    options.convective_terms = c.convective;
    std::vector<PointDamper<double>> dampers = paper_dampers(t, 12.0);
    if (c.regularised)
      for (auto& d : dampers) d.law = RegularisedLaw<double>(0.3, 1e-2);
    if (c.mixed) dampers[1].contact_point = ContactPoint::Fixed;
    System sys(t.frame, t.basis, std::move(dampers), c.function_load ? function_load(t) : paper_load(t), options);
    ASSERT_GT(sys.audit_size(), 0);
    for (int k = 0; k < 3; ++k) {
      const double time = std::uniform_real_distribution<double>(0.0, 0.05)(rng);
      const System::State x = random_state(sys, rng);
      System::Matrix J;
      sys.jacobian(c.mode, time, x, J);
      ASSERT_EQ(J.rows(), sys.state_size());
      ASSERT_EQ(J.cols(), sys.state_size());
      const Eigen::MatrixXd R = reference_jacobian(sys, c.mode, time, x);
      const RowError e = row_error(J, R);
      EXPECT_LE(e.value, c.tolerance) << "row " << e.row << ", column " << e.col << ": " << e.got << " vs "
                                     << e.want << " (state size " << sys.state_size() << ", contact offset "
                                     << sys.contact_offset() << ")";
      // the quadratures never feed back: their columns are zero
      EXPECT_EQ(J.rightCols(sys.audit_size()).cwiseAbs().maxCoeff(), 0.0);
    }
  }
}

TEST(Jacobian, Rosenbrock23AtFixedContactsWithATimeFunctionLoadMatchesDormandPrince) {
  // Rosenbrock23 takes J at every step; with fixed contacts and a time_function load that is the
  // tangent of the solve with no contact coordinates in the state. Reference: the same run by
  // DOPRI 5(4) (no Jacobian). Both at rtol 1e-9, atol 1e-13 (q ~ 1e-5, q' ~ 1e-2): the global
  // errors of either method stay within ~1e-6 of the state's scale over 10 ms with its
  // stick-slip switches; a wrong Jacobian in the implicit stages changes the W-method's
  // stability only, not its order, so the run's stick-slip history is the sensitive part:
  // the same number of contact switches and the final state within 1e-5 of its scale.
  TScene t = make_t_frame(4);
  ModelOptions<double> options;
  options.moving_contact = false;
  System sys(t.frame, t.basis, paper_dampers(t, 2.0), function_load(t), options);
  ASSERT_EQ(sys.contact_offset(), -1);
  RunOptions<double> run;
  run.stepper.rtol = 1e-9;
  run.stepper.atol = 1e-13;
  System::State x0 = sys.initial_state();
  DamperStates mode = sys.requested_mode();
  ASSERT_TRUE(sys.make_consistent(mode, 0.0, x0));
  sys.clear_events();
  const auto dopri = simulate(sys, mode, 0.0, x0, 0.01, run);
  const std::size_t dopri_switches = sys.events().size();
  sys.clear_events();
  run.integrator = Integrator::Rosenbrock23;
  const auto ros = simulate(sys, mode, 0.0, x0, 0.01, run);
  ASSERT_EQ(dopri.status, Status::Success);
  ASSERT_EQ(ros.status, Status::Success);
  EXPECT_GT(dopri_switches, 0u);  // the run switches (else the comparison is of a linear run)
  EXPECT_EQ(sys.events().size(), dopri_switches);
  const Index n = sys.num_modes();
  EXPECT_LE((ros.x.head(n) - dopri.x.head(n)).cwiseAbs().maxCoeff(), 1e-5 * dopri.x.head(n).cwiseAbs().maxCoeff());
}

TEST(Jacobian, RejectsAStateOfTheWrongSize) {
  TScene t = make_t_frame(6);
  System sys(t.frame, t.basis, paper_dampers(t, 12.0), paper_load(t), ModelOptions<double>{});
  System::Matrix J;
  const System::State x = System::State::Zero(sys.state_size() + 1);
  EXPECT_THROW(sys.jacobian(both(ContactState::Stick, ContactState::Stick), 0.0, x, J), std::invalid_argument);
}

}  // namespace jacobian_test
