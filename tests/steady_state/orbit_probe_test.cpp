// Probes (orbit_probe.hpp): an orbit's outputs in metres at user-chosen structure points, from the
// run that closed the orbit. Reference: a damped cantilever without dampers under a harmonic tip
// load F sin(W t) is linear, and its steady response at a point is the receptance times the
// force, u(t) = Im(H F e^{i W t}), H = sum_j psi_j phi_j / (omega_j^2 - W^2 + i c_j W), with the
// mode rows psi (probe) and phi (load) taken from FrictionDampedSystem::point_shape (the load
// path of the model, not structure_point_row which the probes use).

#include <stickslip/steady_state.hpp>

#include <gtest/gtest.h>

#include <complex>
#include <vector>

namespace steady_state_probe_test {  // named: the steady-state test files share one unity TU
namespace {

using System = stickslip::FrictionDampedSystem<double>;

struct Beam {
  stickslip::FrameModel<double> frame;
  stickslip::MemberId member = 0;
  stickslip::ModalBasis<double> basis;
  double length = 0.2;
};

// A 0.2 m steel cantilever along x, 8 elements, 3 modes with 2 % modal damping.
Beam make_beam() {
  Beam b;
  const stickslip::SectionProperties<double> sec{2.06e11, 7800.0, 6e-5, 2e-11};
  const auto root = b.frame.add_node(0.0, 0.0), tip = b.frame.add_node(b.length, 0.0);
  b.member = b.frame.add_member(root, tip, sec, 8);
  b.frame.clamp(root);
  stickslip::ModalOptions<double> mo;
  mo.num_modes = 3;
  b.basis = stickslip::compute_modes(b.frame.assemble(), mo).with_modal_damping(Eigen::Vector3d::Constant(0.02));
  return b;
}

TEST(SteadyStateProbes, LinearCantileverProbeAmplitudesAreTheReceptanceTimesTheForce) {
  const Beam b = make_beam();
  const double F = 2.0;
  const double w1 = b.basis.omega()[0], W = 1.3 * w1;  // between the first two modes
  const double T = 2 * 3.14159265358979323846 / W;
  using Load = System::Load;
  System sys(b.frame, b.basis, {}, {Load::harmonic(b.member, b.length, stickslip::LoadDirection::GlobalY, F, W)});
  // Probes: mid-span displacement along Y, along a 30-degree direction, and the tip velocity.
  std::vector<stickslip::OrbitProbe<double>> probes(3);
  probes[0].point = {b.member, 0.1};
  probes[0].direction = stickslip::PlaneDirection<double>::global_y();
  probes[1].point = {b.member, 0.15};
  probes[1].direction = stickslip::PlaneDirection<double>::at_angle(0.5236);
  probes[2].point = {b.member, b.length};
  probes[2].direction = stickslip::PlaneDirection<double>::global_y();
  probes[2].quantity = stickslip::ProbeQuantity::Velocity;
  stickslip::ShootingOptions<double> opt;
  opt.periodic = stickslip::ShootingOptions<double>::first(2 * sys.num_modes());  // q, q' (not the audit)
  opt.samples_per_period = 64;
  stickslip::set_probes(opt, sys, b.frame, b.basis, probes, 3);
  stickslip::Shooting<System> shooting(sys, opt);
  const auto orbit = shooting.forced(sys.requested_mode(), 0.0, sys.initial_state(), T);
  ASSERT_TRUE(orbit.ok()) << orbit.message;
  ASSERT_EQ(orbit.outputs.size(), 3u);

  // The receptance from the model's own load rows: psi_Y at x, psi_X at x (the 30-degree probe
  // is cos a psi_X + sin a psi_Y), phi at the tip.
  const Eigen::VectorXd phi = sys.point_shape(b.member, b.length, stickslip::LoadDirection::GlobalY);
  const auto receptance = [&](const Eigen::VectorXd& psi) {
    std::complex<double> h = 0;
    for (Eigen::Index j = 0; j < psi.size(); ++j)
      h += psi[j] * phi[j] /
           std::complex<double>(sys.omega_squared()[j] - W * W, b.basis.damping_coefficients()[j] * W);
    return h;
  };
  const double a = 0.5236;
  const std::complex<double> h[3] = {
      receptance(sys.point_shape(b.member, 0.1, stickslip::LoadDirection::GlobalY)),
      receptance(std::cos(a) * sys.point_shape(b.member, 0.15, stickslip::LoadDirection::GlobalX) +
                 std::sin(a) * sys.point_shape(b.member, 0.15, stickslip::LoadDirection::GlobalY)),
      std::complex<double>(0, W) * receptance(sys.point_shape(b.member, b.length, stickslip::LoadDirection::GlobalY))};
  for (int j = 0; j < 3; ++j) {
    SCOPED_TRACE(::testing::Message() << "probe " << j);
    const auto& s = orbit.outputs[static_cast<std::size_t>(j)];
    const double amp = std::abs(h[j]) * F;
    ASSERT_GT(amp, 0);
    // Fourier coefficients of y = Im(H F e^{iWt}) = F (Re H sin Wt + Im H cos Wt): exact on the 64
    // samples for a pure harmonic; the orbit's state is right to the Newton tolerance 1e-9 and the
    // runs' rtol 1e-10 (relative), so 1e-6 of the amplitude leaves a margin of 1000.
    EXPECT_NEAR(s.harmonic(1), amp, 1e-6 * amp);
    EXPECT_NEAR(s.cosines[0], F * h[j].imag(), 1e-6 * amp);
    EXPECT_NEAR(s.sines[0], F * h[j].real(), 1e-6 * amp);
    EXPECT_NEAR(s.mean, 0.0, 1e-6 * amp);
    EXPECT_NEAR(s.harmonic(2), 0.0, 1e-6 * amp);
    EXPECT_NEAR(s.harmonic(3), 0.0, 1e-6 * amp);
    // Extremes over steps, events and samples: a sampled sine is short of its peak by at most
    // 1 - cos(pi / 64) = 1.2e-3 of its amplitude (and the steps fall between the samples).
    EXPECT_NEAR(s.amplitude(), amp, 1.3e-3 * amp);
    EXPECT_LE(s.amplitude(), amp * (1 + 1e-6));
  }
}

TEST(SteadyStateProbes, BadProbesAreRefusedNamingThem) {
  const Beam b = make_beam();
  System sys(b.frame, b.basis, {}, {System::Load::harmonic(b.member, b.length, stickslip::LoadDirection::GlobalY, 1.0, 100.0)});
  stickslip::ShootingOptions<double> opt;
  std::vector<stickslip::OrbitProbe<double>> probes(2);
  probes[1].point = {b.member, 0.3};  // beyond the 0.2 m member
  try {
    stickslip::set_probes(opt, sys, b.frame, b.basis, probes);
    FAIL() << "a point off the member was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("probes[1]"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("coordinate"), std::string::npos) << e.what();
  }
  probes[1].point = {b.member, 0.1};
  probes[0].direction = {1.0, 1.0};  // not a unit vector
  EXPECT_THROW(stickslip::set_probes(opt, sys, b.frame, b.basis, probes), std::invalid_argument);
}

}  // namespace
}  // namespace steady_state_probe_test
