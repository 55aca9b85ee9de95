#pragma once
/// \file sweep.hpp
/// \brief Sweeps of independent runs: serial and thread backends, the journal that keeps finished
/// rows for a resumed sweep (the MPI backend,
/// stickslip/sweep/sweep_mpi.hpp, is included on its own since it needs <mpi.h>).

#include "stickslip/sweep/sweep.hpp"
#include "stickslip/sweep/sweep_journal.hpp"
