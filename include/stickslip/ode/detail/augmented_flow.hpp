#pragma once
/// \file augmented_flow.hpp
/// \brief The exact flow of the linear part of a mode in augmented autonomous form (internal to
/// ExactLinearStepper).
///
/// With x = (x_L, x_Q) (linear components, then quadratures) and the clock components
/// c = (1, cos w_1 t, sin w_1 t, ...), the vector y = (x, c) obeys
///
///     y' = Â y + R(t, y),   Â = [[A, 0, b0 bc_1 bs_1 ...], [0, 0, 0], [0, 0, blkdiag(W_k)]],
///     W_k = [[0, -w_k], [w_k, 0]],
///
/// where R = (f(t, x) - (Â y)_x, 0) is the remainder of the mode (zero in the x_L rows where the
/// mode is exact, the quadrature derivatives in the x_Q rows). Constant and harmonic loads,
/// including a harmonic at a resonance of A, are then part of exp(Â tau): no particular-solution
/// special cases.

#include <stickslip/detail/validate.hpp>
#include <stickslip/ode/detail/balance.hpp>
#include <stickslip/ode/detail/pade_exponential.hpp>
#include <stickslip/ode/linear_part.hpp>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace stickslip {

/// Work counters of ExactLinearStepper (beside the StepperStats of the result).
struct ExactStepperStats {
  long exact_steps = 0;          ///< steps of the exact propagation (r_m = 0)
  long exponential_steps = 0;    ///< accepted steps of the exponential Runge-Kutta method
  long matvecs = 0;              ///< products of the augmented generator with a vector
  long propagator_exponentials = 0;  ///< matrices exp(Â delta) computed (Padé, PadeExponential)
  long eigen_decompositions = 0;  ///< eigenvalue computations of A_m (sampling rate)
  long linear_part_calls = 0;    ///< calls of System::linear_part
  long grazing_refinements = 0;  ///< exact evaluations spent by the grazing (Hermite) test
  long long_steps = 0;           ///< exact steps of several grid steps (guard-rate bound)
  long linear_part_refreshes = 0;  ///< refreshes of a frozen linear part in inexact modes
  long mode_cache_hits = 0;      ///< modes whose propagators came from the mode cache
  long dense_outputs = 0;        ///< points taken from a Lawson step's dense output
  long event_reintegrations = 0;  ///< trial steps re-taken to refine an event (Reintegrate)
  long long_slip_steps = 0;      ///< Lawson steps longer than the guard sampling (frozen guards)
  long slip_bound_rejections = 0;  ///< long Lawson steps re-taken at the guard sampling step
};

