// Mistuning studies: the amplification factor over Monte Carlo samples as a sweep, against
// references that do not come from the study: delta = 0 gives exactly the tuned disk (1), the
// rows do not depend on the thread count, and a lumped ring of coupled oscillators (one mode per
// blade, the dampers stuck into the coupling) stays below Whitehead's bound (1 + sqrt N) / 2.

#include "contact/contact_test_util.hpp"
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

namespace disk_study_inputs_test {

using namespace disk_samples;

// Bad input to the dampers, the shift, the travelling-wave solvers and the study is refused
// naming the parameter.
TEST(DiskStudyInputs, BadInputIsRefusedNamingTheParameter) {
  using contact_test::expect_invalid_argument;
  const Disk disk(4, kPitch, builder(), SectorCoupling<double>::springs(1e4, 1e4, 10.0));
  NeighbourDamperSpec<double> spec;
  spec.mass = 0.01;
  spec.inertia = 1e-7;
  spec.preload = 10.0;
  expect_invalid_argument([&] { neighbour_wedge_dampers(disk, {MemberId(7), 0.0}, {kPlatformMember, 0.0}, spec); },
                          {"neighbour_wedge_dampers", "right_wing.member"});
  spec.left.angle = 2.0;
  expect_invalid_argument([&] { neighbour_wedge_dampers(disk, {kPlatformMember, kPlatform}, {kPlatformMember, 0.0}, spec); },
                          {"wedge_damper", "left.angle"});
  // The annulus basis with one mode of the h = 1 pair dropped: not closed under the shift.
  CyclicModalOptions<double> co;
  co.num_modes = 1;
  const auto cm = compute_cyclic_modes(disk, co);
  const ModalBasis<double> whole = annulus_basis(disk, cm);
  Eigen::Index twin = 0;
  while (twin + 1 < whole.size() && whole.omega()(twin) != whole.omega()(twin + 1)) ++twin;
  ASSERT_LT(twin + 1, whole.size());
  std::vector<Eigen::Index> keep;
  for (Eigen::Index j = 0; j < whole.size(); ++j)
    if (j != twin + 1) keep.push_back(j);
  const ModalBasis<double> split(whole.omega()(keep), whole.phi()(Eigen::all, keep), disk.annulus_dofs(),
                                 disk.frame().id(), 0);
  ModalOptions<double> mo;
  mo.num_modes = 2;
  mo.solver = ModalSolver::Dense;
  expect_invalid_argument([&] { modal_cyclic_shift(disk, split, 1); }, {"modal_cyclic_shift", "basis"});
  expect_invalid_argument([&] { modal_cyclic_shift(disk, whole, 4); }, {"modal_cyclic_shift", "sigma"});
  const Disk mistuned(4, kPitch, builder(), SectorCoupling<double>::springs(1e4, 1e4, 10.0), {0.0, 0.01, 0.0, 0.0});
  const ModalBasis<double> mb = compute_modes(mistuned.assemble(), mo);
  expect_invalid_argument([&] { modal_cyclic_shift(mistuned, mb, 1); }, {"modal_cyclic_shift", "disk"});
  // The orthogonality the solver relies on holds for whole families (round-off).
  const Eigen::MatrixXd S = modal_cyclic_shift(disk, whole, 1);
  EXPECT_LE((S.transpose() * S - Eigen::MatrixXd::Identity(S.rows(), S.cols())).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_THROW(engine_order_symmetry(1, 1), std::invalid_argument);

  using System = ContactSystem<double>;
  const std::function<System(double)> make = [&](double W) {
    return System(disk.frame(), whole, {}, engine_order_loads(disk, kBladeMember, kBlade, LoadDirection::GlobalX, 1.0, W, 1));
  };
  const std::function<TravellingWaveShift<double>(const System&)> shift = [&](const System& s) {
    return travelling_wave_shift(disk, whole, s, 1);
  };
  const System sys = make(300.0);
  expect_invalid_argument([&] { travelling_wave_sweep<System>(make, shift, {}, sys.requested_mode(), sys.initial_state()); },
                          {"travelling_wave_sweep", "omegas"});
  expect_invalid_argument([&] { travelling_wave_sweep<System>(make, shift, {300.0, -1.0}, sys.requested_mode(), sys.initial_state()); },
                          {"travelling_wave_sweep", "omegas[1]"});
  System s2 = make(300.0);
  TravellingWaveShooting<System> tw(s2, shift(s2));
  expect_invalid_argument([&] { tw.solve(s2.requested_mode(), 0.0, s2.initial_state(), -1.0); },
                          {"TravellingWaveShooting", "period"});
  const std::function<BladePeak<double>(const std::vector<double>&)> none;
  expect_invalid_argument([&] { mistuning_study<double>(4, 0.01, 2, 1, none); }, {"mistuning_study", "peak"});
  const std::function<BladePeak<double>(const std::vector<double>&)> one = [](const std::vector<double>&) {
    return BladePeak<double>{1.0, 0};
  };
  expect_invalid_argument([&] { mistuning_study<double>(4, -0.01, 2, 1, one); }, {"mistuning_study", "sigma"});
  expect_invalid_argument([&] {
    engine_order_blade_peak(disk, NodeId(3), Dof::X, 1.0, 1, kTip, Dof::X, std::vector<double>{300.0}, 0.01, 4);
  }, {"engine_order_blade_peak", "load_node"});  // node 3: the clamped root
}

}  // namespace disk_study_inputs_test
