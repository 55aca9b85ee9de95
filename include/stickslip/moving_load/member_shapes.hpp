#pragma once
/// \file member_shapes.hpp
/// \brief Retained modes and their derivatives at an arbitrary point of one member of a frame:
/// the paper's approximate analytical modes psi_u, psi_w (eqs 4-7, 10) with psi_w', psi_w''
/// (eqs 18-29), for moving loads such as a damper sliding along a platform.

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "stickslip/detail/validate.hpp"
#include "stickslip/moving_load/element_shape_functions.hpp"
#include "stickslip/moving_load/end_policy.hpp"
#include "stickslip/moving_load/member_nodal_modes.hpp"
#include "stickslip/moving_load/shape_values.hpp"

namespace stickslip {

namespace detail {

/// Shortest decimal form of x that reads back to the same value (for readable messages).
template <class Scalar>
std::string format_shortest(Scalar x) {
  std::ostringstream os;
  for (int digits = 6; digits < 40; ++digits) {
    os.str("");
    os.precision(digits);
    os << x;
    std::istringstream is(os.str());
    Scalar back{};
    if ((is >> back) && back == x) break;
  }
  return os.str();
}

}  // namespace detail

/// Interpolated modes of one member: for n retained modes, the row vectors psi_u(eps),
/// psi_u'(eps), psi_w(eps), psi_w'(eps), psi_w''(eps) at a local coordinate eps in [0, L]
/// (paper eqs 4-7 and 10):
///
///     psi_u(eps) = N_u(x) [u_a, u_b]^T,   psi_w(eps) = N_w(x) [w_a, theta_a, w_b, theta_b]^T
///
/// in the element [s_e, s_e+1) holding eps, x = eps - s_e, with the shape functions of
/// ElementShapeFunctions and the local nodal mode components of MemberNodalModes. The element
/// is found by binary search on the stations (O(log n_e)) or, given an ElementCursor, in O(1)
/// when eps is still in the cursor's element or a neighbour. Evaluation allocates nothing; with a
/// fixed `Modes` every vector is fixed-size.
///
/// Elements are half-open [s_e, s_e+1), the last one closed: at an interior node the element to
/// its right is used (psi_u' and psi_w'' jump there; psi_u, psi_w, psi_w' are continuous and
/// equal the nodal components exactly). Beyond the ends the EndPolicy decides (docs/moving_load.md).
///
/// Immutable after construction: one instance may serve several threads, each with its own
/// cursor and ShapeValues.
template <class Scalar_, int Modes = Eigen::Dynamic>
class MemberShapes {
  static_assert(Modes == Eigen::Dynamic || Modes > 0, "MemberShapes: Modes must be > 0 or Dynamic");

 public:
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;
  /// The five row vectors of evaluate() at one point.
  using Values = ShapeValues<Scalar, Modes>;
  /// One value per mode (fixed-size with a fixed `Modes`).
  using Vector = typename Values::Vector;
  /// Dynamic column vector.
  using DynamicVector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  /// Raw nodal data of a member (constructor input).
  using NodalModes = MemberNodalModes<Scalar>;
  /// Number of modes fixed at compile time, or Eigen::Dynamic (template parameter `Modes`).
  static constexpr int modes_at_compile_time = Modes;

  /// Build from raw nodal data (layer without a FrameModel; see MemberNodalModes).
  /// Throws std::invalid_argument when the stations are not 0 = s_0 < ... < s_ne with ne >= 1,
  /// when u, w, theta do not all have one row per station and the same number n >= 1 of columns,
  /// when a value is not finite, when (cos, sin) is not a unit vector, when free_dofs is neither
  /// empty nor 3 entries per node in [-1, num_free), or when a fixed Modes differs from n.
  explicit MemberShapes(const NodalModes& data, EndPolicy policy = EndPolicy::Throw)
      : member_(data.member), policy_(policy), cos_(data.cos), sin_(data.sin),
        free_dofs_(data.free_dofs), num_free_(data.num_free) {
    validate(data);
    const Eigen::Index nodes = data.stations.size();
    const Eigen::Index n = data.u.cols();
    stations_ = data.stations;
    element_lengths_ = stations_.tail(nodes - 1) - stations_.head(nodes - 1);
    nodal_.resize(n, 3 * nodes);
    for (Eigen::Index k = 0; k < nodes; ++k) {
      nodal_.col(3 * k) = data.u.row(k).transpose();
      nodal_.col(3 * k + 1) = data.w.row(k).transpose();
      nodal_.col(3 * k + 2) = data.theta.row(k).transpose();
    }
  }