namespace detail {

/// out = m v for the small products of the exact stepper: Eigen's coefficient-based product
/// (lazyProduct, inlined) up to 8 columns, where the general matrix-vector kernel's set-up costs
/// more than the arithmetic (a 3 x 3 to 8 x 8 augmented generator of a one- or two-mass system);
/// the kernel above that.
template <class M, class V, class Out>
void small_product(const M& m, const V& v, Out& out) {
  if (m.cols() <= 8)
    out.noalias() = m.lazyProduct(v);
  else
    out.noalias() = m * v;
}

/// Â of a mode, exp(Â tau) y by a scaled Taylor series, and a cached exp(Â delta).
template <class Scalar>
class AugmentedFlow {
 public:
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  /// Build Â from lp for a state of nx components (lp.size() <= nx). The eigenvalues of A_m are
  /// recomputed only when lp.version or the size changed; the cached propagator is dropped only
  /// when Â changed. Returns true when Â changed.
  bool assign(const LinearPart<Scalar>& lp, Eigen::Index nx, ExactStepperStats& st) {
    const Eigen::Index n = lp.size();
    const Eigen::Index nk = static_cast<Eigen::Index>(lp.omega.size());
    const Eigen::Index dim = nx + 1 + 2 * nk;
    build_.setZero(dim, dim);
    build_.topLeftCorner(n, n) = lp.A;
    if (n > 0) {
      build_.block(0, nx, n, 1) = lp.b0;
      for (Eigen::Index k = 0; k < nk; ++k) {
        const Scalar w = lp.omega[static_cast<std::size_t>(k)];
        build_.block(0, nx + 1 + 2 * k, n, 1) = lp.bc.col(k);
        build_.block(0, nx + 2 + 2 * k, n, 1) = lp.bs.col(k);
        build_(nx + 1 + 2 * k, nx + 2 + 2 * k) = -w;
        build_(nx + 2 + 2 * k, nx + 1 + 2 * k) = w;
      }
    }
    const bool same = a_.rows() == dim && a_ == build_;
    bool restored = false;
    if (!same) {
      ++generation_;
      a_.swap(build_);
      ladder_k_ = -1;
      ladder_in_cache_ = false;
      nilpotent_ = -1;
      norm1_ = a_.cwiseAbs().colwise().sum().maxCoeff();
      slot_ = -1;
      for (std::size_t i = 0; i < cache_.size() && i < cache_size_; ++i) {
        Entry& e = cache_[i];
        if (e.ladder_k < 0 || e.a.rows() != dim || !(e.a == a_)) continue;
        ladder_in_cache_ = true;  // read in place (no copy of the K + 1 matrices)
        bal_ = e.bal;             // the balancing of Â with it
        scale_ = e.scale;
        bnorm1_ = e.bnorm1;
        ladder_k_ = e.ladder_k;
        base_ = e.base;
        rate_ = e.rate;
        decay_ = e.decay;
        slot_ = static_cast<int>(i);
        restored = true;
        ++st.mode_cache_hits;
        break;
      }
      if (!restored) balance();
    }
    last_restored_ = restored || (same && last_restored_);
    if (restored) {
      version_ = lp.version;
      rate_valid_ = true;
    }
    const bool rate_stale = !rate_valid_ || version_ != lp.version || n_ != n;
    nx_ = nx;
    n_ = n;
    omega_ = lp.omega;
    if (rate_stale) {
      rate_ = 0;
      decay_ = 0;
      if (n > 0) {
        eig_.compute(lp.A, false);
        ++st.eigen_decompositions;
        if (eig_.info() == Eigen::Success) {
          rate_ = eig_.eigenvalues().cwiseAbs().maxCoeff();
          decay_ = std::max(Scalar(0), -eig_.eigenvalues().real().minCoeff());
        } else {
          rate_ = lp.A.cwiseAbs().rowwise().sum().maxCoeff();  // a bound on |lambda|
          decay_ = rate_;
        }
      }
      version_ = lp.version;
      rate_valid_ = true;
    }
    fastest_ = rate_;
    for (Scalar w : lp.omega) fastest_ = std::max(fastest_, std::abs(w));
    term_.resize(dim);
    prod_.resize(dim);
    return !same;
  }

  Eigen::Index dim() const noexcept { return a_.rows(); }
  Eigen::Index state_size() const noexcept { return nx_; }
  Eigen::Index linear_size() const noexcept { return n_; }
  const Matrix& generator() const noexcept { return a_; }
  /// Changes (increments) whenever Â changes; starts at 1 with the first assign().
  std::uint64_t generation() const noexcept { return generation_; }

  /// max(|lambda(A_m)|, w_k): the fastest rate (rad per time unit) of the mode's solutions.
  Scalar fastest_rate() const noexcept { return fastest_; }

  /// max(0, -Re lambda(A_m)): the fastest decay of the mode's solutions, i.e. the growth rate of
  /// exp(-Â tau) (the clock block is a rotation).
  Scalar decay_rate() const noexcept { return decay_; }

  /// y = (x, 1, cos w_1 t, sin w_1 t, ...).
  template <class X>
  void lift(Scalar t, const X& x, Vector& y) const {
    y.resize(dim());
    y.head(nx_) = x;
    set_clock(t, y);
  }

