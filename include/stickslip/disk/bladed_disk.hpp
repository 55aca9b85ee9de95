#pragma once
/// \file bladed_disk.hpp
/// \brief A bladed disk: N copies of one sector (a blade with its platform, built by a user
/// function) in one plane frame, each coupled to its neighbours (wrap-around at N) by springs or
/// a ring element between designated attachment nodes (docs/disks.md).

#include "stickslip/beam/assembled_frame.hpp"
#include "stickslip/beam/dof.hpp"
#include "stickslip/beam/dof_map.hpp"
#include "stickslip/beam/frame_model.hpp"
#include "stickslip/beam/ids.hpp"
#include "stickslip/beam/mass_type.hpp"
#include "stickslip/detail/validate.hpp"
#include "stickslip/disk/sector_coupling.hpp"
#include "stickslip/model/structure_point.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace stickslip {

/// Where the sector builder is asked to place sector `index`: add every node at
/// origin + (the sector's own coordinates).
template <class Scalar>
struct SectorPlacement {
  Eigen::Index index = 0;                            ///< sector number k, 0 ... N - 1
  Eigen::Matrix<Scalar, 2, 1> origin{Scalar(0), Scalar(0)};  ///< (k pitch, 0) [m]
  /// Mistuning: the builder multiplies the Young's modulus of the sector's members by this,
  /// E_k = E (1 + delta_k) (1 for a tuned disk and for the reference sector).
  Scalar stiffness_factor = Scalar(1);
};

/// The attachment nodes a sector builder reports: the coupling ties `right` of sector k to
/// `left` of sector k + 1 (they may be the same node of the sector, e.g. a blade root tied to
/// the next blade's root). -1: missing (refused).
struct SectorAttachments {
  NodeId left = -1;   ///< node tied to the previous sector's `right`
  NodeId right = -1;  ///< node tied to the next sector's `left`
};

/// A bladed disk in the unrolled (lumped, cyclic) formulation: sector k is the sector built by
/// `builder` at origin (k pitch, 0), in the sector's own coordinates (a translation: every
/// element matrix is the same in every sector), and the coupling ties right(k) to left(k + 1 mod
/// N). The annulus is thus a cyclic chain of identical sectors, which is exactly what cyclic
/// symmetry needs (cyclic_modes.hpp); the geometry of the real circular disk enters only through
/// the sector model and the coupling stiffness.
///
/// Numbering: the builder must add the same nodes and members, in the same order, at every call.
/// Sector k then owns the nodes [k P, (k + 1) P) and the members [k Q, (k + 1) Q) of frame(),
/// P = nodes_per_sector(), Q = members_per_sector(); node(k, n) and member(k, m) map the ids of
/// the reference sector (sector_frame(), which equals sector 0) to sector k.
///
/// The coupling is not part of frame(): assemble the annulus with BladedDisk::assemble(), never
/// frame().assemble() (which gives N uncoupled sectors). Its model id is frame().id(), so the
/// modes of assemble() serve ContactSystem(frame(), basis, ...) and every component that takes a
/// frame and its basis.
template <class Scalar_>
class BladedDisk {
 public:
  using Scalar = Scalar_;                                   ///< floating-point type
  using Index = Eigen::Index;                               ///< index type
  using Vector2 = Eigen::Matrix<Scalar, 2, 1>;              ///< a position (X, Y) [m]
  using Matrix6 = Eigen::Matrix<Scalar, 6, 6>;              ///< coupling element matrix
  /// Builds one sector into `frame` at `placement.origin` and reports its attachment nodes.
  using SectorBuilder = std::function<SectorAttachments(FrameModel<Scalar>& frame,
                                                        const SectorPlacement<Scalar>& placement)>;

  /// Relative tolerance (of the sector's size) of the check that every call of the builder
  /// placed the same nodes.
  static constexpr double geometry_tolerance = 1e-9;

