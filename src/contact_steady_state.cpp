// stickslip::compiled: the steady-state solvers of ContactSystem<double> (PointContact) - one
// period's run with its monodromy (run_period) and Shooting, every member.
#include <stickslip/model/contact_system.hpp>
#include <stickslip/steady_state.hpp>

STICKSLIP_DETAIL_CONTACT_STEADY_STATE(, stickslip::detail::CompiledPointContactSystem)
template class stickslip::Shooting<stickslip::ContactSystem<double>>;
