#pragma once
// The problems with SUNDIALS CVODE as a user would write them: Adams-Moulton (the non-stiff
// method) with the fixed-point nonlinear solver, CVodeRootInit with the mode's guards and their
// directions, and on CV_ROOT_RETURN the mode switch followed by CVodeReInit.

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <Eigen/Core>

#include <string>

#include "peers/peer_problems.hpp"
#include "peers/peer_run.hpp"

namespace peers {

template <int N>
struct CvodeChainData {
  const Chain<N>* chain;
  ContactState mode;
  long rhs_evaluations = 0;
};

template <int N>
int cvode_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data) {
  auto* d = static_cast<CvodeChainData<N>*>(user_data);
  ++d->rhs_evaluations;
  const double* s = N_VGetArrayPointer(y);
  double* ds = N_VGetArrayPointer(ydot);
  using Vec = typename Chain<N>::Vec;
  Vec a;
  d->chain->acceleration(d->mode, t, Eigen::Map<const Vec>(s), Eigen::Map<const Vec>(s + N), a);
  for (int i = 0; i < N; ++i) {
    ds[i] = s[N + i];
    ds[N + i] = a[i];
  }
  return 0;
}

template <int N>
int cvode_guards(sunrealtype t, N_Vector y, sunrealtype* g, void* user_data) {
  const auto* d = static_cast<const CvodeChainData<N>*>(user_data);
  const double* s = N_VGetArrayPointer(y);
  using Vec = typename Chain<N>::Vec;
  d->chain->guards(d->mode, t, Eigen::Map<const Vec>(s), Eigen::Map<const Vec>(s + N), g);
  return 0;
}

template <int N>
RunOutcome run_cvode_n(const ChainParameters& p, double tolerance) {
  using Vec = typename Chain<N>::Vec;
  const Chain<N> chain(p);
  RunOutcome out;
  CvodeChainData<N> data{&chain, ContactState::Stick, 0};
  data.mode = decide_mode(p, p.v0[p.friction_dof] - p.belt_speed,
                          chain.stick_force(0.0, p.x0.head<N>(), p.v0.head<N>()));

  SUNContext ctx = nullptr;
  if (SUNContext_Create(nullptr, &ctx) != 0) {
    out.message = "SUNContext_Create failed";
    return out;
  }
  N_Vector y = N_VNew_Serial(2 * N, ctx);
  double* ys = N_VGetArrayPointer(y);
  for (int i = 0; i < N; ++i) {
    ys[i] = p.x0[i];
    ys[N + i] = p.v0[i];
  }
  void* mem = CVodeCreate(CV_ADAMS, ctx);
  SUNNonlinearSolver nls = SUNNonlinSol_FixedPoint(y, 0, ctx);
  int directions[2] = {-1, -1};  // every guard is a distance that falls to zero
  CVodeInit(mem, cvode_rhs<N>, 0.0, y);
  CVodeSStolerances(mem, tolerance, tolerance);
  CVodeSetNonlinearSolver(mem, nls);
  CVodeSetUserData(mem, &data);
  CVodeSetMaxNumSteps(mem, 5'000'000);
  // In stick the state is nearly constant and CVODE's steps grow past a forcing period, so a
  // guard that changes sign twice within a step is missed (the CVODE guide's caveat on root
  // finding); the documented remedy is a step limit, here 1/8 of the forcing period.
  if (chain.F.cwiseAbs().maxCoeff() > 0.0)
    CVodeSetMaxStep(mem, 2.0 * kPi / p.force_frequency / 8.0);
  CVodeRootInit(mem, chain.num_guards(data.mode), cvode_guards<N>);
  CVodeSetRootDirection(mem, directions);

  const double T = p.t_end;
  double t = 0.0;
  int roots[2] = {0, 0};
  long segment_steps = 0;
  while (true) {
    const int flag = CVode(mem, T, y, &t, CV_NORMAL);
    if (flag == CV_ROOT_RETURN) {
      CVodeGetRootInfo(mem, roots);
      const int fired = roots[0] != 0 ? 0 : 1;
      Vec pos = Eigen::Map<const Vec>(ys), vel = Eigen::Map<const Vec>(ys + N);
      const ContactState next = chain.switch_mode(data.mode, fired, t, pos, vel);
      out.events.push_back({t, data.mode, next});
      data.mode = next;
      for (int i = 0; i < N; ++i) ys[N + i] = vel[i];
      CVodeGetNumSteps(mem, &segment_steps);  // CVodeReInit resets CVODE's counters
      out.steps += segment_steps;
      CVodeReInit(mem, t, y);
      CVodeRootInit(mem, chain.num_guards(data.mode), cvode_guards<N>);
      CVodeSetRootDirection(mem, directions);
      continue;
    }
    if (flag == CV_SUCCESS) {
      out.ok = true;
    } else {
      out.message = "CVode returned " + std::to_string(flag) + " at t = " + std::to_string(t);
    }
    break;
  }
  CVodeGetNumSteps(mem, &segment_steps);
  out.steps += segment_steps;
  out.rhs_evaluations = data.rhs_evaluations;
  out.final_state = Eigen::Map<const Eigen::Matrix<double, 2 * N, 1>>(ys);
  SUNNonlinSolFree(nls);
  CVodeFree(&mem);
  N_VDestroy(y);
  SUNContext_Free(&ctx);
  return out;
}

/// SUNDIALS CVODE (Adams, fixed-point iteration) at rtol = atol = `tolerance`.
inline RunOutcome run_cvode(const ChainParameters& p, double tolerance) {
  return p.dofs == 1 ? run_cvode_n<1>(p, tolerance) : run_cvode_n<2>(p, tolerance);
}

}  // namespace peers