  /// Overwrite the clock components of y with their exact values at t (keeps them from drifting
  /// by round-off over many steps).
  void set_clock(Scalar t, Vector& y) const {
    using std::cos;
    using std::sin;
    y[nx_] = Scalar(1);
    for (std::size_t k = 0; k < omega_.size(); ++k) {
      const Eigen::Index j = nx_ + 1 + 2 * static_cast<Eigen::Index>(k);
      y[j] = cos(omega_[k] * t);
      y[j + 1] = sin(omega_[k] * t);
    }
  }

  /// out[0 .. nx) = (Â y) restricted to the state rows (out may be longer).
  template <class Out>
  void rate(const Vector& y, Out& out, ExactStepperStats& st) const {
    STICKSLIP_ASSERT(out.size() >= nx_ && y.size() == dim());
    out.head(nx_).noalias() = a_.topRows(nx_) * y;
    ++st.matvecs;
  }

  /// Prepare exp(Â tau) for any tau on a binary ladder of base `base` (> 0, finite):
  /// Phi_k = exp(Â base 2^-k), k = 0 .. K, with ||B||_1 base 2^-K <= 2^-ladder_tail_bits (B: the
  /// balanced Â, see expm); Phi_0 and Phi_K by expm, the others by squaring. Kept
  /// while Â and base do not change; with `keep`, also in the mode cache for a later mode with
  /// the same Â.
  void prepare(Scalar base, ExactStepperStats& st, bool keep = true) {
    if (!(base > 0) || !std::isfinite(base) || !(norm1_ > 0)) {
      ladder_k_ = -1;
      ladder_in_cache_ = false;
      return;
    }
    if (ladder_k_ >= 0 && base == base_) return;
    using std::ceil;
    using std::log2;
    const int K = std::max(
        0, static_cast<int>(ceil(log2(std::ldexp(bnorm1_ * base, ladder_tail_bits)))));
    ladder_in_cache_ = false;
    ladder_.resize(static_cast<std::size_t>(K) + 1);
    expm(base / std::pow(Scalar(2), Scalar(K)), ladder_[static_cast<std::size_t>(K)], st);
    for (int k = K; k > 1; --k) {
      const auto ku = static_cast<std::size_t>(k);
      ladder_[ku - 1].noalias() = ladder_[ku] * ladder_[ku];
    }
    if (K > 0)  // the grid propagator, used most, directly (no round-off of K squarings)
      expm(base, ladder_[0], st);
    base_ = base;
    ladder_k_ = K;
    if (keep && cache_size_ > 0) {  // for a later mode with the same Â (round robin)
      if (cache_.size() < cache_size_) cache_.emplace_back();
      slot_ = static_cast<int>(next_slot_ % cache_.size());
      ++next_slot_;
      Entry& e = cache_[static_cast<std::size_t>(slot_)];
      e.a = a_;
      e.ladder = ladder_;
      e.bal = bal_;
      e.scale = scale_;
      e.bnorm1 = bnorm1_;
      e.ladder_k = K;
      e.base = base;
      e.rate = rate_;
      e.decay = decay_;
      ++e.stamp;
    }
  }

  /// Keep the ladders (and eigenvalue bounds) of up to `entries` distinct Â for modes that come
  /// back (0: none); clears the cache.
  void set_cache_size(std::size_t entries) {
    cache_size_ = entries;
    if (ladder_in_cache_) ladder_ = ladder();  // keep the current ladder
    ladder_in_cache_ = false;
    cache_.clear();
    slot_ = -1;
    next_slot_ = 0;
  }
  /// Cache slot holding the current Â's ladder (-1: none) and its stamp, which changes whenever
  /// the slot is given to another Â (for the stepper's own per-mode blocks).
  int cache_slot() const noexcept { return slot_; }
  /// Stamp of cache slot `slot` (see cache_slot()).
  std::uint64_t cache_stamp(int slot) const { return cache_[static_cast<std::size_t>(slot)].stamp; }
  /// True when the current Â's ladder came from the cache (a mode seen before).
  bool restored() const noexcept { return last_restored_; }

