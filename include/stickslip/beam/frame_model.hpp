#pragma once
/// \file frame_model.hpp
/// \brief A plane frame of rigidly joined Euler-Bernoulli members: nodes, members, supports,
/// point masses and springs, and the assembly of K and M.

#include "stickslip/beam/assembled_frame.hpp"
#include "stickslip/beam/dof.hpp"
#include "stickslip/beam/dof_map.hpp"
#include "stickslip/beam/frame_element.hpp"
#include "stickslip/beam/frame_member.hpp"
#include "stickslip/beam/ids.hpp"
#include "stickslip/beam/mass_type.hpp"
#include "stickslip/beam/section_properties.hpp"
#include "stickslip/detail/validate.hpp"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace stickslip {

namespace detail {
/// Process-unique, never-repeating model identifiers (0 is never issued).
inline std::uint64_t next_model_id() noexcept {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}
}  // namespace detail

/// A plane frame (paper Fig. 3: the blade and the platform as two rigidly connected beams).
///
/// Nodes carry 3 DOFs (X, Y, Rz); node i owns global DOFs 3i..3i+2. Members sharing a node are
/// rigidly joined (all three DOFs shared). Every mutation gives the model a fresh id(), so a
/// ModalBasis (which stores the id at assembly) can be checked against the model it came from;
/// copies keep the id of their source until changed.
template <class Scalar_>
class FrameModel {
 public:
  /// Floating-point type (template parameter).
  using Scalar = Scalar_;
  /// Index type (Eigen's).
  using Index = Eigen::Index;
  /// A position (X, Y) [m] in the frame's plane.
  using Vector2 = Eigen::Matrix<Scalar, 2, 1>;
  /// Material and section of a member.
  using Section = SectionProperties<Scalar>;
  /// A member with its node chain and stations.
  using Member = FrameMember<Scalar>;

  /// Relative tolerance (of the model's bounding-box diagonal) below which two user nodes are
  /// coincident, and of the member length for the end stations of explicit meshes.
  static constexpr double coincidence_tolerance = 1e-9;
  /// Most nodes a model may hold (user and interior nodes): 3 * max_nodes DOFs keep the sparse
  /// matrices' int indices and their ~36 nonzeros per element far from overflow, and a model at
  /// the limit assembles in a few GB.
  static constexpr Index max_nodes = Index(1) << 22;
  /// Most elements one member may be divided into (add_member's `elements`, stations.size() - 1).
  static constexpr Index max_elements_per_member = Index(1) << 20;

  FrameModel() = default;

  /// Add a node at (x, y) [m]; returns its id.
  /// \throws std::invalid_argument for non-finite coordinates, or when the node lies within
  ///         coincidence_tolerance * (bounding-box diagonal) of an existing node (the message
  ///         names that node). Cost O(num_nodes()).
  NodeId add_node(Scalar x, Scalar y) {
    static const char* where = "FrameModel::add_node";
    detail::require_finite(where, "x", x);
    detail::require_finite(where, "y", y);
    const Vector2 p(x, y);
    Vector2 lo = p, hi = p;
    for (const Vector2& q : positions_) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    // stableNorm: coordinates beyond ~1e154 m would overflow a plain norm to inf (every node then
    // "coincides"), those below ~1e-154 m underflow it.
    const Scalar tol = Scalar(coincidence_tolerance) * (hi - lo).stableNorm();
    for (std::size_t n = 0; n < positions_.size(); ++n) {
      if ((positions_[n] - p).stableNorm() <= tol)
        throw std::invalid_argument(std::string(where) + ": node at (" + detail::format_value(x) +
                                    ", " + detail::format_value(y) + ") coincides with node " +
                                    std::to_string(n) + " (relative tolerance " +
                                    detail::format_value(coincidence_tolerance) +
                                    " of the model size)");
    }
    return push_node(p);
  }

