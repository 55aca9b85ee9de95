#pragma once
/// \file exact_linear_stepper.hpp
/// \brief ExactLinearStepper: integrates a hybrid system that provides its linear part
/// (linear_part.hpp) exactly where the mode is linear, and by an exponential (Lawson)
/// Runge-Kutta method in the frame of the linear part where it is not. No stability limit from
/// the linear part; guards are sampled at a fixed fraction of the shortest period of the mode,
/// with a Hermite (value + slope) test for grazing between samples, and events are located on
/// the exact (or exponential) solution. See docs/ode_exponential.md, "Exact and exponential integration".

#include <stickslip/detail/validate.hpp>
#include <stickslip/ode/detail/augmented_flow.hpp>
#include <stickslip/ode/detail/hermite_cubic.hpp>
#include <stickslip/ode/detail/lawson_dormand_prince.hpp>
#include <stickslip/ode/detail/step_control.hpp>
#include <stickslip/ode/event_locator.hpp>
#include <stickslip/ode/detail/run_bookkeeping.hpp>
#include <stickslip/ode/hybrid_system.hpp>
#include <stickslip/ode/linear_part.hpp>
#include <stickslip/ode/stepper_options.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace stickslip {

/// Integrator of a hybrid system with a linear part (has_linear_part_v), with event location.
///
/// In a mode whose linear part is exact (LinearPart::exact, r_m = 0) the state is propagated by
/// y(t + delta) = exp(Â delta) y(t) on a grid of spacing delta = min(max_step, 2 pi /
/// (samples_per_period * rate)), rate = max(|lambda(A_m)|, w_k) (no step-size control: the
/// propagation is exact to round-off); a mode without oscillation or load frequency is crossed
/// in one step. States between grid points (events, samples) come from exp(Â tau) y by a scaled
/// Taylor series. Quadrature components are integrated by 5-point Gauss-Legendre over each grid
/// step on the exact x_L. Once an exact mode has lasted closed_form_after grid steps (or
/// samples): quadratures given as quadratic forms (LinearPart::quadrature_forms) are integrated
/// in closed form, x_Q(t + tau) = x_Q(t) + y^T W(tau) y with Van Loan's block exponential;
/// consecutive output samples come from the previous one by exp(Â h_out); and with affine guards
/// the stepper takes long steps of 2^j delta (j <= jump_levels) where a bound on every guard's
/// rate over the step, |g_i'(t + s)| <= (B_j |y(t)|)_i, shows that no guard can reach its trigger.
/// Affine guards of exact modes are evaluated on the augmented state (g = Ĝ y, g' = Ĝ Â y).
/// Where r_m != 0 (or linear_part returns false, then with Â = 0, i.e.
/// plain Dormand-Prince) the Lawson form of Dormand-Prince 5(4) is used with the error control
/// of StepperOptions (rtol, atol, safety, min_step, max_step, initial_step), steps capped at
/// delta in modes with guards - or, where the mode gives frozen affine guards, at 2^j delta
/// (j <= slip_levels) when a bound on the frozen linear part's guard motion shows no guard can
/// reach its trigger, checked after the step with the remainder's share (docs/ode_exponential.md, "Long
/// slipping steps"); the linear part is kept frozen while the remainder does not limit
/// the step (refresh_error; the system's `version` tells whether A_m changed at a refresh), and
/// steps of one length reuse their stage propagators. Samples and event location inside a Lawson
/// step use its dense output (Dormand-Prince's order-4 continuous extension in the frame of Â),
/// and event_state Reintegrate (or Checked) moves the located root onto re-taken steps of the method.
///
/// Events: a guard fires when it crosses at a grid point (GuardMonitor semantics, as in
/// HybridStepper), or when the cubic Hermite interpolant of its value and slope between two
/// points dips into the triggering side while both ends are outside it: the interval is then
/// refined at the interpolant's minimum on the exact solution until a crossing is bracketed or
/// the interval is below event_time_tolerance (a touch, not an event). The crossing is located by
/// Illinois root finding on the exact solution; the state handed to `transition` is the exact
/// state at the bracket end past the guard. Slopes come from the affine guards when the mode
/// gives them (LinearPart::Gx ...), else from a central difference along the exact flow.
///
/// Options used: output_interval, event_time_tolerance, guard_zero_tolerance, the Zeno guard,
/// max_steps, max_step, and (inexact modes) the step control and event_state. fixed_step and
/// event_location are ignored. Work counters beyond StepperStats: work().
template <class System>
class ExactLinearStepper {
  static_assert(is_hybrid_system_v<System>,
                "ExactLinearStepper: System needs Scalar, State, Mode, rhs, num_guards, guards, "
                "guard_direction and transition; see docs/ode.md");
  static_assert(has_linear_part_v<System>,
                "ExactLinearStepper: System needs bool linear_part(mode, t, x, "
                "LinearPart<Scalar>&); see stickslip/ode/linear_part.hpp");

 public:
  /// Floating-point type of the system.
  using Scalar = typename System::Scalar;
  /// Continuous state type of the system.
  using State = typename System::State;
  /// Discrete mode type of the system.
  using Mode = typename System::Mode;
  /// Result of a run (status, final state, counters).
  using Result = HybridResult<Scalar, State, Mode>;
  /// Run-time options.
  using Options = StepperOptions<Scalar>;
  /// Guard values of a mode.
  using GuardVector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  /// Dynamic column vector.
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  /// Dynamic matrix.
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  /// Guard samples per shortest period 2 pi / rate of a mode.
  static constexpr int samples_per_period = 8;
  /// Grid steps (or output samples) of an exact mode after which the stepper computes the
  /// propagator of the grid step (or of the output interval) together with the closed-form
  /// quadrature matrices (Van Loan; a few matrix exponentials of twice the augmented size), and
  /// from then on uses one product per step (or sample) instead of a Taylor series and a
  /// Gauss-Legendre rule through rhs. Short modes keep the cheaper set-up (the Van Loan blocks
  /// cost about as much as a few hundred Gauss-Legendre grid steps of the blade model).
  static constexpr long closed_form_after = 256;
  /// Grid steps of an exact mode after which long steps are considered (their set-up, the
  /// guard-rate bounds over 2^jump_levels grid steps, costs about a thousand grid steps).
  static constexpr long long_steps_after = 1024;
  /// Long steps of an exact mode: up to 2^jump_levels grid steps in one product, taken when a
  /// bound on every guard's rate over the step shows that no guard can reach its trigger (see
  /// the class comment).
  static constexpr int jump_levels = 8;

  /// Augmented generators Â of more than this order (Â is (state + 1 + 2 K) square) defer their
  /// grid ladder (see set_deferred_ladders): its set-up, two Padé exponentials and about 8
  /// squarings, ~44 d^3 flops, is the price of ~d Taylor steps of ~25 extra products of 2 d^2
  /// flops each, while such a mode may last a few tens of grid steps (a bladed disk: d ~ 300, a
  /// switch every ~20 steps).
  static constexpr Eigen::Index eager_ladder_order = 64;

  /// Inexact modes whose linear part gives frozen affine guards (LinearPart::Gx in an inexact
  /// mode): Lawson steps of up to 2^slip_levels grid steps where the guards' rate bound shows
  /// that none can reach its trigger (see the class comment); else steps are capped at the grid
  /// step delta as in modes without them.
  static constexpr int slip_levels = 3;

  /// Inexact modes keep the linear part of their last refresh (A_m frozen, e.g. at the contact
  /// point X* of a moving contact) and leave its change in the remainder, r_m(t, x) = f(t, x) -
  /// A_m(X*) x_L - b_m(t). The remainder is the only part the Lawson method does not integrate
  /// exactly, so it alone makes the error estimate err: the linear part is refreshed at the end
  /// of an accepted step whose err exceeds refresh_error (the step control's target is
  /// safety^5 ~ 0.59), i.e. when the grown remainder starts to limit the step.
  static constexpr double refresh_error = 0.5;

  /// Keeps a reference to `system`. Throws std::invalid_argument ("ExactLinearStepper:
  /// options.<name> ...") for options out of range.
  explicit ExactLinearStepper(System& system, StepperOptions<Scalar> options = {})
      : sys_(system), opt_(options) {
    opt_.validate("ExactLinearStepper");
  }

  /// Integrate from (mode, t0, x0) to t_end >= t0 with observer callbacks as HybridStepper.
  /// Throws std::invalid_argument for invalid arguments, or when linear_part fills sizes that do
  /// not match the state and guards.
  template <class Observer>
  Result integrate(Mode mode, Scalar t0, const State& x0, Scalar t_end, Observer& observer);

  /// Integrate without observer.
  Result integrate(Mode mode, Scalar t0, const State& x0, Scalar t_end) {
    NullObserver none;
    return integrate(std::move(mode), t0, x0, t_end, none);
  }

  /// Mode cache: the propagators of up to `entries` distinct augmented generators Â (the grid
  /// ladder, the eigenvalue bound, and in exact modes the Van Loan blocks of the grid step and of
  /// the output interval) are kept for modes that come back, as the few modes of a stick-slip
  /// run alternate; a revisited mode then uses its closed forms from its first step. Default 8;
  /// 0 switches the cache off. Entries are kept across integrate() calls.
  void set_mode_cache_size(std::size_t entries) {
    flow_.set_cache_size(entries);
    blocks_.clear();
  }

