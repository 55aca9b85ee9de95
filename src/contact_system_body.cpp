// stickslip::compiled: ContactSystem<double, BodyContact<double>>, every member, and simulate()'s
// runs on it (each method, the exponential run, the dispatcher).
#include <stickslip/model/detail/compiled_contact_system.hpp>

template class stickslip::ContactSystem<double, stickslip::BodyContact<double>>;
STICKSLIP_DETAIL_CONTACT_SIMULATE(, stickslip::detail::CompiledBodyContactSystem)