  /// Add a member from node_a to node_b discretised into `elements` equal elements (creates
  /// elements - 1 interior nodes); returns the member id.
  /// \throws std::invalid_argument for a missing node, node_a == node_b, elements outside
  ///         [1, max_elements_per_member], more than max_nodes nodes in all, or an invalid section
  MemberId add_member(NodeId node_a, NodeId node_b, const Section& section, Index elements) {
    static const char* where = "FrameModel::add_member";
    check_element_count(where, "elements", elements);
    const Scalar length = checked_length(where, node_a, node_b, section);
    std::vector<Scalar> stations(static_cast<std::size_t>(elements) + 1);
    for (Index e = 0; e <= elements; ++e)
      stations[static_cast<std::size_t>(e)] = length * Scalar(e) / Scalar(elements);
    stations.back() = length;
    return push_member(node_a, node_b, section, length, std::move(stations));
  }

  /// Add a member with an explicit (e.g. graded) mesh: `stations` are the ascending local
  /// coordinates [m] of the node chain, stations.front() = 0 and stations.back() = member
  /// length (each within coincidence_tolerance * length; they are then set exactly).
  /// \throws std::invalid_argument for a missing node, node_a == node_b, fewer than two stations,
  ///         non-ascending or non-finite stations, wrong end stations, more than
  ///         max_elements_per_member elements or max_nodes nodes, or an invalid section
  MemberId add_member(NodeId node_a, NodeId node_b, const Section& section, std::vector<Scalar> stations) {
    static const char* where = "FrameModel::add_member";
    const Scalar length = checked_length(where, node_a, node_b, section);
    if (stations.size() < 2) detail::throw_invalid(where, "stations.size() must be >= 2", stations.size());
    check_element_count(where, "stations.size() - 1", static_cast<Index>(stations.size()) - 1);
    using std::abs;
    const Scalar tol = Scalar(coincidence_tolerance) * length;
    if (!(abs(stations.front()) <= tol))
      detail::throw_invalid(where, "stations.front() must be 0", stations.front());
    if (!(abs(stations.back() - length) <= tol))
      detail::throw_invalid(where, "stations.back() must equal the member length " +
                                       detail::format_value(length), stations.back());
    stations.front() = Scalar(0);
    stations.back() = length;
    for (std::size_t i = 1; i < stations.size(); ++i) {
      if (!(stations[i] > stations[i - 1]))
        detail::throw_invalid(where, "stations must be finite and strictly ascending; stations[" +
                                         std::to_string(i) + "]", stations[i]);
    }
    return push_member(node_a, node_b, section, length, std::move(stations));
  }

  /// Fix all three DOFs of a node (clamped support). \throws std::invalid_argument if missing
  void clamp(NodeId node) {
    check_node("FrameModel::clamp", "node", node);
    for (Dof d : {Dof::X, Dof::Y, Dof::Rz}) constrain(node, d);
  }

  /// Fix X and Y of a node (pinned support). \throws std::invalid_argument if missing
  void pin(NodeId node) {
    check_node("FrameModel::pin", "node", node);
    constrain(node, Dof::X);
    constrain(node, Dof::Y);
  }

  /// Fix one DOF of a node (e.g. a roller). \throws std::invalid_argument if missing
  void fix(NodeId node, Dof dof) {
    check_node("FrameModel::fix", "node", node);
    constrain(node, dof);
  }

  /// Add a point mass m [kg] on the X and Y DOFs of a node (accumulates).
  /// \throws std::invalid_argument for a missing node, m non-finite or < 0, or a sum that
  ///         overflows
  void add_point_mass(NodeId node, Scalar m) {
    static const char* where = "FrameModel::add_point_mass";
    check_node(where, "node", node);
    detail::require_non_negative(where, "m", m);
    accumulate(where, "m", node, nodal_mass_, {Dof::X, Dof::Y}, m);
  }

