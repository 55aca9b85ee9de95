// Fuzz harness: frame building (FrameModel, assemble) and compute_modes, dense and sparse, with
// Rayleigh damping. Layout of an input: the frame (fuzz_frames.hpp), then num_modes integer,
// solver choice(3), Rayleigh alpha and beta.
//
// Rules checked on a basis that compute_modes returns (independent references):
//  * an assembly error does not blame a node not attached to a member (every node is);
//  * the direction cosines of every member form a unit vector (to 1e-12; a 1e-160 m member must be
//    refused or get exact cosines);
//  * omega finite, >= 0, ascending; Phi finite; no more zero frequencies than
//    FrameModel::count_rigid_body_modes() (a clamped cantilever has none);
//  * each pair solves K phi = omega^2 M phi with relative backward error
//    |K phi - omega^2 M phi| / ((|K| + omega^2 |M|) |phi|) <= 1e-6 (1-norms), and Phi^T M Phi = I
//    to 1e-6: both are ~1e-14 for a well-conditioned frame; 1e-6 leaves room for the condition
//    factor of graded meshes while catching wrong pairs (residual ~1);
//  * dense and sparse agree: when the frame has <= 200 free DOFs the other solver is run too and
//    each omega agrees to 1e-6 relative (Spectra's tolerance is 1e-10 on the shifted Ritz values);
//  * a clamped uniform cantilever (no point masses or springs, consistent mass, bending below half
//    the first axial frequency) has omega_1 within 1 % of Euler-Bernoulli's closed form
//    (beta_1 L)^2 sqrt(EI / (rho A L^4)), beta_1 L = 1.8751040687: one cubic element is 0.5 % high,
//    finer meshes are closer (a 1e-6 m element gave omega_1 = 311 for 261 rad/s);
//  * with_rayleigh_damping(alpha, beta) gives c_i = alpha + beta omega_i^2 (closed form), finite
//    for alpha, beta <= 1e100.
#include "fuzz/fuzz_frames.hpp"

#include <stickslip/modal.hpp>

#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <string>

