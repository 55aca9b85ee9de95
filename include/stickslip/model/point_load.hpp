#pragma once
/// \file point_load.hpp
/// \brief External point loads on a member: harmonic or a user function of time.

#include "stickslip/beam/ids.hpp"
#include "stickslip/detail/validate.hpp"
#include "stickslip/model/detail/enum_checks.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

namespace stickslip {

/// Direction of a point load.
enum class LoadDirection {
  GlobalX,     ///< force along global X
  GlobalY,     ///< force along global Y
  Axial,       ///< force along the member's local u axis
  Transverse,  ///< force along the member's local w axis
  Moment       ///< moment about Z
};

/// A point load F(t) at coordinate `coordinate` of member `member` (the paper's F psi_w1(Y0)).
/// F(t) = amplitude sin(omega t + phase) + offset, unless `time_function` is set, which then
/// gives F(t) itself.
template <class Scalar>
struct PointLoad {
  MemberId member = 0;  ///< member the load acts on
  Scalar coordinate{};  ///< position along the member [m]
  /// Direction of the force (or Moment: a moment about Z [N m]); default GlobalX.
  LoadDirection direction = LoadDirection::GlobalX;
  Scalar amplitude{};   ///< [N] or [N m]
  Scalar omega{};       ///< [rad/s]
  Scalar phase{};       ///< [rad]
  Scalar offset{};      ///< constant part [N]
  std::function<Scalar(Scalar)> time_function;  ///< optional F(t)

  /// Value of F at time t.
  Scalar value(Scalar t) const {
    using std::sin;
    if (time_function) return time_function(t);
    return amplitude * sin(omega * t + phase) + offset;
  }

  /// Harmonic load F(t) = amplitude sin(omega t + phase).
  static PointLoad harmonic(MemberId member, Scalar coordinate, LoadDirection direction,
                            Scalar amplitude, Scalar omega, Scalar phase = Scalar(0)) {
    PointLoad p;
    p.member = member;
    p.coordinate = coordinate;
    p.direction = direction;
    p.amplitude = amplitude;
    p.omega = omega;
    p.phase = phase;
    return p;
  }

  /// Throws std::invalid_argument naming the load and the parameter.
  void validate(Eigen::Index index) const {
    const std::string where = "PointLoad[" + std::to_string(index) + "]";
    detail::require_finite(where, "coordinate", coordinate);
    detail::require_enumerator(where, "direction", "LoadDirection", direction, LoadDirection::Moment);
    detail::require_finite(where, "amplitude", amplitude);
    detail::require_finite(where, "omega", omega);
    detail::require_finite(where, "phase", phase);
    detail::require_finite(where, "offset", offset);
  }
};

/// The modal row of a point load in `direction` from a member's shape values at the point
/// (MemberShapes::Values: psi_u, psi_w, dpsi_w) and the member's direction cosine and sine:
/// Axial psi_u, Transverse psi_w, Moment psi_w', GlobalX c psi_u - s psi_w, GlobalY
/// s psi_u + c psi_w.
template <class Values, class Scalar>
auto load_direction_row(const Values& v, Scalar c, Scalar s, LoadDirection direction)
    -> std::decay_t<decltype(v.psi_u)> {
  switch (direction) {
    case LoadDirection::Axial: return v.psi_u;
    case LoadDirection::Transverse: return v.psi_w;
    case LoadDirection::Moment: return v.dpsi_w;
    case LoadDirection::GlobalX: return c * v.psi_u - s * v.psi_w;
    case LoadDirection::GlobalY: return s * v.psi_u + c * v.psi_w;
  }
  detail::throw_invalid("PointLoad", "direction must be a LoadDirection enumerator", static_cast<int>(direction));
}

namespace detail {
/// The distinct |omega| of the harmonic loads without a time function, appended to `omega` in
/// order of first appearance (the frequencies of a linear part's b_m(t), linear_part.hpp).
template <class Scalar>
void add_load_frequencies(const std::vector<PointLoad<Scalar>>& loads, std::vector<Scalar>& omega) {
  using std::abs;
  for (const PointLoad<Scalar>& l : loads)
    if (!l.time_function && l.omega != Scalar(0) &&
        std::find(omega.begin(), omega.end(), abs(l.omega)) == omega.end())
      omega.push_back(abs(l.omega));
}
}  // namespace detail

}  // namespace stickslip
