// Assembly and modal analysis cost for straight cantilevers and square grid frames of 1e2..1e5
// elements. Counters: free DOFs, nonzeros and bytes of K + M, solver iterations / solves, and for
// the cantilever the relative error of the first frequency against beta_1 L = 1.875104.

#include "stickslip/beam.hpp"
#include "stickslip/modal.hpp"

#include <benchmark/benchmark.h>

#include <cmath>

namespace {

using namespace stickslip;

const SectionProperties<double> kSteel{2.1e11, 7800.0, 1e-4, 1e-9};

FrameModel<double> cantilever(Eigen::Index elements) {
  FrameModel<double> m;
  const auto a = m.add_node(0, 0), b = m.add_node(1, 0);
  m.add_member(a, b, kSteel, elements);
  m.clamp(a);
  return m;
}

// N x N bays of 1 m, every member split into 2 elements, bottom row clamped:
// 4 N (N + 1) elements.
FrameModel<double> grid(Eigen::Index bays) {
  FrameModel<double> m;
  const Eigen::Index n = bays + 1;
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i) m.add_node(double(i), double(j));
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i) {
      if (i + 1 < n) m.add_member(j * n + i, j * n + i + 1, kSteel, 2);
      if (j + 1 < n) m.add_member(j * n + i, (j + 1) * n + i, kSteel, 2);
    }
  for (Eigen::Index i = 0; i < n; ++i) m.clamp(i);
  return m;
}

Eigen::Index bays_for(Eigen::Index elements) {  // 4 N (N + 1) ~ elements
  return Eigen::Index(std::lround(std::sqrt(double(elements) / 4.0)));
}

void matrix_counters(benchmark::State& state, const AssembledFrame<double>& f, Eigen::Index elements) {
  const double nnz = double(f.stiffness.nonZeros() + f.mass.nonZeros());
  state.counters["elements"] = double(elements);
  state.counters["free_dofs"] = double(f.num_free());
  state.counters["nnz_KM"] = nnz;
  const double bytes = nnz * double(sizeof(double) + sizeof(int)) + 2.0 * double(f.num_free() + 1) * double(sizeof(int));
  state.counters["MiB_KM"] = bytes / 1048576.0;
}

void BM_AssembleCantilever(benchmark::State& state) {
  const auto model = cantilever(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(model.assemble());
  matrix_counters(state, model.assemble(), model.num_elements());
  state.SetItemsProcessed(state.iterations() * model.num_elements());
}

void BM_AssembleGrid(benchmark::State& state) {
  const auto model = grid(bays_for(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(model.assemble());
  matrix_counters(state, model.assemble(), model.num_elements());
  state.SetItemsProcessed(state.iterations() * model.num_elements());
}

void run_modes(benchmark::State& state, const FrameModel<double>& model, bool cantilever_reference) {
  ModalOptions<double> options;
  options.num_modes = 10;
  ModalSolveReport<double> report;
  ModalBasis<double> basis;
  for (auto _ : state) {
    const auto frame = model.assemble();
    basis = compute_modes(frame, options, &report);
    benchmark::DoNotOptimize(basis.omega().data());
  }
  matrix_counters(state, model.assemble(), model.num_elements());
  state.counters["sparse"] = report.solver == ModalSolver::Sparse ? 1 : 0;
  state.counters["solves"] = double(report.operations);
  state.counters["restarts"] = double(report.iterations);
  state.counters["f1_Hz"] = basis.frequencies_hz()(0);
  if (cantilever_reference) {
    const double unit = std::sqrt(kSteel.E * kSteel.I / (kSteel.rho * kSteel.A));
    state.counters["f1_rel_err"] = std::abs(basis.omega()(0) / (1.875104069 * 1.875104069 * unit) - 1.0);
  }
}

void BM_ModesCantilever(benchmark::State& state) { run_modes(state, cantilever(state.range(0)), true); }
void BM_ModesGrid(benchmark::State& state) { run_modes(state, grid(bays_for(state.range(0))), false); }

BENCHMARK(BM_AssembleCantilever)->Arg(100)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AssembleGrid)->Arg(100)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ModesCantilever)->Arg(100)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_ModesGrid)->Arg(100)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
