#pragma once
/// \file pitchfork.hpp
/// \brief Symmetry breaking along a branch of symmetric forced periodic orbits: a multiplier
/// through +1 classified as a symmetry-breaking pitchfork (its Floquet vector antisymmetric) or
/// a fold (symmetric), the pitchfork located to a tolerance, and the pair of asymmetric branches
/// born there, one continued and the other its mirror image.
///
/// The system's symmetry is a linear involution S of the state (S S = I; e.g. the permutation
/// that swaps two identical substructures, with the mode mapped the same way) that maps
/// solutions onto solutions: x(t) solves the equations iff S x(t) does (the forcing is
/// S-invariant). A symmetric orbit has S x(t) = x(t); its monodromy M commutes with S, so M
/// maps each eigenspace of S into itself:
///
///     V+ = {v : S v = v},  V- = {v : S v = -v},   M V+ in V+,  M V- in V-,
///
/// and its multipliers split into those of M restricted to V+ (symmetric Floquet vectors) and to
/// V- (antisymmetric ones). A real multiplier of the V- block through +1 is a symmetry-breaking
/// pitchfork: the symmetric branch goes on (the crossing is not in its own equations, which
/// stay regular in V+), and a pair of asymmetric orbits x and S x branches off along the
/// antisymmetric Floquet vector. A multiplier of the V+ block through +1 is a fold of the
/// symmetric branch (or a transcritical point within the symmetric orbits).
///
/// With a half-period shift (half_period_shift()) the symmetry maps a solution x(t) onto
/// S x(t + T/2): mirror-image substructures forced in antiphase (the mirror maps F cos(w t) onto
/// -F cos(w t) = F cos(w (t + T/2)); the paper's blade with its two dampers under a tangential
/// tip force). A symmetric orbit has x(t0 + T/2) = S x(t0); its monodromy is M = H^2 with the
/// half-period map H = S dx(t0 + T/2)/dx(t0), and a multiplier of M through +1 is a
/// symmetry-breaking pitchfork where an eigenvalue of H crosses -1 (the Floquet vector v comes
/// back after half a period as -S v), a fold where one crosses +1. Each classification then
/// runs half a period with its sensitivity.

#include <stickslip/detail/validate.hpp>
#include <stickslip/steady_state/bifurcation.hpp>
#include <stickslip/steady_state/continuation.hpp>
#include <stickslip/steady_state/detail/branch_start.hpp>
#include <stickslip/steady_state/detail/half_period_map.hpp>
#include <stickslip/steady_state/half_period_symmetry.hpp>
#include <stickslip/steady_state/shooting.hpp>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace stickslip {

/// A multiplier through +1 between two points of a symmetric branch (SymmetricBranches).
template <class System>
struct SymmetryBreakingPoint {
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  /// Dynamic vector type.
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  bool ok = false;      ///< classified (and, for a pitchfork from locate(), located); else see message
  std::string message;  ///< why not
  /// Pitchfork: the crossing multiplier's Floquet vector is antisymmetric (S v = -v): symmetry
  /// breaking. Fold: it is symmetric (S v = v).
  BifurcationKind kind = BifurcationKind::Fold;
  /// true: `parameter` is where the multiplier is 1 to the tolerance of locate(); false: the
  /// linear interpolation between the two points (classify(), or a fold).
  bool located = false;
  Scalar parameter = 0;   ///< p at the crossing
  Scalar multiplier = 0;  ///< the crossing multiplier at `orbit`
  /// The symmetric orbit nearest the crossing (at `parameter` when located).
  PeriodicOrbit<System> orbit;
  /// Real Floquet vector of the crossing multiplier in the periodic components (max norm 1).
  Vector eigenvector;
  /// The symmetric branch's unit tangent in (x_P, p) (the secant of the two points).
  Vector tangent;
};

/// Symmetry breaking on the branches that Continuation follows (same system, parameter map,
/// period and options), for the symmetry `S` (a linear involution of the state; see the file's
/// description). The system is left at the parameter of the last orbit.
template <class System>
class SymmetricBranches {
 public:
  /// Floating-point type.
  using Scalar = typename System::Scalar;
  /// State of the system.
  using State = typename System::State;
  /// Mode of the system.
  using Mode = typename System::Mode;
  /// The continuation whose branches are examined.
  using Cont = Continuation<System>;
  /// Dynamic vector type.
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  /// Dynamic matrix type.
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  /// The mode of the mirror image of a state in `mode` (e.g. the contact states of two mirrored
  /// dampers swapped).
  using ModeImage = std::function<Mode(const Mode&)>;

