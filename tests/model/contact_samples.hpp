#pragma once
// Shared by the ContactSystem tests: an observer that records the output samples, and tight
// run options (rtol 1e-10, atol 1e-14) whose integration error the tests' tolerances assume.

#include <stickslip/stickslip.hpp>

#include <Eigen/Core>

#include <vector>

namespace contact_samples {

/// Records the response at output samples.
struct Samples : stickslip::NullObserver {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> x;
  template <class S, class X, class M>
  bool on_sample(S time, const X& state, const M&) {
    t.push_back(time);
    x.push_back(state);
    return true;
  }
};

/// Dormand-Prince at rtol 1e-10, atol 1e-14, samples every `output_interval` (0: none).
inline stickslip::RunOptions<double> tight(double output_interval) {
  stickslip::RunOptions<double> run;
  // Named, so that scenes of either contact type run the same method (Integrator::Auto would run
  // an exactly linear PointContact scene by the exponential method and a mixed one by DOPRI).
  run.integrator = stickslip::Integrator::DormandPrince54;
  run.stepper.rtol = 1e-10;
  run.stepper.atol = 1e-14;
  run.stepper.output_interval = output_interval;
  return run;
}

}  // namespace contact_samples
