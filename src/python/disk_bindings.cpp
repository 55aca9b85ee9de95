// Python bindings of the bladed disk (docs/disks.md): the disk assembly from a Python sector
// builder, its cyclic-symmetry modes, engine-order loads, friction joints between neighbouring
// platforms, travelling-wave orbits (TravellingWaveShooting) and their frequency sweep, and
// Monte Carlo mistuning studies.

#include "call_guard.hpp"

#include <stickslip/disk.hpp>

#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace {

using namespace stickslip;
using Index = Eigen::Index;
using Disk = BladedDisk<double>;
using CSystem = ContactSystem<double>;
using stickslip_python::PyContactSystem;
using stickslip_python::SignalCheck;
using stickslip_python::with_system;
using Orbit = TravellingWaveOrbit<CSystem>;
using Shift = TravellingWaveShift<double>;

std::vector<ContactState> states_of(const CSystem::Mode& mode) {
  std::vector<ContactState> v;
  for (Index i = 0; i < mode.size(); ++i) v.push_back(mode[i]);
  return v;
}
CSystem::Mode mode_of(const std::vector<ContactState>& states) {
  CSystem::Mode mode(static_cast<Index>(states.size()));
  for (std::size_t i = 0; i < states.size(); ++i) mode[static_cast<Index>(i)] = states[i];
  return mode;
}

/// A Python CoulombLaw, StribeckLaw or RegularisedLaw as the law variant.
FrictionLawVariant<double> law_of(const py::handle& law, const char* where) {
  if (py::isinstance<CoulombLaw<double>>(law)) return law.cast<CoulombLaw<double>>();
  if (py::isinstance<StribeckLaw<double>>(law)) return law.cast<StribeckLaw<double>>();
  if (py::isinstance<RegularisedLaw<double>>(law)) return law.cast<RegularisedLaw<double>>();
  throw std::invalid_argument(std::string(where) + ": law must be a CoulombLaw, StribeckLaw or RegularisedLaw");
}

/// TravellingWaveOptions from the keyword arguments of the Python calls.
TravellingWaveOptions<double> wave_options(double tolerance, int max_iterations, double rtol, double atol,
                                           bool full_annulus_check, int mode_retries, int settle_periods,
                                           int settle_after) {
  TravellingWaveOptions<double> o;
  o.mode_retries = mode_retries;
  o.settle_periods = settle_periods;
  o.settle_after = settle_after;
  o.shooting.tolerance = tolerance;
  o.shooting.max_iterations = max_iterations;
  o.shooting.stepper.rtol = rtol;
  o.shooting.stepper.atol = atol;
  o.full_annulus_check = full_annulus_check;
  return o;
}

