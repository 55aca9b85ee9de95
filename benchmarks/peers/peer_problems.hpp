#pragma once
// The peer benchmark's problems as plain data, and the physics every implementation shares.
//
// A chain of n = 1 or 2 masses with friction on one of them (dof j) against a surface moving at
// v_b (0 = ground), Coulomb's law with mu_s >= mu_k, constant normal force N:
//
//   M x'' + C x' + K x = F cos(omega t + phi) + f e_j,
//   slip (v = x_j' - v_b != 0):  f = -mu_k N sgn(v),
//   stick (v = 0):               x_j'' = 0, f = f_req = (K x + C x')_j - F_j cos(omega t + phi).
//
// Every implementation evaluates the same acceleration (chain_acceleration) so that the
// comparison is one of integrators and event handling, not of right-hand sides.

#include <stickslip/contact/contact_state.hpp>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace peers {

using stickslip::ContactState;

inline constexpr double kPi = 3.14159265358979323846;

/// One problem: parameters of the chain, the initial state and the horizon.
struct ChainParameters {
  std::string name;
  std::string description;
  int dofs = 1;                                   // n, 1 or 2
  Eigen::Vector2d mass{1.0, 1.0};                 // kg (first n used)
  Eigen::Matrix2d stiffness = Eigen::Matrix2d::Identity();  // N/m (top-left n x n)
  Eigen::Matrix2d damping = Eigen::Matrix2d::Zero();        // N s/m
  Eigen::Vector2d force_amplitude{0.0, 0.0};      // F, N
  double force_frequency = 1.0;                   // omega, rad/s
  double force_phase = 0.0;                       // phi, rad
  int friction_dof = 0;                           // j
  double normal_force = 1.0;                      // N, newtons
  double mu_s = 0.3;
  double mu_k = 0.3;
  double belt_speed = 0.0;                        // v_b, m/s
  Eigen::Vector2d x0{0.0, 0.0};
  Eigen::Vector2d v0{0.0, 0.0};
  double t_end = 200.0;                           // s
};

/// |v| below this counts as v = 0 when a mode is decided (the library's CoulombContact default,
/// sqrt(machine epsilon)).
inline double velocity_tolerance() { return 1.4901161193847656e-08; }

/// Mode after an event or at the start (eq. 1 of the paper, the rules of docs/contact.md):
/// slip in sgn(v) when |v| > tol; stick when |f_req| <= mu_s N; else slip in -sgn(f_req).
inline ContactState decide_mode(const ChainParameters& p, double v_rel, double f_req) {
  const double tol = velocity_tolerance();
  if (std::abs(v_rel) > tol) return stickslip::slip_state(v_rel);
  if (std::abs(f_req) <= p.mu_s * p.normal_force) return ContactState::Stick;
  return stickslip::slip_state(-f_req);
}

/// Physics of a chain with n = N masses, fixed-size.
template <int N>
struct Chain {
  using Vec = Eigen::Matrix<double, N, 1>;
  using Mat = Eigen::Matrix<double, N, N>;

  explicit Chain(const ChainParameters& p)
      : prm(p),
        m(p.mass.head<N>()),
        K(p.stiffness.topLeftCorner<N, N>()),
        C(p.damping.topLeftCorner<N, N>()),
        F(p.force_amplitude.head<N>()),
        j(p.friction_dof),
        capacity(p.mu_s * p.normal_force),
        slip_force(p.mu_k * p.normal_force) {}

  double phase(double t) const { return prm.force_frequency * t + prm.force_phase; }

  /// f_req = (K x + C v)_j - F_j cos(omega t + phi): the force that keeps x_j'' = 0.
  double stick_force(double t, const Vec& x, const Vec& v) const {
    return K.row(j).dot(x) + C.row(j).dot(v) - F[j] * std::cos(phase(t));
  }

  /// x'' = M^-1 (F cos(omega t + phi) - K x - C v + f e_j); row j zero in stick.
  void acceleration(ContactState s, double t, const Vec& x, const Vec& v, Vec& a) const {
    a.noalias() = F * std::cos(phase(t)) - K * x - C * v;
    if (s == ContactState::Stick) {
      a[j] = 0.0;
    } else {
      a[j] -= static_cast<double>(stickslip::slip_sign(s)) * slip_force;
    }
    a.array() /= m.array();
  }

  /// Guards as distances, positive inside the mode; an event is a fall to <= 0.
  /// Stick: d0 = mu_s N - f_req (-> slip negative), d1 = mu_s N + f_req (-> slip positive).
  /// Slip: d0 = sgn * (x_j' - v_b).
  int num_guards(ContactState s) const { return s == ContactState::Stick ? 2 : 1; }
  void guards(ContactState s, double t, const Vec& x, const Vec& v, double* d) const {
    if (s == ContactState::Stick) {
      const double f = stick_force(t, x, v);
      d[0] = capacity - f;
      d[1] = capacity + f;
    } else {
      d[0] = static_cast<double>(stickslip::slip_sign(s)) * (v[j] - prm.belt_speed);
    }
  }

