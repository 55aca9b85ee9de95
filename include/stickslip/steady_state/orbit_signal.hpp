#pragma once
/// \file orbit_signal.hpp
/// \brief Linear outputs y = c^T x of a periodic orbit measured over the orbit's own period:
/// extremes, mean and Fourier coefficients, taken from the run that closed the orbit (the
/// shooting's or the continuation corrector's last run) and never from a separate run, which
/// leaves an unstable orbit at the rate of its largest multiplier.

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <vector>

namespace stickslip {

/// One linear output y(t) = c^T x(t) of an orbit over one period [t0, t0 + T]:
///
///     y(t) ~ mean + sum_{h=1..H} (cosines[h-1] cos(h w (t - t0)) + sines[h-1] sin(h w (t - t0))),
///
/// w = 2 pi / T, the coefficients by the trapezoidal rule on the N uniform samples
/// t0 + k T / N, k = 0 .. N - 1 (N = ShootingOptions::samples_per_period; exact for the
/// harmonics below N / 2 of a trigonometric polynomial, spectrally accurate for a smooth orbit,
/// O(N^-2) and better where the orbit has kinks). min and max are over every step, event and
/// sample of the run: a sampled sine misses its peak by at most 1 - cos(pi / N) of its amplitude.
template <class Scalar>
struct OrbitSignal {
  /// Dynamic vector type.
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  Scalar min = 0;   ///< smallest y over the period
  Scalar max = 0;   ///< largest y over the period
  Scalar mean = 0;  ///< (1/T) integral of y over the period
  Vector cosines;   ///< cos coefficients of harmonics 1 .. H (ShootingOptions::output_harmonics)
  Vector sines;     ///< sin coefficients of harmonics 1 .. H
  /// Half the peak-to-peak, (max - min) / 2.
  Scalar amplitude() const { return (max - min) / 2; }
  /// |y_h| = sqrt(cosines[h-1]^2 + sines[h-1]^2) for h in 1 .. H (0 outside).
  Scalar harmonic(Eigen::Index h) const {
    if (h < 1 || h > cosines.size()) return Scalar(0);
    using std::hypot;
    return hypot(cosines[h - 1], sines[h - 1]);
  }
};

namespace detail {

/// Accumulates OrbitSignals from a run's steps, events and samples (no allocation per call: the
/// signals are sized by start()). Reads x[i] for i < c.cols(), so it serves the plain and the
/// augmented (variational) state alike.
template <class Scalar>
struct SignalAccumulator {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  const Matrix* c = nullptr;  // rows: outputs (may be empty)
  std::vector<OrbitSignal<Scalar>>* signals = nullptr;
  Scalar t0 = 0, T = 1;
  int samples = 0;  // N: the uniform samples per period that the Fourier sums take
  bool seen = false;

  /// Sizes the signals for `harmonics` harmonics over the period [t0, t0 + T] sampled N times.
  void start(Scalar t0_, Scalar T_, int N, int harmonics) {
    t0 = t0_;
    T = T_;
    samples = N;
    seen = false;
    signals->assign(static_cast<std::size_t>(c->rows()), OrbitSignal<Scalar>{});
    for (auto& s : *signals) {
      s.cosines.setZero(harmonics);
      s.sines.setZero(harmonics);
    }
  }
  template <class X>
  Scalar value(Eigen::Index j, const X& x) const {
    Scalar y = 0;
    for (Eigen::Index i = 0; i < c->cols(); ++i) y += (*c)(j, i) * x[i];
    return y;
  }
  /// A point of the run (step end, event, sample): the extremes.
  template <class X>
  void extremes(const X& x) {
    for (Eigen::Index j = 0; j < c->rows(); ++j) {
      auto& s = (*signals)[static_cast<std::size_t>(j)];
      const Scalar y = value(j, x);
      s.min = seen ? std::min(s.min, y) : y;
      s.max = seen ? std::max(s.max, y) : y;
    }
    seen = true;
  }
  /// A uniform sample at t: the extremes, and the Fourier sums for t in [t0, t0 + T) (the
  /// sample at t0 + T repeats the one at t0).
  template <class X>
  void sample(Scalar t, const X& x) {
    extremes(x);
    if (samples <= 0 || !(t - t0 < T - T / (Scalar(2) * Scalar(samples)))) return;
    using std::cos;
    using std::sin;
    const Scalar a = Scalar(2) * Scalar(3.14159265358979323846264338327950288) * (t - t0) / T;
    const Scalar w = Scalar(1) / Scalar(samples);
    const Scalar c1 = cos(a), s1 = sin(a);
    for (Eigen::Index j = 0; j < c->rows(); ++j) {
      auto& s = (*signals)[static_cast<std::size_t>(j)];
      const Scalar y = value(j, x);
      s.mean += w * y;
      Scalar ch = c1, sh = s1;  // cos(h a), sin(h a) by the angle-sum recurrence
      for (Eigen::Index h = 0; h < s.cosines.size(); ++h) {
        s.cosines[h] += 2 * w * y * ch;
        s.sines[h] += 2 * w * y * sh;
        const Scalar cn = ch * c1 - sh * s1;
        sh = sh * c1 + ch * s1;
        ch = cn;
      }
    }
  }
};

}  // namespace detail

}  // namespace stickslip
