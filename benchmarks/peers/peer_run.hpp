#pragma once
// What one run of one implementation reports, and the table of implementations.

#include <Eigen/Core>

#include <string>
#include <vector>

#include "peers/peer_problems.hpp"

namespace peers {

/// Result of integrating one problem over [0, t_end] at one tolerance setting.
struct RunOutcome {
  bool ok = false;
  std::string message;          // why not ok
  Eigen::VectorXd final_state;  // (x, x') at t_end
  std::vector<Event> events;
  long steps = 0;               // step attempts (accepted + rejected)
  long rhs_evaluations = 0;
  // The library's HybridStepper only (StepperStats), -1 elsewhere: of rhs_evaluations, those
  // spent on the state at events and on restarting after them.
  long event_state_rhs = -1, restart_rhs = -1;
};

/// One implementation: a name and a function integrating a problem at rtol = atol = tolerance.
/// The lead adds the library's modal-exact method as one more row of implementations() in
/// peer_benchmark.cpp (e.g. {"library_modal_exact", "library", &run_library<ModalExact>}).
struct Implementation {
  const char* name;
  const char* family;  // "library", "odeint" or "cvode": the ratio columns compare families
  RunOutcome (*run)(const ChainParameters&, double tolerance);
};

}  // namespace peers
