#pragma once
/// \file steady_state.hpp
/// \brief Umbrella header of the steady-state component: periodic orbits by shooting, monodromy
/// with saltation matrices, Floquet multipliers and pseudo-arclength continuation.

#include "stickslip/steady_state/continuation.hpp"
#include "stickslip/steady_state/floquet.hpp"
#include "stickslip/steady_state/period_run.hpp"
#include "stickslip/steady_state/shooting.hpp"
#include "stickslip/steady_state/shooting_options.hpp"
#include "stickslip/steady_state/variational_system.hpp"
