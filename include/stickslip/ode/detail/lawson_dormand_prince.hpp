#pragma once
/// \file lawson_dormand_prince.hpp
/// \brief Integrating-factor (Lawson) form of the Dormand-Prince 5(4) pair in the frame of the
/// augmented generator Â (internal to ExactLinearStepper).
///
/// For y' = Â y + R(t, y), the Dormand-Prince pair applied to w(s) = exp(-Â s) y(t + s) gives,
/// written back in y (c_i non-decreasing, so that only exp(Â tau) with tau >= 0 appears):
///
///     Y_i   = exp(c_i h Â) y_0 + h sum_{j<i} a_ij exp((c_i - c_j) h Â) R_j,  R_j = R(t + c_j h, Y_j)
///     y_1   = exp(h Â) y_0 + h sum_j b_j exp((1 - c_j) h Â) R_j
///     err   = h sum_j (b_j - bhat_j) exp((1 - c_j) h Â) R_j   (R_7 = R(t + h, y_1), FSAL)
///
/// The linear part is exact for any h (no stability limit from Â); the order is 5 for a smooth
/// remainder (Hochbruck & Ostermann, Acta Numerica 19, 2010, Sec. 2.2), error estimate O(h^5).
///
/// Dense output: Dormand-Prince's continuous extension of order 4 (Hairer, Norsett & Wanner I,
/// Sec. II.6, dopri5's CONTD5) applied to w, with K_j = exp(-c_j h Â) R_j, written back in y:
///
///     y(t + theta h) = exp(theta h Â) v(theta),   v(theta) = y_0 + h sum_j b_j(theta) K_j,
///
/// local error O(h^5) uniformly in theta in [0, 1] for a smooth remainder (the error of w's
/// extension, carried by exp(theta h Â)). The K_j come from the stages carried to c = 1 by one
/// backward propagator, K_j = exp(-h Â) exp((1 - c_j) h Â) R_j: usable where exp(-h Â) stays
/// bounded (h times the largest decay rate of Â small; see dense_usable).

#include <stickslip/detail/validate.hpp>
#include <stickslip/ode/detail/augmented_flow.hpp>
#include <stickslip/ode/detail/step_control.hpp>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace stickslip {
namespace detail {

template <class Scalar>
class LawsonDormandPrince {
 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  static constexpr int order = 5;
  static constexpr int error_order = 4;

  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  /// Size the stage vectors (allocates only when dim grows).
  void initialize(Eigen::Index dim) {
    for (Vector& v : k_) v.resize(dim);
    for (Vector* v : {&p_, &ys_, &prod_, &w0_, &dd_, &q3_, &q4_, &q5_}) v->resize(dim);
  }

  /// Largest h d (d: the largest decay rate -Re lambda of Â) for which the dense output is used:
  /// exp(-h Â) then amplifies by at most e^2 ~ 7.4 (round-off of the stages, relative to the
  /// solution); beyond it the caller re-takes trial steps.
  static constexpr double max_backward_growth = 2.0;

  /// True when the dense output of a step of size h on the flow's Â is usable (see
  /// max_backward_growth).
  static bool dense_usable(const AugmentedFlow<Scalar>& flow, Scalar h) {
    return h * flow.decay_rate() <= Scalar(max_backward_growth);
  }