  /// Deferred grid ladders (default on): an exact mode whose Â is of order d > eager_ladder_order
  /// and not in the mode cache propagates by Taylor series (AugmentedFlow::expv without a
  /// ladder: exact to round-off, the same grid) until it has lasted d grid steps, and only then
  /// computes its ladder of propagators (and enters the mode cache); a short mode never pays for
  /// it. Off: every exact mode computes its ladder at its start. The two differ by round-off.
  void set_deferred_ladders(bool on) noexcept { defer_ladders_ = on; }

  /// Long Lawson steps in inexact modes that give frozen affine guards (docs/ode_exponential.md, "Long
  /// slipping steps"): off by default - on the blade model they cost more (bounds and stage
  /// propagators per frozen Â) than the few steps they save, the remainder's error limiting the
  /// steps to about delta anyway (docs/measurements/exponential.md).
  void set_long_slipping_steps(bool on) noexcept { long_slip_ = on; }

  /// The options of the stepper (validated at construction).
  const Options& options() const { return opt_; }
  /// Work counters of the last run.
  const ExactStepperStats& work() const { return work_; }

 private:
  // ---- the mode ----------------------------------------------------------------------------
  void check_linear_part(const Mode& m) const;
  bool start_mode(const Mode& m, Scalar t, StepperStats& st);
  // linear_part at (t, x_): Â, the sampling interval, y_ and (inexact modes, when Â changed or
  // `force`) the remainder r_. False when the remainder is not finite.
  bool refresh_linear_part(const Mode& m, Scalar t, bool force, StepperStats& st);

  // Inexact modes: true when the frozen linear part is to be refreshed after an accepted step
  // with error estimate err (see refresh_error); always without a linear form (Â = 0: nothing
  // is frozen, linear_part may give one at the next point).
  // A long step (h > delta, frozen guards) is judged by the error a step of delta would have made,
  // err (delta / h)^5: the refreshes stay as frequent as with steps capped at delta.
  bool remainder_grown(Scalar err, Scalar h) const {
    using std::pow;
    const Scalar scale =
        long_slip_ && frozen_ && guarded_ && h > delta_ ? pow(delta_ / h, Scalar(5)) : Scalar(1);
    return lp_.size() == 0 || err * scale > Scalar(refresh_error);
  }

  // ---- evaluations -------------------------------------------------------------------------
  bool remainder(const Mode& m, Scalar t, const Vector& y, Vector& out, StepperStats& st) {
    xr_ = y.head(nx_);
    sys_.rhs(m, t, xr_, fr_);
    ++st.rhs_evaluations;
    flow_.rate(y, out, work_);
    out.head(nx_) = fr_ - out.head(nx_);
    out.tail(out.size() - nx_).setZero();
    return detail::all_finite(fr_);
  }
  // x' at (t, y): the exact rate where r = 0 (rhs only for the quadratures), else rhs.
  bool derivative(const Mode& m, Scalar t, const Vector& y, const State& x, State& xdot,
                  StepperStats& st) {
    if (exact_) {
      flow_.rate(y, xdot, work_);
      if (nq_ == 0) return true;
    }
    sys_.rhs(m, t, x, fr_);
    ++st.rhs_evaluations;
    if (exact_) xdot.tail(nq_) = fr_.tail(nq_);
    else xdot = fr_;
    return detail::all_finite(fr_);
  }
  // x' at a point (t, y, x) of the solution into xd_: derivative() in exact modes, Â y + r (r:
  // the remainder there) in inexact ones.
  bool tangent(const Mode& m, Scalar t, const Vector& y, const State& x, const Vector& r,
               StepperStats& st) {
    if (exact_) return derivative(m, t, y, x, xd_, st);
    flow_.rate(y, xd_, work_);
    xd_ += r.head(nx_);
    return true;
  }
  void eval_guards(const Mode& m, Scalar t, const State& x, GuardVector& g, StepperStats& st) {
    if (g.size() == 0) return;
    sys_.guards(m, t, x, g);
    ++st.guard_evaluations;
  }
  // Guard rates dg/dt along the solution through (t, x) with x' = xdot.
  void guard_slopes(const Mode& m, Scalar t, const State& x, const State& xdot, GuardVector& s,
                    StepperStats& st);
  // Quadratures at b from y at a (x_L exact): 5-point Gauss-Legendre on pieces <= delta.
  bool quadrature(const Mode& m, Scalar a, const Vector& ya, Scalar b, Vector& yb,
                  StepperStats& st);
  // What eval_point computes beside the state x_L (and the whole state in inexact modes).
  // kSystemGuards: the guards from System::guards even where Ĝ y would do (root finding and the
  // located state: the transition then sees the crossing the system itself computes).
  // kNear (exact modes): start from the last kNear point (near_t_, near_y_) by a short hop when
  // that is closer than the step start, and keep the result as the next one (a root search;
  // near_t_ = NaN starts afresh).
  enum Need : unsigned {
    kGuards = 1u,
    kSlopes = 2u,
    kQuadratures = 4u,
    kSystemGuards = 8u,
    kNear = 16u
  };
  // Exact (or exponential) state at tau in [t_, t1] into ys_ / xs_; with kGuards the guards into
  // gt_, with kSlopes also their slopes into st_; with kQuadratures (exact modes) the quadratures
  // too (else they keep their values at t_: guards never read them). False when not finite.
  bool eval_point(const Mode& m, Scalar tau, unsigned need, StepperStats& st);
  // Exact modes with affine guards: g = Ĝ y and g' = Ĝ Â y on the augmented state (no system
  // call).
  bool closed_form_guards() const noexcept { return exact_ && affine_; }
  // x_Q(y1) = x_Q(y) + y^T W_j y with the stacked W of van_loan (exact modes with
  // quadrature_forms).
  void add_quadratures(const Vector& y, const Matrix& w, Vector& y1) {
    wy_.noalias() = w * y;
    ++work_.matvecs;
    const Eigen::Index d = flow_.dim(), n = lp_.size();
    for (Eigen::Index j = 0; j < nq_; ++j) y1[n + j] = y[n + j] + y.dot(wy_.segment(j * d, d));
  }
  // Grid propagator of an exact mode with closed-form quadratures, once the mode has lasted
  // closed_form_after grid steps; true when w_grid_ is ready.
  bool grid_quadrature_ready();
  // Long steps: the propagators, quadrature matrices and guard-rate bounds of H_j = 2^j delta
  // (j = 1 .. jump_levels), once per mode (after long_steps_after grid steps); the longest H_j
  // (0: none) with no guard able to reach its trigger from (t_, y_) and t_ + H_j <= t_end.
  bool jumps_possible() const;
  void prepare_jumps();
  int choose_jump(Scalar t_end);

  // Entrywise bounds over [0, 2^j delta] (j = 1 .. levels) of |rows exp(Â s)| into out[j - 1].
  void guard_bounds(int levels, const Matrix& rows, std::vector<Matrix>& out);
  // Inexact modes with frozen guards: the longest level j <= slip_levels (0: none) whose step
  // 2^j delta the frozen guards' rate bound clears from (t_, y_).
  int choose_slip_level();
  // After a Lawson step of h > delta at level j, accepted by the error control and with gb_, sb_
  // at its end: true when no guard can have reached its trigger inside it (see the class comment).
  bool slip_step_clear(int level, Scalar h);
  // How far the free flow of the frozen linear part can move guard i towards its trigger over
  // [0, H] from rate s0 = (Ĝ Â y)_i: H max(0, -d') + 1.1 H^2 / 2 b2 (d' = s0 towards the trigger,
  // b2 >= |g_i''| over the step: Taylor with the remainder bounded; the margin 1.1 covers the
  // round-off of the bound).
  Scalar free_reach(Eigen::Index i, Scalar H, Scalar s0, Scalar b2) const {
    const Scalar d1 = monitor_.distance(i, ga_[i] + s0) - monitor_.distance(i, ga_[i]);
    return H * std::max(Scalar(0), -d1) + Scalar(0.55) * H * H * b2;
  }
  // Guards gb_ and slopes sb_ at the step end (t1, x1_, y1_, r1_) by the system (modes without
  // closed-form guards); false when not finite.
  bool end_guards(const Mode& m, Scalar t1, StepperStats& st);

