// stickslip::compiled: simulate()'s run with Rosenbrock23 on FrictionDampedSystem<double> (one
// translation unit per method, so that they compile in parallel).
#include <stickslip/model/detail/compiled_simulate.hpp>

STICKSLIP_DETAIL_SIMULATE_WITH(, stickslip::detail::CompiledSystem, stickslip::Rosenbrock23)