void bind_orbit(py::module_& m) {
  py::enum_<FloquetCheck>(m, "FloquetCheck", "Which Floquet analysis a travelling-wave orbit carries.")
      .value("TravellingWave", FloquetCheck::TravellingWave, "from the run over the shift time tau only")
      .value("FullAnnulus", FloquetCheck::FullAnnulus, "and from an independent run of the annulus over T");
  py::class_<EngineOrderSymmetry>(m, "EngineOrderSymmetry",
                                  "The symmetry of engine-order loads: F_k(t + tau) = F_{k + sigma}(t), tau = T / L.")
      .def_readonly("num_sectors", &EngineOrderSymmetry::num_sectors, "N")
      .def_readonly("engine_order", &EngineOrderSymmetry::engine_order, "EO reduced to [0, N)")
      .def_readonly("sector_shift", &EngineOrderSymmetry::sector_shift, "sigma in [0, N)")
      .def_readonly("shifts_per_period", &EngineOrderSymmetry::shifts_per_period, "L = N / gcd(EO, N) = T / tau")
      .def("period_fraction", &EngineOrderSymmetry::period_fraction, "tau / T = 1 / L.");
  py::class_<Shift>(m, "TravellingWaveShift",
                    "The state map S of a travelling wave, (S x)_k = x_{k + sigma}, and the contacts' permutation.")
      .def_readonly("symmetry", &Shift::symmetry, "the EngineOrderSymmetry (sigma, L)")
      .def_readonly("state", &Shift::state, "S over the whole state (numpy); the audit integrals unchanged")
      .def_readonly("contact_source", &Shift::contact_source,
                    "the shifted mode's contact i takes the state of contact_source[i]");
  py::class_<Orbit>(m, "TravellingWaveOrbit",
                    "A travelling-wave orbit x(t0 + tau) = S x(t0) (or the last Newton iterate when it failed).")
      .def_property_readonly("ok", &Orbit::ok, "True when converged")
      .def_readonly("status", &Orbit::status, "the ShootingStatus")
      .def_readonly("message", &Orbit::message, "empty when converged; otherwise what failed")
      .def_readonly("t0", &Orbit::t0, "start time [s]")
      .def_readonly("period", &Orbit::period, "T of the forcing [s]")
      .def_readonly("shift_time", &Orbit::shift_time, "tau = T / L [s]")
      .def_readonly("symmetry", &Orbit::symmetry, "sigma and L")
      .def_property_readonly("mode", [](const Orbit& o) { return states_of(o.mode); }, "the contact states at t0")
      .def_readonly("x0", &Orbit::x0, "the orbit's state at t0 (numpy)")
      .def_readonly("residual", &Orbit::residual, "max |x_P(t0 + tau) - (S x0)_P|")
      .def_readonly("iterations", &Orbit::iterations, "runs over tau made")
      .def_readonly("settled_periods", &Orbit::settled_periods,
                    "forcing periods of the settling transient the solve started from (0: from the guess)")
      .def_readonly("amplitudes", &Orbit::amplitudes, "max |x_i| over [t0, t0 + tau] of the amplitude components")
      .def_readonly("shift_map", &Orbit::shift_map, "A = S_PP^T M_PP(tau), the linearised map of one shift")
      .def_property_readonly("max_multiplier", [](const Orbit& o) { return o.floquet.max_modulus; },
                             "max |mu| of the full-period monodromy S^L A^L")
      .def_property_readonly("stable", [](const Orbit& o) { return o.floquet.stable; },
                             "every full-period multiplier inside the unit circle (to the tolerance)")
      .def_property_readonly("multipliers", [](const Orbit& o) { return o.floquet.multipliers; },
                             "the full-period Floquet multipliers (complex numpy)")
      .def_property_readonly("shift_multipliers", [](const Orbit& o) { return o.shift_multipliers.multipliers; },
                             "eigenvalues of A (complex numpy)")
      .def_readonly("check", &Orbit::check, "which Floquet analysis was done (FloquetCheck)")
      .def_readonly("full_residual", &Orbit::full_residual, "full-annulus check: max |x_P(t0 + T) - x_P(t0)|")
      .def_readonly("full_mode_closes", &Orbit::full_mode_closes, "full-annulus check: the mode closes over T")
      .def_property_readonly("full_max_multiplier", [](const Orbit& o) { return o.full_floquet.max_modulus; },
                             "full-annulus check: max |mu| of its own monodromy over T")
      .def_readonly("full_seconds", &Orbit::full_seconds, "full-annulus check: wall time of its run [s]")
      .def_property_readonly("steps", [](const Orbit& o) { return o.stats.accepted_steps; },
                             "accepted steps of the last run over tau");
}

