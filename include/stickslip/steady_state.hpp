#pragma once
/// \file steady_state.hpp
/// \brief Umbrella header of the steady-state component: periodic orbits by shooting, monodromy
/// with saltation matrices, Floquet multipliers and pseudo-arclength continuation (in parts on
/// several threads: SplitContinuation).

#include "stickslip/steady_state/bifurcation.hpp"
#include "stickslip/steady_state/branch_restart.hpp"
#include "stickslip/steady_state/contact_statistics.hpp"
#include "stickslip/steady_state/continuation.hpp"
#include "stickslip/steady_state/floquet.hpp"
#include "stickslip/steady_state/half_period_symmetry.hpp"
#include "stickslip/steady_state/orbit_probe.hpp"
#include "stickslip/steady_state/orbit_signal.hpp"
#include "stickslip/steady_state/peak_response.hpp"
#include "stickslip/steady_state/period_doubling.hpp"
#include "stickslip/steady_state/period_run.hpp"
#include "stickslip/steady_state/pitchfork.hpp"
#include "stickslip/steady_state/poincare.hpp"
#include "stickslip/steady_state/shooting.hpp"
#include "stickslip/steady_state/shooting_options.hpp"
#include "stickslip/steady_state/split_continuation.hpp"
#include "stickslip/steady_state/variational_system.hpp"

#ifdef STICKSLIP_COMPILED
// The compiled mode (docs/compiled.md): stickslip::compiled holds the steady-state solvers of
// the default model (src/steady_state.cpp), so that a unit using them does not instantiate them.
#include "stickslip/model/friction_damped_system.hpp"

namespace stickslip {
extern template PeriodRun<FrictionDampedSystem<double>> run_period<FrictionDampedSystem<double>>(
    FrictionDampedSystem<double>&, const FrictionDampedSystem<double>::Mode&, double,
    const FrictionDampedSystem<double>::State&, double, const ShootingOptions<double>&, bool);
extern template class Shooting<FrictionDampedSystem<double>>;
extern template class Continuation<FrictionDampedSystem<double>>;
extern template class SplitContinuation<FrictionDampedSystem<double>>;
}  // namespace stickslip
// run_period and Shooting on ContactSystem<double> (PointContact; src/contact_steady_state.cpp).
#include "stickslip/model/detail/compiled_contact_system.hpp"

#define STICKSLIP_DETAIL_CONTACT_STEADY_STATE(EXTERN, SYSTEM)                                    \
  EXTERN template ::stickslip::PeriodRun<SYSTEM> stickslip::run_period<SYSTEM>(                  \
      SYSTEM&, const SYSTEM::Mode&, double, const SYSTEM::State&, double,                        \
      const ::stickslip::ShootingOptions<double>&, bool);
STICKSLIP_DETAIL_CONTACT_STEADY_STATE(extern, stickslip::detail::CompiledPointContactSystem)
extern template class stickslip::Shooting<stickslip::ContactSystem<double>>;
#endif
