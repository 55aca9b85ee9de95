#pragma once
// An observer for the observer-independence tests: it counts the samples and, when `read` is
// set, calls evaluate() on the system at each of them (as a recorder of forces does). A run with
// read = false is the reference that a run with read = true must reproduce bitwise.
#include <stickslip/model.hpp>

namespace model_test {

template <class System>
struct ForceReader : stickslip::NullObserver {
  System* sys = nullptr;
  bool read = false;
  long samples = 0;
  double sum = 0;  ///< of the forces read (N and f), so that the evaluations are used
  template <class Scalar, class State, class Mode>
  bool on_sample(Scalar t, const State& x, const Mode& m) {
    ++samples;
    if (read) {
      const auto& e = sys->evaluate(m, t, x);
      sum += e.N.sum() + e.f.sum();
    }
    return true;
  }
};

}  // namespace model_test
