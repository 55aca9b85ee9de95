// stickslip::compiled: FrictionDampedSystem<double> (dynamic modes, the default law variant),
// every member.
#include <stickslip/model/friction_damped_system.hpp>

template class stickslip::FrictionDampedSystem<double>;