namespace frame_modes_fuzz {

using namespace stickslip;
using stickslip_fuzz::require;
using stickslip_fuzz::str;

double norm1(const Eigen::SparseMatrix<double>& A) {
  Eigen::VectorXd col = Eigen::VectorXd::Zero(A.cols());
  for (Eigen::Index k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) col(it.col()) += std::abs(it.value());
  return col.size() ? col.maxCoeff() : 0.0;
}

void check_basis(const AssembledFrame<double>& K_M, const ModalBasis<double>& b, Eigen::Index rigid) {
  const auto& w = b.omega();
  const auto& phi = b.phi();
  require(w.allFinite() && phi.allFinite(), "non-finite omega or Phi");
  Eigen::Index zeros = 0;
  for (Eigen::Index i = 0; i < w.size(); ++i) {
    require(w(i) >= 0 && (i == 0 || w(i) >= w(i - 1)), "omega not >= 0 and ascending at " + std::to_string(i));
    zeros += w(i) == 0 ? 1 : 0;
  }
  require(zeros <= rigid, std::to_string(zeros) + " zero frequencies for " + std::to_string(rigid) +
                              " rigid-body modes the supports allow");
  const double nK = norm1(K_M.stiffness), nM = norm1(K_M.mass);
  for (Eigen::Index i = 0; i < w.size(); ++i) {
    const double lambda = w(i) * w(i);
    const Eigen::VectorXd r = K_M.stiffness * phi.col(i) - lambda * (K_M.mass * phi.col(i));
    const double be = r.lpNorm<1>() / ((nK + lambda * nM) * phi.col(i).lpNorm<1>());
    require(be <= 1e-6, "mode " + std::to_string(i) + " (omega = " + str(w(i)) +
                            ") has backward error " + str(be));
  }
  const Eigen::MatrixXd G = phi.transpose() * (K_M.mass * phi);
  const double orth = (G - Eigen::MatrixXd::Identity(G.rows(), G.cols())).cwiseAbs().maxCoeff();
  require(orth <= 1e-6, "Phi^T M Phi - I = " + str(orth));
}

void run(stickslip_fuzz::Input& in) {
  stickslip_fuzz::FuzzFrame f = stickslip_fuzz::build_frame(in);
  for (Eigen::Index m = 0; m < f.frame.num_members(); ++m) {
    const auto& mem = f.frame.member(m);
    require(std::abs(mem.cos * mem.cos + mem.sin * mem.sin - 1) <= 1e-12,
            "member " + std::to_string(m) + " of length " + str(mem.length) + " has cos^2 + sin^2 = " +
                str(mem.cos * mem.cos + mem.sin * mem.sin));
  }
  ModalOptions<double> opt;
  opt.num_modes = static_cast<Eigen::Index>(stickslip_fuzz::bounded_count(in.integer(1, 8), 64));
  opt.solver = static_cast<ModalSolver>(in.choice(3));
  const double alpha = in.real(0.0, 20.0), beta = in.real(0.0, 1e-5);

  // Every node of these frames lies on a member: an assembly error saying otherwise names the
  // wrong cause (an overflowing rho A was reported so).
  const AssembledFrame<double> K_M = [&] {
    try {
      return f.frame.assemble(f.lumped ? MassType::Lumped : MassType::Consistent);
    } catch (const std::invalid_argument& e) {
      require(std::string(e.what()).find("not attached") == std::string::npos,
              std::string("assemble blames an unattached node: ") + e.what());
      throw;
    }
  }();
  const Eigen::Index rigid = f.frame.count_rigid_body_modes();
  ModalSolveReport<double> report;
  const ModalBasis<double> basis = compute_modes(K_M, opt, &report);
  check_basis(K_M, basis, rigid);

  const auto& w = basis.omega();
  if (f.topology == 0 && !f.extras && !f.lumped) {
    const auto& s = f.section;
    const double bending = std::pow(1.8751040687, 2) * std::sqrt(s.E * s.I / (s.rho * s.A)) / (f.length * f.length);
    const double axial = 1.5707963267948966 * std::sqrt(s.E / s.rho) / f.length;
    if (std::isnormal(bending) && std::isfinite(axial) && bending < 0.5 * axial)
      require(std::abs(w(0) / bending - 1) <= 1e-2,
              "cantilever omega_1 = " + str(w(0)) + ", Euler-Bernoulli " + str(bending));
  }

  if (K_M.num_free() <= 200 && opt.num_modes < K_M.num_free()) {
    ModalOptions<double> other = opt;
    other.solver = report.solver == ModalSolver::Dense ? ModalSolver::Sparse : ModalSolver::Dense;
    const ModalBasis<double> b2 = compute_modes(K_M, other);
    check_basis(K_M, b2, rigid);
    const Eigen::Index n = std::min(b2.size(), basis.size());
    for (Eigen::Index i = 0; i < n; ++i)
      require(std::abs(b2.omega()(i) - w(i)) <= 1e-6 * std::max(w(i), b2.omega()(i)),
              std::string(to_string(report.solver)) + " omega_" + std::to_string(i) + " = " + str(w(i)) +
                  ", " + to_string(other.solver) + " " + str(b2.omega()(i)));
  }

  const ModalBasis<double> damped = basis.with_rayleigh_damping(alpha, beta);
  if (alpha <= 1e100 && beta <= 1e100) {
    for (Eigen::Index i = 0; i < w.size(); ++i) {
      const double c = alpha + beta * w(i) * w(i);
      if (std::isfinite(c))
        require(damped.damping_coefficients()(i) == c,
                "Rayleigh c_" + std::to_string(i) + " = " + str(damped.damping_coefficients()(i)) +
                    ", alpha + beta omega^2 = " + str(c));
    }
  }
}

}  // namespace frame_modes_fuzz

STICKSLIP_FUZZ_ENTRY(frame_modes, frame_modes_fuzz::run)