  /// The mode after guard `fired` of mode s triggered at (t, x, v); puts v_j on the belt in
  /// stick. What a user of a general-purpose integrator writes.
  ContactState switch_mode(ContactState s, int fired, double t, const Vec& x, Vec& v) const {
    ContactState next;
    if (s == ContactState::Stick) {
      next = fired == 0 ? ContactState::SlipNegative : ContactState::SlipPositive;
    } else {
      next = decide_mode(prm, 0.0, stick_force(t, x, v));
    }
    if (next == ContactState::Stick) v[j] = prm.belt_speed;
    return next;
  }

  const ChainParameters& prm;
  Vec m;
  Mat K, C;
  Vec F;
  int j;
  double capacity, slip_force;
};

/// One event: time and the modes before and after.
struct Event {
  double t;
  ContactState from, to;
};

/// Den Hartog's non-stop steady state of m x'' + k x = F0 cos(omega t + phi) -/+ R (m = k = 1,
/// R = mu N): amplitude X = sqrt((F0 V)^2 - (R U)^2), V = 1/(1 - omega^2),
/// U = tan(pi / (2 omega)) / omega, and the forcing phase theta at the instant of the velocity
/// reversal at x = -X: sin(theta) = R U / (F0 V), cos(theta) = -X / (F0 V)
/// (J. P. Den Hartog, Trans. ASME 53, 1931, rederived in docs/measurements/peers.md).
struct DenHartogSteadyState {
  double amplitude, theta, V, b;

  DenHartogSteadyState(double F0, double omega, double R) {
    V = 1.0 / (1.0 - omega * omega);
    const double U = std::tan(kPi / (2.0 * omega)) / omega;
    amplitude = std::sqrt(F0 * V * F0 * V - R * U * R * U);
    theta = std::atan2(R * U / (F0 * V), -amplitude / (F0 * V));
    b = R * std::tan(kPi / (2.0 * omega));
    F0_ = F0;
    omega_ = omega;
    R_ = R;
  }

  /// (x, x') at time t of the motion that reverses at x = -X at t = 0 (phase theta there):
  /// in the half period k (t = k pi/omega + tau), x = s [F0 V cos(omega tau + theta) - R +
  /// R cos tau + b sin tau] with s = +1 for even k, -1 for odd k.
  Eigen::Vector2d state(double t) const {
    const double half = kPi / omega_;
    const double k = std::floor(t / half);
    const double tau = t - k * half;
    const double s = std::fmod(k, 2.0) == 0.0 ? 1.0 : -1.0;
    const double x = F0_ * V * std::cos(omega_ * tau + theta) - R_ + R_ * std::cos(tau) +
                     b * std::sin(tau);
    const double v = -F0_ * V * omega_ * std::sin(omega_ * tau + theta) - R_ * std::sin(tau) +
                     b * std::cos(tau);
    return {s * x, s * v};
  }

 private:
  double F0_ = 0, omega_ = 1, R_ = 0;
};

/// The problems of the benchmark.
inline std::vector<ChainParameters> make_problems() {
  std::vector<ChainParameters> out;
  {
    // Den Hartog, non-stop motion: started on the closed-form periodic orbit (x = -X, v = 0 at
    // the reversal), so the reference can be checked against the closed form over [0, 200].
    ChainParameters p;
    p.name = "den_hartog_nonstop";
    p.description = "m=k=1, c=0, F0=1, omega=0.6, mu_s=mu_k=0.3, N=1; on Den Hartog's steady state";
    p.force_amplitude = {1.0, 0.0};
    p.force_frequency = 0.6;
    p.mu_s = p.mu_k = 0.3;
    const DenHartogSteadyState ss(1.0, p.force_frequency, p.mu_k * p.normal_force);
    p.force_phase = ss.theta;
    p.x0 = {-ss.amplitude, 0.0};
    out.push_back(p);
  }
  {
    ChainParameters p;
    p.name = "den_hartog_stops";
    p.description = "m=k=1, c=0, F0=1, omega=0.5, mu_s=mu_k=0.6, N=1; from rest (motion with stops)";
    p.force_amplitude = {1.0, 0.0};
    p.force_frequency = 0.5;
    p.mu_s = p.mu_k = 0.6;
    out.push_back(p);
  }
  {
    ChainParameters p;
    p.name = "belt";
    p.description = "m=k=1, c=0, no forcing, mu_s=0.4, mu_k=0.3, N=1, belt at v_b=0.1; from stick at x=0";
    p.mu_s = 0.4;
    p.mu_k = 0.3;
    p.belt_speed = 0.1;
    p.v0 = {0.1, 0.0};
    out.push_back(p);
  }
  {
    ChainParameters p;
    p.name = "chain2";
    p.description =
        "2 unit masses, springs 1 (ground-m1) and 2 (m1-m2), C = 0.02 K, F=(0,1) cos(0.9 t), "
        "friction on m1: mu_s=0.5, mu_k=0.4, N=1; from rest";
    p.dofs = 2;
    p.stiffness << 3.0, -2.0, -2.0, 2.0;
    p.damping = 0.02 * p.stiffness;
    p.force_amplitude = {0.0, 1.0};
    p.force_frequency = 0.9;
    p.mu_s = 0.5;
    p.mu_k = 0.4;
    out.push_back(p);
  }
  return out;
}

}  // namespace peers
