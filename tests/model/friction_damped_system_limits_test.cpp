// FrictionDampedSystem in its linear and simplified limits, against references that do not go
// through the model: (1) dampers permanently stuck = the Ritz-reduced linear stuck system, solved
// in closed form by a generalized eigendecomposition; with all modes of a small frame it equals the
// FE frame with the dampers attached as point masses and grounded springs; (2) mu = 0 = the linear
// system with only the dampers' vertical inertia; (3) constant normal load + fixed contact = an
// independent single-damper hybrid system written here (Sherman-Morrison accelerations).
// Mode values come from component 2 at nodes (ModalBasis::nodal), never from component 3.
#include "model_test_scenes.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace {
using namespace model_test;
using Eigen::MatrixXd;
using Eigen::VectorXd;

constexpr double kLoadOmega = 200.0;  // paper_load's excitation [rad/s]

// Largest |tip(t) - tip_ref(t)| over the samples, relative to max |tip_ref|.
struct TipError {
  double max_error = 0, max_tip = 0;
  double relative() const { return max_error / max_tip; }
};

// Tip displacement of the T scene and the load vector, both from nodal modal rows.
VectorXd tip_row(const TScene& s) { return nodal(s.basis, s.tip, Dof::X); }
VectorXd load_row(const TScene& s) {
  return nodal(s.basis, s.frame.member(s.blade).nodes[2], Dof::X);  // y0 = 0.05 = node 2 of 8
}
// Platform nodes under the dampers of paper_dampers (X = 0.01, 0.03 on 4 elements).
Index damper_node(const TScene& s, int i) {
  return s.frame.member(s.platform).nodes[i == 0 ? 1u : 3u];
}

RunOptions<double> tight_run(double rtol, double output_interval) {
  RunOptions<double> run;
  run.integrator = Integrator::DormandPrince54;
  run.stepper.rtol = rtol;
  run.stepper.atol = 1e-16;  // modal coordinates ~1e-5, velocities ~1e-2: pure relative control
  run.stepper.output_interval = output_interval;
  return run;
}

// ---- 1. permanently stuck dampers ----------------------------------------------------------------

TEST(StuckLimit, AllDampersStuckMatchClosedFormOfRitzStuckSystem) {
  const TScene s = make_t_frame();
  // mu_s = 10: the capacity 10 N is never reached (|f| stays below ~1 N), so nothing slips.
  System sys(s.frame, s.basis, paper_dampers(s, 12.0, 10.0, 0.3), paper_load(s));
  const Index n = s.basis.size();
  MatrixXd M = MatrixXd::Identity(n, n);
  MatrixXd K = s.basis.omega().array().square().matrix().asDiagonal();
  VectorXd c = VectorXd::Zero(n);
  VectorXd b[2];
  for (int i = 0; i < 2; ++i) {
    const auto& d = sys.dampers()[static_cast<std::size_t>(i)];
    const VectorXd a = nodal(s.basis, damper_node(s, i), Dof::Y);  // platform w = global Y
    b[i] = nodal(s.basis, damper_node(s, i), Dof::X);                // platform u = global X
    M += d.effective_mass() * (a * a.transpose() + b[i] * b[i].transpose());
    K += d.effective_stiffness() * b[i] * b[i].transpose();
    c += d.preload * a;
  }
  const LinearClosedForm ref(M, K, 20.0 * load_row(s), c, kLoadOmega);

  Recorder rec;
  const auto r = run_from_rest(sys, 0.1, tight_run(1e-12, 5e-4), rec);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_TRUE(sys.events().empty()) << "a damper left stick";
  const VectorXd tip = tip_row(s);
  TipError e;
  double x_err = 0, x_max = 0, drift = 0;
  for (std::size_t k = 0; k < rec.t.size(); ++k) {
    const VectorXd qr = ref.q(rec.t[k]);
    const VectorXd q = rec.x[k].head(n);
    e.max_error = std::max(e.max_error, std::abs(tip.dot(q - qr)));
    e.max_tip = std::max(e.max_tip, std::abs(tip.dot(qr)));
    for (int i = 0; i < 2; ++i) {
      const double xi = rec.x[k][sys.x_offset() + i];
      x_err = std::max(x_err, std::abs(xi - b[i].dot(qr)));
      x_max = std::max(x_max, std::abs(b[i].dot(qr)));
      drift = std::max(drift, std::abs(xi - b[i].dot(q)));
      EXPECT_EQ(rec.mode[k][i], ContactState::Stick);
    }
  }
  ASSERT_GT(rec.t.size(), 100u);
  std::printf("tip error %.3e of %.3e, damper error %.3e of %.3e, stick drift %.3e\n", e.max_error,
              e.max_tip, x_err, x_max, drift);
  // rtol 1e-12 per step over ~2e4 steps of a neutrally stable linear system: the global error
  // grows at most linearly, ~1e-12 x steps-per-period x periods << 1e-8.
  EXPECT_LT(e.relative(), 1e-8);
  EXPECT_LT(x_err, 1e-8 * x_max);
  // In stick x' = b^T q' holds in every stage, so x - b^T q stays at its initial 0 up to round-off.
  EXPECT_LT(drift, 1e-12 * x_max);
}