  /// Phi = exp(Â tau) and, for quadratic forms Q_j of the quadrature rates (LinearPart::
  /// quadrature_forms, in z = (x_L, clock); none: w empty), the stacked
  /// W_j = int_0^tau exp(Â^T s) Q̂_j exp(Â s) ds (rows j dim .. (j + 1) dim of w, Q̂_j = Q_j placed
  /// at the x_L and clock rows and columns of y), so that x_Q[j](t + tau) = x_Q[j](t) + y^T W_j y
  /// for y = y(t). Van Loan's block exponential (IEEE Trans. Automat. Control 23, 1978):
  /// exp([[-Â^T, Q̂_j], [0, Â]] tau) = [[exp(-Â^T tau), exp(-Â^T tau) W_j], [0, Phi]].
  void van_loan(Scalar tau, const std::vector<Matrix>& forms, Matrix& phi, Matrix& w,
                ExactStepperStats& st) {
    const Eigen::Index d = dim(), n = n_, c = d - nx_;
    const auto nq = static_cast<Eigen::Index>(forms.size());
    w.setZero(nq * d, d);
    if (nq == 0) {
      expm(tau, phi, st);
      return;
    }
    for (Eigen::Index j = 0; j < nq; ++j) {
      const Matrix& q = forms[static_cast<std::size_t>(j)];
      STICKSLIP_ASSERT(q.rows() == n + c && q.cols() == n + c);
      big_.setZero(2 * d, 2 * d);
      big_.topLeftCorner(d, d) = -tau * a_.transpose();
      big_.bottomRightCorner(d, d) = tau * a_;
      auto qh = big_.topRightCorner(d, d);
      qh.topLeftCorner(n, n) = tau * q.topLeftCorner(n, n);
      qh.block(0, nx_, n, c) = tau * q.topRightCorner(n, c);
      qh.block(nx_, 0, c, n) = tau * q.bottomLeftCorner(c, n);
      qh.bottomRightCorner(c, c) = tau * q.bottomRightCorner(c, c);
      // Balanced as in expm: the blocks hold Â and Âᵀ, as badly scaled as Â.
      balance_in_place(big_, big_scale_);
      big_pade_.compute(big_, big_exp_);
      unbalance(big_exp_, big_scale_);
      ++st.propagator_exponentials;
      if (j == 0) phi = big_exp_.bottomRightCorner(d, d);
      w.middleRows(j * d, d).noalias() =
          big_exp_.bottomRightCorner(d, d).transpose() * big_exp_.topRightCorner(d, d);
    }
  }

  /// out = exp(Â tau) by Padé with scaling and squaring (PadeExponential) on the balanced
  /// generator: exp(Â tau) = D exp(B tau) D^-1, B = D^-1 Â D (see balance()), where ||B|| ~ the
  /// spectral radius of Â rather than ||Â|| (modal coordinates: ||Â||_1 ~ w_max^2 against
  /// w_max), so that the approximant needs few or no squarings. D is a power of 2 per component:
  /// the similarity is exact in floating point.
  void expm(Scalar tau, Matrix& out, ExactStepperStats& st) {
    pade_.compute(bal_ * tau, out);
    unbalance(out, scale_);
    ++st.propagator_exponentials;
  }

  /// out = exp(|Â| tau) (|Â| entrywise), the entrywise bound |exp(Â u)| <= exp(|Â| tau) for
  /// 0 <= u <= tau, computed as D exp(|B| tau) D^-1 (|Â| = D |B| D^-1 for the positive diagonal D
  /// of the balancing), which needs no squarings where ||B|| tau is small.
  void abs_expm(Scalar tau, Matrix& out, ExactStepperStats& st) {
    pade_.compute(bal_.cwiseAbs() * tau, out);
    unbalance(out, scale_);
    ++st.propagator_exponentials;
  }

