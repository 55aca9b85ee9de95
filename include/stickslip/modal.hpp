#pragma once
/// \file modal.hpp
/// \brief Component 2 (modal): natural frequencies, mass-normalised modes and modal damping.

#include "stickslip/modal/compute_modes.hpp"
#include "stickslip/modal/modal_basis.hpp"
#include "stickslip/modal/modal_options.hpp"