// With every mode of a small frame retained, the Ritz stuck system is exact: the frame with the
// dampers' effective masses on X and Y and their springs on X at the contact nodes (component 1
// alone) has the same natural frequencies. The model's stuck accelerations give M_r^-1 K_r.
TEST(StuckLimit, AllModesStuckSystemEqualsFrameWithAttachedMassesAndSprings) {
  const SectionProperties<double> sec{2.06e11, 7800.0, 6e-5, 2e-11};
  struct Attached {
    int station;
    double mass, stiffness, share, preload;
  };
  const Attached att[2] = {{2, 0.05, 2e4, 0.5, 3.0}, {3, 0.02, 5e3, 1.0, 1.0}};
  auto make_frame = [&](bool attach) {
    FrameModel<double> f;
    const Index a = f.add_node(0.0, 0.0), bnode = f.add_node(0.3, 0.0);
    f.add_member(a, bnode, sec, 3);
    f.clamp(a);
    if (attach)
      for (const Attached& d : att) {
        const Index node = f.member(0).nodes[static_cast<std::size_t>(d.station)];
        f.add_point_mass(node, d.share * d.mass);
        f.add_spring(node, Dof::X, d.share * d.stiffness);
      }
    return f;
  };
  const FrameModel<double> bare = make_frame(false), loaded = make_frame(true);
  ModalOptions<double> all;
  all.num_modes = 9;  // 3 elements x 3 DOFs, root clamped
  all.solver = ModalSolver::Dense;
  const ModalBasis<double> basis = compute_modes(bare.assemble(), all);
  const ModalBasis<double> fe = compute_modes(loaded.assemble(), all);
  ASSERT_EQ(basis.size(), 9);
  ASSERT_EQ(fe.size(), 9);

  std::vector<PointDamper<double>> dampers;
  const Index n = basis.size();
  MatrixXd M = MatrixXd::Identity(n, n);
  MatrixXd K = basis.omega().array().square().matrix().asDiagonal();
  VectorXd b[2];
  for (int i = 0; i < 2; ++i) {
    const Attached& d = att[i];
    const Index node = bare.member(0).nodes[static_cast<std::size_t>(d.station)];
    dampers.emplace_back(0, bare.member(0).stations[static_cast<std::size_t>(d.station)], d.mass,
                         d.stiffness, d.preload, CoulombLaw<double>(10.0, 0.3), d.share);
    const VectorXd a = nodal(basis, node, Dof::Y);
    b[i] = nodal(basis, node, Dof::X);
    M += d.share * d.mass * (a * a.transpose() + b[i] * b[i].transpose());
    K += d.share * d.stiffness * b[i] * b[i].transpose();
  }
  System sys(bare, basis, dampers);
  // Columns of -M_r^-1 K_r from the model's stuck acceleration solve (q = e_j, x_i = b_i^T q,
  // q' = 0), minus the preload's constant part (q = 0).
  const DamperStates stuck(2, ContactState::Stick);
  System::State x = sys.initial_state();
  const VectorXd qdd0 = sys.evaluate(stuck, 0.0, x).qdd;
  MatrixXd A(n, n);
  for (Index j = 0; j < n; ++j) {
    x.setZero();
    x = sys.initial_state();
    x[j] = 1.0;
    for (int i = 0; i < 2; ++i) x[sys.x_offset() + i] = b[i][j];
    A.col(j) = sys.evaluate(stuck, 0.0, x).qdd - qdd0;
  }
  Eigen::EigenSolver<MatrixXd> model_es(-A);
  VectorXd model_w2 = model_es.eigenvalues().real();
  std::sort(model_w2.data(), model_w2.data() + n);
  const VectorXd ritz_w2 = Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd>(K, M).eigenvalues();
  for (Index j = 0; j < n; ++j) {
    const double w_fe = fe.omega()[j];
    std::printf("mode %ld: FE %.12e  Ritz %.12e  model %.12e rad/s\n", static_cast<long>(j), w_fe,
                std::sqrt(ritz_w2[j]), std::sqrt(model_w2[j]));
    // Same matrices, three assembly/solution paths; the lowest eigenvalue of a pencil with
    // condition ~ (w_max / w_min)^2 ~ 1e6 is accurate to ~ eps x 1e6 ~ 1e-10 in omega^2.
    EXPECT_NEAR(std::sqrt(ritz_w2[j]) / w_fe, 1.0, 1e-9) << "Ritz mode " << j;
    EXPECT_NEAR(std::sqrt(model_w2[j]) / w_fe, 1.0, 1e-9) << "model mode " << j;
    EXPECT_LT(std::abs(model_es.eigenvalues()[j].imag()), 1e-9 * model_w2.maxCoeff());
  }
}