  /// \param num_sectors N >= 2 blades
  /// \param pitch  distance [m] between neighbouring sectors in the unrolled plane (along X);
  ///        must exceed the sector's X extent (the sectors lie side by side); the ring element's
  ///        geometry depends on it, springs do not
  /// \param builder the sector (see SectorBuilder), called once for sector_frame() and once per
  ///        sector
  /// \param coupling springs and/or ring element between right(k) and left(k + 1)
  /// \param mistuning delta_k per sector (empty: tuned), passed to the builder as
  ///        SectorPlacement::stiffness_factor = 1 + delta_k (draw_mistuning draws them)
  /// \throws std::invalid_argument naming the parameter: num_sectors < 2, pitch not finite or
  ///         not above the sector's extent, an empty builder, missing or foreign attachment
  ///         nodes (attachments.left / attachments.right), a builder that builds a different
  ///         sector at another call (sector: node count, member count, node position, support),
  ///         an invalid coupling, mistuning of another size than N or with a delta_k not
  ///         finite and > -1 (mistuning[k]); the builder's own exceptions propagate.
  BladedDisk(Index num_sectors, Scalar pitch, SectorBuilder builder, SectorCoupling<Scalar> coupling,
             std::vector<Scalar> mistuning = {})
      : num_sectors_(num_sectors), pitch_(pitch), coupling_(std::move(coupling)), mistuning_(std::move(mistuning)) {
    static const char* where = "BladedDisk";
    if (num_sectors < 2) detail::throw_invalid(where, "num_sectors must be >= 2", num_sectors);
    if (num_sectors > FrameModel<Scalar>::max_nodes)
      detail::throw_invalid(where, "num_sectors must be <= FrameModel::max_nodes", num_sectors);
    detail::require_positive(where, "pitch", pitch);
    if (!builder) throw std::invalid_argument(std::string(where) + ": builder must be callable (it is empty)");
    coupling_.validate(where);
    if (mistuning_.empty()) mistuning_.assign(static_cast<std::size_t>(num_sectors), Scalar(0));
    if (static_cast<Index>(mistuning_.size()) != num_sectors)
      detail::throw_invalid(where, "mistuning must be empty or hold num_sectors = " + std::to_string(num_sectors) +
                                       " values; mistuning.size()", mistuning_.size());
    for (std::size_t k = 0; k < mistuning_.size(); ++k)
      if (!(detail::is_finite(mistuning_[k]) && mistuning_[k] > Scalar(-1)))
        detail::throw_invalid(where, "mistuning[" + std::to_string(k) + "] must be finite and > -1", mistuning_[k]);

    attachments_ = builder(sector_, SectorPlacement<Scalar>{0, Vector2::Zero(), Scalar(1)});
    nodes_per_sector_ = sector_.num_nodes();
    members_per_sector_ = sector_.num_members();
    if (nodes_per_sector_ < 1) detail::throw_invalid(where, "sector: the builder added no node; num_nodes", 0);
    check_attachment(where, "attachments.left", attachments_.left);
    check_attachment(where, "attachments.right", attachments_.right);
    Vector2 lo = sector_.node_position(0), hi = lo;
    for (Index n = 1; n < nodes_per_sector_; ++n) {
      lo = lo.cwiseMin(sector_.node_position(n));
      hi = hi.cwiseMax(sector_.node_position(n));
    }
    if (!(pitch > hi.x() - lo.x()))
      detail::throw_invalid(where, "pitch must exceed the sector's X extent " + detail::format_value(hi.x() - lo.x()) +
                                       " m (the unrolled sectors lie side by side); pitch", pitch);
    const Scalar tol = Scalar(geometry_tolerance) * std::max((hi - lo).stableNorm(), pitch);

    for (Index k = 0; k < num_sectors; ++k) {
      const Vector2 origin(Scalar(k) * pitch, Scalar(0));
      const SectorAttachments a =
          builder(frame_, SectorPlacement<Scalar>{k, origin, Scalar(1) + mistuning_[static_cast<std::size_t>(k)]});
      const std::string sector = "sector " + std::to_string(k);
      if (frame_.num_nodes() != (k + 1) * nodes_per_sector_ || frame_.num_members() != (k + 1) * members_per_sector_)
        throw std::invalid_argument(std::string(where) + ": " + sector + ": the builder must add the same " +
                                    std::to_string(nodes_per_sector_) + " nodes and " +
                                    std::to_string(members_per_sector_) + " members at every call");
      if (a.left != node(k, attachments_.left) || a.right != node(k, attachments_.right))
        detail::throw_invalid(where, sector + ": the builder must report the same attachments at every call; "
                                              "attachments.left", Index(a.left));
      for (Index n = 0; n < nodes_per_sector_; ++n) {
        const Index m = node(k, n);
        if (!((frame_.node_position(m) - origin - sector_.node_position(n)).stableNorm() <= tol))
          detail::throw_invalid(where, sector + ": node " + std::to_string(n) +
                                           " must lie at origin + the sector's position (the builder must add every "
                                           "node at placement.origin + its own coordinates); node",
                                m);
        for (Dof d : {Dof::X, Dof::Y, Dof::Rz})
          if (frame_.is_constrained(m, d) != sector_.is_constrained(n, d))
            detail::throw_invalid(where, sector + ": the supports must be the same in every sector; node", m);
      }
    }
    // Geometry of the coupling: R of sector k to L of sector k + 1 in the unrolled plane.
    right_position_ = sector_.node_position(attachments_.right);
    left_next_position_ = sector_.node_position(attachments_.left) + Vector2(pitch, Scalar(0));
    (void)coupling_stiffness();  // a zero-length ring throws here, at construction
    sector_dofs_ = dof_map_of(sector_);
    annulus_dofs_ = dof_map_of(frame_);
  }

