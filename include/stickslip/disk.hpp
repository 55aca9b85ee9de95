#pragma once
/// \file disk.hpp
/// \brief Bladed disks: N sectors coupled in a cyclic chain, cyclic-symmetry modes, engine-order
/// excitation, mistuning, friction joints and wedge dampers between neighbouring platforms (docs/disks.md).

#include "stickslip/disk/bladed_disk.hpp"
#include "stickslip/disk/cyclic_modes.hpp"
#include "stickslip/disk/cyclic_shift.hpp"
#include "stickslip/disk/engine_order.hpp"
#include "stickslip/disk/mistuning.hpp"
#include "stickslip/disk/mistuning_study.hpp"
#include "stickslip/disk/neighbour_dampers.hpp"
#include "stickslip/disk/neighbour_joints.hpp"
#include "stickslip/disk/sector_coupling.hpp"
#include "stickslip/disk/travelling_wave.hpp"
#include "stickslip/disk/travelling_wave_sweep.hpp"
