#pragma once
/// \file mistuning_study.hpp
/// \brief Monte Carlo mistuning studies of a bladed disk as a sweep: per sample (one seed each)
/// the largest blade peak of the mistuned disk over the tuned one, the amplification factor, one
/// row per sample, run on threads (sweep/sweep.hpp); and the largest blade peak of a linear disk
/// under engine-order forcing from its annulus modes (docs/disks.md).

#include "stickslip/beam/dof.hpp"
#include "stickslip/beam/ids.hpp"
#include "stickslip/detail/validate.hpp"
#include "stickslip/disk/bladed_disk.hpp"
#include "stickslip/disk/engine_order.hpp"
#include "stickslip/disk/mistuning.hpp"
#include "stickslip/modal/compute_modes.hpp"
#include "stickslip/sweep/sweep.hpp"

#include <Eigen/Core>

#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace stickslip {

/// The largest blade response of one disk: its value and the blade that has it.
template <class Scalar>
struct BladePeak {
  Scalar peak{};             ///< largest response amplitude over blades (and frequencies)
  Eigen::Index blade = -1;   ///< the blade that has it
};

/// A Monte Carlo mistuning study (mistuning_study).
template <class Scalar>
struct MistuningStudy {
  Scalar sigma{};                      ///< standard deviation of delta
  BladePeak<Scalar> tuned;             ///< the tuned disk (delta = 0)
  std::vector<std::uint64_t> seeds;    ///< sample k's seed (first_seed + k)
  /// Sample k: the largest blade peak over the tuned one (NaN when the sample failed: its
  /// outcome holds the error).
  std::vector<Scalar> amplification;
  std::vector<SweepOutcome> outcomes;  ///< one row per sample: seed,sigma,peak,blade,amplification
  /// The header of the rows.
  static const char* header() { return "seed,sigma,peak,blade,amplification"; }
  /// The largest amplification over the samples that ran (NaN when none did).
  Scalar max_amplification() const {
    Scalar m = std::numeric_limits<Scalar>::quiet_NaN();
    for (Scalar a : amplification)
      if (!std::isnan(a) && !(a <= m)) m = a;
    return m;
  }
  /// CSV: sample,seed,sigma,peak,blade,amplification,error (write_sweep_csv).
  void write_csv(std::ostream& os) const {
    write_sweep_csv(os, "sample", [](std::size_t k) { return std::to_string(k); }, header(), outcomes);
  }
};

/// The study: the tuned peak `peak(0 ... 0)` once, then for k = 0 ... count - 1 the sample
/// draw_mistuning(N, sigma, first_seed + k) and its amplification peak(deltas).peak / tuned.peak,
/// on `threads` threads (run_sweep_threads; 0: all cores, 1: this thread). `peak` must be safe to
/// call concurrently (build each sample's disk and model inside it). A sample whose `peak`
/// throws is a row with the error (amplification NaN); the study goes on. The rows depend on k
/// alone, so any thread count gives the same rows.
/// \throws std::invalid_argument naming the parameter: num_sectors < 1, sigma not finite or < 0,
///         an empty peak, or a tuned peak that is not finite and > 0 (peak)
template <class Scalar>
MistuningStudy<Scalar> mistuning_study(Eigen::Index num_sectors, Scalar sigma, std::size_t count, std::uint64_t first_seed,
                                       const std::function<BladePeak<Scalar>(const std::vector<Scalar>&)>& peak,
                                       unsigned threads = 0, const SweepProgress& progress = {}) {
  static const char* where = "mistuning_study";
  if (num_sectors < 1) detail::throw_invalid(where, "num_sectors must be >= 1", num_sectors);
  detail::require_non_negative(where, "sigma", sigma);
  if (!peak) detail::throw_invalid(where, "peak must be set", "empty");
  MistuningStudy<Scalar> study;
  study.sigma = sigma;
  study.tuned = peak(std::vector<Scalar>(static_cast<std::size_t>(num_sectors), Scalar(0)));
  if (!(study.tuned.peak > Scalar(0)) || !std::isfinite(study.tuned.peak))
    detail::throw_invalid(where, "peak of the tuned disk must be finite and > 0", study.tuned.peak);
  study.seeds.resize(count);
  study.amplification.assign(count, std::numeric_limits<Scalar>::quiet_NaN());
  for (std::size_t k = 0; k < count; ++k) study.seeds[k] = first_seed + k;
  const SweepItem item = [&](std::size_t k) {
    const MistuningSample<Scalar> sample = draw_mistuning(num_sectors, sigma, study.seeds[k]);
    const BladePeak<Scalar> p = peak(sample.deltas);
    const Scalar a = p.peak / study.tuned.peak;
    study.amplification[k] = a;  // each item writes its own entry
    char row[160];
    std::snprintf(row, sizeof row, "%llu,%.17g,%.17g,%ld,%.17g", static_cast<unsigned long long>(sample.seed),
                  double(sigma), double(p.peak), static_cast<long>(p.blade), double(a));
    return std::string(row);
  };
  study.outcomes = threads == 1 ? run_sweep_serial(count, item, progress)
                                : run_sweep_threads(count, item, threads, progress);
  return study;
}

