#pragma once
/// \file moving_load.hpp
/// \brief Component 3 (moving_load): retained modes and their derivatives at an arbitrary point
/// of a member, for loads that move along it (paper eqs 4-7, 10, 18-29). See docs/moving_load.md.

#include "stickslip/moving_load/element_shape_functions.hpp"
#include "stickslip/moving_load/end_policy.hpp"
#include "stickslip/moving_load/member_nodal_modes.hpp"
#include "stickslip/moving_load/member_shapes.hpp"
#include "stickslip/moving_load/shape_values.hpp"
