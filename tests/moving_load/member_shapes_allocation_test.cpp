// The hot-path evaluations of MemberShapes allocate nothing. Two counters, hence its own test
// binary: every global operator new, and every Eigen heap allocation (Eigen allocates with
// std::malloc; EIGEN_RUNTIME_NO_MALLOC makes it report through eigen_assert, which is redefined
// here to count failures in any build type instead of aborting only without NDEBUG).

namespace {
long g_eigen_assert_failures = 0;
}  // namespace
#define EIGEN_RUNTIME_NO_MALLOC
#define eigen_assert(x) \
  do {                  \
    if (!(x)) ++g_eigen_assert_failures; \
  } while (false)

#include "stickslip/moving_load/member_shapes.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <new>
#include <random>
#include <vector>

#include "moving_load/moving_load_test_support.hpp"

namespace {
long g_allocations = 0;
}  // namespace

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// GCC flags free() on memory from (this very) operator new as a mismatch; it is the pair's own
// allocator, so the warning does not apply here.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

namespace stickslip {
namespace {

template <int Modes>
void expect_allocation_free(Eigen::Index modes) {
  std::mt19937_64 rng(test::announced_seed(77));
  const MemberShapes<double, Modes> shapes(test::random_member(rng, 50, modes, 0.04));
  typename MemberShapes<double, Modes>::Values v(modes);
  typename MemberShapes<double, Modes>::Vector gx, gy, force;
  gx.resize(modes);
  gy.resize(modes);
  force.resize(modes);
  ElementCursor cursor;
  const long before = g_allocations;
  const long eigen_before = g_eigen_assert_failures;
  Eigen::internal::set_is_malloc_allowed(false);
  double sum = 0.0;
  for (int i = 0; i <= 4000; ++i) {
    const double eps = 0.04 * i / 4000.0;
    shapes.evaluate(eps, v, cursor);
    shapes.evaluate(0.04 - eps, v);  // binary search path
    shapes.evaluate_global(eps, gx, gy, cursor);
    shapes.modal_force(eps, 1.0, 2.0, 0.1, force, cursor);
    sum += v.psi_w(0) + gx(0) + force(0) + static_cast<double>(shapes.locate_element(eps));
  }
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(g_allocations, before) << "operator new called during evaluation";
  EXPECT_EQ(g_eigen_assert_failures, eigen_before) << "Eigen allocated during evaluation";
  EXPECT_TRUE(std::isfinite(sum));
}

TEST(MemberShapesAllocation, FixedModesEvaluationAllocatesNothing) { expect_allocation_free<6>(6); }

TEST(MemberShapesAllocation, DynamicModesEvaluationAllocatesNothingOnceSized) {
  expect_allocation_free<Eigen::Dynamic>(24);
}

// The counters themselves work (a test that could not fail would prove nothing).
TEST(MemberShapesAllocation, CountersSeeAllocations) {
  // The vector escapes through a volatile pointer: without it an optimiser may elide the
  // new-expression (C++14 [expr.new]) and the counter would see one allocation instead of two.
  static std::vector<double>* volatile sink = nullptr;
  const long before = g_allocations;
  sink = new std::vector<double>(100);
  delete sink;
  EXPECT_GE(g_allocations - before, 2);
  const long eigen_before = g_eigen_assert_failures;
  Eigen::internal::set_is_malloc_allowed(false);
  Eigen::VectorXd x(100);
  Eigen::internal::set_is_malloc_allowed(true);
  x.setZero();
  EXPECT_GE(g_eigen_assert_failures - eigen_before, 1);
}

}  // namespace
}  // namespace stickslip
