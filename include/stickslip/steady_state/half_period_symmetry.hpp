#pragma once
/// \file half_period_symmetry.hpp
/// \brief A symmetry with a half-period shift, x(t) -> c + S (x(t + T/2) - c), for shooting the
/// symmetric orbits on half a period (Shooting::half_period_symmetry).

#include <stickslip/detail/validate.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <string>

namespace stickslip {

namespace detail {
/// Throws std::invalid_argument (naming `name`) unless S is a non-empty, finite, square
/// involution: max |S S - I| <= 1e-10 max(1, max |S|^2).
template <class Matrix>
void require_involution(const std::string& where, const std::string& name, const Matrix& S) {
  using Scalar = typename Matrix::Scalar;
  if (S.rows() == 0 || S.rows() != S.cols())
    throw_invalid(where, name + " must be a non-empty square matrix, rows", S.rows());
  if (!all_finite(S)) throw std::invalid_argument(where + ": " + name + " must be finite");
  const Scalar scale = std::max(Scalar(1), S.cwiseAbs().maxCoeff() * S.cwiseAbs().maxCoeff());
  const Scalar defect = (S * S - Matrix::Identity(S.rows(), S.rows())).cwiseAbs().maxCoeff();
  if (!(defect <= Scalar(1e-10) * scale))
    throw_invalid(where, name + " must be an involution (S S = I); max |S S - I|", defect);
}
}  // namespace detail

/// The symmetry of a system forced so that x(t) is a solution iff c + S (x(t + T/2) - c) is
/// (mirror-image substructures forced in antiphase). Its symmetric orbits satisfy
///
///     c + S (x(t0 + T/2) - c) = x(t0),   mode_image(mode(t0 + T/2)) = mode(t0),
///
/// a problem on half the period whose Jacobian H - I, H = S dx(t0 + T/2)/dx(t0), stays regular
/// where the full period's M - I = H^2 - I is singular at a symmetry-breaking pitchfork (an
/// eigenvalue of H through -1).
template <class System>
struct HalfPeriodSymmetry {
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  /// State of the system.
  using State = typename System::State;
  /// Mode of the system.
  using Mode = typename System::Mode;
  /// Dynamic matrix type.
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  /// The linear involution S (S S = I) of the state.
  Matrix S;
  /// The state the symmetry keeps fixed, c; empty (or, for a fixed-size State, its default
  /// zero): c = 0.
  State centre = no_centre();
  /// The mode of a mirrored state; empty: the same mode.
  std::function<Mode(const Mode&)> mode_image;

  /// The default centre: an empty State, or zero when State has a fixed size.
  static State no_centre() {
    if constexpr (State::RowsAtCompileTime == Eigen::Dynamic) return State();
    else return State::Zero();
  }
  /// c + S (x - c).
  State mirror(const State& x) const {
    if (centre.size() == 0) return S * x;
    return centre + S * (x - centre);
  }
  /// mode_image(mode), or mode without a mode_image.
  Mode mirror_mode(const Mode& mode) const { return mode_image ? mode_image(mode) : mode; }

  /// Throws std::invalid_argument (from `where`) unless S is a finite square involution of size
  /// n and centre is empty or finite of size n.
  void validate(const std::string& where, Eigen::Index n) const {
    detail::require_involution(where, "S", S);
    if (S.rows() != n) detail::throw_invalid(where, "S must have the state size " + std::to_string(n) + ", rows", S.rows());
    if (centre.size() != 0 && centre.size() != n)
      detail::throw_invalid(where, "centre must be empty or have the state size " + std::to_string(n) + ", size",
                            centre.size());
    if (!detail::all_finite(centre)) throw std::invalid_argument(where + ": centre must be finite");
  }
};

}  // namespace stickslip
