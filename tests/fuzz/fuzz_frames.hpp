#pragma once
// Frames built from a fuzz input, shared by the frame_modes, member_shapes and model harnesses.
//
// Layout (fuzz_input.hpp encoding): topology choice(5); section E, rho, A, I; member length L;
// direction angle theta; elements integer; graded flag and, when set, the first element's length
// `tiny`; mass type flag; point-mass count choice(3) and per mass (node choice, m); spring flag and
// its k.
// Topologies: 0 cantilever (one member from a clamped node at theta), 1 free-free beam (three
// rigid-body modes), 2 T-frame (blade of length L clamped at the root, platform of length L/5
// across its tip: the paper's geometry), 3 free-free T-frame, 4 beam pinned at the root (one
// rigid-body mode, the rotation about the pin).
// Work bound: more than 64 elements per member (but fewer than 2^40) become 64; counts of 2^40
// and more pass to a uniform mesh, and must be refused by name; a graded mesh
// has 1 to 64 elements after its first.
#include "fuzz/fuzz_input.hpp"

#include <stickslip/beam.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace stickslip_fuzz {

struct FuzzFrame {
  stickslip::FrameModel<double> frame;
  unsigned topology = 0;
  stickslip::SectionProperties<double> section{};
  double length = 0;
  bool graded = false;
  bool lumped = false;
  bool extras = false;  ///< point masses or springs were added
  long long elements = 0;
  /// Members: the cantilever / free beam / blade first, the platform of a T-frame second.
  std::vector<Eigen::Index> members;
};

/// A count from the input with legitimate but heavy values (bound < v < 2^40) cut to `bound`; absurd
/// ones (>= 2^40, or <= 0) pass, for the library to refuse by name.
inline long long bounded_count(long long v, long long bound) {
  return (v > bound && v < (1LL << 40)) ? bound : v;
}

/// Stations of a member of length L: a first element of length `tiny`, then `rest` equal ones.
inline std::vector<double> graded_stations(double L, double tiny, long long rest) {
  std::vector<double> s{0.0, tiny};
  for (long long e = 1; e <= rest; ++e) s.push_back(tiny + (L - tiny) * double(e) / double(rest));
  s.back() = L;
  return s;
}

/// Builds the frame an input describes; throws what the library throws.
inline FuzzFrame build_frame(Input& in) {
  FuzzFrame f;
  f.topology = in.choice(5);
  f.section.E = in.real(1e10, 3e11);
  f.section.rho = in.real(1e3, 2e4);
  f.section.A = in.real(1e-6, 1e-3);
  f.section.I = in.real(1e-12, 1e-8);
  f.length = in.real(0.01, 1.0);
  const double theta = in.real(-3.2, 3.2);
  f.elements = bounded_count(in.integer(1, 12), 64);
  f.graded = in.flag();
  const double tiny = f.graded ? in.real(1e-4, 1e-2) : 0.0;
  f.lumped = in.flag();
  auto member = [&](auto a, auto b, double L) {
    // The harness builds graded stations itself: their count is kept in [1, 64] (absurd counts
    // reach the library through the uniform mesh).
    if (f.graded)
      return f.frame.add_member(a, b, f.section, graded_stations(L, tiny, std::clamp(f.elements, 1LL, 64LL)));
    return f.frame.add_member(a, b, f.section, static_cast<Eigen::Index>(f.elements));
  };
  const double c = std::cos(theta), s = std::sin(theta), L = f.length;
  const auto root = f.frame.add_node(0.0, 0.0);
  const auto tip = f.frame.add_node(L * c, L * s);
  if (f.topology == 2 || f.topology == 3) {  // platform of length L/5 centred on the tip, across the blade
    const auto left = f.frame.add_node(L * c + 0.1 * L * s, L * s - 0.1 * L * c);
    const auto right = f.frame.add_node(L * c - 0.1 * L * s, L * s + 0.1 * L * c);
    f.members.push_back(member(root, tip, L));
    f.frame.add_member(left, tip, f.section, 2);
    const auto platform = f.frame.add_member(tip, right, f.section, 2);
    f.members.push_back(platform);
  } else {
    f.members.push_back(member(root, tip, L));
  }
  if (f.topology == 0 || f.topology == 2) f.frame.clamp(root);
  if (f.topology == 4) f.frame.pin(root);
  const unsigned masses = in.choice(3);
  for (unsigned i = 0; i < masses; ++i) {
    const auto node = in.flag() ? tip : root;
    f.frame.add_point_mass(node, in.real(0.0, 1.0));
    f.extras = true;
  }
  if (in.flag()) {
    f.frame.add_spring(tip, stickslip::Dof::Y, in.real(0.0, 1e6));
    f.extras = true;
  }
  return f;
}

}  // namespace stickslip_fuzz
