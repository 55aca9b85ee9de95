// A user program: consumes stickslip through its CMake package (find_package or
// add_subdirectory), builds a cantilever and checks its first bending frequency against the
// closed form omega_1 = 1.875104^2 sqrt(EI / (rho A L^4)) (Euler-Bernoulli).
#include <stickslip/stickslip.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>

int main() {
  if (std::strcmp(stickslip::version_string(), STICKSLIP_VERSION_STRING) != 0) return 1;
  using namespace stickslip;
  const double E = 2.06e11, rho = 7800, A = 6e-5, I = 2e-11, L = 0.2;
  FrameModel<double> frame;
  const auto root = frame.add_node(0.0, 0.0);
  const auto tip = frame.add_node(0.0, L);
  frame.add_member(root, tip, SectionProperties<double>{E, rho, A, I}, 10);
  frame.clamp(root);
  ModalOptions<double> options;
  options.num_modes = 2;
  const auto basis = compute_modes(frame.assemble(), options);
  const double exact = 1.875104 * 1.875104 * std::sqrt(E * I / (rho * A * L * L * L * L));
  const double rel = std::abs(basis.omega()[0] - exact) / exact;
  std::printf("stickslip %s consumed: first cantilever frequency %.4f Hz (closed form %.4f Hz)\n",
              version_string(), basis.omega()[0] / (2 * M_PI), exact / (2 * M_PI));
  // Ten Hermite elements put the first frequency within 1e-5 of the closed form.
  return rel < 1e-4 ? 0 : 1;
}