  /// The ladder's finest step leaves ||B|| tau <= 2^-ladder_tail_bits for the Taylor tail of expv:
  /// ~5 terms there against ~K/2 ladder products on the way (the balance of the two costs).
  static constexpr int ladder_tail_bits = 8;

  /// True when prepare() built a ladder (Â != 0 and a finite base).
  bool has_ladder() const noexcept { return ladder_k_ >= 0; }

  /// exp(Â base) of the ladder (prepare() first).
  const Matrix& propagator() const {
    STICKSLIP_ASSERT(ladder_k_ >= 0 && "AugmentedFlow: prepare() first");
    return ladder()[0];
  }

  /// v <- exp(Â dt) v for a short hop of either sign, ||B||_1 |dt| <= 1/2 (B: the balanced Â),
  /// by one Taylor series; false (v unchanged) when the hop is longer. Moves a point of a root
  /// search to the next one close by for a few products instead of a ladder walk from the step
  /// start.
  bool hop(Scalar dt, Vector& v, ExactStepperStats& st) {
    using std::abs;
    if (!(bnorm1_ * abs(dt) <= Scalar(0.5))) return false;
    taylor(dt, v, st);
    return true;
  }

  /// v <- exp(Â tau) v, tau >= 0: floor(tau / base) products with Phi_0, one with each Phi_k of
  /// the binary digits of the rest, and a Taylor series (||Â|| tau' <= 1/2) for what remains;
  /// without a ladder, s Taylor sub-steps with ||B||_1 tau / s <= 1 (B: the balanced Â), or one
  /// sum where Â is structurally nilpotent (the series ends).
  void expv(Scalar tau, Vector& v, ExactStepperStats& st) {
    if (!(tau > 0) || !(norm1_ > 0)) return;
    if (ladder_k_ >= 0) {
      using std::floor;
      const Scalar whole = floor(tau / base_);
      const std::vector<Matrix>& lad = ladder();
      for (long i = 0; i < static_cast<long>(whole); ++i) apply(lad[0], v, st);
      Scalar rest = tau - whole * base_;
      Scalar step = base_;
      for (int k = 1; k <= ladder_k_; ++k) {
        step /= Scalar(2);
        if (rest >= step) {
          apply(lad[static_cast<std::size_t>(k)], v, st);
          rest -= step;
        }
      }
      taylor(rest, v, st);
      return;
    }
    if (nilpotent_ < 0) nilpotent_ = structurally_nilpotent() ? 1 : 0;
    if (nilpotent_ == 1) {  // the series ends (a stick phase without forcing): one sum is exact
      taylor(tau, v, st);
      return;
    }
    using std::ceil;
    const Scalar s_real = std::max(Scalar(1), ceil(bnorm1_ * tau));
    const Scalar dt = tau / s_real;
    for (long i = 0; i < static_cast<long>(s_real); ++i) taylor(dt, v, st);
  }

 private:
  void apply(const Matrix& phi, Vector& v, ExactStepperStats& st) {
    small_product(phi, v, prod_);
    v.swap(prod_);
    ++st.matvecs;
  }
  // v <- sum_k (Â dt)^k / k! v, in the balanced coordinates w = D^-1 v (terms (B dt)^k / k! w),
  // until the term is below the unit round-off relative to the sum.
  void taylor(Scalar dt, Vector& v, ExactStepperStats& st) {
    if (!(dt != 0)) return;
    const Scalar eps = std::numeric_limits<Scalar>::epsilon();
    v.array() /= scale_.array();
    term_ = v;
    for (int k = 1; k <= 40; ++k) {
      small_product(bal_, term_, prod_);
      ++st.matvecs;
      term_ = (dt / Scalar(k)) * prod_;
      v += term_;
      if (term_.template lpNorm<Eigen::Infinity>() <= eps * v.template lpNorm<Eigen::Infinity>())
        break;
    }
    v.array() *= scale_.array();
  }

