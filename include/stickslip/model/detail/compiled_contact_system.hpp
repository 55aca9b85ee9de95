#pragma once
/// \file compiled_contact_system.hpp
/// \brief The compiled mode (STICKSLIP_COMPILED, set by linking stickslip::compiled): the
/// contact systems that more than one of a program's units typically build -
/// ContactSystem<double> (PointContact) and ContactSystem<double, BodyContact<double>> - and
/// simulate()'s runs on them are declared extern here and instantiated once, in the
/// stickslip_compiled library (src/contact_system_point.cpp, src/contact_system_body.cpp), not in
/// every translation unit that builds a contact scene. Shooting on ContactSystem<double> is
/// declared in <stickslip/steady_state.hpp>. See docs/compiled.md.

#include "stickslip/model/body_contact.hpp"
#include "stickslip/model/contact_system.hpp"
#include "stickslip/model/detail/compiled_simulate.hpp"
#include "stickslip/model/point_contact.hpp"
#include "stickslip/model/simulate.hpp"

namespace stickslip::detail {
/// The contact systems the compiled mode instantiates (names without commas for the macros).
using CompiledPointContactSystem = ContactSystem<double, PointContact<double>>;
using CompiledBodyContactSystem = ContactSystem<double, BodyContact<double>>;
}  // namespace stickslip::detail

/// Declares (EXTERN = extern) or defines (EXTERN empty) the instantiation of simulate()'s runs
/// on SYSTEM: each method, the exponential run, the dispatcher.
#define STICKSLIP_DETAIL_CONTACT_SIMULATE(EXTERN, SYSTEM)                                        \
  STICKSLIP_DETAIL_SIMULATE_WITH(EXTERN, SYSTEM, ::stickslip::RungeKutta4)                       \
  STICKSLIP_DETAIL_SIMULATE_WITH(EXTERN, SYSTEM, ::stickslip::DormandPrince54)                   \
  STICKSLIP_DETAIL_SIMULATE_WITH(EXTERN, SYSTEM, ::stickslip::Rosenbrock23)                      \
  STICKSLIP_DETAIL_SIMULATE_EXPONENTIAL(EXTERN, SYSTEM)                                          \
  STICKSLIP_DETAIL_SIMULATE_DISPATCH(EXTERN, SYSTEM)

/// Declares (EXTERN = extern) or defines (EXTERN empty) the instantiation of each member of
/// SYSTEM defined outside the class body, but for the members of contacts with a rigid-body
/// side, which a PointContact system never calls (`template class` would compile them too, and
/// they do not compile for a contact without that side). SYSTEM is a template-id (a typedef may
/// not qualify an explicit instantiation) without a leading :: (which would bind to the return
/// type before it): stickslip::ContactSystem<double>.
#define STICKSLIP_DETAIL_CONTACT_MEMBERS(EXTERN, SYSTEM)                                         \
  EXTERN template SYSTEM::ContactSystem(const ::stickslip::FrameModel<double>&,                 \
                                        const ::stickslip::ModalBasis<double>&,                  \
                                        std::vector<SYSTEM::Body>, std::vector<SYSTEM::Contact>, \
                                        std::vector<SYSTEM::Load>, SYSTEM::Options);             \
  EXTERN template SYSTEM::State SYSTEM::initial_state() const;                                   \
  EXTERN template SYSTEM::Mode SYSTEM::requested_mode() const;                                   \
  EXTERN template void SYSTEM::validate_state(const SYSTEM::Mode&, const SYSTEM::State&,        \
                                              const char*) const;                                \
  EXTERN template bool SYSTEM::make_consistent(SYSTEM::Mode&, double, SYSTEM::State&);           \
  EXTERN template void SYSTEM::rhs(const SYSTEM::Mode&, double, const SYSTEM::State&,            \
                                   SYSTEM::State&);                                              \
  EXTERN template SYSTEM::Index SYSTEM::num_guards(const SYSTEM::Mode&) const;                   \
  EXTERN template void SYSTEM::guards(const SYSTEM::Mode&, double, const SYSTEM::State&,         \
                                      SYSTEM::GuardVector&);                                     \
  EXTERN template ::stickslip::CrossingDirection SYSTEM::guard_direction(const SYSTEM::Mode&,    \
                                                                         SYSTEM::Index) const;   \
  EXTERN template ::stickslip::TransitionAction SYSTEM::transition(                              \
      SYSTEM::Mode&, const ::stickslip::TriggeredGuards&, double, SYSTEM::State&);               \
  EXTERN template const SYSTEM::Evaluation& SYSTEM::evaluate(const SYSTEM::Mode&, double,        \
                                                             const SYSTEM::State&);              \
  EXTERN template double SYSTEM::mechanical_energy(const SYSTEM::State&) const;                  \
  EXTERN template SYSTEM::EnergyBalance SYSTEM::energy_balance(const SYSTEM::State&, double)     \
      const;                                                                                     \
  EXTERN template std::vector<std::complex<double>> SYSTEM::linear_rates() const;                \
  EXTERN template bool SYSTEM::linear_part(const SYSTEM::Mode&, double, const SYSTEM::State&,    \
                                           ::stickslip::LinearPart<double>&);                    \
  EXTERN template bool SYSTEM::exact_mode(const SYSTEM::Mode&) const;

STICKSLIP_DETAIL_CONTACT_MEMBERS(extern, stickslip::ContactSystem<double>)
namespace stickslip {
extern template class ContactSystem<double, BodyContact<double>>;
}  // namespace stickslip
STICKSLIP_DETAIL_CONTACT_SIMULATE(extern, stickslip::detail::CompiledPointContactSystem)
STICKSLIP_DETAIL_CONTACT_SIMULATE(extern, stickslip::detail::CompiledBodyContactSystem)