// ---- 2. frictionless platform --------------------------------------------------------------------

TEST(FrictionlessLimit, MuZeroLeavesDampersAtRestAndStructureLinear) {
  const TScene s = make_t_frame();
  ModelOptions<double> opt;
  opt.moving_contact = false;
  System sys(s.frame, s.basis, paper_dampers(s, 12.0, 0.0, 0.0), paper_load(s), opt);
  const Index n = s.basis.size();
  MatrixXd M = MatrixXd::Identity(n, n);
  const MatrixXd K = s.basis.omega().array().square().matrix().asDiagonal();
  VectorXd c = VectorXd::Zero(n);
  for (int i = 0; i < 2; ++i) {
    const auto& d = sys.dampers()[static_cast<std::size_t>(i)];
    const VectorXd a = nodal(s.basis, damper_node(s, i), Dof::Y);
    M += d.effective_mass() * a * a.transpose();  // vertical inertia only: N = N0 - m a^T q''
    c += d.preload * a;
  }
  const LinearClosedForm ref(M, K, 20.0 * load_row(s), c, kLoadOmega);
  Recorder rec;
  const auto r = run_from_rest(sys, 0.1, tight_run(1e-12, 5e-4), rec);
  ASSERT_TRUE(r.ok()) << r.message;
  const VectorXd tip = tip_row(s);
  TipError e;
  double x_max = 0, xd_max = 0, v_max = 0;
  for (std::size_t k = 0; k < rec.t.size(); ++k) {
    const VectorXd qr = ref.q(rec.t[k]);
    e.max_error = std::max(e.max_error, std::abs(tip.dot(rec.x[k].head(n) - qr)));
    e.max_tip = std::max(e.max_tip, std::abs(tip.dot(qr)));
    const auto& ev = sys.evaluate(rec.mode[k], rec.t[k], rec.x[k]);
    for (int i = 0; i < 2; ++i) {
      EXPECT_TRUE(detail::is_slipping(rec.mode[k][i])) << "t = " << rec.t[k];
      EXPECT_EQ(ev.f[i], 0.0);  // -0 x N, exactly
      x_max = std::max(x_max, std::abs(rec.x[k][sys.x_offset() + i]));
      xd_max = std::max(xd_max, std::abs(rec.x[k][sys.xd_offset() + i]));
      v_max = std::max(v_max, std::abs(ev.V[i]));
    }
  }
  std::printf("tip error %.3e of %.3e over %zu samples, %zu events; max |x| %.3e, |x'| %.3e\n",
              e.max_error, e.max_tip, rec.t.size(), sys.events().size(), x_max, xd_max);
  EXPECT_LT(e.relative(), 1e-8);  // as in the stuck limit: rtol 1e-12, linear error growth
  // With f = 0, m x'' + k x = 0 from rest keeps x = x' = 0, except that at each located zero of V
  // (a slip reversal) the model resets x' so that V = 0 exactly: a velocity kick of the size of
  // the location overshoot |V'| x 1e-12 s, < 1e-9 of the sliding speeds.
  EXPECT_LT(xd_max, 1e-9 * v_max);
  EXPECT_LT(x_max, 1e-9 * e.max_tip);
}