  /// Keeps a reference to `system`. Throws std::invalid_argument for empty callbacks, invalid
  /// options, or a `symmetry` that is not a finite square involution (max |S S - I| <= 1e-10
  /// max(1, max |S|^2)).
  SymmetricBranches(System& system, typename Cont::SetParameter set_parameter, typename Cont::PeriodOf period,
                    Matrix symmetry, ShootingOptions<Scalar> shooting = {}, ContinuationOptions<Scalar> options = {})
      : sys_(system), set_(std::move(set_parameter)), period_(std::move(period)),
        shooting_(std::move(shooting)), opt_(options) {
    static const std::string where = "SymmetricBranches";
    if (!set_) throw std::invalid_argument(where + ": set_parameter must not be empty");
    if (!period_) throw std::invalid_argument(where + ": period must not be empty");
    opt_.validate(where);
    detail::require_involution(where, "symmetry", symmetry);
    sym_.S = std::move(symmetry);
  }

  /// The symmetry acts with a half-period shift (see the file's description): x(t) solves the
  /// equations iff S x(t + T/2) does, symmetric orbits have x(t0 + T/2) = S x(t0), and the
  /// classification splits the multipliers by the half-period map's eigenvalues (-1: pitchfork,
  /// +1: fold). Default false: x(t) solves them iff S x(t) does.
  void half_period_shift(bool on) { half_ = on; }
  /// The state the symmetry keeps fixed: the map is x -> c + S (x - c) (default c = 0, the map
  /// S x). For coordinates that a mirror maps affinely, e.g. contact positions X measured from a
  /// member's end, X -> L - X: give c the mirror-symmetric reference state. Throws
  /// std::invalid_argument unless c is finite and of the symmetry's size.
  void symmetry_centre(const State& c) {
    static const std::string where = "SymmetricBranches::symmetry_centre";
    check_size(where, c.size());
    if (!detail::all_finite(c)) throw std::invalid_argument(where + ": c must be finite");
    sym_.centre = c;
  }
  /// The image of a state: c + S (x - c) (S x without a centre).
  State mirror(const State& x) const { return sym_.mirror(x); }
  /// The mode of a mirrored state (default: the same mode).
  void mode_image(ModeImage f) { sym_.mode_image = std::move(f); }
  /// The symmetry (S, centre, mode image) as Shooting::half_period_symmetry and
  /// Continuation::half_period_symmetry take it, to follow the symmetric branch on the half period.
  const HalfPeriodSymmetry<System>& symmetry() const noexcept { return sym_; }
  /// The start-mode rule of the continued branches and mirrored orbits (Continuation::start_mode).
  void start_mode(typename Cont::StartMode rule) { start_mode_ = std::move(rule); }
  /// An orbit counts as symmetric when max |S x0 - x0| over its periodic components is at most
  /// `relative` max(1, max |x0|) (default 1e-6). Throws std::invalid_argument unless > 0.
  void symmetry_tolerance(Scalar relative) {
    detail::require_positive("SymmetricBranches::symmetry_tolerance", "relative", relative);
    sym_tol_ = relative;
  }

  /// max |mirror(x) - x| over the periodic components (0 for a symmetric state; without a
  /// half-period shift). Throws std::invalid_argument when x's size is not the symmetry's.
  Scalar asymmetry(const State& x) const {
    check_size("SymmetricBranches::asymmetry", x.size());
    const State d = mirror(x) - x;
    Scalar m = 0;
    for (const auto i : shooting_.periodic_indices(x.size())) m = std::max(m, std::abs(d[i]));
    return m;
  }

