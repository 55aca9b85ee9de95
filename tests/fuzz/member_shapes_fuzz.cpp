// Fuzz harness: MemberShapes (moving-load shape functions of a member) on a fuzzed frame.
// Layout of an input: the frame (fuzz_frames.hpp), num_modes integer, member choice(2), end policy
// choice(3), then up to 8 coordinates eps.
//
// Rules checked (references independent of MemberShapes' interpolation):
//  * at every node of the member the shape values equal the basis' nodal values rotated to the
//    member's axes: psi_u = cos Phi_X + sin Phi_Y, psi_w = -sin Phi_X + cos Phi_Y, psi_w' = Phi_Rz
//    (to 1e-12 of max |Phi|: a Hermite interpolant reproduces its nodal data up to round-off);
//  * for finite eps inside [0, L] (any policy) or up to 10 L outside with Extrapolate, the values
//    are finite; Throw refuses eps outside [0, L] (std::invalid_argument); Clamp gives the values
//    of the nearest end.
#include "fuzz/fuzz_frames.hpp"

#include <stickslip/modal.hpp>
#include <stickslip/moving_load.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace member_shapes_fuzz {

using namespace stickslip;
using stickslip_fuzz::require;
using stickslip_fuzz::str;
using Shapes = MemberShapes<double>;

bool all_finite(const Shapes::Values& v) {
  return v.psi_u.allFinite() && v.dpsi_u.allFinite() && v.psi_w.allFinite() && v.dpsi_w.allFinite() &&
         v.ddpsi_w.allFinite();
}

void check_nodes(const FrameModel<double>& frame, Eigen::Index member, const ModalBasis<double>& basis,
                 const Shapes& shapes) {
  const auto& m = frame.member(member);
  const double scale = basis.phi().cwiseAbs().maxCoeff();
  for (std::size_t k = 0; k < m.nodes.size(); ++k) {
    const auto node = m.nodes[k];
    const Eigen::RowVectorXd X = basis.nodal(node, Dof::X), Y = basis.nodal(node, Dof::Y),
                             R = basis.nodal(node, Dof::Rz);
    const Shapes::Values v = shapes.evaluate(m.stations[k]);
    const double eu = (v.psi_u.transpose() - (m.cos * X + m.sin * Y)).cwiseAbs().maxCoeff();
    const double ew = (v.psi_w.transpose() - (-m.sin * X + m.cos * Y)).cwiseAbs().maxCoeff();
    const double et = (v.dpsi_w.transpose() - R).cwiseAbs().maxCoeff();
    require(std::max({eu, ew, et}) <= 1e-12 * scale,
            "node " + std::to_string(k) + " at eps = " + str(m.stations[k]) + ": |psi_u - u| = " + str(eu) +
                ", |psi_w - w| = " + str(ew) + ", |psi_w' - theta| = " + str(et) + " (max |Phi| " + str(scale) + ")");
  }
}

void run(stickslip_fuzz::Input& in) {
  stickslip_fuzz::FuzzFrame f = stickslip_fuzz::build_frame(in);
  ModalOptions<double> opt;
  opt.num_modes = static_cast<Eigen::Index>(stickslip_fuzz::bounded_count(in.integer(1, 6), 64));
  opt.solver = ModalSolver::Dense;
  const ModalBasis<double> basis = compute_modes(f.frame.assemble(), opt);
  const auto member = f.members[in.choice(static_cast<unsigned>(f.members.size()))];
  const auto policy = static_cast<EndPolicy>(in.choice(3));
  const Shapes shapes(f.frame, member, basis, policy);
  check_nodes(f.frame, member, basis, shapes);
  const double L = f.frame.member(member).length;
  for (int k = 0; k < 8 && !in.empty(); ++k) {
    const double eps = in.real(-0.1 * L, 1.1 * L);
    const bool inside = eps >= 0 && eps <= L;
    Shapes::Values v;
    try {
      shapes.evaluate(eps, v);
    } catch (const std::invalid_argument&) {
      require(!std::isfinite(eps) || (policy == EndPolicy::Throw && !inside),
              "evaluate(" + str(eps) + ") threw with policy " + std::to_string(int(policy)) + " on [0, " + str(L) + "]");
      continue;
    }
    require(std::isfinite(eps) && (inside || policy != EndPolicy::Throw),
            "evaluate(" + str(eps) + ") accepted outside [0, " + str(L) + "] with policy Throw");
    if (inside || policy == EndPolicy::Clamp || std::abs(eps) <= 10 * L)
      require(all_finite(v), "non-finite shape values at eps = " + str(eps));
    if (policy == EndPolicy::Clamp && !inside) {
      const Shapes::Values end = shapes.evaluate(eps < 0 ? 0.0 : L);
      require(v.psi_u == end.psi_u && v.psi_w == end.psi_w && v.dpsi_w == end.dpsi_w,
              "Clamp at eps = " + str(eps) + " differs from the end value");
    }
  }
}

}  // namespace member_shapes_fuzz

STICKSLIP_FUZZ_ENTRY(member_shapes, member_shapes_fuzz::run)
