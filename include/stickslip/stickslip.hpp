#pragma once
/// \file stickslip.hpp
/// \brief Umbrella header: every public component of stickslip.

#include "stickslip/version.hpp"