  /// One step of size h from (t, y0) with r0 = R(t, y0): writes y1 and r1 = R(t + h, y1), returns
  /// the weighted RMS error (over the first nx components). `rem(t, y, out)` evaluates R and
  /// returns false when it is not finite (the step then returns NaN). With `reuse` (steps of the
  /// run, not trial points inside one), a step of the same h as the previous such step on the same
  /// Â uses the five stage propagators exp((c_i - c_{i-1}) h Â), computed once for that h by Padé
  /// (one product per carried vector instead of a ladder walk and a Taylor series).
  template <class Remainder>
  Scalar step(AugmentedFlow<Scalar>& flow, Remainder&& rem, Scalar t, const Vector& y0,
              const Vector& r0, Scalar h, Vector& y1, Vector& r1, Scalar rtol, Scalar atol,
              ExactStepperStats& st, bool reuse = false) {
    const auto c = [](double v) { return static_cast<Scalar>(v); };
    static constexpr std::array<double, 7> cs{0.0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1.0, 1.0};
    static constexpr double a[6][5] = {
        {0, 0, 0, 0, 0},
        {1.0 / 5, 0, 0, 0, 0},
        {3.0 / 40, 9.0 / 40, 0, 0, 0},
        {44.0 / 45, -56.0 / 15, 32.0 / 9, 0, 0},
        {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729, 0},
        {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656}};
    static constexpr std::array<double, 7> b{35.0 / 384, 0.0, 500.0 / 1113, 125.0 / 192,
                                             -2187.0 / 6784, 11.0 / 84, 0.0};
    static constexpr std::array<double, 7> e{71.0 / 57600,     0.0,         -71.0 / 16695,
                                             71.0 / 1920,      -17253.0 / 339200,
                                             22.0 / 525,       -1.0 / 40};
    const Eigen::Index nx = flow.state_size();
    bool cached = false;
    if (reuse) {
      const PropagatorKey key{h, flow.generation()};
      set_ = find_set(key);
      const bool stages = set_ >= 0 && sets_[static_cast<std::size_t>(set_)].has_stages;
      if (!stages && last_key_.matches(key)) {
        if (set_ < 0) set_ = replace_set(key);  // (else the set holds only the backward one)
        for (int i = 1; i < 6; ++i) {
          const auto iu = static_cast<std::size_t>(i);
          flow.expm(c(cs[iu] - cs[iu - 1]) * h, sets_[static_cast<std::size_t>(set_)].stage[iu - 1], st);
        }
        sets_[static_cast<std::size_t>(set_)].has_stages = true;
      }
      cached = set_ >= 0 && sets_[static_cast<std::size_t>(set_)].has_stages;
      last_key_ = key;
    }
    stages_of_run_step_ = reuse;
    p_ = y0;
    k_[0] = r0;
    for (int i = 1; i < 6; ++i) {
      // Carry y0 and R_0 .. R_{i-1} from c_{i-1} h to c_i h.
      const auto iu = static_cast<std::size_t>(i);
      const Scalar dt = c(cs[iu] - cs[iu - 1]) * h;
      if (cached) {
        const Matrix& prop = sets_[static_cast<std::size_t>(set_)].stage[iu - 1];
        carry(prop, p_, st);
        for (std::size_t j = 0; j < iu; ++j) carry(prop, k_[j], st);
      } else {
        flow.expv(dt, p_, st);
        for (int j = 0; j < i; ++j) flow.expv(dt, k_[static_cast<std::size_t>(j)], st);
      }
      ys_ = p_;
      for (int j = 0; j < i; ++j)
        if (a[i][j] != 0.0) ys_.noalias() += (h * c(a[i][j])) * k_[static_cast<std::size_t>(j)];
      if (!rem(t + c(cs[static_cast<std::size_t>(i)]) * h, ys_, k_[static_cast<std::size_t>(i)]))
        return std::numeric_limits<Scalar>::quiet_NaN();
    }
    // All carried to c = 1 (c_6 = 1): the solution and the error estimate.
    y1 = p_;
    for (std::size_t j = 0; j < 6; ++j)
      if (b[j] != 0.0) y1.noalias() += (h * c(b[j])) * k_[j];
    if (!rem(t + h, y1, r1)) return std::numeric_limits<Scalar>::quiet_NaN();
    ys_ = (h * c(e[6])) * r1;
    for (std::size_t j = 0; j < 6; ++j)
      if (e[j] != 0.0) ys_.noalias() += (h * c(e[j])) * k_[j];
    return weighted_rms(ys_.head(nx), y0.head(nx), y1.head(nx), rtol, atol);
  }

  /// exp(h Â) y0 of the last step (the free flow of the linear part over it); valid until the
  /// next step.
  const Vector& free_flow() const noexcept { return p_; }

