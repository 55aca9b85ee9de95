// The Python module `stickslip` (docs/python.md): frames, modes, dampers and loads, simulate()
// with any integrator returning histories as numpy arrays, events, the energy audit, per-damper
// statistics and trade_study(). Exceptions keep their messages: std::invalid_argument becomes
// ValueError, other std::exception types their pybind11 counterparts (RuntimeError, ...).
#include "call_guard.hpp"
#include "continuation_support.hpp"

#include <stickslip/stickslip.hpp>

#include <pybind11/complex.h>
#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace py = pybind11;

namespace pybind11::detail {
/// NodeId and MemberId are Python ints.
template <class Tag>
struct type_caster<stickslip::detail::TaggedIndex<Tag>> {
  PYBIND11_TYPE_CASTER(stickslip::detail::TaggedIndex<Tag>, const_name("int"));
  bool load(handle src, bool convert) {
    make_caster<Eigen::Index> index;
    if (!index.load(src, convert)) return false;
    value = cast_op<Eigen::Index>(index);
    return true;
  }
  static handle cast(stickslip::detail::TaggedIndex<Tag> id, return_value_policy, handle) {
    return PyLong_FromLongLong(static_cast<long long>(id.value));
  }
};
}  // namespace pybind11::detail

void bind_firstuser(py::module_& m);  // firstuser_bindings.cpp: probes, orbit signals, progress

namespace {

using namespace stickslip;
using Index = Eigen::Index;
using System = FrictionDampedSystem<double>;
using CSystem = ContactSystem<double>;
using BSystem = ContactSystem<double, BodyContact<double>>;
using MSystem = ContactSystem<double, AnyContact<double>>;
using State = System::State;
using Mode = System::Mode;
using Law = FrictionLawVariant<double>;
using stickslip_python::copy_of;
using stickslip_python::PyBodyContactSystem;
using stickslip_python::PyContactSystem;
using stickslip_python::PyMixedContactSystem;
using stickslip_python::PySystem;
using stickslip_python::SignalCheck;
using stickslip_python::with_system;
using stickslip_python::cast_as;
using stickslip_python::check_start;
using stickslip_python::check_callables;
using stickslip_python::checked_max_steps;
using stickslip_python::continuation_options;
using stickslip_python::kWrapSectionDoc;
using stickslip_python::ContinuationCallbacks;
using stickslip_python::default_periodic_size;
using stickslip_python::num_contacts_of;
using stickslip_python::periodic_set;
using stickslip_python::PyContinuation;
using stickslip_python::PyContinuationPart;
using stickslip_python::PyContinuationPoint;
using stickslip_python::PyOrbit;
using stickslip_python::set_outputs_and_progress;
using stickslip_python::shooting_options;
using stickslip_python::set_orbit_details;
using stickslip_python::to_list;
using stickslip_python::to_mode;
using stickslip_python::to_py;
using stickslip_python::Transition;


/// A Python CoulombLaw, StribeckLaw or RegularisedLaw as the law variant (else ValueError naming
/// `where` and law).
Law to_law(const py::handle& law, const std::string& where = "PointDamper") {
  if (py::isinstance<CoulombLaw<double>>(law)) return law.cast<CoulombLaw<double>>();
  if (py::isinstance<StribeckLaw<double>>(law)) return law.cast<StribeckLaw<double>>();
  if (py::isinstance<RegularisedLaw<double>>(law)) return law.cast<RegularisedLaw<double>>();
  throw std::invalid_argument(where + ": law must be a CoulombLaw, StribeckLaw or RegularisedLaw");
}

/// A Python callable f(t) as a std::function (None: empty), for a load's F(t) or a contact's N(t);
/// ValueError "<where>: time_function must be None or a callable ..." otherwise. Copies share one
/// reference, released with the GIL held (copies may live on other threads); each call takes the
/// GIL and casts the result (TypeError naming `where` unless a float).
std::function<double(double)> python_time_function(const py::object& f, const std::string& where,
                                                   const char* quantity) {
  if (f.is_none()) return nullptr;
  if (!PyCallable_Check(f.ptr()))
    throw std::invalid_argument(where + ": time_function must be None or a callable " + quantity + "(t)");
  std::shared_ptr<py::object> fn(new py::object(f), [](py::object* o) {
    py::gil_scoped_acquire gil;
    delete o;
  });
  const std::string what = where + ": time_function(t) must return a float";
  return [fn, what](double t) {
    py::gil_scoped_acquire gil;
    return cast_as<double>((*fn)(t), what);
  };
}

/// A point of the frame whose displacement simulate() records at every sample:
/// point_shape(member, coordinate, direction)^T q.
struct Probe {
  MemberId member = 0;
  double coordinate = 0;
  LoadDirection direction = LoadDirection::GlobalX;
};

/// What simulate() returns: the result, the sampled histories and the audit.
struct Run {
  Status status = Status::Success;
  std::string message;
  double t = 0;
  State x;
  std::vector<ContactState> mode;
  StepperStats stats;
  double E0 = 0;
  std::optional<System::EnergyBalance> energy;          // a FrictionDampedSystem's audit
  std::optional<std::variant<CSystem::EnergyBalance, BSystem::EnergyBalance, MSystem::EnergyBalance>> contact_energy;  // a ContactSystem's
  std::vector<double> sample_t;
  std::vector<State> samples;  // empty unless record_states
  std::vector<std::vector<ContactState>> sample_modes;
  std::vector<std::vector<double>> probe_values;  // per sample
  std::vector<double> force_t;                     // samples with t >= evaluate_from
  std::vector<System::Vector> N, f, V, y, X;  // y and X: FrictionDampedSystem only
  std::vector<Transition> transitions;
  std::vector<DamperWindowStatistics<double>> statistics;
};

/// Rows of `rows` (each of `cols` values) as a 2-D numpy array.
template <class T, class Rows, class Get>
py::array_t<T> stack(const Rows& rows, Index cols, Get get) {
  py::array_t<T> a({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(cols)});
  auto m = a.template mutable_unchecked<2>();
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (Index c = 0; c < cols; ++c) m(static_cast<py::ssize_t>(r), static_cast<py::ssize_t>(c)) = get(rows[r], c);
  return a;
}

/// simulate()'s observer: samples (t, x, mode, probes, forces after evaluate_from), transitions,
/// and DamperStatistics when a window is given (a FrictionDampedSystem's run: Sys is System or
/// CSystem, the State and Mode types are the same); stops the run when a signal handler raised.
template <class Sys>
class Recorder {
 public:
  Recorder(Sys& system, Run& run, std::vector<System::Vector> probe_shapes, bool record_states,
           double evaluate_from, std::optional<DamperStatistics<System>>& statistics, SignalCheck& signals)
      : system_(system), run_(run), shapes_(std::move(probe_shapes)), record_states_(record_states),
        evaluate_from_(evaluate_from), statistics_(statistics), signals_(signals) {}

  bool on_step(double t, const State& x, const Mode& mode) {
    if (statistics_) statistics_->on_step(t, x, mode);
    return !signals_();
  }
  void on_event(const EventRecord<double, Mode>& record, const State& x_after) {
    run_.transitions.push_back(Transition{record.t, to_list(record.from), to_list(record.to)});
    if (statistics_) statistics_->on_event(record, x_after);
  }
  bool on_sample(double t, const State& x, const Mode& mode) {
    run_.sample_t.push_back(t);
    if (record_states_) run_.samples.push_back(x);
    run_.sample_modes.push_back(to_list(mode));
    std::vector<double> p(shapes_.size());
    for (std::size_t k = 0; k < shapes_.size(); ++k) p[k] = shapes_[k].dot(x.head(system_.num_modes()));
    run_.probe_values.push_back(std::move(p));
    if (t >= evaluate_from_ - 1e-12) {  // the tolerance of examples/blade_damper's record window
      const auto& e = system_.evaluate(mode, t, x);
      run_.force_t.push_back(t);
      run_.N.push_back(e.N);
      run_.f.push_back(e.f);
      if constexpr (std::is_same_v<Sys, System>) {
        run_.V.push_back(e.V);
        run_.y.push_back(e.y);
        run_.X.push_back(e.X);
      } else {
        run_.V.push_back(e.v);
      }
    }
    return !signals_();
  }