  // ---- events ------------------------------------------------------------------------------
  struct Bracket {
    Scalar lo, dlo, hi, dhi;
  };
  bool grazing_bracket(const Mode& m, Eigen::Index i, Scalar a, Scalar da, Scalar sa, Scalar b,
                       Scalar db, Scalar sb, Bracket& out, StepperStats& st);
  // Earliest event in [t_, t1]; on true, xe_ holds the exact state at the returned time te_.
  bool find_event(const Mode& m, Scalar t1, StepperStats& st);
  // After find_event placed an event at te_: when a guard that fired was disarmed but lies more
  // than the zero tolerance on its safe side at a point tc of the solution inside (t_, te_) (the
  // middle and quarter points), it left zero and came back within the step: a new crossing, not
  // an immediate one. The step is then cut back to tc (exact modes: the exact state there;
  // inexact ones: a step of the method re-taken to tc, h and err its size and error estimate),
  // with t1, y1_, x1_ (r1_) and the guards gb_, sb_ at tc, so that it ends where the guard is
  // armed, and true is returned. False (nothing changed) otherwise.
  bool cut_back_to_rearm(const Mode& m, Scalar& t1, Scalar& h, Scalar& err, StepperStats& st);
  // Inexact modes: y at tau in [t_, t_ + step_h_] on the dense output of the accepted Lawson step
  // into ys_ (built at its first use, before any trial step); false where it is not usable
  // (LawsonDormandPrince::dense_usable), then trial steps are re-taken from t_.
  bool dense_point(Scalar tau);
  // Inexact modes: a Lawson step re-taken from (t_, y_) to tau into ys_ (rs_: the remainder
  // there); its error estimate, NaN where the remainder is not finite.
  Scalar trial_step(const Mode& m, Scalar tau, StepperStats& st) {
    return lawson_.step(
        flow_, [&](Scalar tt, const Vector& y, Vector& out) { return remainder(m, tt, y, out, st); },
        t_, y_, r_, tau - t_, ys_, rs_, opt_.rtol, opt_.atol, work_);
  }
  // Inexact modes, EventState::Reintegrate: the root `first` of guard i on the dense output moved
  // to the root of trial steps from t_ (detail::refine_root_on_steps); xe_, gt_ and the returned
  // time are those of the trial step at the bracket end past the guard.
  Scalar refine_on_steps(const Mode& m, Eigen::Index i, Scalar first, Scalar t1, StepperStats& st);

  template <class Observer>
  bool emit_samples(Observer& obs, const Mode& m, Scalar upto, Scalar t1, StepperStats& st);

  static Result finish(Result& r, Status s, Scalar t, const State& x, const Mode& m,
                       std::string message) {
    return detail::finish_run(r, s, t, x, m, std::move(message));
  }

  System& sys_;
  Options opt_;
  ExactStepperStats work_;
  LinearPart<Scalar> lp_;
  detail::AugmentedFlow<Scalar> flow_;
  detail::LawsonDormandPrince<Scalar> lawson_;
  detail::GuardMonitor<Scalar> monitor_;
  // Step start (t_, y_, x_, r_), step end (y1_, x1_, r1_), trial point (ys_, xs_, rs_).
  Vector y_, y1_, ys_, r_, r1_, rs_, yq_;
  State x_, x1_, xs_, xe_, xd_, xr_, fr_, xg_;
  GuardVector ga_, gb_, gt_, sa_, sb_, st_, gp_, gm_, roots_;
  Scalar near_t_ = std::numeric_limits<Scalar>::quiet_NaN();  // see Need::kNear
  Vector near_y_;
  TriggeredGuards triggered_;
  detail::ZenoGuard<Scalar> zeno_;
  Scalar t_ = 0, te_ = 0, t0_ = 0, delta_ = 0;
  Eigen::Index nx_ = 0, nq_ = 0;
  long next_sample_ = 0;
  // Dense output of the accepted Lawson step [t_, t_ + step_h_].
  enum class Dense { Unknown, Ready, Unusable };
  Dense dense_ = Dense::Unusable;
  Scalar step_h_ = 0;
  bool linear_ = false, exact_ = false, affine_ = false, guarded_ = false;
  // Exact modes: affine guards on y (ghat_, gdot_ = ghat_ Â), closed-form quadratures (forms_:
  // the mode gives them; w_grid_ for the grid step; phi_out_, w_out_ for the output interval),
  // the sample chain (y_chain_ = the state at sample index k_chain_, same mode) and the mode's
  // step and sample counts.
  Matrix ghat_, gdot_, w_grid_, phi_grid_, phi_out_, w_out_;
  std::vector<Matrix> forms_seen_;
  Vector wy_, y_chain_;
  long k_chain_ = -1, mode_steps_ = 0, mode_samples_ = 0;
  Scalar phi_grid_delta_ = 0;
  std::vector<Matrix> jump_phi_, jump_w_, jump_bound_;
  Matrix jump_r_, jump_rmax_, jump_e_, jump_tmp_, jump_phi_sigma_;
  // Inexact modes with frozen guards (frozen_): rows (Ĝ Â; Ĝ) and their bounds per slip level for
  // the Â of generation slip_generation_ and grid step slip_delta_; after a long step that failed
  // its check, one step at delta (slip_retry_).
  Matrix slip_rows_;
  std::vector<Matrix> slip_bound_;
  std::uint64_t slip_generation_ = 0;
  Scalar slip_delta_ = 0;
  bool frozen_ = false, slip_retry_ = false, long_slip_ = false;
  // An exact mode's ladder waits (set_deferred_ladders): ladder_waits_ until the mode lasted
  // flow_.dim() grid steps.
  bool defer_ladders_ = true, ladder_waits_ = false;
  Vector absr_;
  GuardVector free_g0_, free_s0_, free_g1_, free_s1_, rbound_;
  // The 14 guard-sized vectors above, parked per guard count (see start_mode).
  static constexpr std::size_t kGuardVectors = 14;
  std::vector<std::array<GuardVector, kGuardVectors>> guard_banks_;
  Vector absy_, bound_, yp_;
  bool jumps_valid_ = false;
  // Per slot of the flow's mode cache: the Van Loan blocks of the Â in that slot (valid while the
  // slot's stamp is unchanged) for the grid step delta, the output interval and the forms given.
  struct ModeBlocks {
    std::uint64_t stamp = 0;
    Scalar delta = 0;
    std::vector<Matrix> forms;
    Matrix phi_grid, w_grid, phi_out, w_out;
    bool grid = false, out = false;
  };
  std::vector<ModeBlocks> blocks_;
  ModeBlocks* mode_blocks(bool create);
  void restore_blocks();
  bool forms_ = false, w_grid_valid_ = false, out_valid_ = false;
};

// ------------------------------------------------------------------------------------------
template <class System>
void ExactLinearStepper<System>::check_linear_part(const Mode& m) const {
  static const std::string where = "System::linear_part";
  const Eigen::Index n = lp_.size();
  const auto nk = static_cast<Eigen::Index>(lp_.omega.size());
  if (lp_.A.cols() != n || n > nx_)
    detail::throw_invalid(where, "A must be square with size() <= the state size", n);
  if (lp_.b0.size() != n) detail::throw_invalid(where, "b0 must have size() rows", lp_.b0.size());
  if (nk > 0 && (lp_.bc.rows() != n || lp_.bs.rows() != n || lp_.bc.cols() != nk ||
                 lp_.bs.cols() != nk))
    detail::throw_invalid(where, "bc and bs must be size() x omega.size()", lp_.bc.cols());
  if (lp_.has_affine_guards()) {
    const Eigen::Index ng = sys_.num_guards(m);
    if (lp_.Gx.rows() != ng || lp_.Gx.cols() != n || lp_.g0.size() != ng ||
        (nk > 0 && (lp_.gc.rows() != ng || lp_.gs.rows() != ng || lp_.gc.cols() != nk ||
                    lp_.gs.cols() != nk)))
      detail::throw_invalid(where, "affine guards must be num_guards x size() (Gx), "
                                   "num_guards (g0), num_guards x omega.size() (gc, gs)",
                            lp_.Gx.rows());
  }
  if (lp_.exact && lp_.has_quadrature_forms()) {
    const auto nf = static_cast<Eigen::Index>(lp_.quadrature_forms.size());
    if (nf != nx_ - n)
      detail::throw_invalid(where, "quadrature_forms must hold one matrix per quadrature", nf);
    for (const auto& q : lp_.quadrature_forms)
      if (q.rows() != n + 1 + 2 * nk || q.cols() != q.rows())
        detail::throw_invalid(where, "quadrature_forms must be square of size() + 1 + 2 K",
                              q.rows());
  }
}