  /// Add a rotary inertia J [kg m^2] on the Rz DOF of a node (accumulates).
  /// \throws std::invalid_argument for a missing node, J non-finite or < 0, or a sum that overflows
  void add_rotary_inertia(NodeId node, Scalar J) {
    static const char* where = "FrameModel::add_rotary_inertia";
    check_node(where, "node", node);
    detail::require_non_negative(where, "J", J);
    accumulate(where, "J", node, nodal_mass_, {Dof::Rz}, J);
  }

  /// Add a grounded spring k [N/m, or N m/rad for Rz] on one DOF of a node (accumulates).
  /// \throws std::invalid_argument for a missing node, k non-finite or < 0, or a sum that overflows
  void add_spring(NodeId node, Dof dof, Scalar k) {
    static const char* where = "FrameModel::add_spring";
    check_node(where, "node", node);
    detail::require_non_negative(where, "k", k);
    accumulate(where, "k", node, nodal_spring_, {dof}, k);
  }

  /// Member `id`. \throws std::invalid_argument when out of range
  const Member& member(MemberId id) const {
    if (id < 0 || id >= num_members())
      throw std::invalid_argument("FrameModel::member: id = " + std::to_string(id) +
                                  " does not exist (model has " + std::to_string(num_members()) +
                                  " members)");
    return members_[idx(id)];
  }

  /// Number of members added.
  Index num_members() const noexcept { return static_cast<Index>(members_.size()); }
  /// Number of nodes: user nodes and the interior nodes of the member meshes.
  Index num_nodes() const noexcept { return static_cast<Index>(positions_.size()); }
  /// Total number of elements over all members.
  Index num_elements() const noexcept { return num_elements_; }

  /// Position (X, Y) [m] of a node. \throws std::invalid_argument when missing
  Vector2 node_position(NodeId node) const {
    check_node("FrameModel::node_position", "node", node);
    return positions_[idx(node)];
  }

  /// True when the nodal DOF is constrained. \throws std::invalid_argument when missing
  bool is_constrained(NodeId node, Dof dof) const {
    check_node("FrameModel::is_constrained", "node", node);
    return constrained_[idx(global_dof(node, dof))];
  }

  /// Identifier of this model's current content (changes with every mutation, unique in the
  /// process); copied into AssembledFrame::model_id and ModalBasis::model_id().
  std::uint64_t id() const noexcept { return id_; }

  /// Largest ratio (longest member of the model) / (element length) that assemble() accepts for
  /// an element of a locally refined mesh (shorter than half its member's longest element) with
  /// no clamped end node: (tau / (6 eps))^(1/3), about 908 for double (tau = 1e-6, the relative
  /// accuracy of omega kept; sqrt(eps) for types too coarse for 1e-6). Derivation: every entry of
  /// the assembled K carries a relative round-off of ~eps, so an element of length h adds an
  /// absolute error ~eps 12 EI / h^3 to the stiffness of any motion of its nodes (its rigid
  /// motions are no longer exact null vectors); against the bending stiffness ~3 EI / L^3 that a
  /// lowest mode of a member of length L shows, lambda = omega^2 is off by up to ~4 eps (L / h)^3
  /// relative. Measured on a clamped 0.2 m cantilever with a short element at its free end:
  /// 0.7 eps (L / h)^3 to 3.3 eps (L / h)^3 for L / h = 2e3 and 2e4 (L / h = 1.6e4 gave omega_1
  /// wrong by 9e-4, a short element in mid-span at L / h = 2e5 1e-2, every check passing: no
  /// solver recovers what the assembly rounded away); the limit keeps 12 eps (L / h)^3, a factor
  /// 4 to 17 above those, below 2 tau. An element with a clamped end node is exempt: its stiffness then
  /// supports the other node, which the modes hardly move. Uniform meshes are exempt too: the same
  /// round-off bounds their accuracy (docs/modal.md, "Accuracy limit"), which a member of more
  /// than ~900 elements reaches.
  static Scalar max_element_length_ratio() {
    using std::cbrt;
    using std::sqrt;
    const Scalar eps = std::numeric_limits<Scalar>::epsilon();
    const Scalar tau = std::max(Scalar(1e-6), sqrt(eps));
    return cbrt(tau / (Scalar(6) * eps));
  }

