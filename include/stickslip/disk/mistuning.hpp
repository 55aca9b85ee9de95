#pragma once
/// \file mistuning.hpp
/// \brief Random blade-to-blade stiffness scatter of a bladed disk, E_k = E (1 + delta_k), drawn
/// reproducibly from a recorded seed.

#include "stickslip/detail/validate.hpp"

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace stickslip {

/// A mistuning sample: delta_k per blade and how it was drawn.
template <class Scalar>
struct MistuningSample {
  std::uint64_t seed = 0;       ///< seed of std::mt19937_64
  Scalar sigma{};               ///< standard deviation of delta
  std::vector<Scalar> deltas;   ///< delta_k, k = 0 ... N - 1 (BladedDisk's `mistuning`)
};

/// delta_k = sigma z_k with z_k standard normal, by the Box-Muller transform of std::mt19937_64(seed)
/// (the engine's sequence is fixed by the C++ standard, the distributions' are not: the same seed
/// gives the same sample with every standard library). A draw with delta_k <= -1 (possible only
/// for large sigma) is redrawn, so that E_k stays > 0.
/// \throws std::invalid_argument naming the parameter: num_sectors < 1, sigma not finite or < 0
template <class Scalar>
MistuningSample<Scalar> draw_mistuning(Eigen::Index num_sectors, Scalar sigma, std::uint64_t seed) {
  static const char* where = "draw_mistuning";
  if (num_sectors < 1) detail::throw_invalid(where, "num_sectors must be >= 1", num_sectors);
  detail::require_non_negative(where, "sigma", sigma);
  MistuningSample<Scalar> out;
  out.seed = seed;
  out.sigma = sigma;
  std::mt19937_64 engine(seed);
  // Uniform in (0, 1]: 53 random bits, never 0 (the logarithm below).
  const auto uniform = [&engine] { return (double(engine() >> 11) + 1.0) * 0x1.0p-53; };
  while (static_cast<Eigen::Index>(out.deltas.size()) < num_sectors) {
    const double r = std::sqrt(-2.0 * std::log(uniform())), a = 2.0 * 3.14159265358979323846 * uniform();
    for (double z : {r * std::cos(a), r * std::sin(a)}) {
      const Scalar d = sigma * Scalar(z);
      if (d > Scalar(-1) && static_cast<Eigen::Index>(out.deltas.size()) < num_sectors) out.deltas.push_back(d);
    }
  }
  return out;
}

}  // namespace stickslip
