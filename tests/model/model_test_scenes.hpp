#pragma once
// Small scenes shared by the model tests: a T-shaped blade/platform frame (the paper's geometry on
// a coarse mesh) with two dampers under the platform, and helpers to read quantities back.
#include <stickslip/stickslip.hpp>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace model_test {

using namespace stickslip;
using System = FrictionDampedSystem<double>;
using Index = Eigen::Index;

struct TScene {
  FrameModel<double> frame;
  Index blade = 0, platform = 0, root = 0, tip = 0;
  ModalBasis<double> basis;
};

/// The paper's T-frame (L1 = 0.2, L2 = 0.04, steel section of section 3) on a coarse mesh.
inline TScene make_t_frame(int modes = 6, int blade_elements = 8, int platform_elements = 4) {
  TScene s;
  const SectionProperties<double> sec{2.06e11, 7800.0, 6e-5, 2e-11};
  s.root = s.frame.add_node(0.0, 0.0);
  const Index left = s.frame.add_node(-0.02, 0.2), right = s.frame.add_node(0.02, 0.2);
  s.platform = s.frame.add_member(left, right, sec, platform_elements);
  s.tip = s.frame.member(s.platform).nodes[static_cast<std::size_t>(platform_elements / 2)];
  s.blade = s.frame.add_member(s.root, s.tip, sec, blade_elements);
  s.frame.clamp(s.root);
  ModalOptions<double> mo;
  mo.num_modes = modes;
  s.basis = compute_modes(s.frame.assemble(), mo);
  return s;
}

/// A 0.2 m steel cantilever along x (the T-frame's section), clamped at x = 0, 8 elements, one
/// mode: its bending mode has psi_u = 0 everywhere and psi_w = 0 at the root.
struct Cantilever {
  FrameModel<double> frame;
  Index member = 0;
  ModalBasis<double> basis;
  double length = 0.2;
  Cantilever() {
    const SectionProperties<double> sec{2.06e11, 7800.0, 6e-5, 2e-11};
    const Index root = frame.add_node(0.0, 0.0), tip = frame.add_node(length, 0.0);
    member = frame.add_member(root, tip, sec, 8);
    frame.clamp(root);
    ModalOptions<double> mo;
    mo.num_modes = 1;
    basis = compute_modes(frame.assemble(), mo);
  }
};

/// DOPRI settings for single-damper runs checked against closed forms to ~1e-8: rtol 1e-10,
/// atol 1e-14 (states ~1e-3 .. 1e-1), samples every `output_interval`.
inline RunOptions<double> closed_form_run_options(double output_interval) {
  RunOptions<double> run;
  run.stepper.rtol = 1e-10;
  run.stepper.atol = 1e-14;
  run.stepper.output_interval = output_interval;
  return run;
}

/// Two dampers at X = 0.01 and 0.03 on the platform with the paper's spring, share and friction.
inline std::vector<PointDamper<double>> paper_dampers(const TScene& s, double preload,
                                                      double mu_s = 0.35, double mu_k = 0.3,
                                                      double k = 1e4) {
  const double m = preload / (0.5 * 0.46 * 50.0 * 50.0);
  std::vector<PointDamper<double>> d;
  d.emplace_back(s.platform, 0.01, m, k, preload, CoulombLaw<double>(mu_s, mu_k), 0.5);
  d.emplace_back(s.platform, 0.03, m, k, preload, CoulombLaw<double>(mu_s, mu_k), 0.5);
  return d;
}

/// The paper's excitation: 20 sin(200 t) N along global X at 0.05 m above the root.
inline std::vector<PointLoad<double>> paper_load(const TScene& s, double amplitude = 20.0) {
  return {PointLoad<double>::harmonic(s.blade, 0.05, LoadDirection::GlobalX, amplitude, 200.0)};
}

