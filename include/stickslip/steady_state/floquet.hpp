#pragma once
/// \file floquet.hpp
/// \brief Floquet multipliers of a periodic orbit (eigenvalues of its monodromy matrix), its
/// stability and the kind of instability.

#include <stickslip/detail/validate.hpp>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace stickslip {

/// How a periodic orbit is unstable: through which point of the unit circle its leading
/// multiplier has left (the bifurcation at which the branch lost stability).
enum class Instability : std::uint8_t {
  None,            ///< all multipliers inside the unit circle (stable)
  Fold,            ///< a real multiplier > 1 (it left through +1: a fold / cyclic fold)
  PeriodDoubling,  ///< a real multiplier < -1 (it left through -1: period doubling / flip)
  NeimarkSacker    ///< a complex pair outside (it left as a pair: Neimark-Sacker, torus)
};

/// Human-readable name of an instability kind.
inline const char* to_string(Instability i) noexcept {
  switch (i) {
    case Instability::None: return "none";
    case Instability::Fold: return "fold";
    case Instability::PeriodDoubling: return "period_doubling";
    case Instability::NeimarkSacker: return "neimark_sacker";
  }
  return "unknown";
}

/// Floquet multipliers mu of an orbit: the eigenvalues of its monodromy matrix M = dx(T)/dx(0).
template <class Scalar>
struct FloquetMultipliers {
  /// Complex type of the multipliers.
  using Complex = std::complex<Scalar>;
  /// The multipliers (autonomous orbits: without the trivial one), by decreasing modulus.
  Eigen::Matrix<Complex, Eigen::Dynamic, 1> multipliers;
  /// Autonomous orbits: the multiplier nearest to 1 (the flow direction), reported apart.
  Complex trivial{Scalar(1), Scalar(0)};
  bool has_trivial = false;   ///< an autonomous orbit (trivial is set)
  Scalar max_modulus = 0;     ///< max |mu| over `multipliers` (0 when there are none)
  bool stable = true;         ///< max_modulus <= 1 + tolerance
  /// The kind of the leading multiplier outside the unit circle.
  Instability instability = Instability::None;
};

/// The Floquet multipliers of the monodromy matrix M (Eigen::EigenSolver). For an autonomous
/// orbit the eigenvalue nearest to 1 is the trivial one (perturbation along the orbit) and is
/// reported apart. Stable when every other |mu| <= 1 + tolerance; otherwise the leading
/// multiplier gives the instability kind (imaginary part above `tolerance`: Neimark-Sacker).
/// Throws std::invalid_argument when M is not square or not finite, or tolerance is negative or
/// not finite.
template <class Scalar>
FloquetMultipliers<Scalar> floquet_multipliers(
    const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& M, bool autonomous,
    Scalar tolerance) {
  using Complex = std::complex<Scalar>;
  static const std::string where = "floquet_multipliers";
  if (M.rows() != M.cols())
    detail::throw_invalid(where, "M must be square (it has " + std::to_string(M.rows()) + " rows)",
                          M.cols());
  if (!detail::all_finite(M)) throw std::invalid_argument(where + ": M must be finite");
  detail::require_non_negative(where, "tolerance", tolerance);
  FloquetMultipliers<Scalar> r;
  if (M.size() == 0) return r;
  const Eigen::EigenSolver<Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>> es(M, false);
  Eigen::Matrix<Complex, Eigen::Dynamic, 1> mu = es.eigenvalues();
  std::sort(mu.data(), mu.data() + mu.size(),
            [](const Complex& a, const Complex& b) { return std::abs(a) > std::abs(b); });
  if (autonomous) {
    Eigen::Index k = 0;
    (mu.array() - Complex(Scalar(1), Scalar(0))).abs().minCoeff(&k);
    r.trivial = mu[k];
    r.has_trivial = true;
    r.multipliers.resize(mu.size() - 1);
    for (Eigen::Index i = 0, j = 0; i < mu.size(); ++i)
      if (i != k) r.multipliers[j++] = mu[i];
  } else {
    r.multipliers = mu;
  }
  if (r.multipliers.size() == 0) return r;
  const Complex lead = r.multipliers[0];
  r.max_modulus = std::abs(lead);
  r.stable = r.max_modulus <= Scalar(1) + tolerance;
  if (!r.stable) {
    if (std::abs(lead.imag()) > tolerance)
      r.instability = Instability::NeimarkSacker;
    else
      r.instability = lead.real() > 0 ? Instability::Fold : Instability::PeriodDoubling;
  }
  return r;
}

}  // namespace stickslip
