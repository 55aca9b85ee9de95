// stickslip::compiled: ContactSystem<double> (PointContact), its members, and simulate()'s runs
// on it (each method, the exponential run, the dispatcher).
#include <stickslip/model/detail/compiled_contact_system.hpp>

STICKSLIP_DETAIL_CONTACT_MEMBERS(, stickslip::ContactSystem<double>)
STICKSLIP_DETAIL_CONTACT_SIMULATE(, stickslip::detail::CompiledPointContactSystem)