// ---- 5. toggles reproduce simpler models ---------------------------------------------------------

// One damper, constant normal load N0, fixed contact: an independent hybrid system with state
// [q, q', x, x'] and mode = the damper's ContactState.
//   stick: (I + m b b^T) q'' = r - k x b, r = F(t) psi_F - w^2 q + N0 a   (Sherman-Morrison)
//          f = m b^T q'' + k x,  x'' = b^T q''
//   slip:  f = -sgn mu_k N0,  q'' = r - f b,  x'' = (f - k x) / m
class SingleDamperReference {
 public:
  using Scalar = double;
  using State = VectorXd;
  using Mode = ContactState;

  SingleDamperReference(VectorXd omega2, VectorXd a, VectorXd b, VectorXd psi_f, double F, double W,
                        double m, double k, double N0, CoulombLaw<double> law)
      : w2_(std::move(omega2)), a_(std::move(a)), b_(std::move(b)), psi_f_(std::move(psi_f)),
        F_(F), W_(W), m_(m), k_(k), N0_(N0), contact_(law), law_(law) {}

  void rhs(const Mode& s, double t, const State& x, State& dx) {
    const Index n = w2_.size();
    const double xdd = accelerations(s, t, x);
    dx.resize(x.size());
    dx.head(n) = x.segment(n, n);
    dx.segment(n, n) = qdd_;
    dx[2 * n] = x[2 * n + 1];
    dx[2 * n + 1] = xdd;
  }
  Index num_guards(const Mode& s) const { return CoulombContact<CoulombLaw<double>>::num_guards(s, false); }
  void guards(const Mode& s, double t, const State& x, VectorXd& g) {
    const Index n = w2_.size();
    accelerations(s, t, x);
    g.resize(num_guards(s));
    const double V = s == ContactState::Stick ? 0.0 : x[2 * n + 1] - b_.dot(x.segment(n, n));
    contact_.guards(s, V, N0_, f_, false, g.data());
  }
  CrossingDirection guard_direction(const Mode& s, Index i) const {
    return CoulombContact<CoulombLaw<double>>::guard_direction(s, i, false);
  }
  // At a stick/slip event V = 0: reset it exactly, then stick if the required force fits in
  // mu_s N0, else slip against it (eq 1).
  TransitionAction transition(Mode& s, const TriggeredGuards&, double t, State& x) {
    const Index n = w2_.size();
    x[2 * n + 1] = b_.dot(x.segment(n, n));
    accelerations(ContactState::Stick, t, x);
    s = contact_.decide(ContactState::Stick, 0.0, N0_, f_);
    return TransitionAction::proceed();
  }