void bind_mistuning(py::module_& m) {
  using Study = MistuningStudy<double>;
  py::class_<BladePeak<double>>(m, "BladePeak", "The largest blade response of one disk and the blade that has it.")
      .def(py::init([](double peak, Index blade) { return BladePeak<double>{peak, blade}; }), py::arg("peak"),
           py::arg("blade"), "A peak value and its blade (what a mistuning_study's peak callable returns).")
      .def_readwrite("peak", &BladePeak<double>::peak, "largest response amplitude")
      .def_readwrite("blade", &BladePeak<double>::blade, "the blade that has it");
  py::class_<Study>(m, "MistuningStudy", "A Monte Carlo mistuning study: the amplification factor per sample.")
      .def_readonly("sigma", &Study::sigma, "standard deviation of delta")
      .def_readonly("tuned", &Study::tuned, "the tuned disk's BladePeak")
      .def_readonly("seeds", &Study::seeds, "sample k's seed")
      .def_readonly("amplification", &Study::amplification, "per sample: its peak over the tuned one (NaN: failed)")
      .def("max_amplification", &Study::max_amplification, "The largest amplification over the samples that ran.")
      .def("errors", [](const Study& s) {
            std::vector<std::string> e;
            for (const auto& o : s.outcomes) e.push_back(o.error);
            return e;
          }, "Per sample: the error of a sample whose peak raised (empty when it ran).")
      .def("csv", [](const Study& s) {
            std::ostringstream os;
            s.write_csv(os);
            return os.str();
          }, "The rows as CSV: sample,seed,sigma,peak,blade,amplification,error.");
  m.def("draw_mistuning", [](Index n, double sigma, std::uint64_t seed) { return draw_mistuning(n, sigma, seed).deltas; },
        py::arg("num_sectors"), py::arg("sigma"), py::arg("seed"),
        "delta_k = sigma z_k, z_k standard normal by Box-Muller from std::mt19937_64(seed): the same seed gives the "
        "same list everywhere.");
  m.def(
      "mistuning_study",
      [](Index n, double sigma, std::size_t count, std::uint64_t first_seed, const py::function& peak,
         unsigned threads) {
        // The callable is Python: each call takes the GIL, the study runs with it released.
        const std::function<BladePeak<double>(const std::vector<double>&)> call = [&peak](const std::vector<double>& d) {
          py::gil_scoped_acquire gil;
          return peak(d).cast<BladePeak<double>>();
        };
        py::gil_scoped_release release;
        return mistuning_study<double>(n, sigma, count, first_seed, call, threads);
      },
      py::arg("num_sectors"), py::arg("sigma"), py::arg("count"), py::arg("first_seed"), py::arg("peak"),
      py::arg("threads") = 1,
      "Sample k = draw_mistuning(N, sigma, first_seed + k); peak(deltas) -> BladePeak of the disk with that scatter, "
      "divided by peak of the tuned disk (zeros): the amplification factor. threads > 1 runs samples on threads "
      "(each call of peak takes the GIL). A sample whose peak raises keeps its error (errors()).");
  m.def(
      "engine_order_blade_peak",
      [](const Disk& disk, Index load_node, Dof load_dof, double amplitude, Index eo, Index response_node,
         Dof response_dof, const std::vector<double>& omegas, double zeta, Index num_modes) {
        py::gil_scoped_release release;
        return engine_order_blade_peak(disk, NodeId(load_node), load_dof, amplitude, eo, NodeId(response_node),
                                       response_dof, omegas, zeta, num_modes);
      },
      py::arg("disk"), py::arg("load_node"), py::arg("load_dof"), py::arg("amplitude"), py::arg("engine_order"),
      py::arg("response_node"), py::arg("response_dof"), py::arg("omegas"), py::arg("zeta"), py::arg("num_modes"),
      "The largest blade amplitude of a linear disk under engine-order forcing over the frequencies omegas, from the "
      "modal receptance of the annulus' num_modes lowest modes (modal damping ratio zeta); mistuned disks welcome.");
}

}  // namespace