  /// The multipliers of a symmetric orbit's monodromy (PeriodicOrbit::monodromy, over the
  /// periodic components of a state of size n) split by the symmetry of their Floquet vectors:
  /// {those of M on V+, those of M on V-}. Throws std::invalid_argument when the sizes do not
  /// match the symmetry's, or with a half-period shift (the split then needs the half-period
  /// map: half_period_multipliers()).
  std::pair<Eigen::Matrix<std::complex<Scalar>, Eigen::Dynamic, 1>, Eigen::Matrix<std::complex<Scalar>, Eigen::Dynamic, 1>>
  multipliers_by_symmetry(const Matrix& monodromy, Eigen::Index n) const {
    static const std::string where = "SymmetricBranches::multipliers_by_symmetry";
    check_size(where, n);
    if (half_) throw std::invalid_argument(where + ": with a half-period shift use half_period_multipliers(point)");
    const auto np = static_cast<Eigen::Index>(shooting_.periodic_indices(n).size());
    if (monodromy.rows() != np || monodromy.cols() != np)
      detail::throw_invalid(where, "monodromy must be square over the periodic components (" + std::to_string(np) +
                                       "), rows",
                            monodromy.rows());
    const auto block = [&](int sign) {
      const Matrix Q = basis(n, sign);
      Eigen::Matrix<std::complex<Scalar>, Eigen::Dynamic, 1> mu;
      if (Q.cols() > 0) mu = Eigen::EigenSolver<Matrix>(Q.transpose() * monodromy * Q, false).eigenvalues();
      return mu;
    };
    return {block(1), block(-1)};
  }

  /// With a half-period shift: the orbit at `point` (the system set to its parameter) run over
  /// half its period, max |x(t0 + T/2) - S x(t0)| over the periodic components (0 for a
  /// symmetric orbit) and the eigenvalues of the half-period map H (the orbit's multipliers are
  /// their squares; an eigenvalue near -1 belongs to an antisymmetric Floquet vector). Not ok
  /// (with the message) when the run fails. Throws std::invalid_argument without a half-period
  /// shift or when the sizes do not match the symmetry's.
  struct HalfPeriodMultipliers {
    bool ok = false;                                             ///< the run succeeded
    std::string message;                                         ///< why not
    Scalar asymmetry = 0;                                        ///< max |x(t0 + T/2) - S x(t0)|
    Eigen::Matrix<std::complex<Scalar>, Eigen::Dynamic, 1> eigenvalues;  ///< of H
  };
  /// See HalfPeriodMultipliers.
  HalfPeriodMultipliers half_period_multipliers(const ContinuationPoint<System>& point) const {
    static const std::string where = "SymmetricBranches::half_period_multipliers";
    if (!half_) throw std::invalid_argument(where + ": needs half_period_shift(true)");
    check_size(where, point.orbit.x0.size());
    HalfPeriodMultipliers out;
    const auto h = half_map(point, true);
    out.ok = h.ok;
    out.message = h.message;
    out.asymmetry = h.asymmetry;
    if (h.ok) out.eigenvalues = Eigen::EigenSolver<Matrix>(h.H, false).eigenvalues();
    return out;
  }

  /// The multiplier through +1 between points `a` and `b` of a symmetric branch (a Fold or
  /// Pitchfork of locate_bifurcations): Pitchfork when det(M - I) on the V- block changes sign
  /// between them (a real multiplier of that block crossed +1; a complex pair contributes
  /// |mu - 1|^2 > 0), Fold when det(M - I) on the V+ block does. `parameter`: the linear
  /// interpolation of that determinant's zero. Not ok when an orbit is not symmetric
  /// (symmetry_tolerance) or neither determinant changes sign.
  SymmetryBreakingPoint<System> classify(const ContinuationPoint<System>& a, const ContinuationPoint<System>& b) const;

  /// classify(), and a pitchfork located: the V- multiplier mu nearest +1 driven to
  /// |mu - 1| <= tolerance by a secant in p on det(M - I) over V- (Illinois: the bracket [a, b]
  /// kept; the determinant is smooth in p where the multiplier itself may be complex), each orbit shot
  /// at fixed p from the bracket's nearer orbit made symmetric ((x + S x) / 2). A fold is
  /// returned as classified (not located: there is no orbit past it at fixed p). Not ok when the
  /// points lie on different sections t0, a shooting fails or the secant does not converge in
  /// 40 orbits.
  SymmetryBreakingPoint<System> locate(const ContinuationPoint<System>& a, const ContinuationPoint<System>& b,
                                       Scalar tolerance = Scalar(1e-8));

