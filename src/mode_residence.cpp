// stickslip::compiled: mode_residence<double> (Integrator::Auto's proof that a run stays in its
// start mode).
#include <stickslip/ode/mode_residence.hpp>

template stickslip::ModeResidence<double> stickslip::mode_residence<double>(
    const stickslip::LinearPart<double>&, double, const Eigen::Matrix<double, Eigen::Dynamic, 1>&, double);
