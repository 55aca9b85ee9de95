#pragma once
/// \file disk_linear.hpp
/// \brief The disk's two linear limits in closed form (docs/disks.md, "The example"): the
/// engine-order response of the retained modes with every damper stuck (a constraint per damper:
/// the two wings do not slide along the damper's direction) or without dampers, and the largest
/// blade tip amplitude over a frequency grid (the mistuning study's peak).

#include "disk_scene.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <complex>
#include <vector>

namespace bladed_disk {

/// Tip amplitudes |u_k| of every blade at Omega in the steady state of the linear modal system
///   (omega^2 - Omega^2 + i Omega c) Q + G^T lambda = g,   G Q = 0 (stuck) / no G (free),
/// g = sum_k F e^{2 pi i EO k / N} psi_k (psi_k: the modes at blade k's load node), G: the
/// dampers' sliding rows (ContactSystem::contact_row; a stuck Coulomb joint holds its sliding
/// velocity at zero, so the harmonic part of the slip vanishes).
class LinearDisk {
 public:
  LinearDisk(const DiskScene& scene, bool stuck) : scene_(scene) {
    const auto& p = scene.parameters;
    const Index n = scene.basis.size(), N = p.sectors;
    g_ = Eigen::VectorXcd::Zero(n);
    const Index eo = stickslip::reduced_engine_order(p.engine_order, N);
    for (Index k = 0; k < N; ++k) {
      const double phase = 2 * M_PI * double((eo * k) % N) / double(N);
      g_ += scene.basis.nodal(scene.disk.node(k, scene.load_node), stickslip::Dof::X).transpose().cast<std::complex<double>>() *
            std::polar(p.blade.force, phase);
    }
    if (stuck) {
      const System sys = scene.system(1.0, 1.0);
      G_.resize(sys.num_contacts(), n);
      for (Index i = 0; i < sys.num_contacts(); ++i) G_.row(i) = sys.contact_row(i).transpose();
    }
  }

  /// The modal amplitudes Q at Omega (q(t) = Re(Q e^{i Omega t})).
  Eigen::VectorXcd modal(double omega) const {
    const auto& b = scene_.basis;
    const Index n = b.size(), c = G_.rows();
    Eigen::MatrixXcd A = Eigen::MatrixXcd::Zero(n + c, n + c);
    for (Index r = 0; r < n; ++r)
      A(r, r) = std::complex<double>(b.omega()(r) * b.omega()(r) - omega * omega, omega * b.damping_coefficients()(r));
    A.topRightCorner(n, c) = G_.transpose().cast<std::complex<double>>();
    A.bottomLeftCorner(c, n) = G_.cast<std::complex<double>>();
    Eigen::VectorXcd rhs = Eigen::VectorXcd::Zero(n + c);
    rhs.head(n) = g_;
    return A.fullPivLu().solve(rhs).head(n);
  }
  /// The undamped natural frequencies [rad/s] of the modal system, ascending: the retained modes'
  /// without dampers; with them stuck, those of diag(omega^2) on the null space of G (the motions
  /// the stuck dampers allow), from an orthonormal basis Z of it (the right singular vectors of G
  /// beyond its rank): eig(Z^T diag(omega^2) Z).
  Eigen::VectorXd natural_frequencies() const {
    const Eigen::VectorXd w2 = scene_.basis.omega().array().square().matrix();
    if (G_.rows() == 0) return w2.cwiseSqrt();
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(G_, Eigen::ComputeFullV);
    svd.setThreshold(1e-10);
    const Eigen::MatrixXd Z = svd.matrixV().rightCols(G_.cols() - svd.rank());
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Z.transpose() * w2.asDiagonal() * Z, Eigen::EigenvaluesOnly);
    return eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  }

  /// |u_k| of every blade at Omega.
  Eigen::VectorXd tips(double omega) const {
    return (scene_.tip_rows.cast<std::complex<double>>() * modal(omega)).cwiseAbs();
  }

  /// The largest blade tip amplitude over `omegas` and its blade.
  stickslip::BladePeak<double> peak(const std::vector<double>& omegas) const {
    stickslip::BladePeak<double> best{-1.0, -1};
    for (double w : omegas) {
      Index k = 0;
      const double a = tips(w).maxCoeff(&k);
      if (a > best.peak) best = {a, k};
    }
    return best;
  }

 private:
  const DiskScene& scene_;
  Eigen::VectorXcd g_;
  Eigen::MatrixXd G_;
};

}  // namespace bladed_disk
