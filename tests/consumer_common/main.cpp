// A user program: consumes stickslip through its CMake package (find_package or
// add_subdirectory) with the umbrella header, builds a cantilever and checks its static tip
// deflection under a transverse tip load against the closed form delta = P L^3 / (3 E I)
// (Euler-Bernoulli; Hermite elements reproduce it exactly). The check is about packaging: a
// static solve keeps this unit's compile at a few seconds (the modal solver instantiated here
// took ~25 s at -O0); the compiled-mode consumer runs compute_modes and simulate() from the
// library.
#include <stickslip/stickslip.hpp>

#include <Eigen/SparseCholesky>

#include <cmath>
#include <cstdio>
#include <cstring>

int main() {
  if (std::strcmp(stickslip::version_string(), STICKSLIP_VERSION_STRING) != 0) return 1;
  using namespace stickslip;
  const double E = 2.06e11, rho = 7800, A = 6e-5, I = 2e-11, L = 0.2, P = 1.0;
  FrameModel<double> frame;
  const auto root = frame.add_node(0.0, 0.0);
  const auto tip = frame.add_node(0.0, L);
  frame.add_member(root, tip, SectionProperties<double>{E, rho, A, I}, 10);
  frame.clamp(root);
  const auto assembled = frame.assemble();
  Eigen::VectorXd load = Eigen::VectorXd::Zero(assembled.num_free());
  const auto dof = assembled.dofs.free_index(tip, Dof::X);  // transverse to the member along Y
  load[dof] = P;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(assembled.stiffness);
  if (solver.info() != Eigen::Success) return 1;
  const double deflection = solver.solve(load)[dof];
  const double exact = P * L * L * L / (3 * E * I);
  const double rel = std::abs(deflection - exact) / exact;
  std::printf("stickslip %s consumed: cantilever tip deflection %.6e m (closed form %.6e m)\n",
              version_string(), deflection, exact);
  // Exact up to the round-off of the sparse solve (condition of K ~ 1e8 at 10 elements).
  return rel < 1e-8 ? 0 : 1;
}