  /// Assemble K and M over the free DOFs (constrained DOFs eliminated), element matrices from
  /// FrameElement::global_stiffness / global_mass(type), plus point masses, rotary inertias and
  /// springs on the diagonal. Cost O(num_elements()).
  /// \throws std::invalid_argument when there are no free DOFs, an element matrix overflows (the
  ///         message names the member, the element and EA/L, EI/L^3, rho A L), a sum of entries
  ///         of K or M overflows (names the DOF), or a free DOF has no mass (a node not attached
  ///         to any member and carrying no point mass / rotary inertia), or an element of a
  ///         locally refined mesh without a clamped end node is more than
  ///         max_element_length_ratio() times shorter than the longest member (names the member,
  ///         the element, both lengths and the ratio: its round-off would make the lowest
  ///         frequencies wrong)
  AssembledFrame<Scalar> assemble(MassType type = MassType::Consistent) const {
    static const char* where = "FrameModel::assemble";
    AssembledFrame<Scalar> out;
    out.dofs = DofMap(constrained_);
    out.model_id = id_;
    out.mass_type = type;
    const Index n = out.dofs.num_free();
    if (n == 0)
      throw std::invalid_argument(std::string(where) + ": the model has no free DOFs (" +
                                  std::to_string(num_nodes()) + " nodes, all DOFs constrained)");
    check_short_elements(where);

    using Triplet = Eigen::Triplet<Scalar, typename AssembledFrame<Scalar>::SparseMatrix::StorageIndex>;
    using StorageIndex = typename AssembledFrame<Scalar>::SparseMatrix::StorageIndex;
    std::vector<Triplet> k_triplets, m_triplets;
    k_triplets.reserve(static_cast<std::size_t>(36 * num_elements_ + 3 * num_nodes()));
    m_triplets.reserve(static_cast<std::size_t>((type == MassType::Consistent ? 36 : 6) * num_elements_ +
                                                3 * num_nodes()));
    std::array<Index, 6> map{};
    for (const Member& member : members_) {
      for (Index e = 0; e < member.num_elements(); ++e) {
        const auto a = member.nodes[idx(e)], b = member.nodes[idx(e + 1)];
        for (Index j = 0; j < 3; ++j) {
          map[idx(j)] = out.dofs.free_index(a, static_cast<Dof>(j));
          map[idx(j + 3)] = out.dofs.free_index(b, static_cast<Dof>(j));
        }
        const FrameElement<Scalar> element = member.element(e);
        const auto k = element.global_stiffness();
        const auto m = element.global_mass(type);
        if (!detail::all_finite(k) || !detail::all_finite(m))
          throw_element_overflow(where, static_cast<Index>(&member - members_.data()), e, element);
        for (Index c = 0; c < 6; ++c) {
          const Index fc = map[idx(c)];
          if (fc < 0) continue;
          for (Index r = 0; r < 6; ++r) {
            const Index fr = map[idx(r)];
            if (fr < 0) continue;
            const auto sr = static_cast<StorageIndex>(fr), sc = static_cast<StorageIndex>(fc);
            k_triplets.emplace_back(sr, sc, k(r, c));
            if (type == MassType::Consistent || r == c) m_triplets.emplace_back(sr, sc, m(r, c));
          }
        }
      }
    }
    for (Index i = 0; i < n; ++i) {
      const Index g = out.dofs.global_index(i);
      const auto si = static_cast<StorageIndex>(i);
      if (nodal_spring_[idx(g)] != Scalar(0)) k_triplets.emplace_back(si, si, nodal_spring_[idx(g)]);
      if (nodal_mass_[idx(g)] != Scalar(0)) m_triplets.emplace_back(si, si, nodal_mass_[idx(g)]);
    }
    out.stiffness.resize(n, n);
    out.mass.resize(n, n);
    out.stiffness.setFromTriplets(k_triplets.begin(), k_triplets.end());
    out.mass.setFromTriplets(m_triplets.begin(), m_triplets.end());
    out.stiffness.makeCompressed();
    out.mass.makeCompressed();
    require_finite_sum(where, "K", out.stiffness, out.dofs);
    require_finite_sum(where, "M", out.mass, out.dofs);

    const Eigen::Matrix<Scalar, Eigen::Dynamic, 1> diag = out.mass.diagonal();
    for (Index i = 0; i < n; ++i) {
      if (!(diag(i) > Scalar(0))) {
        const auto nd = out.dofs.node_dof(i);
        throw std::invalid_argument(std::string(where) + ": DOF " + to_string(nd.second) +
                                    " of node " + std::to_string(nd.first) +
                                    " is free but has no mass (node not attached to a member "
                                    "and without point mass / rotary inertia; constrain it)");
      }
    }
    out.num_rigid_body_modes = count_rigid_body_modes();
    return out;
  }

