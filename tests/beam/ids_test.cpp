// NodeId and MemberId: a node id passed where a member is expected, or the
// reverse, must not compile, while ids keep working as plain indices. The compile-time half is a
// set of static_asserts on the library's own signatures (they fail to compile if the types merge
// again); the run-time half checks that ids round-trip through the frame unchanged.

#include "beam/beam_test_support.hpp"

#include <stickslip/beam.hpp>
#include <stickslip/modal/modal_basis.hpp>
#include <stickslip/model/point_damper.hpp>
#include <stickslip/model/point_load.hpp>
#include <stickslip/moving_load/member_shapes.hpp>

#include <gtest/gtest.h>

#include <type_traits>

namespace ids_test {

using namespace stickslip;
using Frame = FrameModel<double>;
using Section = SectionProperties<double>;
using Damper = PointDamper<double, CoulombLaw<double>>;

// The two id types never convert into each other ...
static_assert(!std::is_convertible_v<NodeId, MemberId>, "a NodeId must not convert to a MemberId");
static_assert(!std::is_convertible_v<MemberId, NodeId>, "a MemberId must not convert to a NodeId");
// ... but both to and from a plain index (literal ids, storage, comparisons).
static_assert(std::is_convertible_v<Eigen::Index, NodeId> && std::is_convertible_v<NodeId, Eigen::Index>);
static_assert(std::is_convertible_v<Eigen::Index, MemberId> && std::is_convertible_v<MemberId, Eigen::Index>);

// The frame's own functions: nodes where nodes are expected, members where members are.
static_assert(std::is_same_v<decltype(std::declval<Frame&>().add_node(0.0, 0.0)), NodeId>);
static_assert(std::is_same_v<decltype(std::declval<Frame&>().add_member(NodeId{}, NodeId{}, std::declval<const Section&>(), Eigen::Index{1})), MemberId>);
static_assert(std::is_invocable_v<decltype(&Frame::clamp), Frame&, NodeId>);
static_assert(!std::is_invocable_v<decltype(&Frame::clamp), Frame&, MemberId>, "clamp(member) must not compile");
static_assert(!std::is_invocable_v<decltype(&Frame::add_point_mass), Frame&, MemberId, double>);
static_assert(std::is_invocable_v<decltype(&Frame::member), const Frame&, MemberId>);
static_assert(!std::is_invocable_v<decltype(&Frame::member), const Frame&, NodeId>, "member(node) must not compile");

// The components that take a member: a damper, a load, the member shapes.
static_assert(std::is_constructible_v<Damper, MemberId, double, double, double, double, CoulombLaw<double>>);
static_assert(!std::is_constructible_v<Damper, NodeId, double, double, double, double, CoulombLaw<double>>,
              "PointDamper(node, ...) must not compile");
static_assert(!std::is_invocable_v<decltype(&PointLoad<double>::harmonic), NodeId, double, LoadDirection,
                                   double, double, double>, "PointLoad::harmonic(node, ...) must not compile");
static_assert(!std::is_constructible_v<MemberShapes<double>, const Frame&, NodeId, const ModalBasis<double>&>,
              "MemberShapes(model, node, basis) must not compile");
static_assert(!std::is_invocable_v<decltype(&ModalBasis<double>::nodal), const ModalBasis<double>&, MemberId, Dof>,
              "ModalBasis::nodal(member, dof) must not compile");

TEST(Ids, RoundTripThroughTheFrameAsPlainIndices) {
  Frame frame;
  const auto a = frame.add_node(0, 0), b = frame.add_node(0, 0.2), c = frame.add_node(0.04, 0.2);
  EXPECT_EQ(Eigen::Index(a), 0);
  EXPECT_EQ(Eigen::Index(c), 2);
  const Section steel{2.06e11, 7800, 6e-5, 2e-11};
  const auto m0 = frame.add_member(a, b, steel, 2);
  const auto m1 = frame.add_member(b, c, steel, 2);
  EXPECT_EQ(Eigen::Index(m0), 0);
  EXPECT_EQ(Eigen::Index(m1), 1);
  // A member's node chain starts and ends at the nodes it was given.
  EXPECT_EQ(frame.member(m1).nodes.front(), Eigen::Index(b));
  EXPECT_EQ(frame.member(m1).nodes.back(), Eigen::Index(c));
  // A literal index still names a member (0 is the blade).
  EXPECT_DOUBLE_EQ(frame.member(0).length, frame.member(m0).length);
  frame.clamp(a);
  EXPECT_TRUE(frame.is_constrained(a, Dof::Rz));
  EXPECT_FALSE(frame.is_constrained(c, Dof::X));
}

}  // namespace ids_test