 private:
  Sys& system_;
  Run& run_;
  std::vector<System::Vector> shapes_;
  bool record_states_;
  double evaluate_from_;
  std::optional<DamperStatistics<System>>& statistics_;
  SignalCheck& signals_;
};

/// The mechanical energy at the start of a run (both systems' signatures).
double start_energy(System& system, const Mode& mode, double t, const State& x) {
  return system.mechanical_energy(mode, t, x);
}
template <class Contact>
double start_energy(ContactSystem<double, Contact>& system, const Mode&, double, const State& x) {
  return system.mechanical_energy(x);
}

/// simulate() from (mode, t0, x0) - by default the system's initial state made consistent - to
/// t_end, recording as asked. The GIL is released and the system's lock held while the stepper
/// runs; Ctrl-C stops it (KeyboardInterrupt). Py: PySystem, PyContactSystem or PyBodyContactSystem (the
/// last two: no probes nor statistics, ValueError naming them).
template <class Py>
Run run_simulation(Py& py_system, double t_end, const RunOptions<double>& options, double t0,
                   std::optional<State> x0, std::optional<std::vector<ContactState>> mode0,
                   const std::vector<Probe>& probes, bool record_states, double evaluate_from,
                   std::optional<StatisticsWindow<double>> window, bool consistent) {
  constexpr bool kContacts = !std::is_same_v<Py, PySystem>;
  using Sys = typename Py::Wrapped;
  if (std::isnan(evaluate_from))  // every comparison with NaN is false: nothing would be recorded
    throw std::invalid_argument("simulate: evaluate_from must be a time or inf (no forces), got nan");
  if constexpr (kContacts) {
    if (!probes.empty())
      throw std::invalid_argument("simulate: probes must be empty for a ContactSystem (record_states gives q: "
                                  "a point's displacement is its row . q, e.g. contact_row(i) . q)");
    if (window) throw std::invalid_argument("simulate: statistics must be None for a ContactSystem");
  }
  return with_system(py_system, [&](SignalCheck& signals) {
    Sys& system = py_system;
    Run run;
    State x = x0 ? *x0 : system.initial_state();
    Mode mode = mode0 ? to_mode(*mode0) : system.requested_mode();
    check_start(system, mode, x, "simulate");
    system.validate_start(mode, t0, x, "simulate");  // t0 and every x0[k] finite, named
    std::vector<System::Vector> shapes;
    if constexpr (!kContacts)
      for (const Probe& p : probes) shapes.push_back(system.point_shape(p.member, p.coordinate, p.direction));
    if (consistent && !system.make_consistent(mode, t0, x)) {
      run.status = Status::StoppedBySystem;
      run.message = "inconsistent or lifted-off initial contact state at t0";
      run.t = t0;
      run.x = x;
      run.mode = to_list(mode);
      return run;
    }
    run.E0 = system.options().energy_audit ? start_energy(system, mode, t0, x) : 0.0;
    std::optional<DamperStatistics<System>> statistics;
    if constexpr (!kContacts)
      if (window) statistics.emplace(system, mode, t0, x, *window);
    Recorder<Sys> recorder(system, run, std::move(shapes), record_states, evaluate_from, statistics, signals);
    auto result = simulate(system, mode, t0, x, t_end, options, recorder);
    run.status = result.status;
    run.message = result.message;
    run.t = result.t;
    run.x = result.x;
    run.mode = to_list(result.mode);
    run.stats = result.stats;
    if (system.options().energy_audit) {
      if constexpr (kContacts) run.contact_energy = system.energy_balance(result.x, run.E0);
      else run.energy = system.energy_balance(result.mode, result.t, result.x, run.E0);
    }
    if (statistics)
      for (Index i = 0; i < statistics->num_dampers(); ++i) run.statistics.push_back(statistics->statistics(i));
    return run;
  });
}

/// RunOptions from keyword arguments (the StepperOptions field names and the integrator by name).
RunOptions<double> make_run_options(const std::string& integrator, const py::kwargs& kwargs) {
  RunOptions<double> o;
  o.integrator = parse_integrator(integrator);
  auto& s = o.stepper;
  for (const auto& item : kwargs) {
    const std::string key = py::cast<std::string>(item.first);
    const py::handle v = item.second;
    const auto as = [&](auto kind, const char* what) {  // v as kind's type, or TypeError naming the option
      return cast_as<decltype(kind)>(v, "RunOptions: " + key + " must be " + what);
    };
    const auto real = [&] { return as(0.0, "a float"); };
    const auto count = [&] { return as(0L, "an int"); };
    if (key == "fixed_step") s.fixed_step = real();
    else if (key == "initial_step") s.initial_step = real();
    else if (key == "rtol") s.rtol = real();
    else if (key == "atol") s.atol = real();
    else if (key == "safety") s.safety = real();
    else if (key == "min_step") s.min_step = real();
    else if (key == "max_step") s.max_step = real();
    else if (key == "max_steps") s.max_steps = count();
    else if (key == "event_location") s.event_location = as(EventLocation{}, "an EventLocation");
    else if (key == "event_time_tolerance") s.event_time_tolerance = real();
    else if (key == "guard_zero_tolerance") s.guard_zero_tolerance = real();
    else if (key == "guard_samples") s.guard_samples = count();
    else if (key == "zeno_max_events") s.zeno_max_events = count();
    else if (key == "zeno_window") s.zeno_window = real();
    else if (key == "output_interval") s.output_interval = real();
    else if (key == "event_state") s.event_state = as(EventState{}, "an EventState");
    else if (key == "zeno_max_immediate_events") s.zeno_max_immediate_events = count();
    else if (key == "max_samples") s.max_samples = count();
    else if (key == "check_stability_limit") o.check_stability_limit = as(false, "a bool");
    else throw std::invalid_argument("RunOptions: unknown option " + key);
  }
  return o;
}

/// trade_study()'s compared output: a Probe (point_shape^T q) or a Python callable f(t, x).
std::function<double(const System&, double, const State&)> trade_output(const py::object& output) {
  if (py::isinstance<Probe>(output)) {
    const Probe p = output.cast<Probe>();
    return [p](const System& sys, double, const State& x) {
      return sys.point_shape(p.member, p.coordinate, p.direction).dot(x.head(sys.num_modes()));
    };
  }
  if (!PyCallable_Check(output.ptr()))
    throw std::invalid_argument("trade_study: output must be a Probe or a callable f(t, x)");
  return [output](const System&, double t, const State& x) {
    return cast_as<double>(output(t, x), "trade_study: output(t, x) must return a float");
  };
}

void bind_frame(py::module_& m) {
  using Section = SectionProperties<double>;
  py::class_<Section>(m, "SectionProperties",
                      "Material and section of a beam element: Young's modulus E [Pa], density rho [kg/m^3], "
                      "area A [m^2], second moment of area I [m^4] (docs/beam.md).")
      .def(py::init([](double E, double rho, double A, double I) { return Section{E, rho, A, I}; }), py::arg("E"),
           py::arg("rho"), py::arg("A"), py::arg("I"), "A section of Young's modulus E [Pa], density rho [kg/m^3], "
           "area A [m^2] and second moment of area I [m^4].")
      .def_readwrite("E", &Section::E, "Young's modulus [Pa]")
      .def_readwrite("rho", &Section::rho, "density [kg/m^3]")
      .def_readwrite("A", &Section::A, "cross-section area [m^2]")
      .def_readwrite("I", &Section::I, "second moment of area about the bending axis [m^4]");
  py::enum_<Dof>(m, "Dof", "A nodal degree of freedom of a plane frame.")
      .value("X", Dof::X, "displacement along global X [m]")
      .value("Y", Dof::Y, "displacement along global Y [m]")
      .value("Rz", Dof::Rz, "rotation about Z [rad]");
  py::enum_<MassType>(m, "MassType", "The element mass matrix of the assembly.")
      .value("Consistent", MassType::Consistent, "consistent mass matrix (the default)")
      .value("Lumped", MassType::Lumped, "lumped (diagonal) mass matrix");
  using Frame = FrameModel<double>;
  py::class_<Frame>(m, "FrameModel", "A plane frame of Euler-Bernoulli members (docs/beam.md).")
      .def(py::init<>(), "An empty frame.")
      .def("add_node", &Frame::add_node, py::arg("x"), py::arg("y"), "Adds a node at (x, y) [m]; returns its id.")
      .def("add_member", py::overload_cast<NodeId, NodeId, const Frame::Section&, Index>(&Frame::add_member),
           py::arg("node_a"), py::arg("node_b"), py::arg("section"), py::arg("elements"),
           "Adds a member from node_a to node_b meshed into `elements` equal elements; returns its id.")
      .def("add_member",
           py::overload_cast<NodeId, NodeId, const Frame::Section&, std::vector<double>>(&Frame::add_member),
           py::arg("node_a"), py::arg("node_b"), py::arg("section"), py::arg("stations"),
           "Adds a member from node_a to node_b meshed at the ascending local coordinates `stations` [m] "
           "(0 ... its length); returns its id.")
      .def("clamp", &Frame::clamp, py::arg("node"), "Fixes the node's X, Y and Rz.")
      .def("pin", &Frame::pin, py::arg("node"), "Fixes the node's X and Y (free rotation).")
      .def("fix", &Frame::fix, py::arg("node"), py::arg("dof"), "Fixes one DOF (Dof) of the node.")
      .def("add_point_mass", &Frame::add_point_mass, py::arg("node"), py::arg("m"),
           "Adds a point mass m [kg] at the node (to its X and Y).")
      .def("add_rotary_inertia", &Frame::add_rotary_inertia, py::arg("node"), py::arg("J"),
           "Adds a rotary inertia J [kg m^2] at the node.")
      .def("add_spring", &Frame::add_spring, py::arg("node"), py::arg("dof"), py::arg("k"),
           "Adds a grounded spring k [N/m, or N m/rad for Rz] on one DOF of the node.")
      .def("num_members", &Frame::num_members, "Number of members added.")
      .def("num_nodes", &Frame::num_nodes, "Number of nodes: the user's and the interior nodes of the member meshes.")
      .def("num_elements", &Frame::num_elements, "Total number of elements over all members.")
      .def("is_constrained", &Frame::is_constrained, py::arg("node"), py::arg("dof"),
           "True when the nodal DOF is constrained.")
      .def("member_nodes", [](const Frame& f, MemberId id) { return f.member(id).nodes; }, py::arg("member"),
           "Node ids along the member, a ... b (C++: member(id).nodes).")
      .def("member_stations", [](const Frame& f, MemberId id) { return f.member(id).stations; }, py::arg("member"),
           "Local coordinates [m] of the member's nodes, 0 ... length (C++: member(id).stations).")
      .def("member_length", [](const Frame& f, MemberId id) { return f.member(id).length; }, py::arg("member"),
           "The member's length [m] (C++: member(id).length).")
      .def("node_position", [](const Frame& f, NodeId n) { return f.node_position(n); }, py::arg("node"),
           "Position (X, Y) [m] of a node (numpy).");

  using Basis = ModalBasis<double>;
  py::class_<Basis>(m, "ModalBasis",
                    "The n lowest mass-normalised modes of a frame: omega ascending [rad/s], Phi (num_free x n) "
                    "with Phi^T M Phi = I; each modal coordinate obeys q_i'' + c_i q_i' + omega_i^2 q_i = phi_i^T f "
                    "(docs/modal.md).")
      .def("omega", &Basis::omega, "Natural circular frequencies [rad/s], ascending (numpy).")
      .def("frequencies_hz", &Basis::frequencies_hz, "Natural frequencies omega / (2 pi) [Hz] (numpy).")
      .def("phi", &Basis::phi, "The modes Phi, num_free x size() (numpy), Phi^T M Phi = I.")
      .def("size", &Basis::size, "Number of modes n.")
      .def("num_free", &Basis::num_free, "Number of free DOFs (rows of Phi).")
      .def("num_rigid_body_modes", &Basis::num_rigid_body_modes, "Number of leading rigid-body (zero-frequency) modes.")
      .def("damping_ratios", &Basis::damping_ratios, "Modal damping ratios zeta_i (numpy; 0 until set).")
      .def("damping_coefficients", &Basis::damping_coefficients,
           "Modal damping coefficients c_i [1/s] of q_i'' + c_i q_i' + omega_i^2 q_i = ... (numpy): 2 zeta_i omega_i, "
           "or alpha + beta omega_i^2 after with_rayleigh_damping.")
      .def("nodal", [](const Basis& b, NodeId node, Dof dof) { return Eigen::RowVectorXd(b.nodal(node, dof)); },
           py::arg("node"), py::arg("dof"),
           "Row of Phi for a nodal DOF: its value in each mode (numpy, zeros when constrained); the DOF's "
           "displacement is nodal(node, dof) @ q.")
      .def("expand", [](const Basis& b, const Eigen::VectorXd& q) { return b.expand(q); }, py::arg("q"),
           "Free-DOF displacements x = Phi q (numpy) of the modal coordinates q (size() entries).")
      .def("nodal_displacements", [](const Basis& b, const Eigen::VectorXd& q) { return b.nodal_displacements(q); },
           py::arg("q"),
           "Displacements of all 3 num_nodes nodal DOFs (constrained ones 0), ordered 3 node + dof (numpy), "
           "of the modal coordinates q.")
      .def("__len__", [](const Basis& b) { return b.size(); }, "Number of modes n.")
      .def("truncated", &Basis::truncated, py::arg("n"), "The n lowest modes (with their damping), 1 <= n <= size().")
      .def("with_modal_damping", &Basis::with_modal_damping, py::arg("ratios"),
           "A copy with modal damping ratios zeta_i (size() entries, >= 0): c_i = 2 zeta_i omega_i.")
      .def("with_rayleigh_damping", &Basis::with_rayleigh_damping, py::arg("alpha"), py::arg("beta"),
           "A copy with Rayleigh damping C = alpha M + beta K: c_i = alpha + beta omega_i^2 (alpha [1/s], beta [s], "
           ">= 0).");
  m.def(
      "compute_modes",
      [](const Frame& frame, std::optional<Index> num_modes, double max_omega, MassType mass) {
        const AssembledFrame<double> assembled = frame.assemble(mass);
        ModalOptions<double> o;
        o.num_modes = num_modes ? *num_modes : assembled.num_free();
        o.max_omega = max_omega;
        return compute_modes(assembled, o);
      },
      py::arg("frame"), py::arg("num_modes") = 10, py::arg("max_omega") = std::numeric_limits<double>::infinity(),
      py::arg("mass") = MassType::Consistent,
      "The lowest num_modes modes (default 10; None: all, one per free DOF) of the frame assembled with `mass`, "
      "dropping those above max_omega [rad/s] (C++: compute_modes(frame.assemble(mass), ModalOptions)).");
}

void bind_dampers(py::module_& m) {
  py::enum_<ContactState>(m, "ContactState", "The state of one friction contact (docs/contact.md).")
      .value("Stick", ContactState::Stick, "v = 0, |f| <= mu_s N")
      .value("SlipPositive", ContactState::SlipPositive, "v > 0, f = -mu_k(|v|) N")
      .value("SlipNegative", ContactState::SlipNegative, "v < 0, f = +mu_k(|v|) N")
      .value("LiftOff", ContactState::LiftOff, "N <= 0: no contact force, f = 0")
      .value("Separated", ContactState::Separated, "the damper flies free of the member, N = 0, f = 0");
  py::enum_<MemberEnd>(m, "MemberEnd", "What a moving contact does at one end of its member (docs/model_separation.md).")
      .value("Default", MemberEnd::Default, "as ModelOptions.end_policy says: Throw -> Stop, Clamp/Extrapolate -> Extend")
      .value("Stop", MemberEnd::Stop, "stop the run with StopReason.LeftMember")
      .value("Extend", MemberEnd::Extend, "continue with the end element's shapes")
      .value("Wall", MemberEnd::Wall, "a rigid end stop: V -> -e V (PointDamper.wall_restitution)");
  py::enum_<Separation>(m, "Separation", "What happens when a damper's normal force reaches zero (docs/model_separation.md).")
      .value("Stop", Separation::Stop, "stop the run with StopReason.LiftOff (permanent contact; default)")
      .value("Separate", Separation::Separate,
             "the damper leaves the member, flies and lands again through an impact (PointDamper.restitution)");
  py::enum_<LoadDirection>(m, "LoadDirection", "Direction of a point load or probe.")
      .value("GlobalX", LoadDirection::GlobalX, "along global X")
      .value("GlobalY", LoadDirection::GlobalY, "along global Y")
      .value("Axial", LoadDirection::Axial, "along the member's local u axis")
      .value("Transverse", LoadDirection::Transverse, "along the member's local w axis")
      .value("Moment", LoadDirection::Moment, "a moment about Z (a probe: the rotation)");
  py::enum_<NormalLoad>(m, "NormalLoad", "A damper's normal force model.")
      .value("Constant", NormalLoad::Constant, "N = N0: no vertical inertia of the damper")
      .value("Inertial", NormalLoad::Inertial, "N = N0 - s m y'': the damper follows the member (paper eqs 23-24)");
  py::enum_<ContactPoint>(m, "ContactPoint", "Whether a damper's contact point moves along its member.")
      .value("Fixed", ContactPoint::Fixed, "X = X0: the shapes at the contact are evaluated once")
      .value("Moving", ContactPoint::Moving, "X' = V: the contact slides with the relative motion (paper eqs 10, 19)");
  py::enum_<EndPolicy>(m, "EndPolicy", "What a contact point beyond a member end does (docs/moving_load.md).")
      .value("Throw", EndPolicy::Throw, "stop the run with StopReason.LeftMember (default)")
      .value("Clamp", EndPolicy::Clamp, "evaluate the shapes at the nearest end")
      .value("Extrapolate", EndPolicy::Extrapolate, "continue the end element's interpolants beyond the end");
  using Coulomb = CoulombLaw<double>;
  py::class_<Coulomb>(m, "CoulombLaw", "Coulomb friction with static mu_s >= kinetic mu_k (dimensionless).")
      .def(py::init<double, double>(), py::arg("mu_s"), py::arg("mu_k"),
           "Static coefficient mu_s, kinetic mu_k (0 <= mu_k <= mu_s).")
      .def("mu_s", &Coulomb::mu_s, "Static coefficient mu_s.")
      .def("mu_k", &Coulomb::mu_k, "Kinetic coefficient mu_k.")
      .def("static_coefficient", &Coulomb::static_coefficient, "mu_s: stick holds while |f| <= mu_s N.")
      .def("kinetic_coefficient", &Coulomb::kinetic_coefficient, py::arg("speed"),
           "mu_k at a sliding speed [m/s] >= 0 (constant).");
  using Stribeck = StribeckLaw<double>;
  py::class_<Stribeck>(m, "StribeckLaw",
                       "Stribeck friction mu(v) = mu_k + (mu_s - mu_k) exp(-(|v| / v_s)^exponent).")
      .def(py::init<double, double, double, double>(), py::arg("mu_s"), py::arg("mu_k"), py::arg("v_s"),
           py::arg("exponent") = 2.0,
           "Static mu_s, kinetic mu_k, Stribeck velocity v_s [m/s] > 0, exponent (default 2).")
      .def("mu_s", &Stribeck::mu_s, "Static coefficient mu_s.")
      .def("mu_k", &Stribeck::mu_k, "Kinetic coefficient mu_k (the limit at high speed).")
      .def("v_s", &Stribeck::v_s, "Stribeck velocity v_s [m/s].")
      .def("exponent", &Stribeck::exponent, "Exponent of the Stribeck decay.")
      .def("static_coefficient", &Stribeck::static_coefficient, "mu_s = mu(0): stick holds while |f| <= mu_s N.")
      .def("kinetic_coefficient", &Stribeck::kinetic_coefficient, py::arg("speed"),
           "mu(speed) for a sliding speed [m/s] >= 0.");
  py::enum_<RegularisedShape>(m, "RegularisedShape", "The shape of a RegularisedLaw.")
      .value("Tanh", RegularisedShape::Tanh, "mu tanh(v / v_eps): smooth")
      .value("LinearSaturated", RegularisedShape::LinearSaturated,
             "mu clamp(v / v_eps, -1, 1): exact Coulomb for |v| >= v_eps");
  using Regularised = RegularisedLaw<double>;
  py::class_<Regularised>(m, "RegularisedLaw",
                          "Regularised friction without a stick state: f = -mu s(v / v_eps) N (s: tanh by default).")
      .def(py::init([](double mu, double v_eps, RegularisedShape shape) { return Regularised(mu, v_eps, shape); }),
           py::arg("mu"), py::arg("v_eps"), py::arg("shape") = RegularisedShape::Tanh,
           "Coefficient mu >= 0, regularisation velocity v_eps [m/s] > 0, shape (default Tanh).")
      .def("mu", &Regularised::mu, "Saturated coefficient mu.")
      .def("v_eps", &Regularised::v_eps, "Regularisation velocity v_eps [m/s].")
      .def("coefficient", &Regularised::coefficient, py::arg("v"),
           "Odd friction coefficient at a sliding velocity v [m/s]: f = -coefficient(v) N.");

  using Damper = System::Damper;
  py::class_<Damper>(m, "PointDamper",
                     "A point-contact friction damper on a member (docs/model.md): it slides along the member's "
                     "local axis u, follows its transverse motion w, is held by a spring to its support and pressed "
                     "against the member by the preload N0. The share s scales its mass and spring.")
      .def(py::init([](MemberId member, double coordinate, double mass, double stiffness, double preload,
                       const py::object& law, double share) {
             return Damper(member, coordinate, mass, stiffness, preload, to_law(law), share);
           }),
           py::arg("member"),
           py::arg("contact_coordinate"), py::arg("mass"), py::arg("stiffness"), py::arg("preload"), py::arg("law"),
           py::arg("share") = 1.0,
           "A damper on `member` at contact_coordinate X0 [m] with mass m [kg] > 0, spring k [N/m] >= 0, preload "
           "N0 [N] >= 0, a friction law (CoulombLaw, StribeckLaw or RegularisedLaw) and share s in (0, 1] "
           "(default 1).")
      .def_static(
          "centrifugal",
          [](MemberId member, double coordinate, double mass, double stiffness, double radius, double spin,
             const py::object& law, double share) {
            return Damper::centrifugal(member, coordinate, mass, stiffness, radius, spin,
                                       to_law(law, "PointDamper.centrifugal"), share);
          },
          py::arg("member"), py::arg("contact_coordinate"), py::arg("mass"), py::arg("stiffness"), py::arg("radius"),
          py::arg("spin"), py::arg("law"), py::arg("share") = 1.0,
          "A damper whose preload is the centrifugal force N0 = s m r Omega^2: radius r [m], spin Omega [rad/s].")
      .def_readwrite("member", &Damper::member, "member the damper touches")
      .def_readwrite("contact_coordinate", &Damper::contact_coordinate,
                     "initial contact coordinate X0 along the member [m]")
      .def_readwrite("mass", &Damper::mass, "damper mass m [kg] (> 0)")
      .def_readwrite("stiffness", &Damper::stiffness, "spring k to the damper's support along u [N/m] (>= 0)")
      .def_readwrite("preload", &Damper::preload, "N0, this structure's share of the normal load [N] (>= 0)")
      .def_readwrite("share", &Damper::share, "share factor s in (0, 1] of the damper's mass and spring (default 1)")
      .def_property(
          "law", [](const Damper& d) { return d.law; },
          [](Damper& d, const py::object& law) { d.law = to_law(law, "PointDamper"); },
          "the friction law (CoulombLaw, StribeckLaw or RegularisedLaw)")
      .def_readwrite("side", &Damper::side,
                     "+1: the damper presses the member along its local +w axis (default); -1: along -w")
      .def_readwrite("initial_state", &Damper::initial_state, "ContactState requested at t0 (default Stick)")
      .def_readwrite("normal_load", &Damper::normal_load,
                     "NormalLoad: Inertial (default) or Constant; ModelOptions.normal_load = Constant overrides it")
      .def_readwrite("contact_point", &Damper::contact_point,
                     "ContactPoint: Moving (default) or Fixed; ModelOptions.moving_contact = False overrides it")
      .def_readwrite("separation", &Damper::separation,
                     "Separation when the normal force reaches zero: Stop the run (default) or Separate")
      .def_readwrite("restitution", &Damper::restitution,
                     "coefficient of restitution e in [0, 1] of the damper's impacts (Separate; default 0)")
      .def_readwrite("landing_speed", &Damper::landing_speed,
                     "impacts at or below this normal speed [m/s] land (default 1e-4)")
      .def_readwrite("start_end", &Damper::start_end, "MemberEnd at X = 0 of the member (default Default)")
      .def_readwrite("finish_end", &Damper::finish_end, "MemberEnd at X = L of the member (default Default)")
      .def_readwrite("wall_restitution", &Damper::wall_restitution,
                     "coefficient of restitution e in [0, 1] of a MemberEnd.Wall: V -> -e V (default 1)")
      .def("effective_mass", &Damper::effective_mass, "Effective mass s m [kg].")
      .def("effective_stiffness", &Damper::effective_stiffness, "Effective spring s k [N/m].");
  using Load = System::Load;
  py::class_<Load>(m, "PointLoad",
                   "A point load on a member: F(t) = amplitude sin(omega t + phase) + offset, or time_function(t) "
                   "when set.")
      .def(py::init([](MemberId member, double coordinate, LoadDirection direction, double amplitude, double omega,
                       double phase, double offset) {
             Load l = Load::harmonic(member, coordinate, direction, amplitude, omega, phase);
             l.offset = offset;
             return l;
           }),
           py::arg("member"), py::arg("coordinate"), py::arg("direction") = LoadDirection::GlobalX,
           py::arg("amplitude") = 0.0, py::arg("omega") = 0.0, py::arg("phase") = 0.0, py::arg("offset") = 0.0,
           "A load at `coordinate` [m] along `member` in `direction` (default GlobalX): amplitude [N] (or [N m]), "
           "omega [rad/s], phase [rad], offset [N] (all default 0).")
      .def_static("harmonic", &Load::harmonic, py::arg("member"), py::arg("coordinate"), py::arg("direction"),
                  py::arg("amplitude"), py::arg("omega"), py::arg("phase") = 0.0,
                  "A harmonic load F(t) = amplitude sin(omega t + phase): amplitude [N], omega [rad/s], phase [rad].")
      .def_readwrite("member", &Load::member, "member the load acts on")
      .def_readwrite("coordinate", &Load::coordinate, "position along the member [m]")
      .def_readwrite("direction", &Load::direction, "LoadDirection (Moment: a moment about Z [N m])")
      .def_readwrite("amplitude", &Load::amplitude, "amplitude [N] or [N m]")
      .def_readwrite("omega", &Load::omega, "circular frequency [rad/s]")
      .def_readwrite("phase", &Load::phase, "phase [rad]")
      .def_readwrite("offset", &Load::offset, "constant part [N]")
      .def_property(
          "time_function", [](const Load& l) { return l.time_function; },
          [](Load& l, const py::object& f) { l.time_function = python_time_function(f, "PointLoad", "F"); },
          "optional F(t) [N] (a Python callable, called with the GIL: slower); None: the harmonic form")
      .def("value", &Load::value, py::arg("t"), "F(t) [N] at time t [s].");
  using Options = ModelOptions<double>;
  py::class_<Options>(m, "ModelOptions", "What a friction-damped scene models (docs/model.md).")
      .def(py::init<>(), "The default options: the paper's full model.")
      .def_readwrite("normal_load", &Options::normal_load,
                     "NormalLoad.Inertial (default: N varies with the damper's vertical inertia, paper eqs 23-24) "
                     "or Constant (for every damper)")
      .def_readwrite("moving_contact", &Options::moving_contact,
                     "the contact points move with the slip (default True; False fixes every damper's contact)")
      .def_readwrite("convective_terms", &Options::convective_terms,
                     "keep the convective terms of the damper's vertical acceleration (paper eq 19; default True)")
      .def_readwrite("watch_lift_off", &Options::watch_lift_off,
                     "watch the normal force and stop (or separate) when it reaches zero (default True)")
      .def_readwrite("energy_audit", &Options::energy_audit,
                     "integrate the work and dissipation terms alongside the state (default True)")
      .def_readwrite("end_policy", &Options::end_policy,
                     "EndPolicy of a contact point at a member end (default Throw: the run stops)")
      .def_readwrite("refine_stale_factorisation", &Options::refine_stale_factorisation,
                     "solve by iterative refinement from the last factorisation while it converges (default True; "
                     "False: every result a function of the state alone, bitwise)");
}

/// A FrictionDampedSystem property of a PySystem (pybind11 does not adapt the base's noexcept
/// member functions to the derived class).
template <auto getter>
decltype(auto) system_getter(const PySystem& system) {
  return (static_cast<const System&>(system).*getter)();
}

void bind_system(py::module_& m) {
  py::class_<System::ContactEvent>(m, "ContactEvent", "One damper's contact switch (FrictionDampedSystem.events()).")
      .def_readonly("t", &System::ContactEvent::t, "time of the switch [s]")
      .def_readonly("damper", &System::ContactEvent::damper, "index of the damper that switched")
      .def_readonly("from_state", &System::ContactEvent::from, "its ContactState before (C++: from)")
      .def_readonly("to_state", &System::ContactEvent::to, "its ContactState after (C++: to)");
  using Impact = System::ImpactEvent;
  py::class_<Impact>(m, "ImpactEvent",
                     "One impact of a separated damper on its member, or of a moving contact on a MemberEnd.Wall "
                     "(FrictionDampedSystem.impacts(); docs/model_separation.md).")
      .def_readonly("t", &Impact::t, "time of the impact [s]")
      .def_readonly("damper", &Impact::damper, "index of the damper")
      .def_readonly("normal_impulse", &Impact::normal_impulse, "L_n >= 0 [N s], pushing the damper off the member")
      .def_readonly("tangential_impulse", &Impact::tangential_impulse, "L_t on the damper along u [N s]")
      .def_readonly("normal_velocity", &Impact::normal_velocity, "gap' before the impact [m/s] (< 0: approaching)")
      .def_readonly("normal_velocity_after", &Impact::normal_velocity_after,
                    "gap' after [m/s]: -e v_n (bounce) or 0 (landing)")
      .def_readonly("sliding_velocity", &Impact::sliding_velocity, "V before the impact [m/s]")
      .def_readonly("sliding_velocity_after", &Impact::sliding_velocity_after, "V after [m/s]")
      .def_readonly("energy_loss", &Impact::energy_loss, "kinetic energy lost [J] (the audit's impact term)")
      .def_readonly("to_state", &Impact::to, "Separated (a bounce) or the ContactState of the landing (C++: to)")
      .def_readonly("wall", &Impact::wall, "True for an impact on a MemberEnd.Wall");
  using Balance = System::EnergyBalance;
  py::class_<Balance>(m, "EnergyBalance",
                      "The energy audit of a FrictionDampedSystem [J]: E(t) - E0 = W_ext - D_visc - D_fric + W_slope "
                      "- D_imp + residual.")
      .def_readonly("mechanical", &Balance::mechanical,
                    "E(t): modal kinetic + strain energy, dampers' kinetic, spring and preload potential [J]")
      .def_readonly("external_work", &Balance::external_work, "W_ext, work of the point loads [J]")
      .def_readonly("viscous_dissipation", &Balance::viscous_dissipation, "D_visc >= 0, dissipated by modal damping [J]")
      .def_readonly("friction_dissipation", &Balance::friction_dissipation, "D_fric >= 0, dissipated by friction [J]")
      .def_readonly("slope_work", &Balance::slope_work,
                    "W_slope, work of the normal forces as the contacts slide over a sloped member [J]")
      .def_readonly("impact_loss", &Balance::impact_loss, "D_imp, kinetic energy lost in impacts [J]")
      .def_readonly("residual", &Balance::residual, "(E - E0) - (W_ext - D_visc - D_fric + W_slope - D_imp) [J]")
      .def_readonly("applies", &Balance::applies,
                    "False when a moving contact may go on past a member end under EndPolicy.Clamp, where the audit "
                    "cannot close (docs/howto/forces_events_energy.md)")
      .def("relative_residual", &Balance::relative_residual,
           "|residual| / the largest term of the audit (|residual| when every term is 0), for a run from rest.");
  py::enum_<System::StopReason>(m, "StopReason", "Why a FrictionDampedSystem stopped a run (stop_reason()).")
      .value("None_", System::StopReason::None, "it did not stop one (C++: None, a Python keyword)")
      .value("LiftOff", System::StopReason::LiftOff, "a damper's normal force reached zero (Separation.Stop)")
      .value("LeftMember", System::StopReason::LeftMember, "a contact point left its member (MemberEnd.Stop)")
      .value("NoConsistentState", System::StopReason::NoConsistentState, "no consistent contact state exists")
      .value("NonFiniteLoad", System::StopReason::NonFiniteLoad, "a point load's value was not finite at the start");
  using Fault = System::LoadFault;
  py::class_<Fault>(m, "LoadFault", "The most recent evaluation in which a point load's value was not finite.")
      .def_readonly("load", &Fault::load, "index of the load (-1: none since construction)")
      .def_readonly("t", &Fault::t, "time of that evaluation [s]")
      .def_readonly("value", &Fault::value, "the value F_l(t)")
      .def_readonly("count", &Fault::count, "evaluations with a non-finite load value since construction");
  using Stuck = StuckModes<double>;
  py::class_<Stuck>(m, "StuckModes", "Undamped natural modes of a FrictionDampedSystem with every damper stuck.")
      .def_readonly("omega", &Stuck::omega, "natural circular frequencies [rad/s], ascending (numpy)")
      .def_readonly("shapes", &Stuck::shapes,
                    "column j: mode j in modal coordinates q, normalised to v^T M v = 1 (numpy, n x n)")
      .def("frequencies_hz", [](const Stuck& s) { return Eigen::VectorXd(s.omega / (2 * EIGEN_PI)); },
           "The natural frequencies omega / (2 pi) [Hz] (numpy).");
  // PySystem: the system and the lock of the calls that run or evaluate it (call_guard.hpp).
  py::class_<PySystem>(m, "FrictionDampedSystem",
                       "Frame modes + friction dampers + point loads (paper eqs 26-29; docs/model.md). State [q, q', "
                       "x, x', X (moving contacts), flight coordinates, audit integrals]; modes are lists of "
                       "ContactState, one per damper. Calls that run or evaluate one system from several threads "
                       "run one after the other (docs/python.md).")
      .def(py::init<const FrameModel<double>&, const ModalBasis<double>&, std::vector<System::Damper>,
                    std::vector<System::Load>, const ModelOptions<double>&>(),
           py::arg("frame"), py::arg("basis"), py::arg("dampers"), py::arg("loads") = std::vector<System::Load>{},
           py::arg("options") = ModelOptions<double>{},
           "Composes `basis` (modes of `frame`) with the dampers, the point loads (default none) and the "
           "ModelOptions (default: the full model). ValueError naming the damper or load and the parameter.")
      .def("num_modes", &system_getter<&System::num_modes>, "n, the number of retained modes.")
      .def("num_dampers", &system_getter<&System::num_dampers>, "D, the number of dampers.")
      .def("state_size", &system_getter<&System::state_size>,
           "2n + 2D, + D with a moving contact, + 2S flight coordinates, + audit_size().")
      .def("q_offset", &system_getter<&System::q_offset>, "Offset of the modal coordinates q (n entries): 0.")
      .def("qd_offset", &system_getter<&System::qd_offset>, "Offset of the modal velocities q' (n entries): n.")
      .def("x_offset", &system_getter<&System::x_offset>, "Offset of the damper displacements x_i (D entries): 2n.")
      .def("xd_offset", &system_getter<&System::xd_offset>, "Offset of the damper velocities x_i' (D entries): 2n + D.")
      .def("contact_offset", &system_getter<&System::contact_offset>,
           "Offset of the contact coordinates X (D entries; -1 without a moving contact).")
      .def("flight_offset", &system_getter<&System::flight_offset>,
           "Offset of the flight coordinates y_d, then y_d' (S entries each; -1 when no damper may separate).")
      .def("num_separable", &system_getter<&System::num_separable>, "S, the number of dampers that may separate.")
      .def(
          "flight_slot",
          [](const PySystem& s, Index i) {
            if (i < 0 || i >= s.num_dampers())
              detail::throw_invalid("FrictionDampedSystem.flight_slot",
                                    "i must be in [0, num_dampers() = " + std::to_string(s.num_dampers()) + ")", i);
            return s.flight_slot(i);
          },
          py::arg("i"), "Slot of damper i among the flight coordinates (0 .. S - 1), -1 when it cannot separate.")
      .def("energy_offset", &system_getter<&System::energy_offset>,
           "Offset of the energy-audit integrals (-1 without the audit).")
      .def("audit_size", &system_getter<&System::audit_size>,
           "Number of audit integrals: 0 without the audit, 4 (W_ext, D_visc, D_fric, W_slope), 5 with impacts (D_imp).")
      .def("options", &system_getter<&System::options>, "The ModelOptions the system was built with (a copy).")
      .def("dampers", &system_getter<&System::dampers>, "The dampers, in the order of the state and the mode (copies).")
      .def("loads", &system_getter<&System::loads>, "The point loads (copies).")
      .def("omega_squared", &system_getter<&System::omega_squared>,
           "Squared natural frequencies omega_j^2 of the retained modes [rad^2/s^2] (numpy).")
      .def("linear_rates", [](const PySystem& s) { return s.linear_rates(); },
           "The rates [1/s] (complex) an explicit fixed step must resolve: the modes', the dampers' slip "
           "oscillators, ... (docs/howto/pick_an_integrator.md, \"Step rates\").")
      .def("point_shape", &System::point_shape, py::arg("member"), py::arg("coordinate"), py::arg("direction"),
           "Row psi (numpy) with psi . q the displacement of point `coordinate` [m] of `member` along `direction` "
           "(Moment: the rotation).")
      .def("initial_state", &System::initial_state,
           "The state at rest: q = q' = 0, each damper at its contact coordinate X0 (numpy).")
      .def("requested_mode", [](const PySystem& s) { return to_list(s.requested_mode()); },
           "Each damper's initial_state (a list of ContactState).")
      .def(
          "make_consistent",
          [](PySystem& s, std::vector<ContactState> mode, double t, State x) {
            Mode md = to_mode(mode);
            const bool ok = with_system(s, [&](SignalCheck&) { return s.make_consistent(md, t, x); });
            return py::make_tuple(ok, to_list(md), x);
          },
          py::arg("mode"), py::arg("t"), py::arg("x"),
          "(ok, mode, x) made consistent at t [s]: each damper's state where its forces put it, stuck velocities "
          "projected (ok False: no consistent state, see stop_reason()).")
      .def(
          "evaluate",
          [](PySystem& s, const std::vector<ContactState>& mode, double t, const State& x) {
            const Mode md = to_mode(mode);
            const System::Evaluation e = with_system(s, [&](SignalCheck&) {
              s.validate_state(md, x, "FrictionDampedSystem.evaluate");
              return s.evaluate(md, t, x);  // a copy, made under the lock
            });
            py::dict d;
            d["qdd"] = e.qdd, d["N"] = e.N, d["f"] = e.f, d["V"] = e.V, d["xdd"] = e.xdd, d["X"] = e.X;
            d["slope"] = e.slope, d["y"] = e.y, d["gap"] = e.gap, d["wall_force"] = e.wall_force;
            d["finite"] = e.finite;
            return d;
          },
          py::arg("mode"), py::arg("t"), py::arg("x"),
          "Forces and kinematics at (mode, t, x): a dict of numpy arrays, one entry per damper: qdd (modal "
          "accelerations, n), N normal force [N], f friction force on the damper [N], V sliding velocity [m/s], "
          "xdd, X contact coordinate [m], slope, y normal displacement [m], gap [m], wall_force [N]; finite.")
      .def(
          "events",
          [](const PySystem& s) { return with_system(s, [&](SignalCheck&) { return s.events(); }); },
          "Contact switches (ContactEvent) logged since construction or clear_events().")
      .def(
          "impacts",
          [](const PySystem& s) { return with_system(s, [&](SignalCheck&) { return s.impacts(); }); },
          "Impacts (ImpactEvent) logged since construction or clear_events().")
      .def("clear_events", [](PySystem& s) { with_system(s, [&](SignalCheck&) { s.clear_events(); }); },
           "Forgets the logged switches and impacts.")
      .def(
          "stop_reason", [](const PySystem& s) { return with_system(s, [&](SignalCheck&) { return s.stop_reason(); }); },
          "Why the system stopped the last run (StopReason; None_ when it did not).")
      .def(
          "stop_damper", [](const PySystem& s) { return with_system(s, [&](SignalCheck&) { return s.stop_damper(); }); },
          "The damper that stopped the last run (-1 when none).")
      .def(
          "load_fault", [](const PySystem& s) { return with_system(s, [&](SignalCheck&) { return s.load_fault(); }); },
          "The most recent non-finite point-load value (LoadFault).")
      .def(
          "mechanical_energy",
          [](PySystem& s, const std::vector<ContactState>& mode, double t, const State& x) {
            const Mode md = to_mode(mode);
            return with_system(s, [&](SignalCheck&) {
              s.validate_state(md, x, "FrictionDampedSystem.mechanical_energy");
              return s.mechanical_energy(md, t, x);
            });
          },
          py::arg("mode"), py::arg("t"), py::arg("x"),
          "E at (mode, t, x) [J]: modal kinetic + strain energy, dampers' kinetic, spring and preload potential.")
      .def(
          "energy_balance",
          [](PySystem& s, const std::vector<ContactState>& mode, double t, const State& x, double E0) {
            const Mode md = to_mode(mode);
            return with_system(s, [&](SignalCheck&) {
              s.validate_state(md, x, "FrictionDampedSystem.energy_balance");
              return s.energy_balance(md, t, x, E0);
            });
          },
          py::arg("mode"), py::arg("t"), py::arg("x"), py::arg("E0"),
          "The energy audit (EnergyBalance) at (mode, t, x) from the start's energy E0 [J] (needs "
          "ModelOptions.energy_audit).");
  m.def(
      "stuck_natural_modes",
      [](const PySystem& system, std::optional<Eigen::VectorXd> X) {
        return X ? stuck_natural_modes(static_cast<const System&>(system), *X)
                 : stuck_natural_modes(static_cast<const System&>(system));
      },
      py::arg("system"), py::arg("X") = py::none(),
      "Natural modes (StuckModes) of the system with every damper stuck at the contact coordinates X [m] (one per "
      "damper; default: each damper's contact_coordinate): each stuck damper adds its mass and spring to the "
      "structure; modal damping is left out (docs/model.md).");
}

/// A system's contacts as Python gets them: a single-kind list as it is.
template <class Contact>
const std::vector<Contact>& python_contacts(const std::vector<Contact>& contacts) {
  return contacts;
}
/// A mixed scene's contacts: each the PointContact or BodyContact it holds.
std::vector<AnyContact<double>::Kind> python_contacts(const std::vector<AnyContact<double>>& contacts) {
  std::vector<AnyContact<double>::Kind> out;
  out.reserve(contacts.size());
  for (const auto& c : contacts) out.push_back(c.kind);
  return out;
}

/// The Python class of ContactSystem<double, Contact> (Py: PyContactSystem, PyBodyContactSystem or
/// PyMixedContactSystem):
/// its nested ContactEvent and EnergyBalance and every member but the constructor, which differs
/// (a BodyContactSystem takes the bodies).
template <class Py>
py::class_<Py> bind_contact_system(py::module_& m, const char* name, const char* doc) {
  using Sys = typename Py::Wrapped;
  const std::string cname(name);
  py::class_<Py> cls(m, name, doc);
  py::class_<typename Sys::ContactEvent>(cls, "ContactEvent", "One contact's switch.")
      .def_readonly("t", &Sys::ContactEvent::t, "time of the switch [s]")
      .def_readonly("contact", &Sys::ContactEvent::contact, "which contact switched")
      .def_readonly("from_state", &Sys::ContactEvent::from, "its state before")
      .def_readonly("to_state", &Sys::ContactEvent::to, "its state after");
  using Balance = typename Sys::EnergyBalance;
  py::class_<Balance>(cls, "EnergyBalance", "The energy audit: (E - E0) - (W_ext - D_visc - D_fric) = residual [J].")
      .def_readonly("mechanical", &Balance::mechanical,
                    "E = q'.q'/2 + sum omega_j^2 q_j^2 / 2 + the bodies' kinetic and spring energy [J]")
      .def_readonly("external_work", &Balance::external_work, "W_ext: work of the point and body loads [J]")
      .def_readonly("viscous_dissipation", &Balance::viscous_dissipation, "D_visc: modal damping and dashpots [J]")
      .def_readonly("friction_dissipation", &Balance::friction_dissipation,
                    "D_fric: friction work, stuck projections and impacts [J]")
      .def_readonly("residual", &Balance::residual, "(E - E0) - (W_ext - D_visc - D_fric) [J]")
      .def_readonly("scale", &Balance::scale, "largest magnitude of the terms [J]")
      .def("relative_residual", &Balance::relative_residual, "|residual| / scale (0 when every term is 0).");
  cls.def("num_modes", [](const Py& s) { return s.num_modes(); }, "n, the number of retained modes.")
      .def("num_bodies", [](const Py& s) { return s.num_bodies(); }, "B, the number of rigid bodies.")
      .def("num_coordinates", [](const Py& s) { return s.num_coordinates(); },
           "n + 3B: the modal coordinates q, then each body's (x [m], y [m], theta [rad]).")
      .def("num_contacts", [](const Py& s) { return s.num_contacts(); }, "D, the number of contacts.")
      .def("state_size", [](const Py& s) { return s.state_size(); },
           "2 num_coordinates() (+ 3 with the energy audit): [z, z', W_ext, D_visc, D_fric].")
      .def("audit_offset", [](const Py& s) { return s.audit_offset(); },
           "Index of the first audit integral (W_ext, D_visc, D_fric): 2 num_coordinates().")
      .def(
          "body_offset",
          [cname](const Py& s, Index b) {
            if (b < 0 || b >= s.num_bodies())
              detail::throw_invalid(cname + ".body_offset",
                                    "b must be in [0, num_bodies() = " + std::to_string(s.num_bodies()) + ")", b);
            return s.body_offset(b);
          },
          py::arg("b"), "Index of body b's x in the state (y, theta follow; their rates num_coordinates() later).")
      .def("contacts", [](const Py& s) { return python_contacts(s.contacts()); },
           "The contacts (copies; of a MixedContactSystem each a PointContact or a BodyContact).")
      .def("bodies", [](const Py& s) { return s.bodies(); }, "The rigid bodies (copies).")
      .def("loads", [](const Py& s) { return s.loads(); }, "The point loads (copies).")
      .def("options", [](const Py& s) { return s.options(); }, "The ContactSystemOptions (a copy).")
      .def("linear_rates", [](const Py& s) { return s.linear_rates(); },
           "Roots [1/s] (complex) of s^2 + c_j s + omega_j^2 of every mode and of m s^2 + c s + k of each body's "
           "springs along x and y (the fixed-step stability check).")
      .def(
          "contact_row",
          [cname](const Py& s, Index i) {
            if (i < 0 || i >= s.num_contacts())
              detail::throw_invalid(cname + ".contact_row",
                                    "i must be in [0, num_contacts() = " + std::to_string(s.num_contacts()) + ")", i);
            return Eigen::VectorXd(s.contact_row(i));
          },
          py::arg("i"),
          "Structure part w_i of contact i's sliding-velocity row (without bodies its slip s_i = w_i . q [m], "
          "v_i = w_i . q' [m/s]).")
      .def("initial_state", &Py::initial_state, "Rest: z = z' = 0, audit integrals 0.")
      .def("requested_mode", [](const Py& s) { return to_list(s.requested_mode()); }, "Each contact's initial_state.")
      .def(
          "make_consistent",
          [cname](Py& s, std::vector<ContactState> mode, double t, State x) {
            Mode md = to_mode(mode);
            const std::string where = cname + ".make_consistent";
            const bool ok = with_system(s, [&](SignalCheck&) {
              s.validate_state(md, x, where.c_str());
              return s.make_consistent(md, t, x);
            });
            return py::make_tuple(ok, to_list(md), x);
          },
          py::arg("mode"), py::arg("t"), py::arg("x"),
          "(ok, mode, x) made consistent at t [s]: a contact with |v| above the velocity tolerance slides in sgn(v), "
          "one at rest sticks unless its force exceeds mu_s N; a closed unilateral contact under tension opens; "
          "stuck and closed velocities are projected to 0.")
      .def(
          "evaluate",
          [cname](Py& s, const std::vector<ContactState>& mode, double t, const State& x) {
            const Mode md = to_mode(mode);
            const std::string where = cname + ".evaluate";
            const typename Sys::Evaluation e = with_system(s, [&](SignalCheck&) {
              s.validate_state(md, x, where.c_str());
              return s.evaluate(md, t, x);  // a copy, made under the lock
            });
            py::dict d;
            d["qdd"] = e.qdd, d["f"] = e.f, d["v"] = e.v, d["N"] = e.N, d["vn"] = e.vn, d["gap"] = e.gap;
            d["finite"] = e.finite;
            return d;
          },
          py::arg("mode"), py::arg("t"), py::arg("x"),
          "Forces and kinematics at (mode, t, x): dict of qdd (z''), f (friction force on side a along its tangent "
          "[N]), v (sliding velocity [m/s]), N (normal force [N]; 0 for an open contact), vn (normal velocity [m/s]), "
          "gap [m] (vn and gap 0 under a held normal) and finite.")
      .def(
          "events", [](const Py& s) { return with_system(s, [&](SignalCheck&) { return s.events(); }); },
          "The contact switches (ContactEvent) logged since construction or clear_events().")
      .def("clear_events", [](Py& s) { with_system(s, [&](SignalCheck&) { s.clear_events(); }); },
           "Forgets the logged switches.")
      .def(
          "mechanical_energy",
          [cname](const Py& s, const State& x) {
            const std::string where = cname + ".mechanical_energy";
            return with_system(s, [&](SignalCheck&) {
              s.validate_state(s.requested_mode(), x, where.c_str());
              return s.mechanical_energy(x);
            });
          },
          py::arg("x"),
          "E = q'.q'/2 + sum omega_j^2 q_j^2 / 2 + sum_b (m |V|^2 + J omega^2) / 2 + sum_springs k delta^2 / 2 [J].")
      .def(
          "energy_balance",
          [cname](const Py& s, const State& x, double E0) {
            const std::string where = cname + ".energy_balance";
            return with_system(s, [&](SignalCheck&) {
              s.validate_state(s.requested_mode(), x, where.c_str());
              return s.energy_balance(x, E0);
            });
          },
          py::arg("x"), py::arg("E0"),
          "The energy audit at x from the start's energy E0 [J] (ValueError when options.energy_audit is off).");
  return cls;
}

void bind_contacts(py::module_& m) {
  using Point = StructurePoint<double>;
  using Direction = PlaneDirection<double>;
  using Normal = HeldNormal<double>;
  using Contact = PointContact<double>;
  using COptions = ContactSystemOptions<double>;
  py::class_<Point>(m, "StructurePoint",
                    "A material point of the structure: `coordinate` [m] along member `member` (0 at the member's "
                    "first node), in [0, length] (docs/contacts.md).")
      .def(py::init([](MemberId member, double coordinate) { return Point{member, coordinate}; }), py::arg("member"),
           py::arg("coordinate"), "The point `coordinate` [m] along member `member`.")
      .def_readwrite("member", &Point::member, "member the point lies on")
      .def_readwrite("coordinate", &Point::coordinate, "position along the member [m]")
      .def("__repr__", [](const Point& p) {
        return "StructurePoint(member=" + std::to_string(p.member.value) + ", coordinate=" +
               std::string(py::str(py::float_(p.coordinate))) + ")";
      });
  py::class_<Direction>(m, "PlaneDirection",
                        "An in-plane direction (x, y) in global components; a contact needs a unit vector (|d| = 1 "
                        "to 1e-9, checked by ContactSystem: ValueError naming direction).")
      .def(py::init([](double x, double y) { return Direction{x, y}; }), py::arg("x") = 1.0, py::arg("y") = 0.0,
           "The direction (x, y) in global components (default global X).")
      .def_readwrite("x", &Direction::x, "global X component")
      .def_readwrite("y", &Direction::y, "global Y component")
      .def_static("at_angle", &Direction::at_angle, py::arg("angle"),
                  "The unit direction (cos a, sin a) at angle `angle` [rad] from global X, counter-clockwise.")
      .def_static("global_x", &Direction::global_x, "Global X, (1, 0).")
      .def_static("global_y", &Direction::global_y, "Global Y, (0, 1).");
  py::class_<Normal>(m, "HeldNormal",
                     "A held normal force N(t) [N]: `value`, or time_function(t) when set; > 0 at every t.")
      .def(py::init([](double value, const py::object& time_function) {
             Normal n;
             n.value = value;
             n.time_function = python_time_function(time_function, "HeldNormal", "N");
             return n;
           }),
           py::arg("value") = 1.0, py::arg("time_function") = py::none(),
           "A normal force of `value` [N] (default 1), or time_function(t) [N] when given.")
      .def_readwrite("value", &Normal::value, "constant normal force [N] (default 1)")
      .def_property(
          "time_function", [](const Normal& n) { return n.time_function; },
          [](Normal& n, const py::object& f) { n.time_function = python_time_function(f, "HeldNormal", "N"); },
          "optional N(t) [N] (a Python callable, called with the GIL: slower); None: the constant value")
      .def("__call__", &Normal::operator(), py::arg("t"), "N(t) [N].");
  py::class_<Contact>(m, "PointContact",
                      "A friction contact at a structure point under a held normal force: side a rubs on ground "
                      "(grounded) or on side b (joint) along `direction`; s = (u_a - u_b) . d (docs/contacts.md).")
      .def_static(
          "grounded",
          [](const Point& point, const Direction& direction, const py::object& law, double N) {
            detail::require_positive("PointContact.grounded", "N", N);
            return Contact::grounded(point, direction, to_law(law, "PointContact.grounded"), N);
          },
          py::arg("point"), py::arg("direction"), py::arg("law"), py::arg("N"),
          "A grounded slider: `point` rubs on ground along the unit `direction` with `law` (CoulombLaw, StribeckLaw "
          "or RegularisedLaw) under the normal force N [N] > 0 (ValueError naming N otherwise).")
      .def_static(
          "joint",
          [](const Point& point_a, const Point& point_b, const Direction& direction, const py::object& law, double N) {
            detail::require_positive("PointContact.joint", "N", N);
            return Contact::joint(point_a, point_b, direction, to_law(law, "PointContact.joint"), N);
          },
          py::arg("point_a"), py::arg("point_b"), py::arg("direction"), py::arg("law"), py::arg("N"),
          "A friction joint: `point_a` rubs on `point_b` (another point, e.g. of another member) along the unit "
          "`direction` with `law` under the normal force N [N] > 0.")
      .def_static(
          "with_row",
          [](std::function<Eigen::VectorXd(const FrameModel<double>&, const ModalBasis<double>&)> row,
             const py::object& law, double N) {
            detail::require_positive("PointContact.with_row", "N", N);
            if (!row) throw std::invalid_argument("PointContact.with_row: row must be a callable row(frame, basis)");
            return Contact::with_row(std::move(row), to_law(law, "PointContact.with_row"), N);
          },
          py::arg("row"), py::arg("law"), py::arg("N"),
          "A contact of one's own relation on the same modes: s = w . q with w = row(frame, basis) (one finite value "
          "per retained mode, e.g. basis.nodal(node, Dof.Rz) differences for a rotational hinge; called once "
          "when the ContactSystem is built), with `law` under the normal force N [N] > 0; a, b, direction are not "
          "read (docs/contacts.md, \"A relation of one's own\").")
      .def_property_readonly("has_row", [](const Contact& c) { return static_cast<bool>(c.row); },
                             "whether the relation is a row(frame, basis) of one's own (with_row)")
      .def_readwrite("a", &Contact::a, "the sliding side (a StructurePoint)")
      .def_readwrite("b", &Contact::b, "the other side: a StructurePoint, or None for ground")
      .def_readwrite("direction", &Contact::direction, "tangential unit direction d (global)")
      .def_property(
          "friction", [](const Contact& c) { return c.friction; },
          [](Contact& c, const py::object& law) { c.friction = to_law(law, "PointContact"); },
          "the friction law (CoulombLaw, StribeckLaw or RegularisedLaw)")
      .def_readwrite("normal", &Contact::normal, "the held normal force (HeldNormal) [N]")
      .def_readwrite("initial_state", &Contact::initial_state,
                     "contact state at the start of a run: Stick (default), SlipPositive or SlipNegative")
      .def("law", [](const Contact& c) { return c.law(); }, "The friction law.")
      .def("normal_force", &Contact::normal_force, py::arg("t"), "N(t) [N].")
      .def("start_state", &Contact::start_state, "The contact state at the start of a run.");
  py::class_<COptions>(m, "ContactSystemOptions", "Options of a ContactSystem.")
      .def(py::init<>(), "The default options: the energy audit on.")
      .def_readwrite("energy_audit", &COptions::energy_audit,
                     "carry the audit integrals W_ext, D_visc, D_fric as three extra states (default True)")
      .def_readwrite("velocity_tolerance", &COptions::velocity_tolerance,
                     "|v| [m/s] at or below which v counts as 0 where a contact's state is decided");

  auto cls = bind_contact_system<PyContactSystem>(
      m, "ContactSystem",
      "A frame's retained modes + friction contacts at structure points (PointContact) + point loads: q'' = r + "
      "sum_i w_i f_i with contact rows w_i (s_i = w_i . q) (docs/contacts.md). State [q, q', W_ext, D_visc, "
      "D_fric] (the last three with the energy audit). Calls that run or evaluate one system from several threads "
      "run one after the other (docs/python.md).");
  cls.def(py::init<const FrameModel<double>&, const ModalBasis<double>&, std::vector<Contact>,
                   std::vector<PointLoad<double>>, COptions>(),
          py::arg("frame"), py::arg("basis"), py::arg("contacts"), py::arg("loads") = std::vector<PointLoad<double>>{},
          py::arg("options") = COptions{},
          "Assembles each contact's row from `frame` and `basis` (a basis of that frame). ValueError naming the "
          "contact and the parameter: a side off its member (coordinate), a non-unit direction, a non-positive "
          "normal.value, a contact that cannot slip (zero row), ...");
}

/// Rigid bodies, body contacts, the wedge damper and BodyContactSystem (docs/contacts.md, "Rigid
/// bodies"; docs/python.md, "Rigid bodies and the wedge damper").
void bind_bodies(py::module_& m) {
  using Direction = PlaneDirection<double>;
  using Vec2 = Eigen::Vector2d;
  using BPoint = BodyPoint<double>;
  using Spring = BodySpring<double>;
  using BLoad = BodyLoad<double>;
  using Body = RigidBody<double>;
  using BContact = BodyContact<double>;
  using Face = WedgeFace<double>;
  using Wedge = WedgeDamper<double>;
  using COptions = ContactSystemOptions<double>;
  py::class_<BPoint>(m, "BodyPoint",
                     "A point of a rigid body: the body's index in the scene and r [m] in body coordinates (from "
                     "the centre of mass, in the reference orientation).")
      .def(py::init([](Index body, const Vec2& point) { return BPoint{body, point}; }), py::arg("body"),
           py::arg("point"), "The point r = point [m] (2 entries) of body `body`.")
      .def_readwrite("body", &BPoint::body, "index of the body in the scene")
      .def_readwrite("point", &BPoint::point, "r [m] in body coordinates");
  py::class_<Spring>(m, "BodySpring",
                     "A linear spring k and dashpot c to ground along the global unit direction d, at body point r: "
                     "force -(k delta + c delta') d with delta = d . ((x, y) + (R(theta) - I) r).")
      .def(py::init([](const Vec2& point, const Direction& direction, double stiffness, double damping) {
             return Spring{point, direction, stiffness, damping};
           }),
           py::arg("point"), py::arg("direction"), py::arg("stiffness"), py::arg("damping") = 0.0,
           "A spring of stiffness [N/m] >= 0 and dashpot damping [N s/m] >= 0 at r = point [m] along `direction`.")
      .def_readwrite("point", &Spring::point, "r [m] in body coordinates")
      .def_readwrite("direction", &Spring::direction, "d (global unit vector)")
      .def_readwrite("stiffness", &Spring::stiffness, "k [N/m] >= 0")
      .def_readwrite("damping", &Spring::damping, "c [N s/m] >= 0");
  py::class_<BLoad>(m, "BodyLoad", "A force F(t) d [N] at a body's centre of mass along the global unit direction d.")
      .def(py::init([](const Direction& direction, double value, const py::object& time_function) {
             BLoad l;
             l.direction = direction;
             l.value = value;
             l.time_function = python_time_function(time_function, "BodyLoad", "F");
             return l;
           }),
           py::arg("direction"), py::arg("value") = 0.0, py::arg("time_function") = py::none(),
           "The constant force `value` [N] along `direction`, or time_function(t) [N] when given.")
      .def_readwrite("direction", &BLoad::direction, "d (global unit vector)")
      .def_readwrite("value", &BLoad::value, "constant F [N]")
      .def_property(
          "time_function", [](const BLoad& l) { return l.time_function; },
          [](BLoad& l, const py::object& f) { l.time_function = python_time_function(f, "BodyLoad", "F"); },
          "optional F(t) [N] (a Python callable, called with the GIL: slower); None: the constant value")
      .def("__call__", &BLoad::operator(), py::arg("t"), "F(t) [N].")
      .def_static("centrifugal", &BLoad::centrifugal, py::arg("mass"), py::arg("radius"), py::arg("Omega"),
                  py::arg("radial"),
                  "The centrifugal preload m r Omega^2 [N] of a body of mass [kg] at radius [m] on a rotor turning "
                  "at Omega [rad/s], along the unit direction `radial`.");
  py::class_<Body>(m, "RigidBody",
                   "A planar rigid body: mass m, rotary inertia J about its centre of mass, springs and dashpots to "
                   "ground, loads at the centre of mass; coordinates (x, y, theta) from its reference position.")
      .def(py::init([](double mass, double inertia, std::vector<Spring> springs, std::vector<BLoad> loads) {
             Body b;
             b.mass = mass;
             b.inertia = inertia;
             b.springs = std::move(springs);
             b.loads = std::move(loads);
             return b;
           }),
           py::arg("mass") = 1.0, py::arg("inertia") = 1.0, py::arg("springs") = std::vector<Spring>{},
           py::arg("loads") = std::vector<BLoad>{},
           "A body of mass [kg] > 0 and inertia [kg m^2] > 0 (checked by the system: ValueError naming them).")
      .def_readwrite("mass", &Body::mass, "m [kg] > 0")
      .def_readwrite("inertia", &Body::inertia, "J about the centre of mass [kg m^2] > 0")
      .def_readwrite("springs", &Body::springs, "springs and dashpots to ground (a copy: assign a new list)")
      .def_readwrite("loads", &Body::loads, "loads at the centre of mass (a copy: assign a new list)");
  py::class_<BContact>(m, "BodyContact",
                       "A friction contact of a body point (side a) on a structure point or ground (side b) with a "
                       "unilateral normal: n from b towards a, tangent t = (n_y, -n_x); the normal force is solved, "
                       "the contact lifts off at N = 0 and lands at gap 0 with restitution e (docs/contacts.md).")
      .def_static(
          "on_ground",
          [](const BPoint& point, const Direction& normal, const py::object& law, double restitution) {
            return BContact::on_ground(point, normal, to_law(law, "BodyContact.on_ground"), restitution);
          },
          py::arg("point"), py::arg("normal"), py::arg("law"), py::arg("restitution") = 0.0,
          "`point` on ground whose surface has the unit normal `normal`, with `law` (CoulombLaw, StribeckLaw or "
          "RegularisedLaw) and restitution e in [0, 1].")
      .def_static(
          "on_structure",
          [](const BPoint& point, const StructurePoint<double>& surface, const Direction& normal,
             const py::object& law, double restitution) {
            return BContact::on_structure(point, surface, normal, to_law(law, "BodyContact.on_structure"),
                                          restitution);
          },
          py::arg("point"), py::arg("surface"), py::arg("normal"), py::arg("law"), py::arg("restitution") = 0.0,
          "`point` on the structure point `surface` whose surface has the unit normal `normal`, with `law` and "
          "restitution e in [0, 1].")
      .def_readwrite("a", &BContact::a, "side a: the BodyPoint")
      .def_readwrite("b", &BContact::b, "side b: a StructurePoint, or None for ground")
      .def_readwrite("normal", &BContact::normal, "n (global unit vector, from b towards a)")
      .def_property(
          "friction", [](const BContact& c) { return c.friction; },
          [](BContact& c, const py::object& law) { c.friction = to_law(law, "BodyContact"); },
          "the friction law (CoulombLaw, StribeckLaw or RegularisedLaw)")
      .def_readwrite("restitution", &BContact::restitution, "e in [0, 1] of a landing (0: perfectly plastic)")
      .def_readwrite("initial_gap", &BContact::initial_gap, "g0 [m] >= 0: the gap with every coordinate zero")
      .def_readwrite("contact_point", &BContact::contact_point,
                     "ContactPoint of side b: Fixed (default) at b, or Moving along b's member with the sliding "
                     "(X' = v; needs b on the structure)")
      .def_readwrite("initial_state", &BContact::initial_state,
                     "state at the start of a run: Stick (default), SlipPositive, SlipNegative or Separated")
      .def("law", [](const BContact& c) { return c.law(); }, "The friction law.")
      .def("start_state", &BContact::start_state, "The contact state at the start of a run.")
      .def("tangent_direction", &BContact::tangent_direction, "t = (n_y, -n_x).");
  py::class_<Face>(m, "WedgeFace", "One flat face of a wedge damper (docs/contacts.md, \"The wedge damper\").")
      .def(py::init([](std::vector<StructurePoint<double>> platform, const Vec2& point, double angle,
                       double half_width) { return Face{std::move(platform), point, angle, half_width}; }),
           py::arg("platform"), py::arg("point"), py::arg("angle"), py::arg("half_width") = 0.0,
           "A face touching the platform points `platform` (none: ground; one; or two, under p -+ w t) at p = point "
           "[m] (body coordinates), at `angle` [rad] in (-pi/2, pi/2) from the plane normal to the load, with "
           "half_width w [m] >= 0 (0: one contact point, > 0: two at p -+ w t).")
      .def_readwrite("platform", &Face::platform, "the platform's StructurePoints (empty: ground)")
      .def_readwrite("point", &Face::point, "p on the face, body coordinates [m]")
      .def_readwrite("angle", &Face::angle, "face angle [rad] from the plane normal to the load")
      .def_readwrite("half_width", &Face::half_width, "w [m] >= 0");
  py::class_<Wedge>(m, "WedgeDamper", "The body and the contacts of a wedge damper, to pass to BodyContactSystem.")
      .def(py::init<>(), "An empty damper (wedge_damper() builds one).")
      .def_readwrite("body", &Wedge::body, "the damper (RigidBody, its centrifugal load included)")
      .def_readwrite("contacts", &Wedge::contacts, "BodyContacts: the left face's first, then the right face's");
  m.def(
      "wedge_damper",
      [](Index body, double mass, double inertia, double preload, const Face& left, const Face& right,
         const py::object& law, const Direction& radial, double restitution) {
        return wedge_damper<double>(body, mass, inertia, preload, left, right, to_law(law, "wedge_damper"), radial,
                                    restitution);
      },
      py::arg("body"), py::arg("mass"), py::arg("inertia"), py::arg("preload"), py::arg("left"), py::arg("right"),
      py::arg("law"), py::arg("radial") = Direction::global_y(), py::arg("restitution") = 0.0,
      "A wedge damper: body index `body` of the scene, mass [kg], inertia [kg m^2], the load `preload` [N] (m r "
      "Omega^2) along the unit direction `radial`; the left face's outward normal is `radial` turned "
      "counter-clockwise by its angle, the right one's clockwise; law and restitution on every contact. "
      "ValueError naming the parameter (left.angle, right.half_width, preload, radial, ...).");

  auto cls = bind_contact_system<PyBodyContactSystem>(
      m, "BodyContactSystem",
      "C++ ContactSystem<double, BodyContact<double>>: a frame's retained modes + planar rigid bodies + friction "
      "contacts of body points (BodyContact, unilateral normals) + point loads: M z'' = r + sum_i (g_i f_i + h_i "
      "N_i), z = (q, each body's x [m], y [m], theta [rad]) (docs/contacts.md). State [z, z', W_ext, D_visc, D_fric] "
      "(the last three with the energy audit). Calls on one system from several threads run one after the other.");
  cls.def(py::init<const FrameModel<double>&, const ModalBasis<double>&, std::vector<Body>, std::vector<BContact>,
                   std::vector<PointLoad<double>>, COptions>(),
          py::arg("frame"), py::arg("basis"), py::arg("bodies"), py::arg("contacts"),
          py::arg("loads") = std::vector<PointLoad<double>>{}, py::arg("options") = COptions{},
          "Assembles the contacts' rows from `frame` and `basis` (a basis of that frame). ValueError naming the body "
          "or contact and the parameter: a non-positive mass or inertia, a non-unit normal, a restitution outside "
          "[0, 1], a contact whose a.body names no body, ...");

  using DamperBody = PointDamperBody<double>;
  py::class_<DamperBody>(m, "PointDamperBody",
                         "The paper's damper as a rigid body and a BodyContact (point_damper_body), to pass to "
                         "BodyContactSystem or MixedContactSystem.")
      .def(py::init<>(), "An empty damper body (point_damper_body() builds one).")
      .def_readwrite("body", &DamperBody::body,
                     "the RigidBody: mass s m, spring s k to ground along the member's u, the load N0 towards the "
                     "member")
      .def_readwrite("contact", &DamperBody::contact,
                     "the BodyContact of its centre of mass on the member point (unilateral normal; side b Moving "
                     "or Fixed as the damper's contact_point)");
  m.def(
      "point_damper_body",
      [](const FrameModel<double>& frame, Index body, const System::Damper& damper) {
        return point_damper_body(frame, body, damper);
      },
      py::arg("frame"), py::arg("body"), py::arg("damper"),
      "The PointDamper `damper` on `frame` as body number `body` of a scene (PointDamperBody): the body on its "
      "spring pressed by its preload, and a contact whose side b moves along the member with the sliding (X' = V) "
      "unless damper.contact_point is Fixed; the normal is unilateral (the contact opens at N = 0 and lands with "
      "damper.restitution, or the run stops there under Separation.Stop) (docs/contacts.md). ValueError naming "
      "the parameter: a member not in the frame, a Wall end, the damper's own checks.");

  using Kind = AnyContact<double>::Kind;
  auto mixed = bind_contact_system<PyMixedContactSystem>(
      m, "MixedContactSystem",
      "C++ ContactSystem<double, AnyContact<double>>: one scene with contacts of both kinds, PointContact (held "
      "normal) and BodyContact (unilateral normal), with the rigid bodies and point loads: M z'' = r + sum_i (g_i "
      "f_i + h_i N_i) as BodyContactSystem, a PointContact's N_i held (docs/contacts.md, \"Mixed scenes\"). State "
      "[z, z', W_ext, D_visc, D_fric]. Calls on one system from several threads run one after the other.");
  mixed.def(py::init([](const FrameModel<double>& frame, const ModalBasis<double>& basis, std::vector<Body> bodies,
                        const std::vector<Kind>& contacts, std::vector<PointLoad<double>> loads, COptions options) {
              std::vector<AnyContact<double>> all;
              all.reserve(contacts.size());
              for (const Kind& c : contacts)
                all.push_back(std::visit([](const auto& k) { return AnyContact<double>(k); }, c));
              return std::make_unique<PyMixedContactSystem>(frame, basis, std::move(bodies), std::move(all),
                                                            std::move(loads), options);
            }),
            py::arg("frame"), py::arg("basis"), py::arg("bodies"), py::arg("contacts"),
            py::arg("loads") = std::vector<PointLoad<double>>{}, py::arg("options") = COptions{},
            "Assembles the contacts (a list whose items are PointContact or BodyContact, in the order the system "
            "numbers them) from `frame` and `basis` (a basis of that frame). ValueError naming the body or contact "
            "and the parameter, as ContactSystem and BodyContactSystem.");
}

/// simulate() for one system type (Py: PySystem, PyContactSystem or PyBodyContactSystem).
template <class Py>
void def_simulate(py::module_& m, const char* doc) {
  m.def("simulate", &run_simulation<Py>, py::arg("system"), py::arg("t_end"), py::arg("options") = RunOptions<double>{},
        py::arg("t0") = 0.0, py::arg("x0") = py::none(), py::arg("mode") = py::none(),
        py::arg("probes") = std::vector<Probe>{}, py::arg("record_states") = true,
        py::arg("evaluate_from") = std::numeric_limits<double>::infinity(), py::arg("statistics") = py::none(),
        py::arg("consistent") = true, doc);
}

void bind_simulate(py::module_& m) {
  py::enum_<Integrator>(m, "Integrator", "The integrator of a run (RunOptions names them by string).")
      .value("RungeKutta4", Integrator::RungeKutta4, "\"rk4\": fixed step RunOptions.fixed_step (the paper's method)")
      .value("DormandPrince54", Integrator::DormandPrince54, "\"dopri5\": adaptive explicit 5(4) with dense output")
      .value("Rosenbrock23", Integrator::Rosenbrock23, "\"rosenbrock23\": adaptive linearly implicit, stiffly stable")
      .value("Exponential", Integrator::Exponential,
             "\"exponential\": exact exponential where the mode is linear, Lawson Dormand-Prince elsewhere")
      .value("Auto", Integrator::Auto,
             "\"auto\": chosen per run from the system (choose_integrator; docs/howto/pick_an_integrator.md)");
  py::enum_<EventLocation>(m, "EventLocation", "How a guard crossing is located in time.")
      .value("DenseRootFinding", EventLocation::DenseRootFinding,
             "Illinois root finding on the method's dense output (default)")
      .value("Bisection", EventLocation::Bisection, "halve the step, re-integrating from the step start (the paper)");
  py::enum_<EventState>(m, "EventState", "Which state an event hands to the transition (docs/ode.md).")
      .value("DenseOutput", EventState::DenseOutput, "the dense output at the located time")
      .value("Reintegrate", EventState::Reintegrate,
             "one step of the method from the step start to the event, its root refined on it")
      .value("Checked", EventState::Checked,
             "the dense output where one re-taken step says its error is within the tolerances (default)");
  py::enum_<Status>(m, "Status", "How a run ended (Run.status).")
      .value("Success", Status::Success, "reached t_end")
      .value("StepSizeUnderflow", Status::StepSizeUnderflow, "the step fell below min_step")
      .value("MaxSteps", Status::MaxSteps, "the step budget (max_steps) ran out")
      .value("NonFiniteState", Status::NonFiniteState, "the right-hand side or the state became NaN/Inf")
      .value("ZenoGuard", Status::ZenoGuard, "more events per unit time than allowed (chattering / Zeno)")
      .value("StoppedByObserver", Status::StoppedByObserver, "the run was stopped (e.g. Ctrl-C)")
      .value("StoppedBySystem", Status::StoppedBySystem, "the system asked to stop (reason in the message)");
  m.def("status_name", [](Status s) { return std::string(to_string(s)); }, py::arg("status"),
        "The name of a Status, as C++'s to_string.");
  using Options = RunOptions<double>;
  using Stepper = StepperOptions<double>;
  py::class_<Options> options(m, "RunOptions",
                              "Integrator (auto | rk4 | dopri5 | rosenbrock23 | exponential) and stepper options: the "
                              "fields of C++'s RunOptions and of its StepperOptions `stepper`, flattened "
                              "(docs/ode.md).");
  options.def(py::init(&make_run_options), py::arg("integrator") = "auto",
              "RunOptions(integrator=\"auto\", **options): keywords are the stepper options below and "
              "check_stability_limit (TypeError for a wrong type, ValueError for an unknown name).");
  options.def_property(
      "integrator", [](const Options& o) { return std::string(to_string(o.integrator)); },
      [](Options& o, const std::string& name) { o.integrator = parse_integrator(name); },
      "the integrator's name: auto (default, as C++), rk4, dopri5, rosenbrock23 or exponential");
  const auto stepper_field = [&options](const char* name, auto field, const char* doc) {
    using T = std::decay_t<decltype(std::declval<Stepper&>().*field)>;
    options.def_property(
        name, [field](const Options& o) { return o.stepper.*field; },
        [field](Options& o, T v) { o.stepper.*field = v; }, doc);
  };
  stepper_field("fixed_step", &Stepper::fixed_step, "RK4 step [s] (default 1e-4)");
  stepper_field("initial_step", &Stepper::initial_step, "first trial step of adaptive methods [s]; 0 = automatic");
  stepper_field("rtol", &Stepper::rtol, "relative tolerance of adaptive methods (default 1e-6)");
  stepper_field("atol", &Stepper::atol, "absolute tolerance of adaptive methods (default 1e-9)");
  stepper_field("safety", &Stepper::safety, "step-size safety factor in (0, 1] (default 0.9)");
  stepper_field("min_step", &Stepper::min_step, "smallest step, relative to max(1, |t|) (default 1e-14)");
  stepper_field("max_step", &Stepper::max_step, "largest step of adaptive methods [s] (default inf)");
  stepper_field("max_steps", &Stepper::max_steps, "budget of step attempts, accepted + rejected (default 1e8)");
  stepper_field("event_location", &Stepper::event_location, "EventLocation (default DenseRootFinding)");
  stepper_field("event_state", &Stepper::event_state, "EventState at a root-found event (default Checked)");
  stepper_field("event_time_tolerance", &Stepper::event_time_tolerance,
                "width of the final bracket of an event time [s] (default 1e-12)");
  stepper_field("guard_zero_tolerance", &Stepper::guard_zero_tolerance,
                "|g| below this at a mode start counts as zero (default 1e-12)");
  stepper_field("guard_samples", &Stepper::guard_samples,
                "guard values checked at this many interior points of every step (default 0; docs/ode.md)");
  stepper_field("zeno_max_events", &Stepper::zeno_max_events,
                "more events than this inside zeno_window stop the run with ZenoGuard (default 1000)");
  stepper_field("zeno_window", &Stepper::zeno_window, "length of the window of the event-rate cap [s] (default 1e-6)");
  stepper_field("zeno_max_immediate_events", &Stepper::zeno_max_immediate_events,
                "consecutive immediate events allowed (default 100)");
  stepper_field("output_interval", &Stepper::output_interval,
                "sample interval [s] of simulate()'s histories (default 0: no samples)");
  stepper_field("max_samples", &Stepper::max_samples, "largest number of samples a run may ask for (default 1e8)");
  options.def_readwrite("check_stability_limit", &Options::check_stability_limit,
                        "with rk4: refuse (ValueError) a fixed step above RK4's stability limit (default True)");

  py::class_<Probe>(m, "Probe",
                    "A point whose displacement simulate() records at every sample: point_shape(member, coordinate, "
                    "direction) . q [m] (Moment: the rotation [rad]).")
      .def(py::init([](MemberId member, double coordinate, LoadDirection direction) {
             return Probe{member, coordinate, direction};
           }),
           py::arg("member"), py::arg("coordinate"), py::arg("direction") = LoadDirection::GlobalX,
           "The point `coordinate` [m] along `member`, its displacement along `direction` (default GlobalX).")
      .def_readonly("member", &Probe::member, "the member")
      .def_readonly("coordinate", &Probe::coordinate, "position along the member [m]")
      .def_readonly("direction", &Probe::direction, "the LoadDirection of the recorded displacement");
  using Window = StatisticsWindow<double>;
  py::class_<Window>(m, "StatisticsWindow", "The window [t_start, t_end] of simulate()'s per-damper statistics.")
      .def(py::init([](double t_start, double t_end, double period) { return Window{t_start, t_end, period}; }),
           py::arg("t_start"), py::arg("t_end"), py::arg("period"),
           "The window [t_start, t_end] [s] (t_end > t_start) and the excitation period [s] > 0 the switches are "
           "counted per.")
      .def_readwrite("t_start", &Window::t_start, "start of the window [s]")
      .def_readwrite("t_end", &Window::t_end, "end of the window [s]")
      .def_readwrite("period", &Window::period, "excitation period the switches are counted per [s]");
  py::enum_<DamperRegime>(m, "DamperRegime", "A damper's regime over a window (docs/blade_damper.md).")
      .value("Stick", DamperRegime::Stick, "stuck at least 99.9 % of the time")
      .value("StickSlip", DamperRegime::StickSlip, "in between")
      .value("GrossSlip", DamperRegime::GrossSlip, "stuck less than 5 % of the time")
      .value("NotReached", DamperRegime::NotReached, "the run did not reach the window")
      .value("IntermittentContact", DamperRegime::IntermittentContact,
             "separated from the member at least 1 % of the time");
  m.def("regime_name", [](DamperRegime r) { return std::string(to_string(r)); }, py::arg("regime"),
        "The name of a DamperRegime (\"stick\", \"stick-slip\", ...), as C++'s to_string.");
  using Stats = DamperWindowStatistics<double>;
  py::class_<Stats>(m, "DamperWindowStatistics", "One damper's statistics over the observed part of the window.")
      .def_readonly("observed_time", &Stats::observed_time, "time of the window the run covered [s]")
      .def_readonly("stick_time", &Stats::stick_time, "time stuck within it [s]")
      .def_readonly("stick_fraction", &Stats::stick_fraction, "stick_time / observed_time (NaN when nothing observed)")
      .def_readonly("switches", &Stats::switches, "contact-state changes in the window")
      .def_readonly("switches_per_period", &Stats::switches_per_period, "switches * period / observed_time")
      .def_readonly("separated_time", &Stats::separated_time, "time separated from the member within the window [s]")
      .def_readonly("separated_fraction", &Stats::separated_fraction, "separated_time / observed_time")
      .def_readonly("bounces", &Stats::bounces, "impacts after which the damper flew again")
      .def_readonly("landings", &Stats::landings, "impacts after which it stayed in contact")
      .def_readonly("wall_impacts", &Stats::wall_impacts, "impacts on a member-end wall")
      .def_readonly("wall_rests", &Stats::wall_rests, "times the damper came to rest at a wall")
      .def_readonly("wall_time", &Stats::wall_time, "time resting at a wall within the window [s]")
      .def_readonly("regime", &Stats::regime, "the DamperRegime of these fractions");
  py::class_<StepperStats>(m, "StepperStats", "The stepper's counters of a run.")
      .def_readonly("accepted_steps", &StepperStats::accepted_steps, "accepted steps")
      .def_readonly("rejected_steps", &StepperStats::rejected_steps, "rejected step attempts")
      .def_readonly("rhs_evaluations", &StepperStats::rhs_evaluations, "right-hand-side evaluations")
      .def_readonly("guard_evaluations", &StepperStats::guard_evaluations, "guard-vector evaluations")
      .def_readonly("jacobian_evaluations", &StepperStats::jacobian_evaluations, "Jacobians formed (rosenbrock23)")
      .def_readonly("factorisations", &StepperStats::factorisations, "LU factorisations (rosenbrock23)")
      .def_readonly("events", &StepperStats::events, "located events (transitions)")
      .def_readonly("guard_sample_cuts", &StepperStats::guard_sample_cuts,
                    "steps cut back to an interior guard sample (guard_samples)");
  py::class_<Transition>(m, "Transition", "One transition of the run: every damper's state before and after.")
      .def_readonly("t", &Transition::t, "time of the transition [s]")
      .def_readonly("from_mode", &Transition::from, "every damper's ContactState before (C++: from)")
      .def_readonly("to_mode", &Transition::to, "every damper's ContactState after (C++: to)");

  py::class_<Run>(m, "Run", "The result and histories of simulate().")
      .def_readonly("status", &Run::status, "how the run ended (Status)")
      .def_property_readonly("ok", [](const Run& r) { return r.status == Status::Success; }, "status == Success")
      .def_readonly("message", &Run::message, "why the run ended early (empty on success)")
      .def_readonly("t", &Run::t, "time reached [s]")
      .def_readonly("x", &Run::x, "state at t (numpy)")
      .def_readonly("mode", &Run::mode, "contact states at t")
      .def_readonly("stats", &Run::stats, "the stepper's counters (StepperStats)")
      .def_readonly("E0", &Run::E0, "mechanical energy at the (consistent) start [J]")
      .def_property_readonly(
          "energy",
          [](const Run& r) -> py::object {
            if (r.energy) return py::cast(*r.energy);
            if (r.contact_energy) return std::visit([](const auto& b) { return py::cast(b); }, *r.contact_energy);
            return py::none();
          },
          "the energy audit at t: an EnergyBalance (a ContactSystem's: ContactSystem.EnergyBalance), None without "
          "the audit")
      .def_readonly("transitions", &Run::transitions, "the run's transitions (Transition)")
      .def_readonly("damper_statistics", &Run::statistics,
                    "per damper: DamperWindowStatistics over the `statistics` window (empty without one)")
      .def_property_readonly("sample_t", [](const Run& r) { return py::array_t<double>(py::cast(r.sample_t)); },
                             "sample times [s] (numpy, k)")
      .def_property_readonly("states",
                             [](const Run& r) {
                               const Index n = r.samples.empty() ? r.x.size() : r.samples.front().size();
                               return stack<double>(r.samples, n, [](const State& s, Index c) { return s[c]; });
                             },
                             "the state at each sample (numpy, k x state_size(); empty without record_states)")
      .def_property_readonly("sample_modes",
                             [](const Run& r) {
                               return stack<std::int8_t>(r.sample_modes, static_cast<Index>(r.mode.size()),
                                                         [](const std::vector<ContactState>& s, Index c) {
                                                           return static_cast<std::int8_t>(s[static_cast<std::size_t>(c)]);
                                                         });
                             },
                             "the contact states at each sample as ints of ContactState (numpy, k x D)")
      .def_property_readonly("probes",
                             [](const Run& r) {
                               const Index n = r.probe_values.empty() ? 0 : static_cast<Index>(r.probe_values[0].size());
                               return stack<double>(r.probe_values, n, [](const std::vector<double>& s, Index c) {
                                 return s[static_cast<std::size_t>(c)];
                               });
                             },
                             "each probe's displacement at each sample [m] (numpy, k x number of probes)")
      .def_property_readonly("force_t", [](const Run& r) { return py::array_t<double>(py::cast(r.force_t)); },
                             "the sample times from evaluate_from on [s] (numpy)")
      .def_property_readonly("forces", [](const Run& r) {
        py::dict d;
        const Index D = static_cast<Index>(r.mode.size());
        const auto get = [](const System::Vector& v, Index c) { return v[c]; };
        d["N"] = stack<double>(r.N, D, get), d["f"] = stack<double>(r.f, D, get), d["V"] = stack<double>(r.V, D, get);
        if (r.y.size() == r.N.size()) {  // a FrictionDampedSystem's run
          d["y"] = stack<double>(r.y, D, get), d["X"] = stack<double>(r.X, D, get);
        }
        return d;
      }, "per sample from evaluate_from on, one column per damper or contact: N [N], f [N], V [m/s] (a "
         "ContactSystem's sliding velocity v) and, for a FrictionDampedSystem, y [m] and X [m]");

  def_simulate<PySystem>(
      m,
      "Runs the system from (mode, t0, x0) (default: its initial state) to t_end; samples every "
      "options.output_interval (states, modes, probes; forces N, f, V, y, X from evaluate_from on). The GIL is "
      "released and calls on one system run one after the other; Ctrl-C stops the call (KeyboardInterrupt).");
  def_simulate<PyContactSystem>(
      m,
      "A ContactSystem's run, as above: from (mode, t0, x0) (default: rest, each contact's initial_state) to "
      "t_end [s]; states [q, q', audit integrals], modes, forces N, f, v (as V) of the contacts from "
      "evaluate_from on; energy: a ContactSystem.EnergyBalance. probes and statistics are not available "
      "(ValueError): a point's displacement is its modal row . q.");
  def_simulate<PyBodyContactSystem>(
      m,
      "A BodyContactSystem's run, as above: states [z, z', audit integrals] (z = q, then each body's x, y, "
      "theta), forces N, f, v (as V) of the contacts; energy: a BodyContactSystem.EnergyBalance.");
  def_simulate<PyMixedContactSystem>(
      m,
      "A MixedContactSystem's run, as above: states [z, z', audit integrals], forces N, f, v (as V) of the contacts "
      "(a PointContact's N its held normal); energy: a MixedContactSystem.EnergyBalance.");
}

void bind_trade_study(py::module_& m) {
  using Row = TradeRow<double>;
  py::class_<Row>(m, "TradeRow", "One variant's cost and error against the reference.")
      .def_readonly("name", &Row::name, "the variant's name")
      .def_readonly("started", &Row::started, "False: building or starting the run raised (see message)")
      .def_readonly("status", &Row::status, "how the run ended (Status; meaningful when started)")
      .def_readonly("message", &Row::message, "the run's message, or the exception's")
      .def_readonly("t_reached", &Row::t_reached, "time the run reached [s]")
      .def_readonly("cpu_seconds", &Row::cpu_seconds, "median CPU time of the run over the repeats [s]")
      .def_readonly("rhs_evaluations", &Row::rhs_evaluations, "right-hand-side evaluations of the last repeat")
      .def_readonly("events", &Row::events, "events (transitions) of the last repeat")
      .def_readonly("output_error_max", &Row::output_error_max,
                    "max_k |y_k - y_ref,k| / max_k |y_ref,k| over the common sample grid")
      .def_readonly("output_error_rms", &Row::output_error_rms, "sqrt(mean_k (y_k - y_ref,k)^2) / max_k |y_ref,k|")
      .def_readonly("switch_time_error", &Row::switch_time_error, "largest |t - t_ref| over the matched switches [s]")
      .def_readonly("missed_switches", &Row::missed_switches, "reference switches without a partner in the run")
      .def_readonly("extra_switches", &Row::extra_switches, "switches of the run without a partner in the reference")
      .def_readonly("energy_residual", &Row::energy_residual,
                    "the energy audit's relative closing error at the end (NaN without the audit)")
      .def_property_readonly("ok", &Row::ok, "started and status == Success");
  using Result = TradeStudyResult<double>;
  py::class_<Result>(m, "TradeStudyResult", "What trade_study() returns: the reference, its validation, the rows.")
      .def_readonly("reference", &Result::reference, "the reference run's TradeRow (errors 0 by definition)")
      .def_readonly("validation", &Result::validation,
                    "the tightened rerun of the reference compared with it: the bound of the reference's own error")
      .def_readonly("validation_method", &Result::validation_method, "how the reference was validated, in words")
      .def_readonly("rows", &Result::rows, "one TradeRow per variant, in order (empty if the reference failed)");
  using Variant = TradeVariant<System>;
  py::class_<Variant>(m, "TradeVariant", "A name, a setup() returning a FrictionDampedSystem, and RunOptions.")
      .def(py::init([](std::string name, py::object setup, const RunOptions<double>& run) {
             if (!PyCallable_Check(setup.ptr()))
               throw std::invalid_argument("TradeVariant: setup must be a callable returning a FrictionDampedSystem");
             Variant v;
             v.name = std::move(name);
             v.run = run;
             v.setup = [setup, name = v.name]() {
               System sys = copy_of(
                   cast_as<const PySystem&>(setup(), "TradeVariant " + name + ": setup() must return a FrictionDampedSystem"));
               State x = sys.initial_state();
               Mode mode = sys.requested_mode();
               if (!sys.make_consistent(mode, 0.0, x))
                 throw std::runtime_error("inconsistent or lifted-off initial contact state at t = 0");
               return TradeSetup<System>{std::move(sys), std::move(mode), std::move(x)};
             };
             return v;
           }),
           py::arg("name"), py::arg("setup"), py::arg("run") = RunOptions<double>{},
           "A variant `name` whose setup() returns a FrictionDampedSystem (started from rest made consistent at "
           "t = 0), run with `run` (default RunOptions()).")
      .def_readonly("name", &Variant::name, "the variant's name");
  m.def(
      "trade_study",
      [](const Variant& reference, const std::vector<Variant>& variants, double t_end, const py::object& output,
         double output_interval, int repeats, double validation_factor) {
        TradeStudyOptions<System> o;
        o.t_end = t_end;
        o.output_interval = output_interval;
        o.repeats = repeats;
        o.validation_factor = validation_factor;
        o.output = trade_output(output);
        o.energy_residual = [](System& sys, const SimulationResult<System>& r) {
          // Runs start from rest made consistent: E0 = 0 for a scene with no initial deflection.
          if (!sys.options().energy_audit) return std::numeric_limits<double>::quiet_NaN();
          return sys.energy_balance(r.mode, r.t, r.x, 0.0).relative_residual();
        };
        return trade_study(reference, variants, o);
      },
      py::arg("reference"), py::arg("variants"), py::arg("t_end"), py::arg("output"), py::arg("output_interval") = 1e-3,
      py::arg("repeats") = 3, py::arg("validation_factor") = 100.0,
      "Speed/accuracy of each variant against a validated tight reference (docs/howto/pick_an_integrator.md); each variant's "
      "setup() is called per repeat. output: a Probe or f(t, x).");
  m.def(
      "trade_csv",
      [](const std::vector<Row>& rows) {
        std::ostringstream os;
        write_trade_csv(os, rows);
        return os.str();
      },
      py::arg("rows"), "The rows as CSV text (write_trade_csv).");
}


/// The most parts continue_orbits takes: 4 x the hardware threads (each part is a std::thread and
/// a copy of the system; more parts than cores only add copies, threads and joins).
int max_split_parts() { return 4 * static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }

/// The most memory poincare_sections' record may take: 1 GiB.
constexpr double kMaxSectionBytes = 1024.0 * 1024.0 * 1024.0;

/// ValueError naming record_periods when the sections (record_periods states of state_size
/// doubles, kept twice: the C++ record and the returned array) would take more than
/// kMaxSectionBytes.
void check_section_memory(const std::string& where, long record_periods, Index state_size) {
  const double per_section = 2.0 * 8.0 * static_cast<double>(state_size);
  const long limit = static_cast<long>(kMaxSectionBytes / per_section);
  if (record_periods > limit)
    detail::throw_invalid(where,
                          "record_periods must be <= " + std::to_string(limit) +
                              " (the recorded sections take record_periods x state_size x 16 bytes: at most 1 GiB)",
                          record_periods);
}

/// What poincare_sections returns (PoincareSections, states as rows of a matrix).
struct PyPoincare {
  PoincareStatus status = PoincareStatus::NotPeriodic;
  std::string message;
  int period = 0;
  Eigen::VectorXd recurrence;
  double t0 = 0, period_time = 0;
  Eigen::MatrixXd states;
  std::vector<std::vector<ContactState>> modes;
};

/// find_periodic_orbit for one system type (Py: PySystem, PyContactSystem or PyBodyContactSystem).
template <class Py>
void def_find_periodic_orbit(py::module_& m, const char* doc) {
  using Sys = typename Py::Wrapped;
  m.def(
      "find_periodic_orbit",
      [](Py& system, double period, double t0, std::optional<State> x0, std::optional<std::vector<ContactState>> mode,
         std::optional<std::vector<Index>> periodic, const std::string& monodromy, double tolerance, int max_iterations,
         double rtol, double atol, long max_steps, std::optional<Eigen::MatrixXd> outputs, int output_harmonics,
         const py::object& progress, OrbitIntegrator integrator, int samples_per_period,
         std::optional<std::vector<Index>> amplitude_components, double multiplier_tolerance, double fd_step,
         bool control_sensitivities, double max_step, long guard_samples) {
        return with_system(system, [&](SignalCheck& signals) {
          ShootingOptions<double> opt = shooting_options(system, periodic, monodromy, tolerance, max_iterations, rtol,
                                                         atol, max_steps, integrator, "find_periodic_orbit");
          set_outputs_and_progress(opt, outputs, output_harmonics, progress, "find_periodic_orbit");
          set_orbit_details(opt, samples_per_period, amplitude_components, multiplier_tolerance, fd_step,
                            control_sensitivities, max_step, guard_samples);
          opt.interrupt = [&signals] { return signals(); };
          State x = x0 ? *x0 : system.initial_state();
          Mode md = mode ? to_mode(*mode) : system.requested_mode();
          check_start(system, md, x, "find_periodic_orbit");
          Shooting<Sys> shooting(system, opt);
          return to_py(shooting.forced(md, t0, x, period));
        });
      },
      py::arg("system"), py::arg("period"), py::arg("t0") = 0.0, py::arg("x0") = py::none(), py::arg("mode") = py::none(),
      py::arg("periodic") = py::none(), py::arg("monodromy") = "variational", py::arg("tolerance") = 1e-9,
      py::arg("max_iterations") = 30, py::arg("rtol") = 1e-10, py::arg("atol") = 1e-12,
      py::arg("max_steps") = StepperOptions<double>{}.max_steps, py::arg("outputs") = py::none(),
      py::arg("output_harmonics") = 3, py::arg("progress") = py::none(),
      py::arg("integrator") = OrbitIntegrator::DormandPrince54, py::arg("samples_per_period") = 256,
      py::arg("amplitude_components") = py::none(), py::arg("multiplier_tolerance") = 1e-6, py::arg("fd_step") = 1e-6,
      py::arg("control_sensitivities") = true, py::arg("max_step") = std::numeric_limits<double>::infinity(),
      py::arg("guard_samples") = 0, doc);
}

/// continue_orbits for one system type (Py: PySystem, PyContactSystem or PyBodyContactSystem).
template <class Py>
void def_continue_orbits(py::module_& m, const char* doc) {
  using Sys = typename Py::Wrapped;
  m.def(
      "continue_orbits",
      [](Py& system, const py::object& parameter, double p0, double p_end, const py::object& period, double t0,
         std::optional<State> x0, std::optional<std::vector<ContactState>> mode,
         std::optional<std::vector<Index>> periodic, const std::string& monodromy, double tolerance, int max_iterations,
         double rtol, double atol, double initial_step, double min_step, double max_step, int max_points,
         int max_corrector_iterations, int fast_iterations, double growth, double section_margin,
         int chord_iterations, const py::object& start_mode, const py::object& on_point, int parts,
         const py::object& start, long max_steps, std::optional<Eigen::MatrixXd> outputs, int output_harmonics,
         const py::object& progress, OrbitIntegrator integrator, bool wrap_section, double max_corrector_distance,
         const py::object& stop_when) {
        static const std::string where = "continue_orbits";
        if (!stop_when.is_none() && !PyCallable_Check(stop_when.ptr()))
          throw std::invalid_argument(where + ": stop_when must be None or a callable stop_when(last, next)");
        if (!stop_when.is_none() && parts > 1)
          detail::throw_invalid(where, "stop_when needs parts = 1 (the parts are joined by their own stop rule)", parts);
        if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
          throw std::invalid_argument(where + ": progress must be None or a callable progress(report)");
        if (parts < 1) detail::throw_invalid(where, "parts must be >= 1", parts);
        if (parts > max_split_parts())
          detail::throw_invalid(where,
                                "parts must be <= " + std::to_string(max_split_parts()) +
                                    " (4 x the hardware threads: each part is a thread and a copy of the system, "
                                    "and the speed-up is at most the number of cores)",
                                parts);
        if (!start.is_none() && !PyCallable_Check(start.ptr()))
          throw std::invalid_argument(where + ": start must be None or a callable start(system, p)");
        check_callables(where, parameter, period, start_mode);
        if (!on_point.is_none() && !PyCallable_Check(on_point.ptr()))
          throw std::invalid_argument(where + ": on_point must be None or a callable on_point(point)");
        detail::require_finite(where, "p0", p0);
        detail::require_finite(where, "p_end", p_end);
        if (!(p_end != p0)) detail::throw_invalid(where, "p_end must differ from p0", p_end);
        ContinuationOptions<double> co = continuation_options(
            std::min(p0, p_end), std::max(p0, p_end), initial_step, min_step, max_step, max_points,
            max_corrector_iterations, fast_iterations, growth, section_margin, chord_iterations, wrap_section);
        co.direction = p_end > p0 ? 1 : -1;
        co.max_corrector_distance = max_corrector_distance;
        if (!progress.is_none())
          co.progress = [&progress](const ContinuationProgress& pr) {
            py::gil_scoped_acquire gil;
            progress(pr);
          };
        const ContinuationCallbacks<Py> cb{&parameter, &period, &start_mode, &on_point, &start};
        ShootingOptions<double> opt;
        State x;
        Mode md;
        // parts > 1: the parts run on copies (made under the system's lock, destroyed with the GIL
        // held: a load's Python time_function is copied with them), not on `system`, which is
        // locked again at the end to take part 0's copy (the system at part 0's last point).
        std::vector<Py> copies;
        PyContinuation out = with_system(system, [&](SignalCheck& signals) {
          opt = shooting_options(system, periodic, monodromy, tolerance, max_iterations, rtol, atol, max_steps,
                                 integrator, where);
          set_outputs_and_progress(opt, outputs, output_harmonics, py::none(), where);
          x = x0 ? *x0 : system.initial_state();
          md = mode ? to_mode(*mode) : system.requested_mode();
          check_start(system, md, x, where);
          PyContinuation one;
          if (parts > 1) {
            copies.assign(static_cast<std::size_t>(parts), system);
            return one;
          }
          opt.interrupt = [&signals] { return signals(); };
          Continuation<Sys> cont(
              system, [&cb](Sys& s, double p) { cb.set(s, p); }, [&cb](double p) { return cb.period_of(p); }, opt,
              co);
          if (!start_mode.is_none())
            cont.start_mode(
                [&cb](Sys& s, double t, const State& xs, const Mode& prev) { return cb.mode_of(s, t, xs, prev); });
          if (!on_point.is_none()) cont.on_point([&cb](const ContinuationPoint<Sys>& pt) { cb.point(pt); });
          if (!stop_when.is_none())
            cont.stop_when([&stop_when](const ContinuationPoint<Sys>& last, const ContinuationPoint<Sys>& next) {
              py::gil_scoped_acquire gil;
              return cast_as<bool>(stop_when(to_py(last), to_py(next)),
                                   "continue_orbits: stop_when(last, next) must return a bool");
            });
          const auto result = cont.run(md, t0, x, p0);
          one.status = result.status;
          one.message = result.message;
          one.points = to_py(result.points);
          return one;
        });
        if (parts == 1) return out;
        SignalCheck signals;
        {
          py::gil_scoped_release release;
          opt.interrupt = [&signals] { return signals(); };
          std::vector<Sys*> systems;
          for (Py& c : copies) systems.push_back(&c);
          SplitContinuation<Sys> split(
              systems, [&cb](Sys& s, double p) { cb.set(s, p); }, [&cb](double p) { return cb.period_of(p); },
              opt, co);
          if (!start_mode.is_none())
            split.start_mode(
                [&cb](Sys& s, double t, const State& xs, const Mode& prev) { return cb.mode_of(s, t, xs, prev); });
          if (!on_point.is_none())
            split.on_point([&cb](std::size_t, const ContinuationPoint<Sys>& pt) { cb.point(pt); });
          const auto result = split.run([&](Sys& s, double p) {
            if (start.is_none()) return typename SplitContinuation<Sys>::Guess{md, t0, x};
            return cb.guess(s, p);
          });
          out.status = result.branch.status;
          out.message = result.branch.message;
          out.points = to_py(result.branch.points);
          for (std::size_t k = 0; k < result.parts.size(); ++k) {
            const auto& r = result.parts[k];
            out.parts.push_back(PyContinuationPart{r.start_parameter, r.status, r.message, r.points, r.kept, r.joined,
                                                   r.cpu_seconds, to_py(result.dropped[k].points)});
          }
        }
        signals.rethrow();
        with_system(system, [&](SignalCheck&) { static_cast<Sys&>(system) = copies.front(); });
        return out;
      },
      py::arg("system"), py::arg("parameter"), py::arg("p0"), py::arg("p_end"), py::arg("period"), py::arg("t0") = 0.0,
      py::arg("x0") = py::none(), py::arg("mode") = py::none(), py::arg("periodic") = py::none(),
      py::arg("monodromy") = "variational", py::arg("tolerance") = 1e-9, py::arg("max_iterations") = 30,
      py::arg("rtol") = 1e-10, py::arg("atol") = 1e-12, py::arg("initial_step") = 0.01, py::arg("min_step") = 1e-6,
      py::arg("max_step") = 0.1, py::arg("max_points") = 200, py::arg("max_corrector_iterations") = 8,
      py::arg("fast_iterations") = 3, py::arg("growth") = 1.5, py::arg("section_margin") = 0.02,
      py::arg("chord_iterations") = 0, py::arg("start_mode") = py::none(), py::arg("on_point") = py::none(),
      py::arg("parts") = 1, py::arg("start") = py::none(), py::arg("max_steps") = StepperOptions<double>{}.max_steps,
      py::arg("outputs") = py::none(), py::arg("output_harmonics") = 3, py::arg("progress") = py::none(),
      py::arg("integrator") = OrbitIntegrator::DormandPrince54, py::arg("wrap_section") = true,
      py::arg("max_corrector_distance") = 0.0, py::arg("stop_when") = py::none(), doc);
}

template <class Py>
void def_poincare_sections(py::module_& m, const char* doc) {
  using Sys = typename Py::Wrapped;
  m.def(
      "poincare_sections",
      [](Py& system, double period, double t0, std::optional<State> x0,
         std::optional<std::vector<ContactState>> mode, int transient_periods, int record_periods, int max_period,
         double tolerance, std::optional<std::vector<Index>> periodic, double rtol, double atol, long max_steps) {
        static const std::string where = "poincare_sections";
        detail::require_positive(where, "period", period);
        return with_system(system, [&](SignalCheck& signals) {
          PoincareOptions<double> opt;
          opt.transient_periods = transient_periods;
          opt.record_periods = record_periods;
          opt.max_period = max_period;
          opt.tolerance = tolerance;
          opt.periodic = periodic_set(system, periodic, where);
          opt.stepper.rtol = rtol;
          opt.stepper.atol = atol;
          opt.stepper.max_steps = checked_max_steps(max_steps, where);
          opt.interrupt = [&signals] { return signals(); };
          check_section_memory(where, record_periods, system.state_size());
          if (max_period >= 1 && 2LL * max_period > record_periods)
            detail::throw_invalid(where,
                                  "max_period must be <= record_periods / 2 = " + std::to_string(record_periods / 2) +
                                      " (a period k is told from a record of at least 2k sections)",
                                  max_period);
          const State x = x0 ? *x0 : system.initial_state();
          const Mode md = mode ? to_mode(*mode) : system.requested_mode();
          check_start(system, md, x, where);
          PyPoincare out;
          const auto r = poincare_sections(static_cast<Sys&>(system), md, t0, x, period, opt);
          out.status = r.status;
          out.message = r.message;
          out.period = r.period;
          out.recurrence = Eigen::Map<const Eigen::VectorXd>(r.recurrence.data(), static_cast<Index>(r.recurrence.size()));
          out.t0 = r.t0;
          out.period_time = r.period_time;
          out.states.resize(static_cast<Index>(r.states.size()), x.size());
          for (std::size_t n = 0; n < r.states.size(); ++n) out.states.row(static_cast<Index>(n)) = r.states[n].transpose();
          for (const Mode& mn : r.modes) out.modes.push_back(to_list(mn));
          return out;
        });
      },
      py::arg("system"), py::arg("period"), py::arg("t0") = 0.0, py::arg("x0") = py::none(), py::arg("mode") = py::none(),
      py::arg("transient_periods") = 100, py::arg("record_periods") = 32, py::arg("max_period") = 8,
      py::arg("tolerance") = PoincareOptions<double>{}.tolerance, py::arg("periodic") = py::none(), py::arg("rtol") = 1e-10, py::arg("atol") = 1e-12,
      py::arg("max_steps") = StepperOptions<double>{}.max_steps, doc);
}

void bind_steady_state(py::module_& m) {
  py::enum_<ShootingStatus>(m, "ShootingStatus", "How find_periodic_orbit ended (PeriodicOrbit.status).")
      .value("Converged", ShootingStatus::Converged, "a periodic orbit to the tolerance, its mode sequence closes")
      .value("NoConvergence", ShootingStatus::NoConvergence, "Newton did not reach the tolerance")
      .value("ModeNotPeriodic", ShootingStatus::ModeNotPeriodic, "x(T) = x(0) but the mode at t0 + T is not the start's")
      .value("IntegrationFailed", ShootingStatus::IntegrationFailed, "a run ended early (see the message)")
      .value("SingularJacobian", ShootingStatus::SingularJacobian, "the Newton matrix is singular");
  py::enum_<OrbitIntegrator>(m, "OrbitIntegrator",
                             "The integrator of the orbit runs (find_periodic_orbit's and continue_orbits' "
                             "integrator=; C++ ShootingOptions::integrator).")
      .value("DormandPrince54", OrbitIntegrator::DormandPrince54,
             "adaptive Dormand-Prince 5(4) (default; any system, the monodromy by `monodromy`)")
      .value("Exponential", OrbitIntegrator::Exponential,
             "exact propagation in linear modes (ExactLinearStepper), whatever the fastest mode; the monodromy by "
             "central differences of exact runs (`monodromy` ignored)");
  py::enum_<Instability>(m, "Instability", "How a periodic orbit loses stability (its Floquet multipliers).")
      .value("Stable", Instability::None,  // "None" is a Python keyword
             "all multipliers inside the unit circle (C++: None, a Python keyword)")
      .value("Fold", Instability::Fold, "a real multiplier > 1 (fold)")
      .value("PeriodDoubling", Instability::PeriodDoubling, "a real multiplier < -1 (period doubling)")
      .value("NeimarkSacker", Instability::NeimarkSacker, "a complex pair outside (Neimark-Sacker, torus)");
  py::class_<PyOrbit>(m, "PeriodicOrbit",
                      "A periodic orbit found by shooting (docs/steady_state.md); C++'s PeriodicOrbit with its "
                      "floquet fields (multipliers, max_modulus, stable, instability) flattened.")
      .def_readonly("status", &PyOrbit::status, "how the shooting ended (ShootingStatus)")
      .def_property_readonly("ok", [](const PyOrbit& o) { return o.status == ShootingStatus::Converged; },
                             "status == Converged")
      .def_readonly("message", &PyOrbit::message, "why it failed (empty when Converged)")
      .def_readonly("t0", &PyOrbit::t0, "time of the section [s]")
      .def_readonly("period", &PyOrbit::period, "the period T [s]")
      .def_readonly("residual", &PyOrbit::residual, "max |x_i(T) - x_i(0)| over the periodic components")
      .def_readonly("iterations", &PyOrbit::iterations, "orbit runs made")
      .def_readonly("x0", &PyOrbit::x0, "the orbit's state at t0")
      .def_readonly("mode", &PyOrbit::mode, "contact states at t0")
      .def_readonly("monodromy", &PyOrbit::monodromy, "dx_P(T)/dx_P(0) over the periodic components P")
      .def_readonly("multipliers", &PyOrbit::multipliers, "Floquet multipliers (numpy, complex; C++: floquet.multipliers)")
      .def_readonly("max_modulus", &PyOrbit::max_modulus, "the largest |multiplier|")
      .def_readonly("stable", &PyOrbit::stable, "every multiplier inside the unit circle")
      .def_readonly("instability", &PyOrbit::instability, "how it is unstable (Instability; Stable when stable)")
      .def_readonly("amplitudes", &PyOrbit::amplitudes, "max |x_i| over the orbit (the periodic components)")
      .def_readonly("events", &PyOrbit::events, "the contact switches of one period")
      .def_readonly("stick_fractions", &PyOrbit::stick_fractions, "per damper: time stuck / T")
      .def_readonly("switches", &PyOrbit::switches, "per damper: its contact-state changes in one period")
      .def_readonly("outputs", &PyOrbit::outputs,
                    "per row of outputs= (e.g. probe_rows): an OrbitSignal over the orbit's period (min, max, "
                    "amplitude, mean, harmonics), from the run that closed the orbit");
  def_find_periodic_orbit<PySystem>(
      m,
      "Forced periodic orbit of the given period by shooting from (mode, t0, x0) (default: the system's initial "
      "state), with its monodromy and Floquet multipliers (Shooting::forced, docs/steady_state.md). periodic: the "
      "state indices that must repeat (default: q, q', x_d, x_d', the first 2n + 2D); max_steps: step attempts "
      "allowed per orbit run (a run beyond it fails: IntegrationFailed). The GIL is released; Ctrl-C stops the "
      "call (KeyboardInterrupt). outputs: rows c (numpy, one column per state component, e.g. probe_rows(...)) "
      "whose y = c . x the orbit reports over its period (PeriodicOrbit.outputs, output_harmonics harmonics); "
      "progress(report): called after every Newton iteration with a ShootingProgress (residual, CPU seconds, an "
      "estimate of those left). A failure's message names what stalled Newton and the option that addresses it. "
      "integrator: the OrbitIntegrator of the runs (Exponential: exact in linear modes, for stiff structures). "
      "C++'s other ShootingOptions fields: samples_per_period (dense-output samples a period for amplitudes and "
      "outputs, default 256), amplitude_components (the components whose max |x_i| is reported; default the "
      "periodic ones), multiplier_tolerance (|mu| > 1 + it is unstable, default 1e-6), fd_step (relative step of "
      "the finite differences, default 1e-6), control_sensitivities (the variational monodromy under the step "
      "control, default True); and the orbit runs' max_step [s] (default inf) and guard_samples (default 0): set "
      "them when a guard can cross and cross back inside one step.");
  def_find_periodic_orbit<PyContactSystem>(
      m,
      "A ContactSystem's forced periodic orbit, as above; the default periodic components are q, q' (the first "
      "2n), not the audit integrals. stick_fractions and switches are per contact.");
  def_find_periodic_orbit<PyBodyContactSystem>(
      m,
      "A BodyContactSystem's forced periodic orbit, as above; the default periodic components are z, z' (q and "
      "the bodies' coordinates, the first 2 num_coordinates()), not the audit integrals.");
  def_find_periodic_orbit<PyMixedContactSystem>(
      m,
      "A MixedContactSystem's forced periodic orbit, as above; the default periodic components are z, z' (the "
      "first 2 num_coordinates()).");

  py::enum_<ContinuationStatus>(m, "ContinuationStatus", "How continue_orbits ended (Branch.status).")
      .value("Completed", ContinuationStatus::Completed, "the branch left the parameter range")
      .value("MaxPoints", ContinuationStatus::MaxPoints, "max_points reached inside the range")
      .value("StepTooSmall", ContinuationStatus::StepTooSmall, "the corrector failed down to min_step")
      .value("StartFailed", ContinuationStatus::StartFailed, "no orbit at the start parameter")
      .value("Stopped", ContinuationStatus::Stopped, "a stop rule ended the branch (parts > 1: a part joined the next)")
      .value("Interrupted", ContinuationStatus::Interrupted, "Ctrl-C stopped the run");
  py::class_<PyContinuationPoint>(m, "ContinuationPoint", "One point of a branch (docs/steady_state.md).")
      .def_readonly("parameter", &PyContinuationPoint::parameter, "the parameter p")
      .def_readonly("step", &PyContinuationPoint::step, "the arclength step that reached it (0 at the start)")
      .def_readonly("stability_changed", &PyContinuationPoint::stability_changed,
                    "the orbit's stability differs from the previous point's")
      .def_readonly("orbit", &PyContinuationPoint::orbit, "the PeriodicOrbit at p");
  py::class_<PyContinuationPart>(m, "BranchPart", "One part of continue_orbits(parts > 1) (SplitContinuation).")
      .def_readonly("start_parameter", &PyContinuationPart::start_parameter, "the parameter of its start orbit")
      .def_readonly("status", &PyContinuationPart::status, "how the part's run ended (Stopped: it joined the next)")
      .def_readonly("message", &PyContinuationPart::message, "why it ended (empty when Completed)")
      .def_readonly("points", &PyContinuationPart::points,
                    "the number of points the part computed (an int, as C++'s ContinuationPart::points; the "
                    "points themselves are in Branch.points)")
      .def_readonly("kept", &PyContinuationPart::kept, "of them in the joined branch")
      .def_readonly("joined", &PyContinuationPart::joined, "its branch ran into the next part's start")
      .def_readonly("cpu_seconds", &PyContinuationPart::cpu_seconds, "CPU time of the part's thread")
      .def_readonly("dropped", &PyContinuationPart::dropped,
                    "its own points when the joined branch does not hold them (an earlier part did not join)");
  py::class_<PyContinuation>(m, "Branch", "A branch computed by continue_orbits (C++: ContinuationResult).")
      .def_readonly("status", &PyContinuation::status, "how the branch ended (ContinuationStatus)")
      .def_readonly("message", &PyContinuation::message, "why it ended early (empty when Completed)")
      .def_readonly("points", &PyContinuation::points, "the branch's ContinuationPoints, in branch order")
      .def_readonly("parts", &PyContinuation::parts, "per part (parts > 1): what it did; empty for one part")
      .def_property_readonly("completed",
                             [](const PyContinuation& c) { return c.status == ContinuationStatus::Completed; },
                             "status == Completed")
      .def_property_readonly(
          "parameters",
          [](const PyContinuation& c) {
            std::vector<double> p;
            for (const auto& pt : c.points) p.push_back(pt.parameter);
            return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(p.data(), static_cast<Index>(p.size())));
          },
          "the points' parameters (numpy)");
  def_continue_orbits<PySystem>(
      m,
      std::string(
      "Pseudo-arclength continuation of forced periodic orbits in a parameter p from p0 towards p_end "
      "(Continuation, docs/steady_state.md): parameter(system, p) returns the FrictionDampedSystem at p (it replaces "
      "`system`, which is left at the last point's p); period is the forcing period, a float or period(p). The start "
      "orbit is shot from (mode, t0, x0) (default: the system's initial state). The arclength norm is Euclidean in "
      "(x_P, p): scale p so that both are of order one. section_margin (default 0.02; 0: a fixed t0) moves the "
      "section t0 away from an event within that fraction of a period; chord_iterations > 0 lets the corrector first iterate on plain runs "
      "with the last point's Jacobian (ContinuationOptions). parts = n > 1 follows the branch in n parts at once "
      "(SplitContinuation: part k starts at the k-th of n equal cuts of [p0, p_end], on its own thread and a copy "
      "of the system, and the parts are joined where one runs into the next one's start); start(system, p) -> "
      "(mode, t0, x0) gives each part's start guess (default: mode, t0, x0 above), on_point is then called as the "
      "parts find their points (not in branch order) and Branch.parts tells what each part did; parts is at most "
      "4 x the hardware threads. max_steps: step attempts allowed per orbit run. A Python exception raised by a "
      "callable ends the run and propagates. The GIL is released during the run and re-acquired for each "
      "callable; Ctrl-C stops the call (KeyboardInterrupt). outputs: rows c (numpy, one column per state "
      "component, e.g. probe_rows(...)) whose y = c . x every orbit reports over its period as "
      "PeriodicOrbit.outputs (OrbitSignal, output_harmonics harmonics); progress(report): called after each point "
      "with a ContinuationProgress (CPU seconds so far, an estimate of those left). A failed branch's message names "
      "what stalled the corrector (an event at the period start, a grazing, a discontinuity of the period map) and "
      "the option that addresses it. max_corrector_distance (> 0): a corrected point farther than it times the "
      "step from its prediction is refused and the step halved (another orbit; default 0: never). stop_when(last, "
      "next) -> bool (parts = 1): asked after each corrected point; True ends the branch (status Stopped) before "
      "`next` is added. " +
          std::string(kWrapSectionDoc))
          .c_str());
  def_continue_orbits<PyContactSystem>(
      m,
      "A ContactSystem's branch, as above: parameter(system, p) returns the ContactSystem at p (the same number of "
      "contacts and state size); periodic defaults to q, q' (the first 2n components). Branch points' "
      "stick_fractions and switches are per contact.");
  def_continue_orbits<PyBodyContactSystem>(
      m,
      "A BodyContactSystem's branch, as above: parameter(system, p) returns the BodyContactSystem at p; periodic "
      "defaults to z, z' (the first 2 num_coordinates() components).");
  def_continue_orbits<PyMixedContactSystem>(
      m,
      "A MixedContactSystem's branch, as above: parameter(system, p) returns the MixedContactSystem at p; periodic "
      "defaults to z, z' (the first 2 num_coordinates() components).");

