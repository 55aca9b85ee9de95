// detail::CheckedBlockSolve (the order 4, 6, 8 systems of the acceleration solve) against Eigen's
// full-pivoting LU, an independent solver: well-conditioned matrices of the solve's form
// (identity plus a sum of rank-one terms) stay in the block form; matrices whose leading block is
// singular or nearly so must fail the backward-error check and fall back to the pivoted LU.
#include "stickslip/model/detail/small_solve.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cstdlib>

namespace {

template <int K>
using Mat = Eigen::Matrix<double, K, K>;
template <int K>
using Vec = Eigen::Matrix<double, K, 1>;

// Relative max-norm error of z against the full-pivoting LU solution of M z = r, in double (a
// dynamic-size reference: one instantiation for every order, which keeps this test quicker to
// compile; each CheckedBlockSolve instantiation costs several seconds, under ASan more).
template <class Scalar, int K>
double relative_error(const Eigen::Matrix<Scalar, K, K>& M, const Eigen::Matrix<Scalar, K, 1>& r,
                      const Eigen::Matrix<Scalar, K, 1>& z) {
  const Eigen::VectorXd ref = Eigen::MatrixXd(M.template cast<double>()).fullPivLu().solve(Eigen::VectorXd(r.template cast<double>()));
  return (z.template cast<double>() - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
}

// I + F L^T with 8 rank-one terms of the sizes of the acceleration solve's (damper mass times
// mode values): condition numbers of order 10.
template <int K>
Mat<K> solve_like_matrix(unsigned seed) {
  std::srand(seed);
  const Eigen::Matrix<double, K, 8> F = Eigen::Matrix<double, K, 8>::Random();
  const Eigen::Matrix<double, K, 8> L = 0.3 * Eigen::Matrix<double, K, 8>::Random();
  return Mat<K>::Identity() + F * L.transpose();
}

template <int K>
void check_well_conditioned() {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Mat<K> M = solve_like_matrix<K>(seed);
    stickslip::detail::CheckedBlockSolve<double, K> solver;
    solver.compute(M);
    // Several right sides with one factorisation (the reuse of a stick phase).
    for (int k = 0; k < 5; ++k) {
      const Vec<K> r = Vec<K>::Random();
      const Vec<K> z = solver.solve(r);
      // Forward error <= cond(M) * backward error <= ~1e2 * 16 K u ~ 3e-12 at worst; 1e-12
      // leaves room for the measured ~1e-15 and still fails an unstable or wrong solve.
      const double cond = Eigen::MatrixXd(M).inverse().cwiseAbs().rowwise().sum().maxCoeff() *
                          M.cwiseAbs().rowwise().sum().maxCoeff();
      ASSERT_LT(cond, 1e3) << "seed " << seed << ": the test matrix is not of the intended kind";
      EXPECT_LT(relative_error(M, r, z), 1e-12) << "K = " << K << ", seed " << seed;
    }
    EXPECT_FALSE(solver.pivoting()) << "K = " << K << ", seed " << seed;
  }
}

TEST(CheckedBlockSolve, WellConditionedSystemsOfOrder4MatchFullPivotingLu) { check_well_conditioned<4>(); }
TEST(CheckedBlockSolve, WellConditionedSystemsOfOrder6MatchFullPivotingLu) { check_well_conditioned<6>(); }
TEST(CheckedBlockSolve, WellConditionedSystemsOfOrder8MatchFullPivotingLu) { check_well_conditioned<8>(); }

// M = [0 I; I I] is perfectly conditioned but its leading block is zero: the block inverse is
// infinite, the check must send the solve to the pivoted LU.
TEST(CheckedBlockSolve, SingularLeadingBlockFallsBackToPivotedLu) {
  Mat<6> M = Mat<6>::Zero();
  M.topRightCorner<3, 3>().setIdentity();
  M.bottomLeftCorner<3, 3>().setIdentity();
  M.bottomRightCorner<3, 3>().setIdentity();
  stickslip::detail::CheckedBlockSolve<double, 6> solver;
  solver.compute(M);
  const Vec<6> r = (Vec<6>() << 1, -2, 3, 0.5, 0.25, -4).finished();
  const Vec<6> z = solver.solve(r);
  EXPECT_TRUE(solver.pivoting());
  EXPECT_LT(relative_error(M, r, z), 1e-15);  // exact in binary: only additions of r's entries
  // The next solves with the same M fail the check again and use the LU kept for M.
  const Vec<6> minus_r = -r;
  EXPECT_LT(relative_error(M, minus_r, solver.solve(minus_r)), 1e-15);
}

// Leading block delta I with delta = 1e-13: finite block factors but S = I - I / delta of order
// 1e13, so block elimination cancels catastrophically; M itself has condition number ~4.
TEST(CheckedBlockSolve, NearlySingularLeadingBlockFallsBackToPivotedLu) {
  const double delta = 1e-13;
  Mat<8> M = Mat<8>::Zero();
  M.topLeftCorner<4, 4>() = delta * Mat<4>::Identity();
  M.topRightCorner<4, 4>().setIdentity();
  M.bottomLeftCorner<4, 4>().setIdentity();
  M.bottomRightCorner<4, 4>() = 2.0 * Mat<4>::Identity();
  std::srand(7);
  const Vec<8> r = Vec<8>::Random();
  // Without the check: the unpivoted block elimination loses digits (asserted here so that the
  // test keeps exercising the fallback if the matrix ever stopped being a hard case).
  const Mat<4> Ai = M.topLeftCorner<4, 4>().inverse();
  const Mat<4> S = M.bottomRightCorner<4, 4>() - M.bottomLeftCorner<4, 4>() * Ai * M.topRightCorner<4, 4>();
  Vec<8> unchecked;
  unchecked.tail<4>() = S.inverse() * (r.tail<4>() - M.bottomLeftCorner<4, 4>() * (Ai * r.head<4>()));
  unchecked.head<4>() = Ai * (r.head<4>() - M.topRightCorner<4, 4>() * unchecked.tail<4>());
  ASSERT_GT(relative_error(M, r, unchecked), 1e-6);

  stickslip::detail::CheckedBlockSolve<double, 8> solver;
  solver.compute(M);
  const Vec<8> z = solver.solve(r);
  EXPECT_TRUE(solver.pivoting());
  EXPECT_LT(relative_error(M, r, z), 1e-14);  // pivoted LU on a matrix of condition ~4

  // A new, benign M returns to the block form.
  solver.compute(solve_like_matrix<8>(3));
  solver.solve(r);
  EXPECT_FALSE(solver.pivoting());
}

// z is a function of (M, r) alone: a solve whose right side fails the check (and goes to the
// LU) must not change the answer to a later right side that passes it. The model relies on this
// for an observer that evaluates the forces at its samples to leave the run bitwise unchanged.
// M as above (leading block 1e-13 I): a right side with r1 = 0 never meets the cancellation and
// passes the check; one with r1 != 0 fails it. The passing right side is chosen so that its
// block and LU answers differ in the last bits (else the comparison could not fail).
TEST(CheckedBlockSolve, AnswerDoesNotDependOnEarlierRightSides) {
  Mat<8> M = Mat<8>::Zero();
  M.topLeftCorner<4, 4>() = 1e-13 * Mat<4>::Identity();
  M.topRightCorner<4, 4>().setIdentity();
  M.bottomLeftCorner<4, 4>().setIdentity();
  M.bottomRightCorner<4, 4>() = 2.0 * Mat<4>::Identity();
  const Eigen::PartialPivLU<Mat<8>> lu(M);
  std::srand(11);
  const Vec<8> r_fail = Vec<8>::Random();
  Vec<8> r_pass = Vec<8>::Zero(), block = Vec<8>::Zero();
  bool found = false;
  for (int k = 0; k < 64 && !found; ++k) {
    r_pass.tail<4>() = Vec<4>::Random();
    stickslip::detail::CheckedBlockSolve<double, 8> fresh;
    fresh.compute(M);
    block = fresh.solve(r_pass);
    found = !fresh.pivoting() && block != lu.solve(r_pass);
  }
  ASSERT_TRUE(found) << "no right side whose block answer differs from the LU's";
  stickslip::detail::CheckedBlockSolve<double, 8> solver;
  solver.compute(M);
  solver.solve(r_fail);
  ASSERT_TRUE(solver.pivoting());
  const Vec<8> again = solver.solve(r_pass);
  EXPECT_FALSE(solver.pivoting());
  EXPECT_TRUE(again == block) << "after a right side that needed the LU: " << again.transpose() << " vs "
                              << block.transpose();
}

// An exactly singular M (a zero row) gives non-finite values, as an LU alone does, never a finite
// wrong answer.
TEST(CheckedBlockSolve, SingularMatrixGivesNonFiniteValues) {
  Mat<4> M = solve_like_matrix<4>(5);
  M.row(3).setZero();
  stickslip::detail::CheckedBlockSolve<double, 4> solver;
  solver.compute(M);
  const Vec<4> z = solver.solve(Vec<4>::Ones());
  EXPECT_FALSE(z.allFinite());
}

}  // namespace