  /// Number of rigid-body (zero-stiffness) modes: for each set of nodes connected by members,
  /// 3 - rank of the supports (constrained DOFs and springs) acting on the three rigid motions
  /// (X and Y translation, rotation) of that set. Cost O(num_nodes()).
  Index count_rigid_body_modes() const {
    // Connected components by union-find over the member node chains.
    const std::size_t nn = positions_.size();
    std::vector<std::size_t> parent(nn);
    for (std::size_t i = 0; i < nn; ++i) parent[i] = i;
    const auto find = [&parent](std::size_t i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    for (const Member& m : members_)
      for (Index node : m.nodes) parent[find(idx(node))] = find(idx(m.nodes.front()));
    // Per component: a reference point and size, then the Gram matrix of the support rows
    // (rigid motion X = a - c y, Y = b + c x, Rz = c in coordinates scaled by the size).
    std::vector<Vector2> lo(nn, Vector2::Constant(std::numeric_limits<Scalar>::max()));
    std::vector<Vector2> hi(nn, Vector2::Constant(std::numeric_limits<Scalar>::lowest()));
    for (std::size_t i = 0; i < nn; ++i) {
      const std::size_t r = find(i);
      lo[r] = lo[r].cwiseMin(positions_[i]);
      hi[r] = hi[r].cwiseMax(positions_[i]);
    }
    using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;
    std::vector<Matrix3> gram(nn, Matrix3::Zero());
    for (std::size_t i = 0; i < nn; ++i) {
      const std::size_t r = find(i);
      const Scalar size = (hi[r] - lo[r]).norm();
      const Vector2 p = size > Scalar(0) ? Vector2((positions_[i] - lo[r]) / size) : Vector2::Zero();
      for (Index d = 0; d < 3; ++d) {
        const std::size_t g = idx(global_dof(static_cast<Index>(i), static_cast<Dof>(d)));
        if (!constrained_[g] && !(nodal_spring_[g] > Scalar(0))) continue;
        Eigen::Matrix<Scalar, 3, 1> row;
        if (d == 0) row << 1, 0, -p.y();
        else if (d == 1) row << 0, 1, p.x();
        else row << 0, 0, 1;
        gram[r] += row * row.transpose();
      }
    }
    Index rigid = 0;
    for (std::size_t i = 0; i < nn; ++i) {
      if (find(i) != i) continue;
      const Eigen::SelfAdjointEigenSolver<Matrix3> es(gram[i], Eigen::EigenvaluesOnly);
      const Scalar tol = Scalar(1e-10) * std::max(es.eigenvalues().maxCoeff(), Scalar(1));
      for (Index k = 0; k < 3; ++k)
        if (es.eigenvalues()(k) <= tol) ++rigid;
    }
    return rigid;
  }

 private:
  static std::size_t idx(Index i) noexcept { return static_cast<std::size_t>(i); }

  void touch() noexcept { id_ = detail::next_model_id(); }

  // values[dof of node] += v for each dof, all or nothing: a sum that overflows throws, naming it.
  void accumulate(const char* where, const char* name, Index node, std::vector<Scalar>& values,
                  std::initializer_list<Dof> dofs, Scalar v) {
    for (Dof d : dofs) {
      const Scalar sum = values[idx(global_dof(node, d))] + v;
      if (!detail::is_finite(sum))
        detail::throw_invalid(where, std::string(name) + ": the sum on DOF " + to_string(d) + " of node " +
                                         std::to_string(node) + " overflows (" +
                                         detail::format_value(values[idx(global_dof(node, d))]) + " + " +
                                         detail::format_value(v) + ")",
                              sum);
    }
    for (Dof d : dofs) values[idx(global_dof(node, d))] += v;
    touch();
  }

  void check_element_count(const char* where, const char* name, Index elements) const {
    if (elements < 1 || elements > max_elements_per_member)
      detail::throw_invalid(where, std::string(name) + " must be in [1, max_elements_per_member = " +
                                       std::to_string(max_elements_per_member) + "]",
                            elements);
    if (elements - 1 > max_nodes - num_nodes())
      detail::throw_invalid(where, std::string(name) + " would create " + std::to_string(elements - 1) +
                                       " interior nodes beside the model's " + std::to_string(num_nodes()) +
                                       ", above max_nodes = " + std::to_string(max_nodes),
                            elements);
  }

  [[noreturn]] static void throw_element_overflow(const char* where, Index member, Index e,
                                                  const FrameElement<Scalar>& element) {
    const Scalar L = element.length();
    const Section& s = element.section();
    throw std::invalid_argument(
        std::string(where) + ": member " + std::to_string(member) + ", element " + std::to_string(e) +
        " (length " + detail::format_value(L) + " m): its stiffness or mass matrix is not finite "
        "(EA/L = " + detail::format_value(s.axial_rigidity() / L) +
        ", EI/L^3 = " + detail::format_value(s.bending_rigidity() / (L * L * L)) +
        ", rho A L = " + detail::format_value(s.mass_per_length() * L) +
        ", rho A L^3 = " + detail::format_value(s.mass_per_length() * L * L * L) +
        "): the element is too short or too long for its section");
  }

  // Refuses a locally refined element whose stiffness round-off would swamp the lowest modes (see
  // max_element_length_ratio()), unless one of its end nodes is clamped.
  void check_short_elements(const char* where) const {
    const Scalar limit = max_element_length_ratio();
    Scalar reference(0);
    for (const Member& member : members_) reference = std::max(reference, member.length);
    const auto clamped = [this](Index node) {
      for (Index d = 0; d < 3; ++d)
        if (!constrained_[idx(global_dof(node, static_cast<Dof>(d)))]) return false;
      return true;
    };
    for (std::size_t m = 0; m < members_.size(); ++m) {
      const Member& member = members_[m];
      Scalar longest(0);
      for (std::size_t e = 0; e + 1 < member.stations.size(); ++e)
        longest = std::max(longest, member.stations[e + 1] - member.stations[e]);
      for (std::size_t e = 0; e + 1 < member.stations.size(); ++e) {
        const Scalar h = member.stations[e + 1] - member.stations[e];
        if (!(h * limit < reference && Scalar(2) * h < longest) || clamped(member.nodes[e]) ||
            clamped(member.nodes[e + 1]))
          continue;
        throw std::invalid_argument(
            std::string(where) + ": member " + std::to_string(m) + ", element " + std::to_string(e) +
            " (length " + detail::format_value(h) + " m) is " + detail::format_value(reference / h) +
            " times shorter than the longest member (" + detail::format_value(reference) +
            " m), beyond max_element_length_ratio() = " + detail::format_value(limit) +
            ": the round-off of its stiffness 12 EI/L^3 (relative ~eps (L_member/L)^3 to the frame's) would "
            "make the lowest frequencies wrong; merge its end station into a neighbour or refine the mesh around it "
            "less");
      }
    }
  }

  // The assembled sums of finite element entries may still overflow (e.g. many heavy point
  // masses and elements at one DOF): name the first DOF whose row holds a non-finite entry.
  static void require_finite_sum(const char* where, const char* name,
                                 const typename AssembledFrame<Scalar>::SparseMatrix& a, const DofMap& dofs) {
    if (detail::all_finite(Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>>(a.valuePtr(), a.nonZeros())))
      return;
    for (Index c = 0; c < a.outerSize(); ++c)
      for (typename AssembledFrame<Scalar>::SparseMatrix::InnerIterator it(a, c); it; ++it)
        if (!detail::is_finite(it.value())) {
          const auto nd = dofs.node_dof(it.row());
          throw std::invalid_argument(std::string(where) + ": the assembled " + name + " has a non-finite entry (" +
                                      detail::format_value(it.value()) + ") in the row of DOF " +
                                      to_string(nd.second) + " of node " + std::to_string(nd.first) +
                                      ": the sum of its element and nodal terms overflows");
        }
  }

  Index push_node(const Vector2& p) {
    if (num_nodes() >= max_nodes)
      detail::throw_invalid("FrameModel::add_node", "the model already holds max_nodes = " +
                                                        std::to_string(max_nodes) + " nodes; num_nodes()",
                            num_nodes());
    positions_.push_back(p);
    for (int d = 0; d < 3; ++d) {
      constrained_.push_back(false);
      nodal_mass_.push_back(Scalar(0));
      nodal_spring_.push_back(Scalar(0));
    }
    touch();
    return num_nodes() - 1;
  }

  void check_node(const char* where, const char* name, Index node) const {
    if (node < 0 || node >= num_nodes())
      throw std::invalid_argument(std::string(where) + ": " + name + " = " + std::to_string(node) +
                                  " does not exist (model has " + std::to_string(num_nodes()) +
                                  " nodes)");
  }

  Scalar checked_length(const char* where, Index node_a, Index node_b, const Section& section) const {
    check_node(where, "node_a", node_a);
    check_node(where, "node_b", node_b);
    if (node_a == node_b)
      detail::throw_invalid(where, "node_b must differ from node_a (zero-length member)", node_b);
    section.validate(where);
    // stableNorm: a plain norm squares the components, which for a member shorter than ~1e-154 m
    // lose precision (subnormal) or underflow, and the direction cosines no longer form a unit
    // vector.
    const Scalar length = (positions_[idx(node_b)] - positions_[idx(node_a)]).stableNorm();
    detail::require_positive(where, "member length", length);
    return length;
  }

  Index push_member(Index node_a, Index node_b, const Section& section, Scalar length,
                    std::vector<Scalar> stations) {
    Member m;
    const Vector2 pa = positions_[idx(node_a)];
    const Vector2 axis = (positions_[idx(node_b)] - pa) / length;
    m.length = length;
    m.cos = axis.x();
    m.sin = axis.y();
    m.section = section;
    m.nodes.reserve(stations.size());
    m.nodes.push_back(node_a);
    for (std::size_t i = 1; i + 1 < stations.size(); ++i) m.nodes.push_back(push_node(pa + stations[i] * axis));
    m.nodes.push_back(node_b);
    m.stations = std::move(stations);
    num_elements_ += m.num_elements();
    members_.push_back(std::move(m));
    touch();
    return num_members() - 1;
  }

  void constrain(Index node, Dof dof) {
    constrained_[idx(global_dof(node, dof))] = true;
    touch();
  }

  std::vector<Vector2> positions_;
  std::vector<Member> members_;
  std::vector<bool> constrained_;    // per global DOF
  std::vector<Scalar> nodal_mass_;   // per global DOF: m on X, Y; J on Rz
  std::vector<Scalar> nodal_spring_; // per global DOF
  Index num_elements_ = 0;
  std::uint64_t id_ = detail::next_model_id();
};

}  // namespace stickslip
