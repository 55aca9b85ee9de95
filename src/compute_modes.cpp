// stickslip::compiled: compute_modes<double> (the dense and the sparse eigensolvers).
#include <stickslip/modal/compute_modes.hpp>

template stickslip::ModalBasis<double> stickslip::compute_modes<double>(
    const stickslip::AssembledFrame<double>&, const stickslip::ModalOptions<double>&,
    stickslip::ModalSolveReport<double>*);
