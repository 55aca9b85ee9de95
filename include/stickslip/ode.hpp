#pragma once
/// \file ode.hpp
/// \brief Umbrella header of component 5: hybrid systems, integration methods, event location
/// and HybridStepper.

#include "stickslip/ode/dormand_prince54.hpp"
#include "stickslip/ode/event_locator.hpp"
#include "stickslip/ode/hybrid_stepper.hpp"
#include "stickslip/ode/hybrid_system.hpp"
#include "stickslip/ode/linear_part.hpp"
#include "stickslip/ode/rosenbrock23.hpp"
#include "stickslip/ode/runge_kutta4.hpp"
#include "stickslip/ode/step_rate.hpp"
#include "stickslip/ode/stepper_options.hpp"
