#pragma once
/// \file ids.hpp
/// \brief Distinct identifier types for the nodes and the members of a FrameModel.
///
/// Both convert implicitly to and from Eigen::Index, so ids can be stored, compared, printed and
/// used as indices like plain integers, and a literal index (`PointLoad::harmonic(0, ...)`) still
/// names a member. What they do not do is convert into each other: that would take two
/// user-defined conversions (NodeId -> Index -> MemberId), which C++ never applies implicitly.
/// So a node id passed where a member is expected (or the reverse) does not compile:
///
///     auto root = frame.add_node(0, 0), tip = frame.add_node(0, 0.2);
///     auto blade = frame.add_member(root, tip, section, 20);
///     PointDamper<double> d(root, ...);   // error: NodeId is not a MemberId
///     frame.clamp(blade);                  // error: MemberId is not a NodeId

#include <Eigen/Core>

namespace stickslip {

namespace detail {
/// An Eigen::Index with a tag, convertible to and from Eigen::Index but not to another tag.
template <class Tag>
struct TaggedIndex {
  Eigen::Index value = 0;
  constexpr TaggedIndex() noexcept = default;
  constexpr TaggedIndex(Eigen::Index v) noexcept : value(v) {}  // implicit by design (see file)
  constexpr operator Eigen::Index() const noexcept { return value; }
};
struct NodeTag {};
struct MemberTag {};
}  // namespace detail

/// Identifier of a node of a FrameModel, as returned by FrameModel::add_node.
using NodeId = detail::TaggedIndex<detail::NodeTag>;
/// Identifier of a member of a FrameModel, as returned by FrameModel::add_member.
using MemberId = detail::TaggedIndex<detail::MemberTag>;

}  // namespace stickslip