template <class System>
bool ExactLinearStepper<System>::refresh_linear_part(const Mode& m, Scalar t, bool force,
                                                     StepperStats& st) {
  ++work_.linear_part_calls;
  lp_.want_inexact_guards = long_slip_;  // (the frozen guards serve long slipping steps only)
  linear_ = sys_.linear_part(m, t, x_, lp_);
  if (!linear_) {
    // No linear form: Â = 0 (the clock only), the Lawson method is Dormand-Prince itself.
    lp_.A.resize(0, 0);
    lp_.b0.resize(0);
    lp_.omega.clear();
    lp_.bc.resize(0, 0);
    lp_.bs.resize(0, 0);
    lp_.Gx.resize(0, 0);
    lp_.exact = false;
  }
  check_linear_part(m);
  exact_ = linear_ && lp_.exact;
  affine_ = linear_ && lp_.exact && lp_.has_affine_guards();
  frozen_ = linear_ && !lp_.exact && lp_.has_affine_guards();
  nq_ = nx_ - lp_.size();
  const bool changed = flow_.assign(lp_, nx_, work_);
  flow_.lift(t, x_, y_);
  const Scalar rate = flow_.fastest_rate();
  const Scalar two_pi = Scalar(2) * Scalar(EIGEN_PI);
  delta_ = rate > 0 ? two_pi / (Scalar(samples_per_period) * rate)
                    : std::numeric_limits<Scalar>::infinity();
  delta_ = std::min(delta_, opt_.max_step);
  // Ladder base: the grid step, or 1 / ||Â|| where the mode has no rate (then no ladder needed).
  // Only exact modes go to the mode cache: a frozen inexact Â (a moving contact) rarely recurs
  // and would evict the few modes of a stick-slip run that do.
  ladder_waits_ = defer_ladders_ && exact_ && flow_.dim() > eager_ladder_order && !flow_.has_ladder() &&
                  std::isfinite(delta_);
  if (!ladder_waits_) flow_.prepare(std::isfinite(delta_) ? delta_ : Scalar(0), work_, exact_);
  lawson_.initialize(flow_.dim());
  for (Vector* v : {&y1_, &ys_, &r_, &r1_, &rs_, &yq_, &y_chain_, &near_y_}) v->resize(flow_.dim());
  // Closed-form pieces of an exact mode: dropped when Â, the grid step or the forms changed.
  const bool forms = exact_ && lp_.has_quadrature_forms();
  bool forms_changed = forms != forms_;
  if (forms && !forms_changed) {
    forms_changed = forms_seen_.size() != lp_.quadrature_forms.size();
    for (std::size_t j = 0; !forms_changed && j < forms_seen_.size(); ++j)
      forms_changed = forms_seen_[j].rows() != lp_.quadrature_forms[j].rows() ||
                      forms_seen_[j] != lp_.quadrature_forms[j];
  }
  if (forms && forms_changed) forms_seen_ = lp_.quadrature_forms;
  forms_ = forms;
  if (changed || forms_changed) out_valid_ = false;
  if (changed || forms_changed || !(phi_grid_delta_ == delta_)) {
    w_grid_valid_ = false;
    jumps_valid_ = false;
  }
  restore_blocks();
  if (closed_form_guards() || frozen_) {
    const Eigen::Index n = lp_.size(), ng = lp_.Gx.rows();
    ghat_.setZero(ng, flow_.dim());
    ghat_.leftCols(n) = lp_.Gx;
    ghat_.col(nx_) = lp_.g0;
    for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(lp_.omega.size()); ++k) {
      ghat_.col(nx_ + 1 + 2 * k) = lp_.gc.col(k);
      ghat_.col(nx_ + 2 + 2 * k) = lp_.gs.col(k);
    }
    gdot_.noalias() = ghat_ * flow_.generator();
  }
  if (!exact_ && (force || changed)) return remainder(m, t, y_, r_, st);
  return true;
}

template <class System>
auto ExactLinearStepper<System>::mode_blocks(bool create) -> ModeBlocks* {
  const int slot = flow_.cache_slot();
  if (!exact_ || slot < 0 || !std::isfinite(delta_)) return nullptr;
  const auto i = static_cast<std::size_t>(slot);
  if (blocks_.size() <= i) {
    if (!create) return nullptr;
    blocks_.resize(i + 1);
  }
  ModeBlocks& b = blocks_[i];
  const std::uint64_t stamp = flow_.cache_stamp(slot);
  const bool forms_match = [&] {
    if (b.forms.size() != lp_.quadrature_forms.size()) return false;
    for (std::size_t j = 0; j < b.forms.size(); ++j)
      if (b.forms[j].rows() != lp_.quadrature_forms[j].rows() || b.forms[j] != lp_.quadrature_forms[j])
        return false;
    return true;
  }();
  if (b.stamp == stamp && b.delta == delta_ && forms_match) return &b;
  if (!create) return nullptr;
  b.stamp = stamp;
  b.delta = delta_;
  b.forms = lp_.quadrature_forms;
  b.grid = b.out = false;
  return &b;
}

template <class System>
void ExactLinearStepper<System>::restore_blocks() {
  if (!flow_.restored()) return;
  const ModeBlocks* b = mode_blocks(false);
  if (b == nullptr) return;
  if (b->grid && !w_grid_valid_) {
    phi_grid_ = b->phi_grid;
    w_grid_ = b->w_grid;
    phi_grid_delta_ = delta_;
    w_grid_valid_ = true;
  }
  if (b->out && !out_valid_) {
    phi_out_ = b->phi_out;
    w_out_ = b->w_out;
    out_valid_ = true;
  }
}

template <class System>
bool ExactLinearStepper<System>::grid_quadrature_ready() {
  // A mode seen before (mode cache: it comes back, so its blocks pay off) uses them from its
  // first step; they are computed once per cache entry.
  if (!forms_ || (mode_steps_ < closed_form_after && !w_grid_valid_ && !flow_.restored()) ||
      !std::isfinite(delta_))
    return false;
  if (!w_grid_valid_) {
    flow_.van_loan(delta_, lp_.quadrature_forms, phi_grid_, w_grid_, work_);
    phi_grid_delta_ = delta_;
    w_grid_valid_ = true;
    if (ModeBlocks* b = mode_blocks(true)) {
      b->phi_grid = phi_grid_;
      b->w_grid = w_grid_;
      b->grid = true;
    }
  }
  return true;
}

template <class System>
bool ExactLinearStepper<System>::jumps_possible() const {
  return exact_ && (!guarded_ || closed_form_guards()) && (forms_ || nq_ == 0) &&
         flow_.has_ladder() && std::isfinite(delta_) && mode_steps_ >= long_steps_after;
}

template <class System>
void ExactLinearStepper<System>::prepare_jumps() {
  const auto L = static_cast<std::size_t>(jump_levels);
  const Eigen::Index d = flow_.dim();
  if (forms_ || nq_ == 0) grid_quadrature_ready();
  jump_phi_.resize(L);
  jump_w_.resize(L);
  jump_bound_.resize(L);
  // Phi(2 tau) = Phi(tau)^2, W(2 tau) = W(tau) + Phi(tau)^T W(tau) Phi(tau) (per form).
  const Matrix* phi = &flow_.propagator();
  const Matrix* w = &w_grid_;
  for (std::size_t j = 0; j < L; ++j) {
    jump_phi_[j].noalias() = (*phi) * (*phi);
    jump_w_[j] = *w;
    for (Eigen::Index q = 0; q < nq_; ++q) {
      jump_tmp_.noalias() = w->middleRows(q * d, d) * (*phi);
      jump_w_[j].middleRows(q * d, d).noalias() += phi->transpose() * jump_tmp_;
    }
    phi = &jump_phi_[j];
    w = &jump_w_[j];
  }
  if (guarded_) guard_bounds(jump_levels, gdot_, jump_bound_);
  jumps_valid_ = true;
}

template <class System>
void ExactLinearStepper<System>::guard_bounds(int levels, const Matrix& rows,
                                              std::vector<Matrix>& out) {
  // Bounds over [0, H_j] of the rows r(s) = R exp(Â s) (R = Ĝ Â: the guards' rates; R = Ĝ: the
  // guards' response). On [m sigma, (m + 1) sigma], |r(s)| = |r(m sigma) exp(Â u)| <=
  // |r(m sigma)| exp(|Â| u) (entrywise: |exp(Â u)| <= exp(|Â| u)), so out_j = max_{m sigma < H_j}
  // |r(m sigma)| exp(|Â| sigma) bounds |r(s)| entrywise over [0, H_j], H_j = 2^j delta;
  // sigma = delta / 8.
  const auto L = static_cast<std::size_t>(levels);
  out.resize(L);
  const Scalar sigma = delta_ / Scalar(8);
  flow_.expm(sigma, jump_phi_sigma_, work_);
  flow_.abs_expm(sigma, jump_e_, work_);
  jump_r_ = rows;
  jump_rmax_ = jump_r_.cwiseAbs();
  long m = 1;
  for (std::size_t j = 0; j < L; ++j) {
    const long upto = 8L << (j + 1);  // H_j / sigma
    for (; m < upto; ++m) {
      jump_tmp_.noalias() = jump_r_ * jump_phi_sigma_;
      jump_r_.swap(jump_tmp_);
      jump_rmax_ = jump_rmax_.cwiseMax(jump_r_.cwiseAbs());
    }
    out[j].noalias() = jump_rmax_ * jump_e_;
  }
}

template <class System>
int ExactLinearStepper<System>::choose_slip_level() {
  if (!long_slip_ || !frozen_ || !guarded_ || slip_retry_ || !std::isfinite(delta_)) return 0;
  const Eigen::Index ng = ga_.size();
  for (Eigen::Index i = 0; i < ng; ++i)
    if (monitor_.disarmed(i)) return 0;
  if (slip_generation_ != flow_.generation() || !(slip_delta_ == delta_)) {
    slip_rows_.resize(2 * ng, flow_.dim());
    slip_rows_.topRows(ng).noalias() = gdot_ * flow_.generator();
    slip_rows_.bottomRows(ng) = ghat_;
    guard_bounds(slip_levels, slip_rows_, slip_bound_);
    slip_generation_ = flow_.generation();
    slip_delta_ = delta_;
  }
  absy_ = y_.cwiseAbs();
  free_s0_.noalias() = gdot_ * y_;
  ++work_.matvecs;
  for (int j = slip_levels; j >= 1; --j) {
    const Scalar H = std::ldexp(delta_, j);
    bound_.noalias() = slip_bound_[static_cast<std::size_t>(j - 1)].topRows(ng) * absy_;
    bool clear = true;
    for (Eigen::Index i = 0; clear && i < ng; ++i)
      clear = monitor_.distance(i, ga_[i]) > free_reach(i, H, free_s0_[i], bound_[i]);
    if (clear) return j;
  }
  return 0;
}