  /// Build for member `member` of `model` from a basis computed for that model (nodal modes
  /// extracted and rotated to local axes by member_nodal_modes). Keeps no reference to either.
  /// \throws std::invalid_argument when the member is not in the model, the basis does not belong
  ///         to the model or its DOF count differs, or a fixed Modes differs from basis.size()
  MemberShapes(const FrameModel<Scalar>& model, MemberId member,
               const ModalBasis<Scalar>& basis, EndPolicy policy = EndPolicy::Throw)
      : MemberShapes(member_nodal_modes(model, member, basis, "MemberShapes"), policy) {}

  /// Evaluate all five row vectors at eps, starting the element search at the cursor's element
  /// (O(1) when eps is in it or a neighbour) and leaving the element found in the cursor.
  /// `out` is resized to num_modes() (allocates only on its first use with Dynamic modes).
  /// Throws std::invalid_argument for non-finite eps, and for eps off [0, L] under EndPolicy::Throw.
  void evaluate(Scalar eps, Values& out, ElementCursor& cursor) const {
    const Scalar x = admit(eps, "MemberShapes::evaluate");
    cursor.element = find_element(x, cursor.element);
    evaluate_unchecked(cursor.element, x, out);
  }

  /// Evaluate at eps with an O(log n_e) element search. Throws as evaluate(eps, out, cursor).
  void evaluate(Scalar eps, Values& out) const {
    ElementCursor cursor;
    evaluate(eps, out, cursor);
  }

  /// Evaluate at eps, returning fresh values (allocates with Dynamic modes).
  Values evaluate(Scalar eps) const {
    Values out;
    evaluate(eps, out);
    return out;
  }

  /// Evaluate the interpolants of one element at eps, even outside that element (its polynomials
  /// continued); no end policy. For checks of continuity at element boundaries.
  /// Throws std::invalid_argument for an element not in [0, num_elements()) or non-finite eps.
  void evaluate_in_element(Eigen::Index element, Scalar eps, Values& out) const {
    const char* where = "MemberShapes::evaluate_in_element";
    if (element < 0 || element >= num_elements())
      detail::throw_invalid(where, "element must be in [0, " + std::to_string(num_elements()) + ")",
                            element);
    detail::require_finite(where, "eps", eps);
    evaluate_unchecked(element, eps, out);
  }

  /// Displacement row vectors in global axes at eps: psi_X = cos psi_u - sin psi_w,
  /// psi_Y = sin psi_u + cos psi_w. Allocation-free once psi_X, psi_Y have num_modes() entries.
  /// Throws as evaluate().
  void evaluate_global(Scalar eps, Vector& psi_X, Vector& psi_Y, ElementCursor& cursor) const {
    const Scalar x = admit(eps, "MemberShapes::evaluate_global");
    const Eigen::Index e = find_element(x, cursor.element);
    cursor.element = e;
    const ElementShapeFunctions<Scalar> f = shape_functions(e, x);
    const auto B = element_block(e);
    psi_X.resize(num_modes());
    psi_Y.resize(num_modes());
    // psi_X temporarily holds psi_u and psi_Y psi_w before the rotation.
    psi_X.noalias() = f.u1 * B.col(0) + f.u2 * B.col(3);
    psi_Y.noalias() = f.w1 * B.col(1) + f.t1 * B.col(2) + f.w2 * B.col(4) + f.t2 * B.col(5);
    for (Eigen::Index j = 0; j < num_modes(); ++j) {
      const Scalar u = psi_X(j), w = psi_Y(j);
      psi_X(j) = cos_ * u - sin_ * w;
      psi_Y(j) = sin_ * u + cos_ * w;
    }
  }

  /// Global-axis displacement row vectors at eps with an O(log n_e) search.
  void evaluate_global(Scalar eps, Vector& psi_X, Vector& psi_Y) const {
    ElementCursor cursor;
    evaluate_global(eps, psi_X, psi_Y, cursor);
  }