  // True when |B|^p = 0 for some p <= dim (entrywise |B|): then B^p w = 0 exactly for every w,
  // whatever the values, and the Taylor series of exp(B tau) w is a polynomial of degree < p.
  // |B|^p (i, j) > 0 exactly when the graph of B's nonzeros (an edge j -> i per B(i, j) != 0) has
  // a walk of length p from j to i, so |B|^p = 0 for some p <= dim exactly when that graph has
  // no cycle (a diagonal entry is one): Kahn's topological sort, O(dim^2).
  bool structurally_nilpotent() {
    const Eigen::Index d = bal_.rows();
    nil_indegree_.setZero(d);  // own scratch: same sizes after warm-up, no allocation
    nil_ready_.resize(d);
    for (Eigen::Index j = 0; j < d; ++j)
      for (Eigen::Index i = 0; i < d; ++i)
        if (bal_(i, j) != Scalar(0)) ++nil_indegree_[i];
    Eigen::Index top = 0, removed = 0;
    for (Eigen::Index i = 0; i < d; ++i)
      if (nil_indegree_[i] == 0) nil_ready_[top++] = i;
    while (top > 0) {
      const Eigen::Index j = nil_ready_[--top];
      ++removed;
      for (Eigen::Index i = 0; i < d; ++i)
        if (bal_(i, j) != Scalar(0) && --nil_indegree_[i] == 0) nil_ready_[top++] = i;
    }
    return removed == d;
  }

  // B = D^-1 Â D with D = diag(scale_), powers of 2, chosen so that each component's row and
  // column (off the diagonal) have comparable 1-norms (Parlett & Reinsch, Numer. Math. 13, 1969,
  // the balancing of LAPACK's gebal without permutations); bnorm1_ = ||B||_1.
  void balance() {
    bal_ = a_;
    balance_in_place(bal_, scale_);
    bnorm1_ = bal_.cwiseAbs().colwise().sum().maxCoeff();
  }
  // m <- D m D^-1 for D = diag(scale) (back from the balanced coordinates; in place, no
  // temporary).
  static void unbalance(Matrix& m, const Vector& scale) {
    m.array().colwise() *= scale.array();
    m.array().rowwise() /= scale.transpose().array();
  }
  // m <- D^-1 m D (see balance()), the powers of 2 of D into scale.
  static void balance_in_place(Matrix& m, Vector& scale) { balance_by_powers_of_two(m, scale); }

  struct Entry {
    Matrix a, bal;
    Vector scale;
    std::vector<Matrix> ladder;
    int ladder_k = -1;
    Scalar base = 0, rate = 0, decay = 0, bnorm1 = 0;
    std::uint64_t stamp = 0;
  };
  std::vector<Entry> cache_;
  std::size_t cache_size_ = 8, next_slot_ = 0;
  int slot_ = -1;
  bool last_restored_ = false;
  Matrix a_, bal_, build_, big_, big_exp_;
  Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1> nil_indegree_, nil_ready_;
  PadeExponential<Scalar> pade_, big_pade_;  // the exponentials of Â (dim) and of Van Loan's blocks (2 dim)
  Vector scale_, big_scale_;
  std::vector<Matrix> ladder_;
  bool ladder_in_cache_ = false;  // the current ladder is cache_[slot_].ladder, not ladder_
  const std::vector<Matrix>& ladder() const {
    return ladder_in_cache_ ? cache_[static_cast<std::size_t>(slot_)].ladder : ladder_;
  }
  Vector term_, prod_;
  std::vector<Scalar> omega_;
  Eigen::EigenSolver<Matrix> eig_;
  Eigen::Index nx_ = 0, n_ = 0;
  Scalar norm1_ = 0, bnorm1_ = 0, rate_ = 0, decay_ = 0, fastest_ = 0, base_ = 0;
  int ladder_k_ = -1;  // -1: no ladder
  int nilpotent_ = -1;  // Â structurally nilpotent: 1 yes, 0 no, -1 not checked yet
  std::uint64_t version_ = 0, generation_ = 0;
  bool rate_valid_ = false;
};

}  // namespace detail
}  // namespace stickslip