void bind_disk(py::module_& m) {
  py::class_<SectorCoupling<double>>(m, "SectorCoupling", "Springs and/or a ring element between neighbouring sectors.")
      .def_static("springs", &SectorCoupling<double>::springs, py::arg("k_x"), py::arg("k_y"), py::arg("k_rz"),
                  "Springs along X [N/m], Y [N/m] and about Z [N m/rad] between R of sector k and L of sector k + 1.")
      .def_static("ring_member", &SectorCoupling<double>::ring_member, py::arg("section"),
                  "One Euler-Bernoulli element of this SectionProperties from R to the next sector's L.")
      .def_readwrite("k_x", &SectorCoupling<double>::k_x, "spring along X [N/m]")
      .def_readwrite("k_y", &SectorCoupling<double>::k_y, "spring along Y [N/m]")
      .def_readwrite("k_rz", &SectorCoupling<double>::k_rz, "spring about Z [N m/rad]");
  py::class_<SectorPlacement<double>>(m, "SectorPlacement", "Where a sector builder places sector `index`.")
      .def_readonly("index", &SectorPlacement<double>::index, "sector number k")
      .def_readonly("origin", &SectorPlacement<double>::origin, "(k pitch, 0) [m]: add every node at origin + its own position")
      .def_readonly("stiffness_factor", &SectorPlacement<double>::stiffness_factor,
                    "1 + delta_k: multiply the sector's Young's modulus by it");

  py::class_<NodalDiameterModes<double>>(m, "NodalDiameterModes", "The cyclic modes of one nodal-diameter family.")
      .def_readonly("nodal_diameter", &NodalDiameterModes<double>::nodal_diameter, "h")
      .def_readonly("pairs", &NodalDiameterModes<double>::pairs, "True for 0 < h < N/2: each omega is a degenerate pair")
      .def_readonly("omega", &NodalDiameterModes<double>::omega, "frequencies [rad/s], ascending (numpy)")
      .def_readonly("sector_shapes", &NodalDiameterModes<double>::sector_shapes,
                    "complex sector shapes over the sector's free DOFs, one column per omega")
      .def_readonly("inverse_form", &NodalDiameterModes<double>::inverse_form, "the inverse form M x = mu K x was used");
  py::class_<CyclicModes<double>>(m, "CyclicModes", "The cyclic-symmetry modes of a tuned disk, families h = 0 ... N/2.")
      .def_readonly("families", &CyclicModes<double>::families, "NodalDiameterModes per h");

  py::class_<Disk>(m, "BladedDisk",
                   "N copies of a sector side by side (sector k at (k pitch, 0)), right attachment of sector k coupled "
                   "to the left attachment of sector k + 1 (wrap-around) (docs/disks.md).")
      .def(py::init([](Index n, double pitch, const py::function& builder, const SectorCoupling<double>& coupling,
                       std::vector<double> mistuning) {
             const Disk::SectorBuilder b = [builder](FrameModel<double>& frame, const SectorPlacement<double>& at) {
               const py::tuple lr = builder(py::cast(&frame, py::return_value_policy::reference), at);
               if (lr.size() != 2) throw std::invalid_argument("BladedDisk: builder must return (left, right) node ids");
               return SectorAttachments{NodeId(lr[0].cast<Index>()), NodeId(lr[1].cast<Index>())};
             };
             return Disk(n, pitch, b, coupling, std::move(mistuning));
           }),
           py::arg("num_sectors"), py::arg("pitch"), py::arg("builder"), py::arg("coupling"),
           py::arg("mistuning") = std::vector<double>{},
           "builder(frame, placement) adds one sector to the FrameModel frame at placement.origin (the same nodes "
           "and members in the same order at every call, E scaled by placement.stiffness_factor) and returns its "
           "(left, right) attachment node ids. mistuning: delta_k per sector (empty: tuned). ValueError naming the "
           "parameter.")
      .def("num_sectors", &Disk::num_sectors, "N")
      .def("pitch", &Disk::pitch, "distance between neighbouring sectors [m]")
      .def("frame", &Disk::frame, py::return_value_policy::reference_internal,
           "The annulus' FrameModel (all sectors, without the coupling: modes from annulus_modes or annulus_basis).")
      .def("sector_frame", &Disk::sector_frame, py::return_value_policy::reference_internal,
           "The reference sector alone (equal to sector 0).")
      .def("mistuning", &Disk::mistuning, "delta_k per sector")
      .def("is_tuned", &Disk::is_tuned, "True when every delta_k is 0")
      .def("nodes_per_sector", &Disk::nodes_per_sector, "P")
      .def("members_per_sector", &Disk::members_per_sector, "Q")
      .def("node", [](const Disk& d, Index k, Index n) { return Index(d.node(k, NodeId(n))); }, py::arg("k"),
           py::arg("sector_node"), "Node of sector k that is sector_node of the reference sector.")
      .def("member", [](const Disk& d, Index k, Index q) { return Index(d.member(k, MemberId(q))); }, py::arg("k"),
           py::arg("sector_member"), "Member of sector k that is sector_member of the reference sector.")
      .def("point", &Disk::point, py::arg("k"), py::arg("point"),
           "The StructurePoint of sector k that is `point` of the reference sector.")
      .def("stiffness", [](const Disk& d) { return Eigen::MatrixXd(d.assemble().stiffness); },
           "K of the annulus over its free DOFs, couplings included (dense numpy).")
      .def("mass", [](const Disk& d) { return Eigen::MatrixXd(d.assemble().mass); },
           "M of the annulus over its free DOFs (dense numpy).")
      .def("annulus_modes", [](const Disk& d, Index n) {
             ModalOptions<double> o;
             o.num_modes = n;
             py::gil_scoped_release release;
             return compute_modes(d.assemble(), o);
           }, py::arg("num_modes"), "The num_modes lowest modes of the whole annulus (a ModalBasis of frame()).");

  m.def("compute_cyclic_modes", [](const Disk& d, Index n) {
          CyclicModalOptions<double> o;
          o.num_modes = n;
          return compute_cyclic_modes(d, o);
        }, py::arg("disk"), py::arg("num_modes") = 10,
        "The num_modes lowest modes of each nodal-diameter family of a tuned disk from one sector.");
  m.def("expand_cyclic_mode", &expand_cyclic_mode<double>, py::arg("disk"), py::arg("modes"), py::arg("h"),
        py::arg("j"), "Annulus mode(s) of family h, mode j: two columns (a pair) for 0 < h < N/2, else one.");
  m.def("annulus_basis", &annulus_basis<double>, py::arg("disk"), py::arg("modes"),
        "Every family's modes expanded to the annulus, ascending, as a ModalBasis of disk.frame() (undamped).");
  m.def("engine_order_loads",
        [](const Disk& d, Index member, double coordinate, LoadDirection direction, double amplitude, double omega,
           Index eo) { return engine_order_loads(d, MemberId(member), coordinate, direction, amplitude, omega, eo); },
        py::arg("disk"), py::arg("sector_member"),
        py::arg("coordinate"), py::arg("direction"), py::arg("amplitude"), py::arg("omega"), py::arg("engine_order"),
        "One PointLoad per blade, F_k(t) = amplitude cos(omega t + 2 pi EO k / N) at the same point of each sector.");
  m.def("reduced_engine_order", &reduced_engine_order, py::arg("engine_order"), py::arg("num_sectors"),
        "EO mod N in [0, N).");
  m.def("engine_order_nodal_diameter", &engine_order_nodal_diameter, py::arg("engine_order"), py::arg("num_sectors"),
        "The nodal diameter min(r, N - r), r = EO mod N, that engine order EO excites.");
  m.def("engine_order_symmetry", &engine_order_symmetry, py::arg("engine_order"), py::arg("num_sectors"),
        "The EngineOrderSymmetry of EO on N blades: sector shift sigma and L = T / tau.");
  m.def(
      "neighbour_joints",
      [](const Disk& d, const StructurePoint<double>& right, const StructurePoint<double>& left,
         const PlaneDirection<double>& direction, const py::object& law, double normal) {
        return neighbour_joints(d, right, left, direction, law_of(law, "neighbour_joints"), normal);
      },
      py::arg("disk"), py::arg("right_wing"), py::arg("left_wing"), py::arg("direction"), py::arg("law"),
      py::arg("normal"),
      "N PointContact joints for ContactSystem: contact k between right_wing of sector k and left_wing of sector "
      "k + 1 (reference-sector points), sliding along direction, held normal force [N].");

  bind_orbit(m);
  m.def(
      "travelling_wave_shift",
      [](const Disk& d, const ModalBasis<double>& basis, const PyContactSystem& system, Index eo) {
        return travelling_wave_shift(d, basis, static_cast<const CSystem&>(system), eo);
      },
      py::arg("disk"), py::arg("basis"), py::arg("system"), py::arg("engine_order"),
      "The TravellingWaveShift of a ContactSystem over disk.frame() and basis (whole nodal-diameter families) whose "
      "contacts are numbered sector by sector, for engine order EO.");
  m.def(
      "travelling_wave",
      [](PyContactSystem& system, const Shift& shift, const std::vector<ContactState>& mode, double t0,
         const CSystem::State& x0, double period, double tolerance, int max_iterations, double rtol, double atol,
         bool full_annulus_check, int mode_retries, int settle_periods, int settle_after) {
        const auto opt = wave_options(tolerance, max_iterations, rtol, atol, full_annulus_check, mode_retries,
                                      settle_periods, settle_after);
        return with_system(system, [&](SignalCheck&) {
          TravellingWaveShooting<CSystem> tw(system, shift, opt);
          return tw.solve(mode_of(mode), t0, x0, period);
        });
      },
      py::arg("system"), py::arg("shift"), py::arg("mode"), py::arg("t0"), py::arg("x0"), py::arg("period"),
      py::arg("tolerance") = 1e-9, py::arg("max_iterations") = 30, py::arg("rtol") = 1e-10, py::arg("atol") = 1e-14,
      py::arg("full_annulus_check") = false, py::arg("mode_retries") = 3, py::arg("settle_periods") = 40,
      py::arg("settle_after") = 8,
      "The travelling-wave orbit x(t0 + tau) = S x(t0) of forcing period T through (mode, t0) from the guess x0 by "
      "Newton's method on runs over tau = T / L (TravellingWaveShooting); full_annulus_check also integrates it "
      "over T with its monodromy. mode_retries (>= 0): when the state closes but the start mode does not, Newton is "
      "repeated from the mode the run ends in (shifted back), at most this many times. settle_periods (>= 0): a "
      "solve that still fails is repeated once from the end of a transient of that many forcing periods from the "
      "guess (TravellingWaveOrbit.settled_periods; 0: never), after settle_after Newton iterations from the guess.");
  m.def(
      "travelling_wave_sweep",
      [](const py::function& make_system, const Disk& d, const ModalBasis<double>& basis, Index eo,
         const std::vector<double>& omegas, const std::vector<ContactState>& mode, const CSystem::State& guess,
         double tolerance, int max_iterations, double rtol, double atol, int mode_retries, int settle_periods,
         int settle_after) {
        const std::function<CSystem(double)> make = [&make_system](double w) {
          py::gil_scoped_acquire gil;
          return CSystem(make_system(w).cast<const PyContactSystem&>());
        };
        const std::function<Shift(const CSystem&)> shift = [&](const CSystem& s) {
          return travelling_wave_shift(d, basis, s, eo);
        };
        const auto opt =
            wave_options(tolerance, max_iterations, rtol, atol, false, mode_retries, settle_periods, settle_after);
        std::vector<TravellingWaveSweepPoint<CSystem>> points;
        {
          py::gil_scoped_release release;
          points = travelling_wave_sweep<CSystem>(make, shift, omegas, mode_of(mode), guess, opt);
        }
        py::list out;
        for (auto& p : points) out.append(py::make_tuple(p.omega, std::move(p.orbit)));
        return out;
      },
      py::arg("make_system"), py::arg("disk"), py::arg("basis"), py::arg("engine_order"), py::arg("omegas"),
      py::arg("mode"), py::arg("guess"), py::arg("tolerance") = 1e-9, py::arg("max_iterations") = 30,
      py::arg("rtol") = 1e-10, py::arg("atol") = 1e-14, py::arg("mode_retries") = 3, py::arg("settle_periods") = 40,
      py::arg("settle_after") = 8, "Travelling waves at the frequencies omegas in order (t0 = 0): make_system(omega) builds the ContactSystem "
      "forced at omega; the first point starts from (mode, guess), the next from the secant through the last two "
      "converged orbits; mode_retries, settle_periods and settle_after as in travelling_wave. Returns [(omega, TravellingWaveOrbit)].");
  bind_mistuning(m);
}