  /// Build the dense output of the last step (taken with `reuse`, no trial step since: the stage
  /// vectors must still be that step's) of size h from (y0, r0), r1 = R at its end; see the file
  /// comment.
  /// Five products with exp(-h Â), computed by Padé once per step length and Â. Call only where
  /// dense_usable(flow, h).
  void prepare_dense(AugmentedFlow<Scalar>& flow, Scalar h, const Vector& y0,
                     const Vector& r0, const Vector& r1, ExactStepperStats& st) {
    STICKSLIP_ASSERT(stages_of_run_step_ && "LawsonDormandPrince: dense output of a trial step");
    const auto c = [](double v) { return static_cast<Scalar>(v); };
    const PropagatorKey key{h, flow.generation()};
    int set = find_set(key);
    if (set < 0) set = replace_set(key);
    PropagatorSet& ps = sets_[static_cast<std::size_t>(set)];
    if (!ps.has_back) {
      flow.expm(-h, ps.back, st);
      ps.has_back = true;
    }
    const Matrix& back = ps.back;
    // K_j in the frame of the step start (K_1 = r0 exactly; K_2 has no weight below).
    for (std::size_t j : {2u, 3u, 4u, 5u}) carry(back, k_[j], st);
    prod_.noalias() = back * r1;
    ++st.matvecs;
    const Vector& k7 = prod_;
    // Hairer's form: v = w0 + theta (D + (1 - theta) (q3 + theta (q4 + (1 - theta) q5))) with
    // D = w1 - w0 = h sum b_j K_j, q3 = h K_1 - D, q4 = D - h K_7 - q3, q5 = h sum d_j K_j.
    w0_ = y0;
    dd_.noalias() = h * (c(35.0 / 384) * r0 + c(500.0 / 1113) * k_[2] + c(125.0 / 192) * k_[3] -
                         c(2187.0 / 6784) * k_[4] + c(11.0 / 84) * k_[5]);
    q3_.noalias() = h * r0 - dd_;
    q4_.noalias() = dd_ - h * k7 - q3_;
    q5_.noalias() = h * (c(-12715105075.0 / 11282082432.0) * r0 +
                         c(87487479700.0 / 32700410799.0) * k_[2] +
                         c(-10690763975.0 / 1880347072.0) * k_[3] +
                         c(701980252875.0 / 199316789632.0) * k_[4] +
                         c(-1453857185.0 / 822651844.0) * k_[5] + c(69997945.0 / 29380423.0) * k7);
    dense_h_ = h;
    stages_of_run_step_ = false;  // the stages are now in the start frame
  }

  /// y(t + theta h) of the step of prepare_dense into out, theta in [0, 1]: v(theta) and one
  /// exp(theta h Â) v by the flow's ladder.
  void dense(AugmentedFlow<Scalar>& flow, Scalar theta, Vector& out, ExactStepperStats& st) const {
    const Scalar s = Scalar(1) - theta;
    out.noalias() = w0_ + theta * (dd_ + s * (q3_ + theta * (q4_ + s * q5_)));
    flow.expv(theta * dense_h_, out, st);
  }

 private:
  void carry(const Matrix& e, Vector& v, ExactStepperStats& st) {
    prod_.noalias() = e * v;
    v.swap(prod_);
    ++st.matvecs;
  }

  std::array<Vector, 6> k_;
  Vector p_, ys_, prod_;
  // A propagator's step length and the generation of the Â it was computed on. Lengths equal to
  // 1e-12 relative share a propagator: the difference is round-off of t (steps cut to end on an
  // output sample differ in the last bits).
  struct PropagatorKey {
    Scalar h = 0;
    std::uint64_t generation = 0;
    bool matches(const PropagatorKey& other) const {
      using std::abs;
      return generation == other.generation && abs(other.h - h) <= Scalar(1e-12) * other.h;
    }
  };
  // Propagators of a few step lengths (the exponential steps of a run take one length, or the
  // few lengths 2^j delta of long steps in modes with frozen guards): the stage propagators
  // exp((c_i - c_{i-1}) h Â) (computed once a length comes twice in a row: last_key_ is the key
  // of the last step with reuse) and the dense output's exp(-h Â), each built at first use.
  struct PropagatorSet {
    PropagatorKey key;
    std::array<Matrix, 5> stage;
    Matrix back;
    bool has_stages = false, has_back = false;
    std::uint64_t used = 0;
  };
  static constexpr std::size_t propagator_sets = 4;
  std::array<PropagatorSet, propagator_sets> sets_;
  std::uint64_t use_clock_ = 0;
  int set_ = -1;
  PropagatorKey last_key_;
  int find_set(const PropagatorKey& key) {
    for (std::size_t i = 0; i < propagator_sets; ++i)
      if ((sets_[i].has_stages || sets_[i].has_back) && sets_[i].key.matches(key)) {
        sets_[i].used = ++use_clock_;
        return static_cast<int>(i);
      }
    return -1;
  }
  // The least recently used set, emptied and given to key.
  int replace_set(const PropagatorKey& key) {
    std::size_t lru = 0;
    for (std::size_t i = 1; i < propagator_sets; ++i)
      if (sets_[i].used < sets_[lru].used) lru = i;
    sets_[lru].key = key;
    sets_[lru].has_stages = sets_[lru].has_back = false;
    sets_[lru].used = ++use_clock_;
    return static_cast<int>(lru);
  }
  // Dense output: the vectors of Hairer's form.
  Vector w0_, dd_, q3_, q4_, q5_;
  Scalar dense_h_ = 0;
  bool stages_of_run_step_ = false;
};

}  // namespace detail
}  // namespace stickslip