/// The largest blade peak of a linear disk (no friction, or dampers modelled as stuck springs in
/// the sector) under engine-order forcing: the annulus modes of disk.assemble() (compute_modes,
/// `num_modes` lowest), modal damping ratio zeta, the load F_k = F cos(Omega t + 2 pi EO k / N) on
/// DOF `load_dof` of sector node `load_node` of every blade, the response amplitude |u| of DOF
/// `response_dof` of sector node `response_node` of every blade, from the modal receptance
///     u_k(Omega) = sum_r phi_r(k) (phi_r^T Fhat) / (omega_r^2 - Omega^2 + 2 i zeta omega_r Omega),
/// the largest over blades and `omegas`. Mistuned disks welcome (the annulus is solved whole).
/// \throws std::invalid_argument naming the parameter: empty omegas, a node outside the sector
///         or a constrained DOF (load_node, response_node), zeta not finite or < 0, and
///         compute_modes' refusals (options.num_modes)
template <class Scalar>
BladePeak<Scalar> engine_order_blade_peak(const BladedDisk<Scalar>& disk, NodeId load_node, Dof load_dof, Scalar amplitude,
                                          Eigen::Index engine_order, NodeId response_node, Dof response_dof,
                                          const std::vector<Scalar>& omegas, Scalar zeta, Eigen::Index num_modes) {
  static const char* where = "engine_order_blade_peak";
  using Index = Eigen::Index;
  using Complex = std::complex<Scalar>;
  if (omegas.empty()) detail::throw_invalid(where, "omegas must not be empty; size", omegas.size());
  detail::require_non_negative(where, "zeta", zeta);
  const Index N = disk.num_sectors();
  for (const auto& [node, dof, name] : {std::tuple<NodeId, Dof, const char*>{load_node, load_dof, "load_node"},
                                        std::tuple<NodeId, Dof, const char*>{response_node, response_dof, "response_node"}})
    if (node < 0 || node >= disk.nodes_per_sector() || disk.annulus_dofs().free_index(disk.node(0, node), dof) < 0)
      detail::throw_invalid(where, std::string(name) + " must be a node of the sector with that DOF free", Index(node));
  ModalOptions<Scalar> mo;
  mo.num_modes = num_modes;
  const ModalBasis<Scalar> basis = compute_modes(disk.assemble(), mo);
  const Index n = basis.size();
  Eigen::Matrix<Complex, Eigen::Dynamic, 1> g = Eigen::Matrix<Complex, Eigen::Dynamic, 1>::Zero(n);
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> out(N, n);
  const Index eo = reduced_engine_order(engine_order, N);
  for (Index k = 0; k < N; ++k) {
    const Complex f = std::polar(amplitude, Scalar(2) * Scalar(EIGEN_PI) * Scalar((eo * k) % N) / Scalar(N));
    g += basis.nodal(disk.node(k, load_node), load_dof).transpose().template cast<Complex>() * f;
    out.row(k) = basis.nodal(disk.node(k, response_node), response_dof);
  }
  BladePeak<Scalar> best;
  best.peak = Scalar(-1);
  for (const Scalar W : omegas) {
    Eigen::Matrix<Complex, Eigen::Dynamic, 1> Q(n);
    for (Index r = 0; r < n; ++r) {
      const Scalar w = basis.omega()(r);
      Q(r) = g(r) / Complex(w * w - W * W, Scalar(2) * zeta * w * W);
    }
    const Eigen::Matrix<Complex, Eigen::Dynamic, 1> u = out.template cast<Complex>() * Q;
    for (Index k = 0; k < N; ++k)
      if (std::abs(u(k)) > best.peak) {
        best.peak = std::abs(u(k));
        best.blade = k;
      }
  }
  return best;
}

}  // namespace stickslip
