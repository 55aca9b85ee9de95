#pragma once
/// \file compiled_simulate.hpp
/// \brief The compiled mode (STICKSLIP_COMPILED, set by linking stickslip::compiled): simulate()'s
/// runs on FrictionDampedSystem<double> (dynamic modes, the default law variant) are declared
/// extern here and instantiated once, in the stickslip_compiled library (src/), not in every
/// translation unit that calls simulate(). See docs/compiled.md.

#include "stickslip/model/friction_damped_system.hpp"
#include "stickslip/model/simulate.hpp"

/// Declares (EXTERN = extern) or defines (EXTERN empty) the instantiation of simulate()'s run
/// with one method on SYSTEM (a type name without commas).
#define STICKSLIP_DETAIL_SIMULATE_WITH(EXTERN, SYSTEM, METHOD)                                  \
  EXTERN template ::stickslip::SimulationResult<SYSTEM>                                          \
  stickslip::detail::simulate_with<SYSTEM, METHOD>(                                              \
      SYSTEM&, SYSTEM::Mode, SYSTEM::Scalar, const SYSTEM::State&, SYSTEM::Scalar,               \
      const ::stickslip::StepperOptions<SYSTEM::Scalar>&, ::stickslip::SimulationObserver<SYSTEM>);

/// The same for the exponential run and for the dispatcher.
#define STICKSLIP_DETAIL_SIMULATE_EXPONENTIAL(EXTERN, SYSTEM)                                    \
  EXTERN template ::stickslip::SimulationResult<SYSTEM>                                          \
  stickslip::detail::simulate_exponential<SYSTEM>(                                               \
      SYSTEM&, SYSTEM::Mode, SYSTEM::Scalar, const SYSTEM::State&, SYSTEM::Scalar,               \
      const ::stickslip::StepperOptions<SYSTEM::Scalar>&, ::stickslip::SimulationObserver<SYSTEM>);
#define STICKSLIP_DETAIL_SIMULATE_DISPATCH(EXTERN, SYSTEM)                                       \
  EXTERN template ::stickslip::SimulationResult<SYSTEM>                                          \
  stickslip::detail::simulate_dispatch<SYSTEM>(                                                  \
      SYSTEM&, SYSTEM::Mode, SYSTEM::Scalar, const SYSTEM::State&, SYSTEM::Scalar,               \
      const ::stickslip::RunOptions<SYSTEM::Scalar>&, ::stickslip::SimulationObserver<SYSTEM>);

namespace stickslip::detail {
/// The system type the compiled mode instantiates.
using CompiledSystem = FrictionDampedSystem<double>;
}  // namespace stickslip::detail

STICKSLIP_DETAIL_SIMULATE_WITH(extern, stickslip::detail::CompiledSystem, stickslip::RungeKutta4)
STICKSLIP_DETAIL_SIMULATE_WITH(extern, stickslip::detail::CompiledSystem, stickslip::DormandPrince54)
STICKSLIP_DETAIL_SIMULATE_WITH(extern, stickslip::detail::CompiledSystem, stickslip::Rosenbrock23)
STICKSLIP_DETAIL_SIMULATE_EXPONENTIAL(extern, stickslip::detail::CompiledSystem)
STICKSLIP_DETAIL_SIMULATE_DISPATCH(extern, stickslip::detail::CompiledSystem)