 private:
  double accelerations(const Mode& s, double t, const State& x) {
    const Index n = w2_.size();
    const auto q = x.head(n);
    const double xi = x[2 * n];
    r_ = F_ * std::sin(W_ * t) * psi_f_ - w2_.cwiseProduct(q) + N0_ * a_;
    if (s == ContactState::Stick) {
      r_ -= k_ * xi * b_;
      qdd_ = r_ - (m_ * b_.dot(r_) / (1.0 + m_ * b_.squaredNorm())) * b_;
      f_ = m_ * b_.dot(qdd_) + k_ * xi;
      return b_.dot(qdd_);
    }
    f_ = (s == ContactState::SlipPositive ? -1.0 : 1.0) * law_.kinetic_coefficient(0.0) * N0_;
    qdd_ = r_ - f_ * b_;
    return (f_ - k_ * xi) / m_;
  }

  VectorXd w2_, a_, b_, psi_f_;
  double F_, W_, m_, k_, N0_;
  CoulombContact<CoulombLaw<double>> contact_;
  CoulombLaw<double> law_;
  VectorXd r_, qdd_;
  double f_ = 0;
};

struct StateRecorder : NullObserver {
  std::vector<double> t;
  std::vector<VectorXd> x;
  template <class Scalar, class State, class Mode>
  bool on_sample(Scalar tt, const State& xx, const Mode&) {
    t.push_back(tt);
    x.push_back(xx);
    return true;
  }
};

TEST(SimplifiedModels, ConstantLoadFixedContactMatchesIndependentSingleDamperSystem) {
  const TScene s = make_t_frame();
  auto dampers = paper_dampers(s, 4.0);
  dampers.pop_back();  // keep the damper at X = 0.01
  ModelOptions<double> opt;
  opt.normal_load = NormalLoad::Constant;
  opt.moving_contact = false;
  opt.energy_audit = false;  // same state [q, q', x, x'] as the reference: same step sequence
  System sys(s.frame, s.basis, dampers, paper_load(s), opt);
  const auto& d = dampers[0];
  SingleDamperReference ref(s.basis.omega().array().square().matrix(),
                            nodal(s.basis, damper_node(s, 0), Dof::Y),
                            nodal(s.basis, damper_node(s, 0), Dof::X), load_row(s), 20.0,
                            kLoadOmega, d.effective_mass(), d.effective_stiffness(), d.preload,
                            std::get<CoulombLaw<double>>(d.law));

  const RunOptions<double> run = tight_run(1e-10, 5e-4);
  Recorder rec;
  const auto r = run_from_rest(sys, 0.2, run, rec);
  ASSERT_TRUE(r.ok()) << r.message;
  HybridStepper<SingleDamperReference, DormandPrince54> stepper(ref, run.stepper);
  StateRecorder ref_rec;
  const auto rr = stepper.integrate(ContactState::Stick, 0.0, VectorXd::Zero(sys.state_size()), 0.2, ref_rec);
  ASSERT_TRUE(rr.ok()) << rr.message;
  ASSERT_EQ(ref_rec.t.size(), rec.t.size());
  std::printf("model: %zu switches, reference: %ld events\n", sys.events().size(), rr.stats.events);
  ASSERT_GE(sys.events().size(), 10u) << "the comparison must cover stick-slip switching";
  const Index n = s.basis.size();
  double err = 0, scale = 0;
  for (std::size_t k = 0; k < rec.t.size(); ++k) {
    err = std::max(err, (rec.x[k].head(n) - ref_rec.x[k].head(n)).cwiseAbs().maxCoeff());
    scale = std::max(scale, ref_rec.x[k].head(n).cwiseAbs().maxCoeff());
  }
  std::printf("max |q - q_ref| = %.3e of %.3e\n", err, scale);
  // Same equations, same stepper and tolerances: the step sequences agree, and the two solves
  // (Woodbury vs Sherman-Morrison) differ by round-off; event times located to 1e-12 s.
  EXPECT_LT(err, 1e-9 * scale);
}

