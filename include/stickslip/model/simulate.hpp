#pragma once
/// \file simulate.hpp
/// \brief Run a hybrid system with an integrator chosen at run time (command lines, sweeps).

#include "stickslip/detail/validate.hpp"
#include "stickslip/ode.hpp"

#include <cstdint>
#include <string>

namespace stickslip {

/// Integrators of component 5, selectable at run time.
enum class Integrator : std::uint8_t {
  RungeKutta4,      ///< fixed step StepperOptions::fixed_step (the paper's method)
  DormandPrince54,  ///< adaptive explicit 5(4) with dense output
  Rosenbrock23      ///< adaptive linearly implicit, stiffly stable
};

/// "rk4", "dopri5", "rosenbrock23".
inline const char* to_string(Integrator i) noexcept {
  switch (i) {
    case Integrator::RungeKutta4: return "rk4";
    case Integrator::DormandPrince54: return "dopri5";
    case Integrator::Rosenbrock23: return "rosenbrock23";
  }
  return "unknown";
}

/// Parses "rk4" | "dopri5" | "rosenbrock23"; throws std::invalid_argument otherwise.
inline Integrator parse_integrator(const std::string& name) {
  if (name == "rk4") return Integrator::RungeKutta4;
  if (name == "dopri5" || name == "dopri") return Integrator::DormandPrince54;
  if (name == "rosenbrock23" || name == "rosenbrock" || name == "stiff") return Integrator::Rosenbrock23;
  detail::throw_invalid("parse_integrator", "integrator must be rk4, dopri5 or rosenbrock23", name);
}

/// Integrator and stepper options of one run.
template <class Scalar>
struct RunOptions {
  Integrator integrator = Integrator::DormandPrince54;
  StepperOptions<Scalar> stepper{};
};

/// Integrates `system` from (t0, x0) in `mode` to t_end with the chosen integrator.
template <class System, class Observer>
HybridResult<typename System::Scalar, typename System::State, typename System::Mode> simulate(
    System& system, typename System::Mode mode, typename System::Scalar t0,
    const typename System::State& x0, typename System::Scalar t_end,
    const RunOptions<typename System::Scalar>& options, Observer& observer) {
  switch (options.integrator) {
    case Integrator::RungeKutta4: {
      HybridStepper<System, RungeKutta4> stepper(system, options.stepper);
      return stepper.integrate(mode, t0, x0, t_end, observer);
    }
    case Integrator::Rosenbrock23: {
      HybridStepper<System, Rosenbrock23> stepper(system, options.stepper);
      return stepper.integrate(mode, t0, x0, t_end, observer);
    }
    case Integrator::DormandPrince54: break;
  }
  HybridStepper<System, DormandPrince54> stepper(system, options.stepper);
  return stepper.integrate(mode, t0, x0, t_end, observer);
}

}  // namespace stickslip