  /// One of the asymmetric pair born at a located pitchfork: the first orbit by Newton on
  /// x_P(t0 + T(p)) - x_P = 0 with (x_P, p) at signed arclength `offset` from the pitchfork
  /// along the antisymmetric Floquet vector (the other sign gives the mirror image), then
  /// Continuation away from the pitchfork in p. StartFailed when the first orbit does not
  /// converge, is the symmetric orbit (asymmetry below 100 Newton tolerances) or lies outside
  /// the range. Throws std::invalid_argument unless `pitchfork` is an ok Pitchfork and `offset`
  /// is finite and non-zero.
  ContinuationResult<System> asymmetric_branch(const SymmetryBreakingPoint<System>& pitchfork, Scalar offset);

  /// The mirror image of a point of an asymmetric branch: the orbit from (mode_image(mode),
  /// S x0) at the same p, shot again (its outputs, events and multipliers are the image's own;
  /// the multipliers equal the point's). Not ok when that shooting fails.
  ContinuationPoint<System> image(const ContinuationPoint<System>& point);

 private:
  void check_size(const std::string& where, Eigen::Index n) const {
    if (n != sym_.S.rows())
      detail::throw_invalid(where, "the state size must be the symmetry's (" + std::to_string(sym_.S.rows()) + "), got",
                            n);
  }
  // Orthonormal bases of V+ (sign +1) and V- (sign -1) in the periodic components.
  Matrix basis(Eigen::Index n, int sign) const {
    const auto P = shooting_.periodic_indices(n);
    const auto np = static_cast<Eigen::Index>(P.size());
    Matrix proj(np, np);
    for (Eigen::Index i = 0; i < np; ++i)
      for (Eigen::Index j = 0; j < np; ++j)
        proj(i, j) = (Scalar(i == j ? 1 : 0) + Scalar(sign) * sym_.S(P[std::size_t(i)], P[std::size_t(j)])) / 2;
    Eigen::ColPivHouseholderQR<Matrix> qr(proj);
    qr.setThreshold(Scalar(1e-8));
    const Matrix Q = qr.householderQ();
    return Q.leftCols(qr.rank());
  }
  // The real multiplier nearest +1 of M restricted to the subspace with orthonormal basis Q (M Q
  // = Q B: B = Q^T M Q), with its Floquet vector Q w (max norm 1); NaN when there is none.
  Scalar nearest_plus_one(const Matrix& M, const Matrix& Q, Vector* v) const {
    if (Q.cols() == 0) return std::numeric_limits<Scalar>::quiet_NaN();
    Vector w;
    const Scalar mu = detail::nearest_real_eigenvalue(Matrix(Q.transpose() * M * Q), Scalar(1),
                                                      shooting_.multiplier_tolerance, v ? &w : nullptr);
    if (v && detail::is_finite(mu)) {
      *v = Q * w;
      const Scalar s = v->cwiseAbs().maxCoeff();
      if (s > 0) *v /= s;
    }
    return mu;
  }
  // The half-period map of the orbit at `point` (the system set to its parameter).
  detail::HalfPeriodMap<System> half_map(const ContinuationPoint<System>& point, bool sensitivity) const {
    set_(sys_, point.parameter);
    return detail::half_period_map(sys_, shooting_, sym_.S, mirror(point.orbit.x0), point.orbit.mode, point.orbit.t0,
                                   point.orbit.x0, point.orbit.period, sensitivity);
  }
  SymmetryBreakingPoint<System> classify_half(const ContinuationPoint<System>& a,
                                              const ContinuationPoint<System>& b) const;
  // What classify and classify_half share: the kind from the sign changes of gm (pitchfork) and
  // gp (fold) between a and b (none: a message of none_m, gm, none_p, gp), p interpolated, and
  // the crossing multiplier with its vector from the nearer point that has one
  // (crossing(k, kind, &v): point k, 0 for a and 1 for b; NaN when none).
  template <class Crossing>
  SymmetryBreakingPoint<System> classified(const ContinuationPoint<System>& a, const ContinuationPoint<System>& b,
                                           std::array<Scalar, 2> gm, std::array<Scalar, 2> gp,
                                           const std::string& none_m, const std::string& none_p,
                                           Crossing&& crossing) const;
  SymmetryBreakingPoint<System> locate_half(SymmetryBreakingPoint<System> c, const ContinuationPoint<System>& a,
                                            const ContinuationPoint<System>& b, Scalar tolerance);
  // det(B - I) of M restricted to the subspace with orthonormal basis Q (1 for an empty one):
  // prod (mu_i - 1) over the block's multipliers, whose sign changes exactly when a real
  // multiplier crosses +1 (a complex pair contributes |mu - 1|^2 > 0).
  static Scalar det_minus_one(const Matrix& M, const Matrix& Q) {
    if (Q.cols() == 0) return Scalar(1);
    return (Q.transpose() * M * Q - Matrix::Identity(Q.cols(), Q.cols())).determinant();
  }
  bool symmetric(const State& x) const {
    Scalar m = 0;
    for (const auto i : shooting_.periodic_indices(x.size())) m = std::max(m, std::abs(x[i]));
    return asymmetry(x) <= sym_tol_ * std::max(Scalar(1), m);
  }
  Mode mirrored_mode(Scalar t0, const State& x, const Mode& mode) {
    const Mode m = sym_.mirror_mode(mode);
    return start_mode_ ? start_mode_(sys_, t0, x, m) : m;
  }

