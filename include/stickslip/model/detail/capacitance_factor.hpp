#pragma once
/// \file capacitance_factor.hpp
/// \brief The capacitance system of ContactSystem's coupled solve (contact_system_solve.hpp):
/// an LU factorisation with full pivoting of the U x U capacitance matrix C of the constrained
/// unknowns, in storage sized once (no allocation in a time step), and a small cache of these
/// factorisations keyed by the set of unknowns, for sets whose rows do not depend on the state.

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace stickslip::detail {

/// P C Q = L U with full pivoting (P, Q permutations, L unit lower triangular) of a U x U matrix
/// C held in the top-left corner of a capacity x capacity store.
///
/// Regularity is the rank test of a full-pivoting LU of the padded matrix diag(C, s I) of order
/// `padded` >= U, s = max_a |C_aa| (1 when that is 0): every pivot must exceed padded * eps
/// times the largest. The padded matrix is block diagonal, so its pivots are C's pivots and
/// padded - U copies of s; the test is therefore decided on C alone. A set of constrained rows
/// that is dependent (to rounding) fails it.
template <class Scalar>
class CapacitanceFactor {
 public:
  using Index = Eigen::Index;                                              ///< index type
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;   ///< dynamic matrix

  /// Storage for matrices of order up to `capacity`.
  explicit CapacitanceFactor(Index capacity = 0)
      : lu_(Matrix::Zero(capacity, capacity)),
        row_(static_cast<std::size_t>(capacity), 0),
        col_(static_cast<std::size_t>(capacity), 0) {}

  Index capacity() const noexcept { return lu_.rows(); }  ///< largest order
  Index size() const noexcept { return size_; }          ///< U of the last block
  bool regular() const noexcept { return regular_; }      ///< the rank test of the last factor()

  /// The U x U block to fill with C before factor() (U <= capacity()).
  auto block(Index U) {
    size_ = U;
    return lu_.topLeftCorner(U, U);
  }

  /// Factors the block filled through block(); `padded` is the order of the padded matrix of
  /// the rank test (see the class). Orders up to 4 (a contact's friction and normal force, two
  /// contacts) run on fixed-size blocks, with the same operations in the same order.
  void factor(Index padded) {
    switch (size_) {
      case 1: regular_ = factor_block(lu_.template topLeftCorner<1, 1>(), padded); break;
      case 2: regular_ = factor_block(lu_.template topLeftCorner<2, 2>(), padded); break;
      case 3: regular_ = factor_block(lu_.template topLeftCorner<3, 3>(), padded); break;
      case 4: regular_ = factor_block(lu_.template topLeftCorner<4, 4>(), padded); break;
      default: regular_ = factor_block(lu_.topLeftCorner(size_, size_), padded);
    }
  }

  /// Overwrites the first size() entries of b with the solution of C x = b (after a regular
  /// factor()).
  template <class Vec>
  void solve(Vec& b) const {
    switch (size_) {
      case 1: solve_block(lu_.template topLeftCorner<1, 1>(), b); break;
      case 2: solve_block(lu_.template topLeftCorner<2, 2>(), b); break;
      case 3: solve_block(lu_.template topLeftCorner<3, 3>(), b); break;
      case 4: solve_block(lu_.template topLeftCorner<4, 4>(), b); break;
      default: solve_block(lu_.topLeftCorner(size_, size_), b);
    }
  }

 private:
  // The factorisation of the U x U block A in place; returns the rank test.
  template <class Block>
  bool factor_block(Block A, Index padded) {
    using std::abs;
    const Index U = A.rows();
    Scalar s = 0;
    for (Index a = 0; a < U; ++a) s = abs(A(a, a)) > s ? abs(A(a, a)) : s;
    if (!(s > 0)) s = Scalar(1);
    Scalar largest = U < padded ? s : Scalar(0);
    Scalar smallest = U < padded ? s : std::numeric_limits<Scalar>::infinity();
    for (Index k = 0; k < U; ++k) {
      Index p = k, q = k;
      Scalar big = -1;
      for (Index j = k; j < U; ++j)
        for (Index i = k; i < U; ++i)
          if (abs(A(i, j)) > big) big = abs(A(i, j)), p = i, q = j;
      row_[static_cast<std::size_t>(k)] = p;
      col_[static_cast<std::size_t>(k)] = q;
      if (!(big > 0)) return false;  // the rest of the block is zero (or not a number): rank < U
      if (p != k) A.row(k).swap(A.row(p));
      if (q != k) A.col(k).swap(A.col(q));
      largest = big > largest ? big : largest;
      smallest = big < smallest ? big : smallest;
      const Scalar pivot = A(k, k);
      for (Index i = k + 1; i < U; ++i) A(i, k) /= pivot;
      for (Index j = k + 1; j < U; ++j) {
        const Scalar u = A(k, j);
        for (Index i = k + 1; i < U; ++i) A(i, j) -= A(i, k) * u;
      }
    }
    return smallest > Scalar(padded) * std::numeric_limits<Scalar>::epsilon() * largest;
  }

  // x = Q U^-1 L^-1 P b in the first U entries of b, A the factors of factor_block.
  template <class Block, class Vec>
  void solve_block(const Block& A, Vec& b) const {
    const Index U = A.rows();
    for (Index k = 0; k < U; ++k) std::swap(b[k], b[row_[static_cast<std::size_t>(k)]]);  // P b
    for (Index k = 0; k < U; ++k)                                                     // L y = P b
      for (Index i = k + 1; i < U; ++i) b[i] -= A(i, k) * b[k];
    for (Index k = U - 1; k >= 0; --k) {                                              // U z = y
      for (Index j = k + 1; j < U; ++j) b[k] -= A(k, j) * b[j];
      b[k] /= A(k, k);
    }
    for (Index k = U - 1; k >= 0; --k) std::swap(b[k], b[col_[static_cast<std::size_t>(k)]]);  // x = Q z
  }

  Matrix lu_;
  std::vector<Index> row_, col_;  // the transpositions of P and Q, in the order of the steps
  Index size_ = 0;
  bool regular_ = false;
};

/// Factorisations of C for sets of constrained unknowns whose rows are constant, keyed by the
/// set (bit i: contact i's friction force), least recently used replaced first. All slots are
/// sized at construction.
template <class Scalar>
class CapacitanceCache {
 public:
  using Index = Eigen::Index;  ///< index type

  /// `slots` factorisations of order up to `capacity`.
  CapacitanceCache(Index slots = 0, Index capacity = 0)
      : factors_(static_cast<std::size_t>(slots), CapacitanceFactor<Scalar>(capacity)),
        keys_(static_cast<std::size_t>(slots), 0),
        used_(static_cast<std::size_t>(slots), 0) {}

  /// The factorisation stored for `key`, or nullptr.
  const CapacitanceFactor<Scalar>* find(std::uint64_t key) {
    for (std::size_t s = 0; s < keys_.size(); ++s)
      if (keys_[s] == key && used_[s] > 0) {
        used_[s] = ++clock_;
        return &factors_[s];
      }
    return nullptr;
  }

  /// The slot to fill for `key` (an empty one or the least recently used): fill its block(U),
  /// then factor().
  CapacitanceFactor<Scalar>& insert(std::uint64_t key) {
    std::size_t oldest = 0;
    for (std::size_t s = 1; s < keys_.size(); ++s)
      if (used_[s] < used_[oldest]) oldest = s;
    keys_[oldest] = key;
    used_[oldest] = ++clock_;
    return factors_[oldest];
  }

 private:
  std::vector<CapacitanceFactor<Scalar>> factors_;
  std::vector<std::uint64_t> keys_;
  std::vector<std::uint64_t> used_;  // 0: empty; else the clock at the last use
  std::uint64_t clock_ = 0;
};

}  // namespace stickslip::detail