// Tip histories of two runs of the T scene differing only in `opt`.
struct TipHistories {
  std::vector<double> tip;
  double max_contact_excursion = 0;
};
TipHistories run_tip(const TScene& s, const std::vector<PointDamper<double>>& dampers,
                     const ModelOptions<double>& opt, double t_end) {
  System sys(s.frame, s.basis, dampers, paper_load(s), opt);
  Recorder rec;
  const auto r = run_from_rest(sys, t_end, tight_run(1e-10, 2e-4), rec);
  EXPECT_TRUE(r.ok()) << r.message;
  TipHistories h;
  const VectorXd tip = tip_row(s);
  for (std::size_t k = 0; k < rec.t.size(); ++k) {
    h.tip.push_back(tip.dot(rec.x[k].head(s.basis.size())));
    if (opt.moving_contact)
      for (Index i = 0; i < sys.num_dampers(); ++i)
        h.max_contact_excursion = std::max(h.max_contact_excursion,
                                           std::abs(rec.x[k][sys.contact_offset() + i] - dampers[static_cast<std::size_t>(i)].contact_coordinate));
  }
  return h;
}
double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}
double max_diff(const std::vector<double>& a, const std::vector<double>& b) {
  EXPECT_EQ(a.size(), b.size());
  double m = 0;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) m = std::max(m, std::abs(a[k] - b[k]));
  return m;
}

TEST(SimplifiedModels, MovingAndFixedContactDifferByLittle) {
  const TScene s = make_t_frame();
  const auto dampers = paper_dampers(s, 3.0);  // stick-slip, contacts creep by a fraction of a mm
  ModelOptions<double> moving, fixed;
  fixed.moving_contact = false;
  const TipHistories hm = run_tip(s, dampers, moving, 0.1), hf = run_tip(s, dampers, fixed, 0.1);
  const double rel = max_diff(hm.tip, hf.tip) / max_abs(hf.tip);
  std::printf("contact excursion %.3e m, relative tip difference %.3e\n", hm.max_contact_excursion, rel);
  // The contacts move by micrometres to a millimetre on a 40 mm platform...
  EXPECT_GT(hm.max_contact_excursion, 1e-7);
  EXPECT_LT(hm.max_contact_excursion, 1e-3);
  // ...so the mode values at the contacts change by O(excursion / element length) and the
  // responses differ, but by a small amount.
  EXPECT_GT(rel, 0.0);
  EXPECT_LT(rel, 0.05);
}

TEST(SimplifiedModels, InertialNormalLoadTendsToConstantAsDamperMassVanishes) {
  const TScene s = make_t_frame();
  // Differences in the tip history between the inertial and the constant normal load for damper
  // masses m and m / 10 (same spring, preload and law): the normal-load variation m y'' is O(m).
  double diff[2], scale = 0;
  const double masses[2] = {1e-3, 1e-4};
  for (int j = 0; j < 2; ++j) {
    auto dampers = paper_dampers(s, 4.0, 0.35, 0.3, 1e2);
    for (auto& d : dampers) d.mass = masses[j];
    ModelOptions<double> inertial, constant;
    constant.normal_load = NormalLoad::Constant;
    const TipHistories hi = run_tip(s, dampers, inertial, 0.05), hc = run_tip(s, dampers, constant, 0.05);
    diff[j] = max_diff(hi.tip, hc.tip);
    scale = std::max(scale, max_abs(hc.tip));
  }
  std::printf("tip difference: m = %.0e: %.3e, m = %.0e: %.3e (of %.3e)\n", masses[0], diff[0],
              masses[1], diff[1], scale);
  EXPECT_LT(diff[1], 1e-3 * scale);  // m y'' / N0 ~ 1e-4 kg x 1e2 m/s^2 / 4 N ~ 3e-3
  // First order in m: the ratio of differences is the mass ratio 10 within a factor 2 (the
  // stick-slip switching times move with the normal load, a non-smooth but O(m) effect).
  EXPECT_GT(diff[0] / diff[1], 5.0);
  EXPECT_LT(diff[0] / diff[1], 20.0);
}

}  // namespace
