#pragma once
/// \file model.hpp
/// \brief Composition layer: friction-damped modal systems built from the five components.

#include "stickslip/model/contact_point.hpp"
#include "stickslip/model/contact_system.hpp"
#include "stickslip/model/damper_states.hpp"
#include "stickslip/model/damper_statistics.hpp"
#include "stickslip/model/friction_damped_system.hpp"
#include "stickslip/model/member_end.hpp"
#include "stickslip/model/model_options.hpp"
#include "stickslip/model/normal_load.hpp"
#include "stickslip/model/point_contact.hpp"
#include "stickslip/model/body_contact.hpp"
#include "stickslip/model/rigid_body.hpp"
#include "stickslip/model/wedge_damper.hpp"
#include "stickslip/model/point_damper.hpp"
#include "stickslip/model/point_load.hpp"
#include "stickslip/model/separation.hpp"
#include "stickslip/model/simulate.hpp"
#include "stickslip/model/static_preload.hpp"
#include "stickslip/model/structure_point.hpp"
#include "stickslip/model/stuck_modes.hpp"
#include "stickslip/model/trade_study.hpp"