/// A random state with modal amplitudes ~ typical of the blade (1e-4) and damper motion.
template <class Sys = System>
typename Sys::State random_state(const Sys& sys, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  typename Sys::State x = sys.initial_state();
  const Index n = sys.num_modes();
  for (Index j = 0; j < n; ++j) {
    x[j] = 1e-4 * u(rng);
    x[n + j] = 1e-2 * u(rng);
  }
  for (Index i = 0; i < sys.num_dampers(); ++i) {
    x[sys.x_offset() + i] = 1e-5 * u(rng);
    x[sys.xd_offset() + i] = 1e-2 * u(rng);
    if (sys.contact_offset() >= 0) x[sys.contact_offset() + i] += 1e-3 * u(rng);
  }
  return x;
}

/// Records the samples (through the dense output) and the events (with the state after the
/// transition) of a run.
struct Recorder : NullObserver {
  struct Event {
    double t;
    DamperStates from, to;
    System::State x;  ///< state after the transition
  };
  std::vector<double> t;
  std::vector<System::State> x;
  std::vector<DamperStates> mode;
  std::vector<Event> events;

  template <class Scalar, class State, class Mode>
  bool on_sample(Scalar tt, const State& xx, const Mode& m) {
    t.push_back(tt);
    x.push_back(xx);
    mode.push_back(m);
    return true;
  }
  template <class Scalar, class Mode, class State>
  void on_event(const EventRecord<Scalar, Mode>& r, const State& xx) {
    events.push_back(Event{r.t, r.from, r.to, xx});
  }
};

/// Starts `sys` from rest in its requested (made consistent) mode and runs it to t_end.
inline HybridResult<double, System::State, DamperStates> run_from_rest(System& sys, double t_end,
                                                                       const RunOptions<double>& run,
                                                                       Recorder& rec, double* E0 = nullptr) {
  System::State x0 = sys.initial_state();
  DamperStates mode = sys.requested_mode();
  EXPECT_TRUE(sys.make_consistent(mode, 0.0, x0));
  if (E0) *E0 = sys.mechanical_energy(mode, 0.0, x0);
  return simulate(sys, mode, 0.0, x0, t_end, run, rec);
}

/// Closed-form response of the undamped linear system M q'' + K q = p sin(W t) + c from rest,
/// through the generalized eigendecomposition K v = lambda M v (V^T M V = I), each modal
/// coordinate solving eta'' + lambda eta = p_j sin(W t) + c_j, eta(0) = eta'(0) = 0:
///   eta = c_j / lambda (1 - cos w t) + p_j / (lambda - W^2) (sin W t - (W / w) sin w t).
class LinearClosedForm {
 public:
  LinearClosedForm(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K, const Eigen::VectorXd& p,
                   const Eigen::VectorXd& c, double W)
      : W_(W) {
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
    lambda_ = es.eigenvalues();
    V_ = es.eigenvectors();
    p_ = V_.transpose() * p;
    c_ = V_.transpose() * c;
  }
  Eigen::VectorXd q(double t) const {
    Eigen::VectorXd eta(lambda_.size());
    for (Index j = 0; j < lambda_.size(); ++j) {
      const double w = std::sqrt(lambda_[j]);
      eta[j] = c_[j] / lambda_[j] * (1 - std::cos(w * t)) +
               p_[j] / (lambda_[j] - W_ * W_) * (std::sin(W_ * t) - W_ / w * std::sin(w * t));
    }
    return V_ * eta;
  }
  const Eigen::VectorXd& eigenvalues() const { return lambda_; }

 private:
  double W_;
  Eigen::VectorXd lambda_, p_, c_;
  Eigen::MatrixXd V_;
};

/// Modal row of a nodal DOF as a column vector (component 2 only; independent of the model's
/// point evaluation by component 3).
inline Eigen::VectorXd nodal(const ModalBasis<double>& basis, Index node, Dof dof) {
  return basis.nodal(node, dof).transpose();
}

}  // namespace model_test