template <class System>
bool ExactLinearStepper<System>::slip_step_clear(int level, Scalar h) {
  // g(t + s) = Ĝ exp(Â s) y(t) + g_rest(s): the free flow of the frozen linear part (free_reach)
  // and the rest - the response to the remainder, Ĝ int_0^s exp(Â (s - u)) r(u) du, bounded by
  // s E_j max(|r(t)|, |r(t + h)|) (E_j: bottom rows of slip_bound_; the remainder at the step's
  // ends stands for its maximum over the step, which the error control resolves), plus the
  // guards' own difference from their frozen affine form, smooth on the step: its excursion is
  // taken from the cubic Hermite interpolant of g_rest's values and slopes at both ends, doubled.
  const Eigen::Index ng = ga_.size();
  const Matrix& bj = slip_bound_[static_cast<std::size_t>(level - 1)];
  absy_ = y_.cwiseAbs();
  absr_ = r_.cwiseAbs().cwiseMax(r1_.cwiseAbs());
  bound_.noalias() = bj.topRows(ng) * absy_;
  rbound_.noalias() = bj.bottomRows(ng) * absr_;
  const Vector& yfree = lawson_.free_flow();
  free_g0_.noalias() = ghat_ * y_;
  free_s0_.noalias() = gdot_ * y_;
  free_g1_.noalias() = ghat_ * yfree;
  free_s1_.noalias() = gdot_ * yfree;
  work_.matvecs += 4;
  for (Eigen::Index i = 0; i < ng; ++i) {
    const detail::HermiteCubic<Scalar> rest{ga_[i] - free_g0_[i], h * (sa_[i] - free_s0_[i]),
                                            gb_[i] - free_g1_[i], h * (sb_[i] - free_s1_[i])};
    const Scalar reach = free_reach(i, h, free_s0_[i], bound_[i]) +
                         Scalar(1.1) * h * rbound_[i] + Scalar(2) * rest.excursion() +
                         opt_.guard_zero_tolerance;
    if (!(monitor_.distance(i, ga_[i]) > reach)) return false;
  }
  return true;
}

template <class System>
bool ExactLinearStepper<System>::end_guards(const Mode& m, Scalar t1, StepperStats& st) {
  eval_guards(m, t1, x1_, gb_, st);
  if (!tangent(m, t1, y1_, x1_, r1_, st)) return false;
  guard_slopes(m, t1, x1_, xd_, sb_, st);
  return detail::all_finite(gb_) && detail::all_finite(sb_);
}

template <class System>
int ExactLinearStepper<System>::choose_jump(Scalar t_end) {
  if (!jumps_possible()) return 0;
  if (!jumps_valid_) prepare_jumps();
  // A sample inside the step must come from the sample chain (or be the step's end): the first
  // one of a mode is not taken across a long step.
  const bool samples = opt_.output_interval > 0;
  const Scalar next = t0_ + static_cast<Scalar>(next_sample_) * opt_.output_interval;
  absy_ = y_.cwiseAbs();
  for (int j = jump_levels; j >= 1; --j) {
    const Scalar H = std::ldexp(delta_, j);
    if (!(t_ + H < t_end)) continue;
    if (samples && k_chain_ < 0 && next < t_ + H) continue;
    if (guarded_) {
      bound_.noalias() = jump_bound_[static_cast<std::size_t>(j - 1)] * absy_;
      bool clear = true;
      // Margin 1.1: round-off of the guard values and of the bound itself.
      for (Eigen::Index i = 0; clear && i < ga_.size(); ++i)
        clear = !monitor_.disarmed(i) &&
                monitor_.distance(i, ga_[i]) > Scalar(1.1) * H * bound_[i];
      if (!clear) continue;
    }
    return j;
  }
  return 0;
}

template <class System>
bool ExactLinearStepper<System>::start_mode(const Mode& m, Scalar t, StepperStats& st) {
  if (!refresh_linear_part(m, t, true, st)) return false;
  k_chain_ = -1;
  mode_steps_ = 0;
  mode_samples_ = 0;
  const Eigen::Index ng = sys_.num_guards(m);
  if (ga_.size() != ng) {
    // Modes with different guard counts (stick and slip of a contact) alternate at every event:
    // park the vectors of the old count and take those of the new one, so that they are
    // allocated once per count, not at every switch.
    std::array<GuardVector*, kGuardVectors> own{&ga_, &gb_, &gt_, &sa_, &sb_, &st_, &gp_,
                                                &gm_, &roots_, &free_g0_, &free_s0_, &free_g1_,
                                                &free_s1_, &rbound_};
    const auto old_ng = static_cast<std::size_t>(ga_.size());
    const auto new_ng = static_cast<std::size_t>(ng);
    if (guard_banks_.size() <= std::max(old_ng, new_ng))
      guard_banks_.resize(std::max(old_ng, new_ng) + 1);
    for (std::size_t j = 0; j < kGuardVectors; ++j) {
      own[j]->swap(guard_banks_[old_ng][j]);
      own[j]->swap(guard_banks_[new_ng][j]);
      own[j]->resize(ng);  // no-op after the first mode with ng guards
    }
  }
  guarded_ = ng > 0;
  eval_guards(m, t, x_, ga_, st);
  if (!detail::all_finite(ga_)) return false;
  monitor_.start_mode(ga_, [&](Eigen::Index i) { return sys_.guard_direction(m, i); },
                      opt_.guard_zero_tolerance);
  if (guarded_ && closed_form_guards()) {
    detail::small_product(gdot_, y_, sa_);
  } else if (guarded_) {
    if (!derivative(m, t, y_, x_, xd_, st)) return false;
    guard_slopes(m, t, x_, xd_, sa_, st);
  }
  return true;
}

template <class System>
void ExactLinearStepper<System>::guard_slopes(const Mode& m, Scalar t, const State& x,
                                              const State& xdot, GuardVector& s,
                                              StepperStats& st) {
  if (affine_) {
    // g' = Gx x_L' + sum_k w_k (-gc_k sin(w_k t) + gs_k cos(w_k t)).
    s.noalias() = lp_.Gx * xdot.head(lp_.size());
    using std::cos;
    using std::sin;
    for (std::size_t k = 0; k < lp_.omega.size(); ++k) {
      const Scalar w = lp_.omega[k];
      const auto j = static_cast<Eigen::Index>(k);
      s.noalias() += (-w * sin(w * t)) * lp_.gc.col(j) + (w * cos(w * t)) * lp_.gs.col(j);
    }
    return;
  }
  // Central difference along the tangent: (g(t + e, x + e x') - g(t - e, x - e x')) / (2 e);
  // e = 1e-5 of the sampling interval (at most 1e-5): truncation O(e^2 g''') and round-off
  // O(eps |g| / e) both far below the values the grazing test compares.
  const Scalar e = Scalar(1e-5) * std::min(Scalar(1), delta_);
  xg_ = x + e * xdot;
  eval_guards(m, t + e, xg_, gp_, st);
  xg_ = x - e * xdot;
  eval_guards(m, t - e, xg_, gm_, st);
  s = (gp_ - gm_) / (Scalar(2) * e);
}

template <class System>
bool ExactLinearStepper<System>::quadrature(const Mode& m, Scalar a, const Vector& ya, Scalar b,
                                            Vector& yb, StepperStats& st) {
  if (nq_ == 0) return true;
  // Gauss-Legendre, 5 nodes on [-1, 1] (exact for degree 9).
  static constexpr std::array<double, 5> node{-0.9061798459386640, -0.5384693101056831, 0.0,
                                              0.5384693101056831, 0.9061798459386640};
  static constexpr std::array<double, 5> weight{0.2369268850561891, 0.4786286704993665,
                                                0.5688888888888889, 0.4786286704993665,
                                                0.2369268850561891};
  // Composite over pieces no longer than the grid step (the rule's accuracy is set for those).
  using std::ceil;
  const Scalar pieces_real =
      std::isfinite(delta_) ? std::max(Scalar(1), ceil((b - a) / delta_ - Scalar(1e-9))) : Scalar(1);
  const auto pieces = static_cast<long>(pieces_real);
  const Scalar half = (b - a) / (Scalar(2) * pieces_real);
  const Eigen::Index n = lp_.size();
  auto acc = yb.segment(n, nq_);
  acc.setZero();
  yp_ = ya;
  for (long p = 0; p < pieces; ++p) {
    const Scalar ap = a + Scalar(2) * half * static_cast<Scalar>(p);
    if (p > 0) flow_.expv(Scalar(2) * half, yp_, work_);
    for (std::size_t j = 0; j < node.size(); ++j) {
      const Scalar tau = ap + half * (Scalar(1) + static_cast<Scalar>(node[j]));
      yq_ = yp_;
      flow_.expv(tau - ap, yq_, work_);
      xr_ = yq_.head(nx_);
      sys_.rhs(m, tau, xr_, fr_);
      ++st.rhs_evaluations;
      acc += static_cast<Scalar>(weight[j]) * fr_.tail(nq_);
    }
  }
  acc = ya.segment(n, nq_) + half * acc;
  return detail::all_finite(acc);
}