  Index num_sectors() const noexcept { return num_sectors_; }               ///< N
  Scalar pitch() const noexcept { return pitch_; }                          ///< [m]
  /// The annulus' frame (all sectors, without the coupling: see assemble()).
  const FrameModel<Scalar>& frame() const noexcept { return frame_; }
  /// The reference sector alone, built at origin 0 (equal to sector 0 of frame()).
  const FrameModel<Scalar>& sector_frame() const noexcept { return sector_; }
  /// The attachment nodes in the reference sector's numbering.
  const SectorAttachments& attachments() const noexcept { return attachments_; }
  /// The coupling between neighbours.
  const SectorCoupling<Scalar>& coupling() const noexcept { return coupling_; }
  /// delta_k per sector (zeros for a tuned disk).
  const std::vector<Scalar>& mistuning() const noexcept { return mistuning_; }
  /// True when every delta_k is 0 (cyclic symmetry holds).
  bool is_tuned() const noexcept {
    return std::all_of(mistuning_.begin(), mistuning_.end(), [](Scalar d) { return d == Scalar(0); });
  }
  Index nodes_per_sector() const noexcept { return nodes_per_sector_; }      ///< P
  Index members_per_sector() const noexcept { return members_per_sector_; }  ///< Q
  /// Free-DOF numbering of the reference sector (sector_frame()).
  const DofMap& sector_dofs() const noexcept { return sector_dofs_; }
  /// Free-DOF numbering of the annulus (frame(), and assemble()).
  const DofMap& annulus_dofs() const noexcept { return annulus_dofs_; }

  /// Node of sector k that is `sector_node` of the reference sector: k P + sector_node.
  /// \throws std::invalid_argument for k or sector_node out of range
  NodeId node(Index k, NodeId sector_node) const {
    check_sector("BladedDisk::node", k);
    if (sector_node < 0 || sector_node >= nodes_per_sector_)
      detail::throw_invalid("BladedDisk::node", "sector_node must be in [0, nodes_per_sector() = " +
                                                    std::to_string(nodes_per_sector_) + ")", Index(sector_node));
    return k * nodes_per_sector_ + sector_node;
  }
  /// Member of sector k that is `sector_member` of the reference sector: k Q + sector_member.
  /// \throws std::invalid_argument for k or sector_member out of range
  MemberId member(Index k, MemberId sector_member) const {
    check_sector("BladedDisk::member", k);
    if (sector_member < 0 || sector_member >= members_per_sector_)
      detail::throw_invalid("BladedDisk::member", "sector_member must be in [0, members_per_sector() = " +
                                                      std::to_string(members_per_sector_) + ")",
                            Index(sector_member));
    return k * members_per_sector_ + sector_member;
  }
  /// The material point of sector k that is `p` of the reference sector. A coordinate in
  /// [0, L] of the reference member (length L) is scaled to sector k's member length L_k: the
  /// translated node coordinates round differently, so L_k differs from L by round-off and a
  /// point at the member's end (coordinate = L) must land on L_k, not beyond it. A coordinate
  /// outside [0, L] is passed on unchanged (to be refused where it is used).
  StructurePoint<Scalar> point(Index k, const StructurePoint<Scalar>& p) const {
    const MemberId m = member(k, p.member);
    const Scalar L = sector_.member(p.member).length, Lk = frame_.member(m).length;
    Scalar s = p.coordinate;
    if (s >= Scalar(0) && s <= L) s = s == L ? Lk : std::min(s * (Lk / L), Lk);
    return StructurePoint<Scalar>{m, s};
  }

  /// Annulus free index of the reference sector's free DOF `sector_free` in sector k.
  Index annulus_free_index(Index k, Index sector_free) const {
    const auto nd = sector_dofs_.node_dof(sector_free);
    return annulus_dofs_.free_index(node(k, nd.first), nd.second);
  }

  /// K_c over (u_R; u_L) of one coupling (SectorCoupling::stiffness at this disk's geometry).
  Matrix6 coupling_stiffness() const { return coupling_.stiffness(right_position_, left_next_position_); }
  /// M_c over (u_R; u_L) of one coupling.
  Matrix6 coupling_mass(MassType type = MassType::Consistent) const {
    return coupling_.mass(right_position_, left_next_position_, type);
  }

  /// Sector free indices of the six coupling DOFs (X, Y, Rz of R; X, Y, Rz of L) in the reference
  /// sector; -1 where a DOF is constrained.
  std::array<Index, 6> coupling_sector_dofs() const {
    std::array<Index, 6> out{};
    for (Index d = 0; d < 3; ++d) {
      out[static_cast<std::size_t>(d)] = sector_dofs_.free_index(attachments_.right, static_cast<Dof>(d));
      out[static_cast<std::size_t>(d + 3)] = sector_dofs_.free_index(attachments_.left, static_cast<Dof>(d));
    }
    return out;
  }

