// stickslip::compiled: the steady-state solvers of FrictionDampedSystem<double> - one period's
// run with its monodromy (run_period), Shooting, Continuation and SplitContinuation, every member.
#include <stickslip/model/friction_damped_system.hpp>
#include <stickslip/steady_state.hpp>

namespace stickslip {
template PeriodRun<FrictionDampedSystem<double>> run_period<FrictionDampedSystem<double>>(
    FrictionDampedSystem<double>&, const FrictionDampedSystem<double>::Mode&, double,
    const FrictionDampedSystem<double>::State&, double, const ShootingOptions<double>&, bool);
template class Shooting<FrictionDampedSystem<double>>;
template class Continuation<FrictionDampedSystem<double>>;
template class SplitContinuation<FrictionDampedSystem<double>>;
}  // namespace stickslip