template <class System>
bool ExactLinearStepper<System>::eval_point(const Mode& m, Scalar tau, unsigned need,
                                            StepperStats& st) {
  const bool slopes = (need & kSlopes) != 0;
  if (exact_) {
    using std::abs;
    const bool near = (need & kNear) != 0;
    bool hopped = false;
    if (near && abs(tau - near_t_) < tau - t_) {
      ys_ = near_y_;
      hopped = flow_.hop(tau - near_t_, ys_, work_);
    }
    if (!hopped) {
      ys_ = y_;
      flow_.expv(tau - t_, ys_, work_);
    }
    if (near) {
      near_y_ = ys_;
      near_t_ = tau;
    }
    if ((need & kQuadratures) != 0) {
      // A state that goes on (a sample, the next link of the sample chain, the event state): its
      // clock exact. Points of a root search keep the propagated clock (within a step of the
      // exact clock of y_, to round-off), which spares them a cosine and sine each.
      flow_.set_clock(tau, ys_);
      if (!quadrature(m, t_, y_, tau, ys_, st)) return false;
    }
    if (closed_form_guards() && (need & (kGuards | kSlopes)) != 0) {
      xs_ = ys_.head(nx_);
      if (!detail::all_finite(xs_)) return false;
      if (slopes) detail::small_product(gdot_, ys_, st_);
      if ((need & kSystemGuards) != 0)
        eval_guards(m, tau, xs_, gt_, st);
      else
        detail::small_product(ghat_, ys_, gt_);
      return detail::all_finite(gt_) && (!slopes || detail::all_finite(st_));
    }
  } else if (dense_point(tau)) {
    if (slopes && !remainder(m, tau, ys_, rs_, st)) return false;
  } else if (std::isnan(trial_step(m, tau, st))) {
    return false;
  }
  xs_ = ys_.head(nx_);
  if (!detail::all_finite(xs_)) return false;
  if ((need & (kGuards | kSlopes)) == 0) return true;
  eval_guards(m, tau, xs_, gt_, st);
  if (slopes) {
    if (!tangent(m, tau, ys_, xs_, rs_, st)) return false;
    guard_slopes(m, tau, xs_, xd_, st_, st);
  }
  return detail::all_finite(gt_);
}

template <class System>
bool ExactLinearStepper<System>::grazing_bracket(const Mode& m, Eigen::Index i, Scalar a,
                                                 Scalar da, Scalar sa, Scalar b, Scalar db,
                                                 Scalar sb, Bracket& out, StepperStats& st) {
  // Distances d >= 0 at both ends; slopes sa, sb of d. Look for an interior minimum of the cubic
  // Hermite interpolant that dips below half the smaller end value; if the exact d there is < 0,
  // [a, tau] brackets a crossing; otherwise search [a, tau] then [tau, b] (depth-first, the
  // earlier half first) until the intervals are below the event time tolerance.
  struct Node {
    Scalar a, da, sa, b, db, sb;
  };
  std::array<Node, 64> stack;
  int top = 0;
  stack[top++] = {a, da, sa, b, db, sb};
  const Scalar tol = opt_.event_time_tolerance;
  while (top > 0) {
    const Node nd = stack[--top];
    const Scalar H = nd.b - nd.a;
    if (!(H > tol) || !(nd.sa < 0 && nd.sb > 0)) continue;  // no interior minimum
    // p(s) = h00 da + h10 H sa + h01 db + h11 H sb on s in [0, 1]; its lowest stationary point.
    const detail::HermiteCubic<Scalar> p{nd.da, H * nd.sa, nd.db, H * nd.sb};
    std::array<Scalar, 2> s{};
    const int ns = p.stationary_points(s);
    Scalar s_min = Scalar(0.5), p_min = std::numeric_limits<Scalar>::infinity();
    for (int k = 0; k < ns; ++k) {
      const Scalar v = p(s[static_cast<std::size_t>(k)]);
      if (v < p_min) {
        p_min = v;
        s_min = s[static_cast<std::size_t>(k)];
      }
    }
    if (!(p_min < Scalar(0.5) * std::min(nd.da, nd.db))) continue;
    const Scalar tau = nd.a + s_min * H;
    ++work_.grazing_refinements;
    if (!eval_point(m, tau, kGuards | kSlopes, st)) continue;
    const Scalar dt = monitor_.distance(i, gt_[i]);
    if (dt < 0) {
      out = {nd.a, nd.da, tau, dt};
      return true;
    }
    const Scalar st_i = monitor_.distance(i, gt_[i] + st_[i]) - dt;
    if (top + 2 > static_cast<int>(stack.size())) continue;
    stack[top++] = {tau, dt, st_i, nd.b, nd.db, nd.sb};  // later half below
    stack[top++] = {nd.a, nd.da, nd.sa, tau, dt, st_i};  // earlier half on top
  }
  return false;
}

template <class System>
bool ExactLinearStepper<System>::find_event(const Mode& m, Scalar t1, StepperStats& st) {
  const Eigen::Index ng = gb_.size();
  const Scalar tol = opt_.event_time_tolerance;
  Scalar first = std::numeric_limits<Scalar>::infinity();
  Eigen::Index first_guard = -1;
  near_t_ = std::numeric_limits<Scalar>::quiet_NaN();  // no point of this step yet
  // Roots per guard (infinity = none).
  for (Eigen::Index i = 0; i < ng; ++i) {
    roots_[i] = std::numeric_limits<Scalar>::infinity();
    const Scalar da = monitor_.distance(i, ga_[i]);
    const Scalar db = monitor_.distance(i, gb_[i]);
    Bracket br{};
    bool found = false;
    if (db < 0) {
      br = {t_, da, t1, db};
      found = true;
    } else if (da >= 0) {
      const Scalar sa = monitor_.distance(i, ga_[i] + sa_[i]) - da;
      const Scalar sb = monitor_.distance(i, gb_[i] + sb_[i]) - db;
      found = grazing_bracket(m, i, t_, da, sa, t1, db, sb, br, st);
    }
    if (!found) continue;
    detail::RootBracket<Scalar> root{};
    if (closed_form_guards()) {
      // The guard's rate comes with the state (Ĝ Â y, one product): Newton on the closed form.
      auto phi = [&](Scalar tc, Scalar& slope) {
        if (!eval_point(m, tc, kGuards | kSlopes | kSystemGuards | kNear, st))
          return -std::numeric_limits<Scalar>::infinity();
        const Scalar d = monitor_.distance(i, gt_[i]);
        slope = monitor_.distance(i, gt_[i] + st_[i]) - d;
        return d;
      };
      // End slopes for the first (Hermite) point where the bracket is the whole step.
      const Scalar nan = std::numeric_limits<Scalar>::quiet_NaN();
      const bool whole = br.lo == t_ && br.hi == t1;
      const Scalar slo = whole ? monitor_.distance(i, ga_[i] + sa_[i]) - br.dlo : nan;
      const Scalar shi = whole ? monitor_.distance(i, gb_[i] + sb_[i]) - br.dhi : nan;
      root = detail::newton_root(phi, br.lo, br.dlo, slo, br.hi, br.dhi, shi, tol);
    } else {
      auto phi = [&](Scalar tc) {
        if (!eval_point(m, tc, kGuards | kSystemGuards, st))
          return -std::numeric_limits<Scalar>::infinity();
        return monitor_.distance(i, gt_[i]);
      };
      root = detail::illinois_root(phi, br.lo, br.dlo, br.hi, br.dhi, tol);
    }
    roots_[i] = root.hi;
    if (root.hi < first) {
      first = root.hi;
      first_guard = i;
    }
  }
  if (first_guard < 0) return false;
  te_ = first;
  if (first >= t1) {
    xe_ = x1_;
    eval_guards(m, t1, xe_, gt_, st);
  } else if (!exact_ && dense_ == Dense::Ready && opt_.event_state != EventState::DenseOutput) {
    te_ = refine_on_steps(m, first_guard, first, t1, st);
  } else {
    // From the root search's last point (a hop of at most the event time tolerance) where it
    // ran on the closed form.
    eval_point(m, first, kQuadratures | kGuards | kSystemGuards | (closed_form_guards() ? kNear : 0u), st);
    xe_ = xs_;
  }
  // Fired (as HybridStepper): every guard crossed at the handed state, and every guard whose root
  // lies within the event time tolerance of the first one (guards that cross together, such as
  // those of two mirror-image contacts, fire together although round-off leaves one of them a
  // hair short of zero).
  triggered_.clear();
  for (Eigen::Index i = 0; i < ng; ++i)
    if (monitor_.crossed(i, gt_[i]) || roots_[i] <= first + tol) triggered_.push_back(i);
  return true;
}

