#pragma once
/// \file beam.hpp
/// \brief Component 1 (beam): plane Euler-Bernoulli frame elements, frame models and assembly.

#include "stickslip/beam/assembled_frame.hpp"
#include "stickslip/beam/dof.hpp"
#include "stickslip/beam/dof_map.hpp"
#include "stickslip/beam/frame_element.hpp"
#include "stickslip/beam/frame_member.hpp"
#include "stickslip/beam/frame_model.hpp"
#include "stickslip/beam/ids.hpp"
#include "stickslip/beam/mass_type.hpp"
#include "stickslip/beam/section_properties.hpp"