  /// Index of the element holding eps (after the end policy), O(log n_e).
  /// Throws as evaluate().
  Eigen::Index locate_element(Scalar eps) const {
    return find_element(admit(eps, "MemberShapes::locate_element"), -1);
  }

  /// Index of the element holding eps, O(1) when it is the cursor's element or a neighbour;
  /// updates the cursor. Throws as evaluate().
  Eigen::Index locate_element(Scalar eps, ElementCursor& cursor) const {
    cursor.element = find_element(admit(eps, "MemberShapes::locate_element"), cursor.element);
    return cursor.element;
  }

  /// Where eps lies: the element holding it (after the end policy) and the shape-function
  /// weights there, so that with B = element_block(element) every row vector of evaluate() is
  /// B times a weight vector (eqs 4-7): psi_u = B (u1, 0, 0, u2, 0, 0)^T,
  /// psi_w = B (0, w1, t1, 0, w2, t2)^T, and so on. Lets a caller form only the products it needs
  /// (e.g. psi^T q = weights . (B^T q)) without the five n-vectors. O(1) with a cursor still in
  /// the element or a neighbour; updates the cursor. Throws as evaluate().
  struct Location {
    /// Element holding eps after the end policy.
    Eigen::Index element;
    /// Shape-function weights at eps in that element (eqs 4-7).
    ElementShapeFunctions<Scalar> weights;
  };
  /// See Location: the element holding eps and the weights there; updates the cursor.
  Location locate(Scalar eps, ElementCursor& cursor) const {
    const Scalar x = admit(eps, "MemberShapes::locate");
    cursor.element = find_element(x, cursor.element);
    return Location{cursor.element, shape_functions(cursor.element, x)};
  }

  /// The local nodal values of element e's two nodes over the modes, an n x 6 block with columns
  /// (u1, w1, theta1, u2, w2, theta2) (a view into this object). No range check.
  auto element_block(Eigen::Index e) const noexcept {
    return nodal_.template middleCols<6>(3 * e);
  }

  /// Generalised force on each mode of a point load at eps (local axes): axial force Fa [N]
  /// along u, transverse force Ft [N] along w and moment M [N m] about Z:
  ///     Q = psi_u(eps) Fa + psi_w(eps) Ft + psi_w'(eps) M       (paper eq. 25 right-hand side)
  /// Throws as evaluate().
  Vector modal_force(Scalar eps, Scalar axial, Scalar transverse, Scalar moment) const {
    Vector out;
    ElementCursor cursor;
    modal_force(eps, axial, transverse, moment, out, cursor);
    return out;
  }

  /// Allocation-free modal_force into `out` (resized to num_modes()), using and updating a cursor.
  void modal_force(Scalar eps, Scalar axial, Scalar transverse, Scalar moment, Vector& out,
                   ElementCursor& cursor) const {
    const Scalar x = admit(eps, "MemberShapes::modal_force");
    cursor.element = find_element(x, cursor.element);
    out.resize(num_modes());
    out.noalias() =
        element_block(cursor.element) * local_load(cursor.element, x, axial, transverse, moment);
  }

  /// Consistent nodal load of the same point load over the model's free DOFs: the element's
  /// local load N_u^T Fa + N_w^T Ft + N_w'^T M rotated to global axes, so that
  /// Phi^T f = modal_force(eps, ...) (work equivalence). Components on constrained DOFs are
  /// dropped. Needs the DOF numbering: available from the FrameModel constructor, or from a
  /// MemberNodalModes with free_dofs. Throws std::invalid_argument without it, and as evaluate().
  DynamicVector consistent_nodal_load(Scalar eps, Scalar axial, Scalar transverse,
                                      Scalar moment) const {
    const char* where = "MemberShapes::consistent_nodal_load";
    if (free_dofs_.size() == 0)
      detail::throw_invalid(where,
                            "no DOF numbering: build from a FrameModel or give "
                            "MemberNodalModes::free_dofs (member)",
                            member_);
    const Scalar x = admit(eps, where);
    const Eigen::Index e = find_element(x, -1);
    const Eigen::Matrix<Scalar, 6, 1> f = local_load(e, x, axial, transverse, moment);
    DynamicVector load = DynamicVector::Zero(num_free_);
    for (Eigen::Index side = 0; side < 2; ++side) {
      const Eigen::Index node = e + side;
      const Scalar fu = f(3 * side), fw = f(3 * side + 1);
      const Scalar global[3] = {cos_ * fu - sin_ * fw, sin_ * fu + cos_ * fw, f(3 * side + 2)};
      for (Eigen::Index d = 0; d < 3; ++d) {
        const Eigen::Index i = free_dofs_(3 * node + d);
        if (i >= 0) load(i) += global[d];
      }
    }
    return load;
  }