  py::enum_<PoincareStatus>(m, "PoincareStatus", "What poincare_sections found (PoincareSections.status).")
      .value("Periodic", PoincareStatus::Periodic, "the sections repeat with period k = period")
      .value("NotPeriodic", PoincareStatus::NotPeriodic, "no k <= max_period: quasi-periodic, chaotic or transient")
      .value("IntegrationFailed", PoincareStatus::IntegrationFailed, "a run failed (see the message)")
      .value("Undecided", PoincareStatus::Undecided,
             "the best recurrence lies within a factor of ten of the tolerance: neither verdict is safe "
             "(period holds the candidate k; docs/steady_state.md)");
  py::class_<PyPoincare>(m, "PoincareSections", "Poincaré sections of a forced response (docs/steady_state.md).")
      .def_readonly("status", &PyPoincare::status, "what was found (PoincareStatus)")
      .def_property_readonly("periodic", [](const PyPoincare& p) { return p.status == PoincareStatus::Periodic; },
                             "status == Periodic")
      .def_readonly("message", &PyPoincare::message, "why a run failed (empty otherwise)")
      .def_readonly("period", &PyPoincare::period, "k of a period-k response, 0 when not periodic")
      .def_readonly("recurrence", &PyPoincare::recurrence,
                    "per k = 1 .. max_period: max_n |x_P(n) - x_P(n - k)| / max_n |x_P(n)| over the record")
      .def_readonly("t0", &PyPoincare::t0, "time of the first section")
      .def_readonly("period_time", &PyPoincare::period_time, "the forcing period T")
      .def_readonly("states", &PyPoincare::states, "the sections x(t0 + nT), one row per n")
      .def_readonly("modes", &PyPoincare::modes, "the contact states at each section");
  def_poincare_sections<PySystem>(
      m,
      "Poincaré sections of the forced response from (mode, t0, x0) (default: the system's initial state): "
      "transient_periods whole periods, then the state at the next record_periods multiples of `period`, and the "
      "smallest k <= max_period with which they repeat to `tolerance` / 10 (relative, over the components "
      "`periodic`, default q, q', x_d, x_d'; the tolerance at least 100 (rtol + atol / scale)): a period-k "
      "response; within a factor 10 of the tolerance Undecided (period: the candidate k); else not periodic "
      "(quasi-periodic, chaotic or still transient). A periodic section is a guess for find_periodic_orbit with period k T (poincare_sections, "
      "docs/steady_state.md). record_periods is bounded by the record's memory (record_periods x state_size x 16 "
      "bytes <= 1 GiB); max_steps: step attempts allowed per period's run. The GIL is released; Ctrl-C stops the "
      "call (KeyboardInterrupt).");
  def_poincare_sections<PyContactSystem>(m, "A ContactSystem's Poincaré sections, as above; periodic defaults to q, q'.");
  def_poincare_sections<PyBodyContactSystem>(
      m, "A BodyContactSystem's Poincaré sections, as above; periodic defaults to z, z' (q and the bodies' coordinates).");
  def_poincare_sections<PyMixedContactSystem>(m, "A MixedContactSystem's Poincaré sections, as above.");
}

}  // namespace

void bind_auto(py::module_& m);  // auto_bindings.cpp
void bind_impulse(py::module_& m);  // impulse_bindings.cpp: impact options of the contact systems
void bind_assembler(py::module_& m);  // assembler_bindings.cpp: body contacts as the paper's damper
void bind_disk(py::module_& m);  // disk_bindings.cpp: bladed disks, travelling waves, mistuning
void bind_branches(py::module_& m);  // branch_bindings.cpp: bifurcations and branch switching
void bind_hybrid(py::module_& m);  // hybrid_bindings.cpp: hybrid systems written in Python

PYBIND11_MODULE(stickslip, m) {
  m.doc() = "stickslip: dynamics of beam frames damped by dry friction (docs/python.md)";
  m.attr("__version__") = STICKSLIP_VERSION_STRING;
  bind_frame(m);
  bind_dampers(m);
  bind_system(m);
  bind_contacts(m);
  bind_bodies(m);
  bind_simulate(m);
  bind_trade_study(m);
  bind_steady_state(m);
  bind_auto(m);
  bind_firstuser(m);
  bind_impulse(m);
  bind_assembler(m);
  bind_disk(m);
  bind_branches(m);
  bind_hybrid(m);
}
