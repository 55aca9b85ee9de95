// Stability at the extremes of the inputs (docs/stability.md, "Input limits"): absurd option
// values are refused by name with their stated limit before anything is allocated.
#include "stability/stability_support.hpp"

#include <climits>
#include <stdexcept>
#include <string>

namespace input_limits {  // named: the stability files may share one (unity) translation unit
namespace {
using namespace stability;

// zeno_max_events sizes a ring buffer of event times: LONG_MAX threw std::length_error from the
// stepper's constructor and 1e9 allocated 8 GB for a 1 ms run. Both are now refused by name with
// the limit 1e6 (8 MB); the limit itself is accepted and the run succeeds.
TEST(InputLimits, ZenoMaxEventsAboveTheLimitIsRefusedByName) {
  const TScene s = make_t_frame(2, 4, 2);
  System sys(s.frame, s.basis, paper_dampers(s, 10.0), paper_load(s));
  NullObserver observer;
  RunOptions<double> run;
  for (long n : {LONG_MAX, 1'000'000'000L, 1'000'001L}) {
    run.stepper.zeno_max_events = n;
    try {
      simulate(sys, sys.requested_mode(), 0.0, sys.initial_state(), 1e-3, run, observer);
      ADD_FAILURE() << "zeno_max_events = " << n << " was accepted";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("options.zeno_max_events must be in [1, 1000000]"), std::string::npos) << what;
      EXPECT_NE(what.find(std::to_string(n)), std::string::npos) << what;
    }
  }
  run.stepper.zeno_max_events = 1'000'000;
  EXPECT_TRUE(simulate(sys, sys.requested_mode(), 0.0, sys.initial_state(), 1e-3, run, observer).ok());
}

}  // namespace
}  // namespace input_limits