  Scalar length() const noexcept { return stations_(stations_.size() - 1); }  ///< L [m]
  MemberId member() const noexcept { return member_; }                    ///< member id
  Eigen::Index num_modes() const noexcept { return nodal_.rows(); }           ///< n
  Eigen::Index num_elements() const noexcept { return element_lengths_.size(); }  ///< n_e
  /// What evaluations beyond the member ends do (Throw, Clamp, Extrapolate).
  EndPolicy end_policy() const noexcept { return policy_; }
  Scalar cos() const noexcept { return cos_; }  ///< member direction cosine
  Scalar sin() const noexcept { return sin_; }  ///< member direction sine
  /// Local coordinates of the member's nodes, 0 ... L [m].
  const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& stations() const noexcept { return stations_; }
  /// True when 0 <= eps <= length() (the ends are on the member).
  bool contains(Scalar eps) const noexcept { return eps >= Scalar(0) && eps <= length(); }
  /// True when consistent_nodal_load() is available.
  bool has_dof_numbering() const noexcept { return free_dofs_.size() != 0; }

 private:
  using NodalMatrix = Eigen::Matrix<Scalar, Modes, Eigen::Dynamic>;

  void validate(const NodalModes& d) const {
    const std::string where = "MemberShapes";
    const Eigen::Index nodes = d.stations.size();
    if (nodes < 2) detail::throw_invalid(where, "stations needs >= 2 entries (one element)", nodes);
    if (!d.stations.allFinite())
      detail::throw_invalid(where, "stations must be finite (member)", d.member);
    if (d.stations(0) != Scalar(0))
      detail::throw_invalid(where, "stations must start at 0", d.stations(0));
    for (Eigen::Index k = 1; k < nodes; ++k)
      if (!(d.stations(k) > d.stations(k - 1)))
        detail::throw_invalid(where,
                              "stations must be strictly ascending, at index " + std::to_string(k),
                              d.stations(k));
    const Eigen::Index n = d.u.cols();
    if (n < 1) detail::throw_invalid(where, "need >= 1 mode (columns of u)", n);
    const auto check = [&](const typename NodalModes::Matrix& m, const char* name) {
      if (m.rows() != nodes || m.cols() != n)
        detail::throw_invalid(where,
                              std::string(name) + " must be " + std::to_string(nodes) + " x " +
                                  std::to_string(n) + " (nodes x modes), rows",
                              m.rows());
      if (!m.allFinite())
        detail::throw_invalid(where, std::string(name) + " must be finite (member)", d.member);
    };
    check(d.u, "u");
    check(d.w, "w");
    check(d.theta, "theta");
    if (Modes != Eigen::Dynamic && n != Modes)
      detail::throw_invalid(where,
                            "the number of modes must equal the fixed Modes = " +
                                std::to_string(Modes) + " (use ModalBasis::truncated)",
                            n);
    using std::abs;
    const Scalar norm2 = d.cos * d.cos + d.sin * d.sin;
    if (!(abs(norm2 - Scalar(1)) <= Scalar(100) * std::numeric_limits<Scalar>::epsilon()))
      detail::throw_invalid(where, "(cos, sin) must be a unit vector, cos^2 + sin^2", norm2);
    if (d.free_dofs.size() != 0) {
      if (d.free_dofs.size() != 3 * nodes)
        detail::throw_invalid(where, "free_dofs must be empty or have 3 entries per node, size",
                              d.free_dofs.size());
      if (d.free_dofs.minCoeff() < -1 || d.free_dofs.maxCoeff() >= d.num_free)
        detail::throw_invalid(where, "free_dofs must lie in [-1, num_free), num_free", d.num_free);
    }
  }

  /// eps itself when on the member, otherwise as the end policy says (cold path).
  Scalar admit(Scalar eps, const char* where) const {
    if (eps >= Scalar(0) && eps <= length()) return eps;
    return admit_off_member(eps, where);
  }

