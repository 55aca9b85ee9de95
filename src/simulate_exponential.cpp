// stickslip::compiled: simulate()'s exponential run (ExactLinearStepper) and its dispatcher on
// FrictionDampedSystem<double>.
#include <stickslip/model/detail/compiled_simulate.hpp>

STICKSLIP_DETAIL_SIMULATE_EXPONENTIAL(, stickslip::detail::CompiledSystem)
STICKSLIP_DETAIL_SIMULATE_DISPATCH(, stickslip::detail::CompiledSystem)
