#pragma once
/// \file frame_member.hpp
/// \brief A straight member of a plane frame: its chain of nodes and the stations of those nodes.

#include "stickslip/beam/frame_element.hpp"
#include "stickslip/beam/section_properties.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace stickslip {

/// A straight member from node a = nodes.front() to node b = nodes.back(), discretised into
/// nodes.size() - 1 elements. The local coordinate eps (paper eqs. 4-7) runs from 0 at node a to
/// `length` at node b; node nodes[i] sits at eps = stations[i].
template <class Scalar_>
struct FrameMember {
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;
  /// Index type (Eigen's).
  using Index = Eigen::Index;

  std::vector<Index> nodes;      ///< node chain a, interior..., b (size num_elements() + 1)
  std::vector<Scalar> stations;  ///< ascending local coordinates of `nodes`, 0 ... length [m]
  Scalar length{};               ///< member length [m]
  Scalar cos{};                  ///< direction cosine of the axis (a -> b) with global X
  Scalar sin{};                  ///< direction cosine of the axis (a -> b) with global Y
  /// Material and section of every element of the member.
  SectionProperties<Scalar> section{};

  /// Number of elements: nodes.size() - 1.
  Index num_elements() const noexcept { return static_cast<Index>(nodes.size()) - 1; }

  /// Element e, between nodes[e] and nodes[e + 1] (0 <= e < num_elements(), asserted).
  FrameElement<Scalar> element(Index e) const {
    STICKSLIP_ASSERT(e >= 0 && e < num_elements());
    const auto i = static_cast<std::size_t>(e);
    return FrameElement<Scalar>(stations[i + 1] - stations[i], cos, sin, section);
  }
};

}  // namespace stickslip
