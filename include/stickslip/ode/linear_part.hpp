#pragma once
/// \file linear_part.hpp
/// \brief The optional linear-part extension of the hybrid-system concept: in a mode m,
///
///     x_L' = A_m x_L + b_m(t) + r_m(t, x),   b_m(t) = b0 + sum_k (bc_k cos(w_k t) + bs_k sin(w_k t)),
///
/// where x_L = x[0 .. size) are the *linear* components, A_m is constant over the mode (or over
/// one step of an exponential method), b_m a sum of constant and harmonic terms and r_m the
/// remainder, identically zero where the mode is exactly linear (`exact`). Components of x past
/// `size` are *quadratures*: their derivative depends on (t, x_L) only and never feeds back (an
/// energy audit, say); steppers obtain it from `rhs`, or, where an exact mode gives their rates
/// as quadratic forms (`quadrature_forms`), integrate them in closed form.
///
/// A system opts in with
///
///     bool linear_part(const Mode& m, Scalar t, const State& x, LinearPart<Scalar>& lp);
///
/// which fills `lp` for mode m at (t, x) and returns false where the mode has no such form. It
/// must not allocate once `lp` has the right sizes. Systems without it keep working with every
/// method; methods that need it `static_assert(has_linear_part_v<System>, ...)`.

#include <Eigen/Core>

#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

namespace stickslip {

/// Linear part of one mode of a hybrid system (see the file comment).
template <class Scalar_>
struct LinearPart {
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;
  /// Dynamic matrix.
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  /// Dynamic column vector.
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  /// A_m, size x size: the number of linear components x_L = x[0 .. size).
  Matrix A;
  /// Constant part b0 of b_m (size).
  Vector b0;
  /// Angular frequencies w_k of the harmonic terms of b_m (rad per time unit), K of them.
  std::vector<Scalar> omega;
  ///@{
  /// Cosine and sine coefficients of the harmonic terms, size x K (column k belongs to omega[k]).
  Matrix bc, bs;
  ///@}
  /// True when r_m is identically zero in this mode: x_L follows the linear ODE exactly.
  bool exact = true;
  /// Changes whenever A_m changes: equal versions promise an equal A_m, so that a method may keep
  /// a decomposition of A_m from one call to the next (b_m may still differ).
  std::uint64_t version = 0;

  /// Optional affine guards, all of them or none (empty Gx): g(t, x) = Gx x_L + g0 +
  /// sum_k (gc_k cos(w_k t) + gs_k sin(w_k t)) with the harmonic frequencies above; rows =
  /// num_guards(m). Lets a method evaluate guards, and bound their rates, in closed form. In an
  /// inexact mode (exact == false) they are the guards of the frozen linear part, g = Gx x_L +
  /// ... + rho(t, x) with rho small near the point of the call and smooth along the solution: a
  /// method uses them only to bound how far the guards can move over a step.
  Matrix Gx;
  Vector g0;   ///< constant part of the affine guards
  Matrix gc;   ///< cosine coefficients of the affine guards (rows x K)
  Matrix gs;   ///< sine coefficients of the affine guards (rows x K)
  /// Set by the method before the call: whether it uses the frozen affine guards of an inexact
  /// mode. A system may leave Gx empty in an inexact mode when false (they cost it a probe of
  /// its guards per component); exact modes give theirs regardless. Default true.
  bool want_inexact_guards = true;

  /// Optional quadratic forms of the quadrature rates in an exact mode, one per quadrature or none
  /// (empty): x_Q[j]' = z^T Q_j z with Q_j = quadrature_forms[j] (square, size() + 1 + 2K; need
  /// not be symmetric) and z = (x_L, 1, cos w_1 t, sin w_1 t, ..., cos w_K t, sin w_K t). Lets a
  /// method integrate the quadratures exactly (Van Loan's block exponential) instead of by a
  /// quadrature rule through rhs. Ignored where `exact` is false.
  std::vector<Matrix> quadrature_forms;

  /// Number of linear components.
  Eigen::Index size() const noexcept { return A.rows(); }
  /// True when the affine guards are given.
  bool has_affine_guards() const noexcept { return Gx.size() > 0; }
  /// True when the quadrature rates are given as quadratic forms.
  bool has_quadrature_forms() const noexcept { return !quadrature_forms.empty(); }

  /// b_m(t) into out (size()); no allocation once out is sized.
  template <class Out>
  void load(Scalar t, Out& out) const {
    out = b0;
    using std::cos;
    using std::sin;
    for (std::size_t k = 0; k < omega.size(); ++k) {
      const auto j = static_cast<Eigen::Index>(k);
      out.noalias() += cos(omega[k] * t) * bc.col(j) + sin(omega[k] * t) * bs.col(j);
    }
  }
};

namespace detail {
template <class S, class = void>
struct has_linear_part : std::false_type {};
template <class S>
struct has_linear_part<
    S, std::void_t<decltype(std::declval<bool&>() = std::declval<S&>().linear_part(
                                std::declval<const typename S::Mode&>(),
                                std::declval<typename S::Scalar>(),
                                std::declval<const typename S::State&>(),
                                std::declval<LinearPart<typename S::Scalar>&>()))>>
    : std::true_type {};
}  // namespace detail

/// True when S provides `bool linear_part(mode, t, x, LinearPart<Scalar>&)`.
template <class S>
inline constexpr bool has_linear_part_v = detail::has_linear_part<S>::value;

}  // namespace stickslip
