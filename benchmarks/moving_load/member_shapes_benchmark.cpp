// Cost of one MemberShapes evaluation of (psi_u, psi_u', psi_w, psi_w', psi_w'') versus the number
// of modes (4 ... 64) and of elements per member (10 ... 1e4), with the locality fast path (an
// ElementCursor, the point moving a little per call as a sliding damper does) and without it
// (binary search on every call). Expected: linear in the modes, flat in the elements on the
// fast path, growing like log2(elements) without it.

#include "stickslip/moving_load/member_shapes.hpp"

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

namespace {

using stickslip::ElementCursor;
using stickslip::MemberNodalModes;
using stickslip::MemberShapes;

constexpr double kLength = 0.04;

MemberNodalModes<double> synthetic_member(Eigen::Index elements, Eigen::Index modes) {
  std::mt19937_64 rng(1234);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  MemberNodalModes<double> d;
  d.stations = Eigen::VectorXd::LinSpaced(elements + 1, 0.0, kLength);
  d.u = Eigen::MatrixXd::NullaryExpr(elements + 1, modes, [&] { return unit(rng); });
  d.w = Eigen::MatrixXd::NullaryExpr(elements + 1, modes, [&] { return unit(rng); });
  d.theta = Eigen::MatrixXd::NullaryExpr(elements + 1, modes, [&] { return unit(rng) / kLength; });
  return d;
}

// A slowly moving point: 4096 positions sweeping the member back and forth, each step ~1/3 of an
// element of the finest mesh, so the cursor's element or a neighbour almost always holds it.
std::vector<double> trajectory(Eigen::Index elements) {
  std::vector<double> eps(4096);
  const double step = kLength / static_cast<double>(elements) / 3.0;
  double x = 0.5 * kLength, dir = 1.0;
  for (double& e : eps) {
    if (x + dir * step > kLength || x + dir * step < 0.0) dir = -dir;
    x += dir * step;
    e = x;
  }
  return eps;
}

template <int Modes, bool UseCursor>
void BM_Evaluate(benchmark::State& state) {
  const Eigen::Index modes = Modes == Eigen::Dynamic ? state.range(0) : Modes;
  const Eigen::Index elements = state.range(1);
  const MemberShapes<double, Modes> shapes(synthetic_member(elements, modes));
  typename MemberShapes<double, Modes>::Values v(modes);
  const std::vector<double> eps = trajectory(elements);
  ElementCursor cursor;
  std::size_t i = 0;
  for (auto _ : state) {
    if constexpr (UseCursor) {
      shapes.evaluate(eps[i], v, cursor);
    } else {
      shapes.evaluate(eps[i], v);
    }
    benchmark::DoNotOptimize(v.psi_w.data());
    benchmark::ClobberMemory();
    i = (i + 1) & 4095;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
  state.counters["modes"] = static_cast<double>(modes);
  state.counters["elements"] = static_cast<double>(elements);
  state.counters["ns_per_mode"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * static_cast<double>(modes),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void grid(benchmark::internal::Benchmark* b) {
  for (const long modes : {4, 8, 16, 32, 64})
    for (const long elements : {10, 100, 1000, 10000}) b->Args({modes, elements});
}

void elements_only(benchmark::internal::Benchmark* b) {
  for (const long elements : {10, 100, 1000, 10000}) b->Args({0, elements});
}

BENCHMARK_TEMPLATE(BM_Evaluate, Eigen::Dynamic, true)->Apply(grid)->Name("Evaluate/cursor");
BENCHMARK_TEMPLATE(BM_Evaluate, Eigen::Dynamic, false)->Apply(grid)->Name("Evaluate/search");
BENCHMARK_TEMPLATE(BM_Evaluate, 6, true)->Apply(elements_only)->Name("Evaluate/fixed6/cursor");
BENCHMARK_TEMPLATE(BM_Evaluate, 6, false)->Apply(elements_only)->Name("Evaluate/fixed6/search");
BENCHMARK_TEMPLATE(BM_Evaluate, 16, true)->Apply(elements_only)->Name("Evaluate/fixed16/cursor");

}  // namespace

BENCHMARK_MAIN();