template <class System>
bool ExactLinearStepper<System>::cut_back_to_rearm(const Mode& m, Scalar& t1, Scalar& h,
                                                   Scalar& err, StepperStats& st) {
  bool disarmed = false;
  for (Eigen::Index i : triggered_) disarmed = disarmed || monitor_.disarmed(i);
  if (!disarmed || !(te_ > t_)) return false;
  for (const Scalar frac : {Scalar(0.5), Scalar(0.25), Scalar(0.75)}) {
    const Scalar tc = t_ + frac * (te_ - t_);
    if (!(tc > t_ && tc < te_)) continue;
    if (!eval_point(m, tc, kGuards | kSystemGuards, st)) continue;
    bool out = true;
    for (Eigen::Index i : triggered_)
      out = out && (!monitor_.disarmed(i) || monitor_.out_of_zero(i, gt_[i]));
    if (!out) continue;
    if (exact_) {
      if (!eval_point(m, tc, kQuadratures, st)) continue;
      y1_ = ys_;
    } else {
      // A step of the run (its stages serve the dense output of [t_, tc]); shorter than the
      // accepted one, so within its tolerance.
      const Scalar hc = tc - t_;
      const Scalar e = lawson_.step(
          flow_,
          [&](Scalar tt, const Vector& y, Vector& out_r) { return remainder(m, tt, y, out_r, st); },
          t_, y_, r_, hc, ys_, rs_, opt_.rtol, opt_.atol, work_, true);
      if (std::isnan(e) || !detail::all_finite(ys_)) continue;
      y1_ = ys_;
      r1_ = rs_;
      h = hc;
      err = e;
      step_h_ = hc;
      dense_ = Dense::Unknown;
    }
    t1 = tc;
    x1_ = y1_.head(nx_);
    if (closed_form_guards()) {
      detail::small_product(ghat_, y1_, gb_);
      detail::small_product(gdot_, y1_, sb_);
      work_.matvecs += 2;
    } else if (!end_guards(m, t1, st)) {
      gb_.setConstant(std::numeric_limits<Scalar>::quiet_NaN());  // (reported by the caller)
    }
    return true;
  }
  return false;
}

template <class System>
bool ExactLinearStepper<System>::dense_point(Scalar tau) {
  if (dense_ == Dense::Unknown) {
    dense_ = lawson_.dense_usable(flow_, step_h_) ? Dense::Ready : Dense::Unusable;
    if (dense_ == Dense::Ready) lawson_.prepare_dense(flow_, step_h_, y_, r_, r1_, work_);
  }
  if (dense_ != Dense::Ready) return false;
  lawson_.dense(flow_, (tau - t_) / step_h_, ys_, work_);
  flow_.set_clock(tau, ys_);
  ++work_.dense_outputs;
  return true;
}

template <class System>
auto ExactLinearStepper<System>::refine_on_steps(const Mode& m, Eigen::Index i, Scalar first,
                                                 Scalar t1, StepperStats& st) -> Scalar {
  const Scalar tol = opt_.event_time_tolerance;
  auto dense_distance = [&](Scalar tc) {
    if (!eval_point(m, tc, kGuards | kSystemGuards, st)) return std::numeric_limits<Scalar>::quiet_NaN();
    return monitor_.distance(i, gt_[i]);
  };
  // Slope of the dense output's guard at first (before trial steps: they use the stage vectors).
  const Scalar w = std::min(first - t_, std::max(Scalar(16) * tol, Scalar(1e-6) * step_h_));
  const Scalar slope = (dense_distance(first) - dense_distance(first - w)) / w;
  auto step_to = [&](Scalar tau) {
    const Scalar err = trial_step(m, tau, st);
    xe_ = ys_.head(nx_);
    if (std::isnan(err) || !detail::all_finite(xe_)) return -std::numeric_limits<Scalar>::infinity();
    eval_guards(m, tau, xe_, gt_, st);
    ++work_.event_reintegrations;
    return monitor_.distance(i, gt_[i]);
  };
  return detail::refine_root_on_steps(step_to, first, slope, t_, monitor_.distance(i, ga_[i]), t1,
                                      monitor_.distance(i, gb_[i]), tol)
      .hi;
}

template <class System>
template <class Observer>
bool ExactLinearStepper<System>::emit_samples(Observer& obs, const Mode& m, Scalar upto, Scalar t1,
                                              StepperStats& st) {
  if (!(opt_.output_interval > 0)) return true;
  for (;;) {
    const Scalar ts = t0_ + static_cast<Scalar>(next_sample_) * opt_.output_interval;
    if (ts > upto) return true;
    ++next_sample_;
    if (ts < t_) continue;
    const long k = next_sample_ - 1;
    const Vector* ysample = nullptr;  // the augmented sample (exact modes: the chain's next link)
    if (ts == t_) {
      xs_ = x_;
      ysample = &y_;
    } else if (ts == t1) {
      xs_ = x1_;
      ysample = &y1_;
    } else if (exact_ && (forms_ || nq_ == 0) && k_chain_ == k - 1 &&
               (mode_samples_ >= closed_form_after || mode_steps_ >= closed_form_after ||
                out_valid_ || flow_.restored())) {
      // One interval on from the previous sample of this mode: y(ts) = exp(Â h_out) y(ts - h_out).
      if (!out_valid_) {
        flow_.van_loan(opt_.output_interval, lp_.quadrature_forms, phi_out_, w_out_, work_);
        out_valid_ = true;
        if (ModeBlocks* b = mode_blocks(true)) {
          b->phi_out = phi_out_;
          b->w_out = w_out_;
          b->out = true;
        }
      }
      ys_.noalias() = phi_out_ * y_chain_;
      ++work_.matvecs;
      if (forms_) add_quadratures(y_chain_, w_out_, ys_);
      flow_.set_clock(ts, ys_);
      xs_ = ys_.head(nx_);
      ysample = &ys_;
    } else if (!eval_point(m, ts, kQuadratures, st)) {
      xs_.setConstant(std::numeric_limits<Scalar>::quiet_NaN());
    } else {
      ysample = &ys_;
    }
    if (exact_ && ysample != nullptr) {
      y_chain_ = *ysample;
      k_chain_ = k;
      ++mode_samples_;
    }
    if (!obs.on_sample(ts, xs_, m)) return false;
  }
}