  System& sys_;
  typename Cont::SetParameter set_;
  typename Cont::PeriodOf period_;
  HalfPeriodSymmetry<System> sym_;  // S, centre c (default 0) and mode image
  ShootingOptions<Scalar> shooting_;
  ContinuationOptions<Scalar> opt_;
  typename Cont::StartMode start_mode_;
  Scalar sym_tol_ = Scalar(1e-6);
  bool half_ = false;
};

template <class System>
SymmetryBreakingPoint<System> SymmetricBranches<System>::classify(const ContinuationPoint<System>& a,
                                                                  const ContinuationPoint<System>& b) const {
  SymmetryBreakingPoint<System> c;
  const Eigen::Index n = a.orbit.x0.size();
  check_size("SymmetricBranches::classify", n);
  check_size("SymmetricBranches::classify", b.orbit.x0.size());
  if (half_) return classify_half(a, b);
  for (const auto* pt : {&a, &b})
    if (!symmetric(pt->orbit.x0)) {
      c.message = "the orbit at p = " + detail::format_value(pt->parameter) +
                  " is not symmetric (max |S x0 - x0| = " + detail::format_value(asymmetry(pt->orbit.x0)) +
                  "): the branch must be a symmetric one";
      return c;
    }
  const Matrix Qm = basis(n, -1), Qp = basis(n, 1);
  const Matrix &Ma = a.orbit.monodromy, &Mb = b.orbit.monodromy;
  return classified(a, b, {det_minus_one(Ma, Qm), det_minus_one(Mb, Qm)}, {det_minus_one(Ma, Qp), det_minus_one(Mb, Qp)},
                    "no real multiplier crosses +1 between the points (det(M - I) on the antisymmetric block ",
                    "; on the symmetric block ", [&](int k, BifurcationKind kind, Vector* v) {
                      return nearest_plus_one((k == 0 ? a : b).orbit.monodromy,
                                              kind == BifurcationKind::Pitchfork ? Qm : Qp, v);
                    });
}

template <class System>
SymmetryBreakingPoint<System> SymmetricBranches<System>::locate(const ContinuationPoint<System>& a,
                                                                const ContinuationPoint<System>& b,
                                                                Scalar tolerance) {
  detail::require_positive("SymmetricBranches::locate", "tolerance", tolerance);
  SymmetryBreakingPoint<System> c = classify(a, b);
  if (!c.ok || c.kind != BifurcationKind::Pitchfork) return c;
  if (!(a.orbit.t0 == b.orbit.t0)) {
    c.ok = false;
    c.message = "the two points lie on different sections t0 (the continuation moved it between them)";
    return c;
  }
  if (half_) return locate_half(std::move(c), a, b, tolerance);
  const Eigen::Index n = a.orbit.x0.size();
  const Matrix Qm = basis(n, -1);
  const auto P = shooting_.periodic_indices(n);
  Shooting<System> shooting(sys_, shooting_);
  using End = detail::SecantEnd<System>;
  // The secant on g = det(M - I) over V-, each orbit shot at fixed p from the bracket's nearer
  // orbit made symmetric.
  const auto shoot = [&](Scalar p, const End& from, End& e, std::string& why) {
    State x = from.orbit.x0;
    const State sx = mirror(x);
    for (const auto i : P) x[i] = (x[i] + sx[i]) / 2;
    set_(sys_, p);
    e.p = p;
    e.orbit = shooting.forced(from.orbit.mode, from.orbit.t0, x, period_(p));
    if (!e.orbit.ok()) {
      why = "the orbit at p = " + detail::format_value(p) + " failed: " + e.orbit.message;
      return false;
    }
    e.g = det_minus_one(e.orbit.monodromy, Qm);
    return true;
  };
  const auto done = [&](const End& e) { return std::abs(nearest_plus_one(e.orbit.monodromy, Qm, nullptr) - 1) <= tolerance; };
  End found;
  if (!detail::illinois_secant(End{a.parameter, det_minus_one(a.orbit.monodromy, Qm), a.orbit},
                               End{b.parameter, det_minus_one(b.orbit.monodromy, Qm), b.orbit}, shoot, done, found,
                               c.message)) {
    c.ok = false;
    return c;
  }
  c.located = true;
  c.parameter = found.p;
  c.orbit = found.orbit;
  c.multiplier = nearest_plus_one(found.orbit.monodromy, Qm, &c.eigenvector);
  return c;
}

