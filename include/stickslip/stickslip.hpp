#pragma once
/// \file stickslip.hpp
/// \brief Umbrella header: every public component of stickslip.

#include "stickslip/version.hpp"
#include "stickslip/beam.hpp"
#include "stickslip/modal.hpp"
#include "stickslip/moving_load.hpp"
#include "stickslip/contact.hpp"
#include "stickslip/ode.hpp"
#include "stickslip/model.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/steady_state.hpp"
#include "stickslip/disk.hpp"