/// The run loop of integrate(mode, t0, x0, t_end, observer), declared in the class.
template <class System>
template <class Observer>
auto ExactLinearStepper<System>::integrate(Mode mode, Scalar t0, const State& x0, Scalar t_end,
                                           Observer& obs) -> Result {
  static const std::string where = "ExactLinearStepper::integrate";
  detail::check_run_arguments(where, t0, x0, t_end);
  detail::check_sample_times(where, t0, t_end, opt_);

  Result r;
  StepperStats& st = r.stats;
  work_ = ExactStepperStats{};
  nx_ = x0.size();
  x_ = x0;
  for (State* v : {&x1_, &xs_, &xe_, &xd_, &xr_, &fr_, &xg_}) v->resizeLike(x0);
  triggered_.clear();
  triggered_.reserve(static_cast<std::size_t>(std::max<Eigen::Index>(sys_.num_guards(mode), 8)));
  zeno_.reset(opt_);
  t0_ = t0;
  next_sample_ = 0;
  t_ = t0;

  if (!start_mode(mode, t_, st))
    return finish(r, Status::NonFiniteState, t_, x_, mode,
                  "right-hand side or guards not finite " + detail::at_time(t_));
  if (!emit_samples(obs, mode, t_, t_, st))
    return finish(r, Status::StoppedByObserver, t_, x_, mode,
                  "stopped by observer " + detail::at_time(t_));

  // Step of the exponential method (inexact modes); carried across events.
  Scalar h = opt_.initial_step > 0 ? opt_.initial_step : Scalar(1e-3);
  bool after_reject = false, jumped = false;
  long attempts = 0;
  using std::pow;

  while (t_ < t_end) {
    if (attempts >= opt_.max_steps)
      return finish(r, Status::MaxSteps, t_, x_, mode,
                    "max_steps " + std::to_string(opt_.max_steps) + " reached " +
                        detail::at_time(t_));
    ++attempts;
    Scalar t1 = 0, err = 0;
    jumped = false;
    bool slip_cleared = false;
    // No step below min_step * max(1, |t|) short of t_end: t + h would not resolve it (the
    // guard sampling step of a stiff mode far out in t), and a run of such steps would spin
    // until max_steps with a clock that does not advance.
    const Scalar hmin = opt_.smallest_step(t_);
    if (exact_) {
      if (ladder_waits_ && mode_steps_ >= flow_.dim()) {  // the mode lasts: its ladder pays
        ladder_waits_ = false;
        flow_.prepare(delta_, work_, true);
      }
      Scalar hs = delta_;
      t1 = t_ + hs;
      if (!(t_end - t1 > Scalar(0.01) * hs)) {
        t1 = t_end;
        hs = t_end - t_;
      } else if (!(hs >= hmin)) {
        return finish(r, Status::StepSizeUnderflow, t_, x_, mode,
                      "guard sampling step " + detail::short_number(hs) +
                          " of the exact mode fell below min_step " + detail::short_number(hmin) +
                          " " + detail::at_time(t_));
      }
      const int level = hs == delta_ ? choose_jump(t_end) : 0;
      const bool grid = hs == delta_ && flow_.has_ladder();
      if (level > 0) {
        const auto j = static_cast<std::size_t>(level - 1);
        t1 = t_ + std::ldexp(delta_, level);
        y1_.noalias() = jump_phi_[j] * y_;
        ++work_.matvecs;
        flow_.set_clock(t1, y1_);
        if (nq_ > 0) add_quadratures(y_, jump_w_[j], y1_);
        ++work_.long_steps;
        jumped = true;
      } else if (grid) {
        detail::small_product(flow_.propagator(), y_, y1_);
        ++work_.matvecs;
      } else {
        y1_ = y_;
        flow_.expv(hs, y1_, work_);
      }
      if (!jumped) {
        // The grid propagator carries the clock exactly up to round-off; reset it to cos / sin of
        // t1 every 16th grid step (and after any other step), which bounds that drift to a few
        // ulps and spares a cosine and a sine per step.
        if (!grid || (mode_steps_ % 16) == 15) flow_.set_clock(t1, y1_);
        if (grid && grid_quadrature_ready())
          add_quadratures(y_, w_grid_, y1_);
        else if (!quadrature(mode, t_, y_, t1, y1_, st))
          return finish(r, Status::NonFiniteState, t_, x_, mode,
                        "quadrature right-hand side not finite " + detail::at_time(t_));
      }
      ++mode_steps_;
    } else {
      // (only where the step control would go past delta: the bounds cost ~60 small products
      // per frozen Â, more than the steps they save where the remainder limits them anyway)
      const int slip_level = h > delta_ ? choose_slip_level() : 0;
      const Scalar cap = slip_level > 0 ? std::ldexp(delta_, slip_level) : delta_;
      h = std::min({h, opt_.max_step, guarded_ ? cap : opt_.max_step});
      // Long steps take the lengths 2^j delta only, whose stage propagators are kept.
      if (slip_level > 0 && h > delta_) h = std::ldexp(delta_, std::ilogb(h / delta_));
      t1 = t_ + h;
      if (t_end - t1 <= Scalar(0.01) * h) {
        t1 = t_end;
        h = t_end - t_;
      } else if (!(h >= hmin)) {
        return finish(r, Status::StepSizeUnderflow, t_, x_, mode,
                      "step size " + detail::short_number(h) + " fell below min_step " +
                          detail::short_number(hmin) + " " + detail::at_time(t_));
      }
      err = lawson_.step(
          flow_,
          [&](Scalar tt, const Vector& y, Vector& out) { return remainder(mode, tt, y, out, st); },
          t_, y_, r_, h, y1_, r1_, opt_.rtol, opt_.atol, work_, true);
      if (std::isnan(err) || !detail::all_finite(y1_) || err > Scalar(1)) {
        ++st.rejected_steps;
        const bool bad = std::isnan(err) || !detail::all_finite(y1_);
        h *= bad ? Scalar(0.5)
                 : std::max(Scalar(0.2), opt_.safety * pow(err, Scalar(-1) / Scalar(5)));
        after_reject = true;
        if (h < hmin)
          return finish(r, bad ? Status::NonFiniteState : Status::StepSizeUnderflow, t_, x_, mode,
                        (bad ? std::string("right-hand side or state became non-finite ")
                             : "step size " + detail::short_number(h) + " fell below min_step " +
                                   detail::short_number(hmin) + " ") +
                            detail::at_time(t_));
        continue;
      }
      if (slip_level > 0 && h > delta_) {
        // A step longer than the guard sampling: kept only where no guard can have reached its
        // trigger inside it, else re-taken at delta.
        x1_ = y1_.head(nx_);
        if (!detail::all_finite(x1_) || !end_guards(mode, t1, st) || !slip_step_clear(slip_level, h)) {
          ++st.rejected_steps;
          ++work_.slip_bound_rejections;
          slip_retry_ = true;
          h = delta_;
          continue;
        }
        slip_cleared = true;
        ++work_.long_slip_steps;
      }
    }
    x1_ = y1_.head(nx_);
    if (!detail::all_finite(x1_))
      return finish(r, Status::NonFiniteState, t_, x_, mode,
                    "state became non-finite " + detail::at_time(t1));
    ++st.accepted_steps;
    if (exact_) {
      ++work_.exact_steps;
    } else {
      ++work_.exponential_steps;
      step_h_ = h;
      dense_ = Dense::Unknown;
    }

    bool event = false;
    if (guarded_ && closed_form_guards()) {
      detail::small_product(ghat_, y1_, gb_);
      detail::small_product(gdot_, y1_, sb_);
      work_.matvecs += 2;
      if (!detail::all_finite(gb_) || !detail::all_finite(sb_))
        return finish(r, Status::NonFiniteState, t1, x1_, mode,
                      "guards not finite " + detail::at_time(t1));
      // A long step has no root by its bound (the search runs only if round-off says otherwise).
      event = (!jumped || monitor_.any_crossed(gb_)) && find_event(mode, t1, st);
    } else if (guarded_) {
      if (!slip_cleared && !end_guards(mode, t1, st))
        return finish(r, Status::NonFiniteState, t1, x1_, mode,
                      "guards or right-hand side not finite " + detail::at_time(t1));
      // A long slipping step has no root by its check.
      event = !slip_cleared && find_event(mode, t1, st);
    }

    if (event) {
      // A disarmed guard that left zero and returns inside the step: the step cut back to where
      // it is out (armed there at the step end); a crossing at the shorter step's end after all
      // (its state differs from the longer step's by the method's error) is located again.
      if (cut_back_to_rearm(mode, t1, h, err, st)) {
        if (!detail::all_finite(x1_) || !detail::all_finite(gb_) || !detail::all_finite(sb_))
          return finish(r, Status::NonFiniteState, t_, x_, mode,
                        "state or guards not finite " + detail::at_time(t1));
        event = find_event(mode, t1, st);
      }
    }
    if (event) {
      if (!emit_samples(obs, mode, te_, t1, st))
        return finish(r, Status::StoppedByObserver, te_, xe_, mode,
                      "stopped by observer " + detail::at_time(te_));
      if (!obs.on_step(te_, xe_, mode))
        return finish(r, Status::StoppedByObserver, te_, xe_, mode,
                      "stopped by observer " + detail::at_time(te_));
      bool immediate = false;
      for (Eigen::Index i : triggered_) immediate = immediate || monitor_.disarmed(i);
      t_ = te_;
      x_ = xe_;
      dense_ = Dense::Unusable;
      const Mode from = mode;
      TransitionAction action = sys_.transition(mode, triggered_, t_, x_);
      ++st.events;
      detail::notify_event(obs, EventRecord<Scalar, Mode>{t_, from, mode, &triggered_}, x_);
      if (action.stop)
        return finish(r, Status::StoppedBySystem, t_, x_, mode,
                      "stopped by system " + detail::at_time(t_) + ": " + action.reason);
      std::string why;
      if (!zeno_.record(t_, immediate, st.events, why))
        return finish(r, Status::ZenoGuard, t_, x_, mode, std::move(why));
      if (!start_mode(mode, t_, st))
        return finish(r, Status::NonFiniteState, t_, x_, mode,
                      "right-hand side or guards not finite after the transition " +
                          detail::at_time(t_));
      continue;
    }

    if (!emit_samples(obs, mode, t1, t1, st))
      return finish(r, Status::StoppedByObserver, t1, x1_, mode,
                    "stopped by observer " + detail::at_time(t1));
    t_ = t1;
    x_ = x1_;
    y_.swap(y1_);
    dense_ = Dense::Unusable;
    if (guarded_) {
      ga_.swap(gb_);
      sa_.swap(sb_);
      monitor_.update_arming(ga_);
    }
    if (!obs.on_step(t_, x_, mode))
      return finish(r, Status::StoppedByObserver, t_, x_, mode,
                    "stopped by observer " + detail::at_time(t_));
    if (!exact_) {
      r_.swap(r1_);
      if (linear_ && remainder_grown(err, h)) {
        // A_m follows the state (the contact point moves): refresh it, keeping the step.
        ++work_.linear_part_refreshes;
        if (!refresh_linear_part(mode, t_, false, st))
          return finish(r, Status::NonFiniteState, t_, x_, mode,
                        "right-hand side not finite " + detail::at_time(t_));
        if (exact_) continue;  // the mode became exact
      }
      Scalar fac = err > 0 ? opt_.safety * pow(err, Scalar(-1) / Scalar(5)) : Scalar(5);
      fac = std::min(Scalar(5), std::max(Scalar(0.2), fac));
      if (after_reject) fac = std::min(fac, Scalar(1));
      h *= fac;
      after_reject = false;
      slip_retry_ = false;
    }
  }
  return finish(r, Status::Success, t_, x_, mode, std::string());
}

}  // namespace stickslip