  /// K and M of the annulus: frame().assemble(type) plus the N couplings right(k) - left(k + 1
  /// mod N). model_id = frame().id(). The rigid-body count is kept when it is 0 (a coupling
  /// only adds stiffness) and otherwise left to compute_modes (-1: a coupling may remove some).
  AssembledFrame<Scalar> assemble(MassType type = MassType::Consistent) const {
    AssembledFrame<Scalar> out = frame_.assemble(type);
    using SparseMatrix = typename AssembledFrame<Scalar>::SparseMatrix;
    using Triplet = Eigen::Triplet<Scalar, typename SparseMatrix::StorageIndex>;
    const Matrix6 kc = coupling_stiffness(), mc = coupling_mass(type);
    std::vector<Triplet> kt, mt;
    kt.reserve(static_cast<std::size_t>(36 * num_sectors_));
    mt.reserve(coupling_.ring ? static_cast<std::size_t>(36 * num_sectors_) : 0);
    for (Index k = 0; k < num_sectors_; ++k) {
      const std::array<Index, 6> map = coupling_annulus_dofs(k);
      for (Index c = 0; c < 6; ++c) {
        const Index fc = map[static_cast<std::size_t>(c)];
        if (fc < 0) continue;
        for (Index r = 0; r < 6; ++r) {
          const Index fr = map[static_cast<std::size_t>(r)];
          if (fr < 0) continue;
          using SI = typename SparseMatrix::StorageIndex;
          if (kc(r, c) != Scalar(0)) kt.emplace_back(static_cast<SI>(fr), static_cast<SI>(fc), kc(r, c));
          if (mc(r, c) != Scalar(0)) mt.emplace_back(static_cast<SI>(fr), static_cast<SI>(fc), mc(r, c));
        }
      }
    }
    const Index n = out.num_free();
    SparseMatrix ck(n, n), cm(n, n);
    ck.setFromTriplets(kt.begin(), kt.end());
    cm.setFromTriplets(mt.begin(), mt.end());
    out.stiffness = SparseMatrix(out.stiffness + ck);
    out.mass = SparseMatrix(out.mass + cm);
    out.stiffness.makeCompressed();
    out.mass.makeCompressed();
    if (out.num_rigid_body_modes > 0) out.num_rigid_body_modes = -1;
    return out;
  }

  /// Annulus free indices of the six DOFs of coupling k (R of sector k; L of sector k + 1 mod N);
  /// -1 where constrained.
  std::array<Index, 6> coupling_annulus_dofs(Index k) const {
    std::array<Index, 6> out{};
    const NodeId r = node(k, attachments_.right), l = node((k + 1) % num_sectors_, attachments_.left);
    for (Index d = 0; d < 3; ++d) {
      out[static_cast<std::size_t>(d)] = annulus_dofs_.free_index(r, static_cast<Dof>(d));
      out[static_cast<std::size_t>(d + 3)] = annulus_dofs_.free_index(l, static_cast<Dof>(d));
    }
    return out;
  }

 private:
  void check_sector(const char* where, Index k) const {
    if (k < 0 || k >= num_sectors_)
      detail::throw_invalid(where, "sector index k must be in [0, num_sectors() = " + std::to_string(num_sectors_) + ")",
                            k);
  }
  void check_attachment(const char* where, const char* name, NodeId n) const {
    if (n < 0 || n >= nodes_per_sector_)
      detail::throw_invalid(where, std::string(name) + " must be a node the sector builder added, in [0, " +
                                       std::to_string(nodes_per_sector_) + ") (-1: missing)",
                            Index(n));
  }
  static DofMap dof_map_of(const FrameModel<Scalar>& f) {
    std::vector<bool> constrained(static_cast<std::size_t>(dofs_per_node * f.num_nodes()));
    for (Index n = 0; n < f.num_nodes(); ++n)
      for (Index d = 0; d < dofs_per_node; ++d)
        constrained[static_cast<std::size_t>(global_dof(n, static_cast<Dof>(d)))] =
            f.is_constrained(n, static_cast<Dof>(d));
    return DofMap(constrained);
  }

  Index num_sectors_ = 0;
  Scalar pitch_{};
  SectorCoupling<Scalar> coupling_;
  std::vector<Scalar> mistuning_;
  FrameModel<Scalar> sector_;
  FrameModel<Scalar> frame_;
  SectorAttachments attachments_;
  Index nodes_per_sector_ = 0, members_per_sector_ = 0;
  Vector2 right_position_ = Vector2::Zero(), left_next_position_ = Vector2::Zero();
  DofMap sector_dofs_, annulus_dofs_;
};

}  // namespace stickslip