template <class System>
ContinuationResult<System> SymmetricBranches<System>::asymmetric_branch(const SymmetryBreakingPoint<System>& pitchfork,
                                                                        Scalar offset) {
  static const std::string where = "SymmetricBranches::asymmetric_branch";
  if (!pitchfork.ok || pitchfork.kind != BifurcationKind::Pitchfork)
    throw std::invalid_argument(where + ": pitchfork must be an ok symmetry-breaking pitchfork");
  detail::require_finite(where, "offset", offset);
  if (offset == 0) throw std::invalid_argument(where + ": offset must not be 0");
  ContinuationResult<System> result;
  result.status = ContinuationStatus::StartFailed;
  const auto np = pitchfork.eigenvector.size();
  // Direction: the antisymmetric Floquet vector without its component along the symmetric
  // branch's tangent (none when S is orthogonal: V- is then orthogonal to the symmetric states).
  Vector dir(np + 1);
  dir.head(np) = pitchfork.eigenvector;
  dir[np] = 0;
  if (pitchfork.tangent.size() == np + 1) dir -= dir.dot(pitchfork.tangent) * pitchfork.tangent;
  if (!(dir.norm() > 0)) {
    result.message = "the Floquet vector is along the symmetric branch";
    return result;
  }
  dir.normalize();
  Scalar p = pitchfork.parameter;
  std::string why;
  const PeriodicOrbit<System> orbit = detail::start_on_branch<System>(sys_, set_, period_, 1, shooting_, pitchfork.orbit,
                                                                      pitchfork.parameter, dir, offset, p, why);
  if (!orbit.ok()) {
    result.message = "the first asymmetric orbit: " + why;
    return result;
  }
  Shooting<System> shooting(sys_, shooting_);
  Scalar asym = 0;
  if (half_) {
    ContinuationPoint<System> first;
    first.parameter = p;
    first.orbit = orbit;
    asym = half_map(first, false).asymmetry;  // NaN-free: 0 when the run fails (then: no branch)
  } else {
    asym = asymmetry(orbit.x0);
  }
  if (!(asym > 100 * shooting.tolerance_at(orbit.x0))) {
    result.message = "the first asymmetric orbit at p = " + detail::format_value(p) +
                     " is the symmetric orbit (raise the offset)";
    return result;
  }
  return detail::continue_new_branch<System>(sys_, set_, period_, shooting_, opt_, start_mode_, orbit, p,
                                             pitchfork.parameter, "asymmetric orbit");
}

template <class System>
ContinuationPoint<System> SymmetricBranches<System>::image(const ContinuationPoint<System>& point) {
  check_size("SymmetricBranches::image", point.orbit.x0.size());
  ContinuationPoint<System> out = point;
  State x = mirror(point.orbit.x0);
  Mode from = point.orbit.mode;
  if (half_) {  // the image of x(t) is S x(t + T/2): at t0 it is S x(t0 + T/2)
    const auto h = half_map(point, false);
    if (!h.ok) {
      out.orbit.status = ShootingStatus::IntegrationFailed;
      out.orbit.message = h.message;
      return out;
    }
    x = mirror(h.x_half);
    from = h.mode_half;
  }
  set_(sys_, point.parameter);
  const Mode m = mirrored_mode(point.orbit.t0, x, from);
  Shooting<System> shooting(sys_, shooting_);
  out.orbit = shooting.forced(m, point.orbit.t0, x, point.orbit.period);
  return out;
}

}  // namespace stickslip

// classified, classify_half and locate_half.
#include <stickslip/steady_state/detail/pitchfork_half_period.hpp>