  Scalar admit_off_member(Scalar eps, const char* where) const {
    using std::isfinite;
    if (!isfinite(eps))
      throw std::invalid_argument(std::string(where) + ": eps = " + detail::format_shortest(eps) +
                                  " is not finite (member " + std::to_string(member_) + ")");
    switch (policy_) {
      case EndPolicy::Clamp: return eps < Scalar(0) ? Scalar(0) : length();
      case EndPolicy::Extrapolate: return eps;
      case EndPolicy::Throw: break;
    }
    throw std::invalid_argument(std::string(where) + ": eps = " + detail::format_shortest(eps) +
                                " is off member " + std::to_string(member_) +
                                " (valid range [0, " + detail::format_shortest(length()) + "])");
  }

  bool in_element(Eigen::Index e, Scalar x) const noexcept {
    return (e == 0 || stations_(e) <= x) && (e + 1 == num_elements() || x < stations_(e + 1));
  }

  /// Element holding x: the hint or a neighbour when they hold it, else std::upper_bound on the
  /// interior stations.
  Eigen::Index find_element(Scalar x, Eigen::Index hint) const noexcept {
    const Eigen::Index ne = num_elements();
    if (hint >= 0 && hint < ne) {
      if (in_element(hint, x)) return hint;
      if (hint + 1 < ne && in_element(hint + 1, x)) return hint + 1;
      if (hint > 0 && in_element(hint - 1, x)) return hint - 1;
    }
    const Scalar* first = stations_.data() + 1;
    return static_cast<Eigen::Index>(std::upper_bound(first, first + (ne - 1), x) - first);
  }

  ElementShapeFunctions<Scalar> shape_functions(Eigen::Index e, Scalar x) const noexcept {
    const Scalar le = element_lengths_(e);
    return ElementShapeFunctions<Scalar>((x - stations_(e)) / le, le);
  }

  /// Local consistent load (u1, w1, theta1, u2, w2, theta2) of a point load at x in element e.
  Eigen::Matrix<Scalar, 6, 1> local_load(Eigen::Index e, Scalar x, Scalar axial,
                                         Scalar transverse, Scalar moment) const noexcept {
    const ElementShapeFunctions<Scalar> f = shape_functions(e, x);
    Eigen::Matrix<Scalar, 6, 1> load;
    load << f.u1 * axial, f.w1 * transverse + f.dw1 * moment, f.t1 * transverse + f.dt1 * moment,
        f.u2 * axial, f.w2 * transverse + f.dw2 * moment, f.t2 * transverse + f.dt2 * moment;
    return load;
  }

  /// One pass over the element's n x 6 nodal block: the five rows psi_u, psi_u', psi_w, psi_w',
  /// psi_w'' of every mode from its six local nodal values (eqs 4-7 and 10). A fused loop: five
  /// separate column expressions cost several times more for the few modes of a reduced model.
  void evaluate_unchecked(Eigen::Index e, Scalar x, Values& out) const {
    const ElementShapeFunctions<Scalar> f = shape_functions(e, x);
    const auto B = element_block(e);
    const Eigen::Index n = num_modes();
    out.resize(n);
    for (Eigen::Index j = 0; j < n; ++j) {
      const Scalar u1 = B(j, 0), w1 = B(j, 1), t1 = B(j, 2), u2 = B(j, 3), w2 = B(j, 4), t2 = B(j, 5);
      out.psi_u(j) = f.u1 * u1 + f.u2 * u2;
      out.dpsi_u(j) = f.du * (u2 - u1);
      out.psi_w(j) = f.w1 * w1 + f.t1 * t1 + f.w2 * w2 + f.t2 * t2;
      out.dpsi_w(j) = f.dw1 * w1 + f.dt1 * t1 + f.dw2 * w2 + f.dt2 * t2;
      out.ddpsi_w(j) = f.ddw1 * w1 + f.ddt1 * t1 + f.ddw2 * w2 + f.ddt2 * t2;
    }
  }

  MemberId member_;
  EndPolicy policy_;
  Scalar cos_, sin_;
  typename NodalModes::IndexVector free_dofs_;
  Eigen::Index num_free_;
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> stations_;
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> element_lengths_;
  NodalMatrix nodal_;  ///< n x 3 (nodes): per node the columns u, w, theta over the modes
};

}  // namespace stickslip
