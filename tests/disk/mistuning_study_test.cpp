// Mistuning studies: the amplification factor over Monte Carlo samples as a sweep, against
// references that do not come from the study: delta = 0 gives exactly the tuned disk (1), the
// rows do not depend on the thread count, and a lumped ring of coupled oscillators (one mode per
// blade, the dampers stuck into the coupling) stays below Whitehead's bound (1 + sqrt N) / 2.

#include "disk/disk_samples.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace mistuning_study_test {

using namespace disk_samples;

std::vector<double> grid(double from, double to, int count) {
  std::vector<double> g;
  for (int i = 0; i < count; ++i) g.push_back(from + (to - from) * i / (count - 1));
  return g;
}

// A frame disk of four blades, its linear EO 1 response over a band about the first family:
// delta = 0 draws give the tuned disk, amplification exactly 1; a scattered sample does not.
TEST(DiskMistuningStudy, ZeroScatterGivesAmplificationOneOnAnyThreadCount) {
  const Eigen::Index N = 4;
  const auto coupling = SectorCoupling<double>::springs(1e4, 1e4, 10.0);
  const Disk tuned(N, kPitch, builder(), coupling);
  CyclicModalOptions<double> co;
  co.num_modes = 1;
  const double w = compute_cyclic_modes(tuned, co).families[1].omega(0);
  const auto omegas = grid(0.9 * w, 1.1 * w, 41);
  const std::function<BladePeak<double>(const std::vector<double>&)> peak = [&](const std::vector<double>& deltas) {
    const Disk disk(N, kPitch, builder(), coupling, deltas);
    return engine_order_blade_peak(disk, kTip, Dof::X, 1.0, 1, kTip, Dof::X, omegas, 0.01, 8);
  };
  const auto zero = mistuning_study<double>(N, 0.0, 3, 11, peak, 2);
  ASSERT_EQ(zero.amplification.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_TRUE(zero.outcomes[k].ok) << zero.outcomes[k].error;
    EXPECT_EQ(zero.amplification[k], 1.0);  // the same computation on the same matrices
    EXPECT_EQ(zero.seeds[k], 11u + k);
  }
  const auto serial = mistuning_study<double>(N, 0.05, 3, 11, peak, 1);
  const auto threaded = mistuning_study<double>(N, 0.05, 3, 11, peak, 2);
  std::ostringstream a, b;
  serial.write_csv(a);
  threaded.write_csv(b);
  EXPECT_EQ(a.str(), b.str());
  EXPECT_NE(serial.amplification[0], 1.0);
  EXPECT_NE(a.str().find("sample,seed,sigma,peak,blade,amplification,error"), std::string::npos);
}

// A ring of N = 8 unit oscillators (omega_0 = 1, damping ratio 0.002) coupled to their
// neighbours by springs k_c = 0.005 (of the order of the scatter: where amplification is
// largest), E_k = 1 + delta_k, forced at EO 2: the largest blade peak of each sample, over a
// frequency grid of 44 points per half-power bandwidth 2 zeta (a peak between two points is
// missed by < 0.1 %), by a direct complex solve.
// Whitehead (1966): the amplification of a lightly damped ring with one mode per blade stays
// below (1 + sqrt N) / 2.
TEST(DiskMistuningStudy, LumpedRingStaysBelowWhiteheadsBound) {
  const Eigen::Index N = 8, eo = 2;
  const double zeta = 0.002, kc = 0.005;
  const auto omegas = grid(0.97, 1.06, 1000);
  const std::function<BladePeak<double>(const std::vector<double>&)> ring = [&](const std::vector<double>& deltas) {
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N, N);
    for (Eigen::Index k = 0; k < N; ++k) {
      K(k, k) = 1 + deltas[static_cast<std::size_t>(k)] + 2 * kc;
      K(k, (k + 1) % N) -= kc;
      K(k, (k + N - 1) % N) -= kc;
    }
    Eigen::VectorXcd f(N);
    for (Eigen::Index k = 0; k < N; ++k) f(k) = std::polar(1.0, 2 * kPi * double(eo * k) / double(N));
    BladePeak<double> best{-1.0, -1};
    for (double W : omegas) {
      Eigen::MatrixXcd D = K.cast<std::complex<double>>();
      D.diagonal().array() += std::complex<double>(-W * W, 2 * zeta * W);
      const Eigen::VectorXcd u = D.partialPivLu().solve(f);
      Eigen::Index k = 0;
      const double a = u.cwiseAbs().maxCoeff(&k);
      if (a > best.peak) best = {a, k};
    }
    return best;
  };
  const auto study = mistuning_study<double>(N, 0.005, 40, 2026, ring, 2);
  const double bound = (1 + std::sqrt(double(N))) / 2;
  for (std::size_t k = 0; k < study.amplification.size(); ++k) {
    ASSERT_TRUE(study.outcomes[k].ok) << study.outcomes[k].error;
    EXPECT_LT(study.amplification[k], bound) << "seed " << study.seeds[k];
  }
  // The scatter does localise the response: the worst sample (measured 1.39) is well above the
  // tuned disk, so the bound is tested where it matters.
  EXPECT_GT(study.max_amplification(), 1.2);
}

}  // namespace mistuning_study_test
