#pragma once
/// \file contact.hpp
/// \brief Umbrella header of component 4: contact states, friction laws, CoulombContact,
/// NewtonImpact (separation and impact).

#include <stickslip/contact/contact_state.hpp>
#include <stickslip/contact/coulomb_contact.hpp>
#include <stickslip/contact/coulomb_law.hpp>
#include <stickslip/contact/friction_law.hpp>
#include <stickslip/contact/newton_impact.hpp>
#include <stickslip/contact/regularised_law.hpp>
#include <stickslip/contact/stribeck_law.hpp>
