#pragma once
// The reference solution: within a mode the chain is linear and time-invariant once the
// forcing is carried as two extra states, so it is integrated exactly by a matrix exponential;
// events are found by sampling the exact solution and bisecting on it.
//
//   z = (x, x', 1, cos(omega t + phi), sin(omega t + phi)),   z' = A_m z,   z(t0 + tau) = e^{A_m tau} z(t0)
//
// with, in mode m, x'' = M^-1 (F c - K x - C x' - s_m mu_k N e_j) (row j zero in stick),
// c' = -omega s, s' = omega c.

#include <unsupported/Eigen/MatrixFunctions>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <vector>

#include "peers/peer_problems.hpp"

namespace peers {

struct ReferenceSolution {
  std::vector<Event> events;
  Eigen::VectorXd final_state;  // (x, x') at t_end
  long mode_phases = 0;
};

/// Options of the reference: sample spacing of the bracketing search and bisection width.
struct ReferenceOptions {
  double sample = 1e-3;           // s; two crossings of one guard closer than this are missed
  double time_tolerance = 1e-14;  // s; final bracket width of an event time (mode-local)
};

template <int N>
class ExactChain {
 public:
  static constexpr int kSize = 2 * N + 3;
  using Z = Eigen::Matrix<double, kSize, 1>;
  using A = Eigen::Matrix<double, kSize, kSize>;
  using Row = Eigen::Matrix<double, 1, kSize>;

  explicit ExactChain(const ChainParameters& p) : p_(p), chain_(p) {}

  /// A_m of the augmented system.
  A matrix(ContactState s) const {
    A a = A::Zero();
    const int one = 2 * N, c = 2 * N + 1, sn = 2 * N + 2;
    a.template block<N, N>(0, N).setIdentity();
    for (int r = 0; r < N; ++r) {
      if (s == ContactState::Stick && r == chain_.j) continue;  // x_j'' = 0
      const double inv_m = 1.0 / chain_.m[r];
      a.template block<1, N>(N + r, 0) = -inv_m * chain_.K.row(r);
      a.template block<1, N>(N + r, N) = -inv_m * chain_.C.row(r);
      a(N + r, c) = inv_m * chain_.F[r];
      if (r == chain_.j)
        a(N + r, one) = -inv_m * static_cast<double>(stickslip::slip_sign(s)) * chain_.slip_force;
    }
    a(c, sn) = -p_.force_frequency;
    a(sn, c) = p_.force_frequency;
    return a;
  }

  /// Guard rows: d_i = row_i . z (the distances of Chain::guards, linear in z).
  int guard_rows(ContactState s, Row* rows) const {
    const int one = 2 * N, c = 2 * N + 1;
    if (s == ContactState::Stick) {
      Row f = Row::Zero();  // f_req = K_j x + C_j v - F_j c
      f.template head<N>() = chain_.K.row(chain_.j);
      f.template segment<N>(N) = chain_.C.row(chain_.j);
      f(c) = -chain_.F[chain_.j];
      rows[0] = -f;
      rows[0](one) += chain_.capacity;
      rows[1] = f;
      rows[1](one) += chain_.capacity;
      return 2;
    }
    const double sg = static_cast<double>(stickslip::slip_sign(s));
    rows[0] = Row::Zero();
    rows[0](N + chain_.j) = sg;
    rows[0](one) = -sg * p_.belt_speed;
    return 1;
  }

  Z initial() const {
    Z z;
    z.template head<N>() = p_.x0.head<N>();
    z.template segment<N>(N) = p_.v0.head<N>();
    z(2 * N) = 1.0;
    z(2 * N + 1) = std::cos(p_.force_phase);
    z(2 * N + 2) = std::sin(p_.force_phase);
    return z;
  }

  ContactState initial_mode() const {
    const auto x = p_.x0.head<N>().eval();
    const auto v = p_.v0.head<N>().eval();
    return decide_mode(p_, v[chain_.j] - p_.belt_speed, chain_.stick_force(0.0, x, v));
  }

  ReferenceSolution solve(const ReferenceOptions& o = {}) const {
    ReferenceSolution out;
    double t = 0.0;
    Z z = initial();
    ContactState mode = initial_mode();
    const double T = p_.t_end;
    Row rows[2];
    while (true) {
      ++out.mode_phases;
      const A a = matrix(mode);
      const int ng = guard_rows(mode, rows);
      const A step = (a * o.sample).exp();
      Z zs = z;
      double prev[2] = {rows[0].dot(z), ng > 1 ? rows[1].dot(z) : 0.0};
      double lo = 0.0;
      int fired = -1;
      double hi = 0.0;
      for (long k = 1;; ++k) {
        double tau = static_cast<double>(k) * o.sample;
        const bool last = t + tau >= T;
        if (last) tau = T - t;
        // Re-anchor every 64 samples: z(tau) = e^{A tau} z(0) exactly, no accumulated products.
        zs = (k % 64 == 0 || last) ? Z((a * tau).exp() * z) : Z(step * zs);
        double d[2] = {0.0, 0.0};
        for (int i = 0; i < ng; ++i) {
          d[i] = rows[i].dot(zs);
          if (prev[i] > 0.0 && d[i] <= 0.0 && fired < 0) fired = i;
        }
        if (fired < 0) std::copy(d, d + ng, prev);
        if (fired >= 0) {
          hi = tau;
          break;
        }
        lo = tau;
        if (last) break;
      }
      if (fired < 0) {  // reached t_end in this mode
        z = (a * (T - t)).exp() * z;
        break;
      }
      // The earliest crossing among the guards in [lo, hi]: bisect on "a guard that was > 0 at
      // lo is <= 0" (prev holds the guards at lo).
      const bool active[2] = {prev[0] > 0.0, ng > 1 && prev[1] > 0.0};
      auto crossed = [&](double tau, int* which) {
        const Z zt = (a * tau).exp() * z;
        for (int i = 0; i < ng; ++i) {
          if (active[i] && rows[i].dot(zt) <= 0.0) {
            *which = i;
            return true;
          }
        }
        return false;
      };
      int which = fired;
      while (hi - lo > o.time_tolerance) {
        const double mid = 0.5 * (lo + hi);
        int w = -1;
        if (crossed(mid, &w)) {
          hi = mid;
          which = w;
        } else {
          lo = mid;
        }
      }
      const Z ze = (a * hi).exp() * z;
      const double te = t + hi;
      if (te >= T) {  // the event falls at t_end: the state there is the pre-event state
        z = (a * (T - t)).exp() * z;
        break;
      }
      Eigen::Matrix<double, N, 1> x = ze.template head<N>(), v = ze.template segment<N>(N);
      const ContactState next = chain_.switch_mode(mode, which, te, x, v);
      out.events.push_back({te, mode, next});
      z = ze;
      z.template segment<N>(N) = v;
      mode = next;
      t = te;
    }
    out.final_state = z.template head<2 * N>();
    return out;
  }

 private:
  const ChainParameters& p_;
  Chain<N> chain_;
};

/// The reference of problem p.
inline ReferenceSolution solve_reference(const ChainParameters& p,
                                         const ReferenceOptions& o = {}) {
  if (p.dofs == 1) return ExactChain<1>(p).solve(o);
  return ExactChain<2>(p).solve(o);
}

}  // namespace peers
