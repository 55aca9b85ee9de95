// The Python module `stickslip` (docs/python.md): frames, modes, dampers and loads, simulate()
// with any integrator returning histories as numpy arrays, events, the energy audit, per-damper
// statistics and trade_study(). Exceptions keep their messages: std::invalid_argument becomes
// ValueError, other std::exception types their pybind11 counterparts (RuntimeError, ...).
#include "call_guard.hpp"

#include <stickslip/stickslip.hpp>

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

namespace {

using namespace stickslip;
using Index = Eigen::Index;
using System = FrictionDampedSystem<double>;
using CSystem = ContactSystem<double>;
using State = System::State;
using Mode = System::Mode;
using Law = FrictionLawVariant<double>;
using stickslip_python::copy_of;
using stickslip_python::PyContactSystem;
using stickslip_python::PySystem;
using stickslip_python::SignalCheck;
using stickslip_python::with_system;

/// A DamperStates as a Python list of ContactState.
std::vector<ContactState> to_list(const Mode& mode) {
  std::vector<ContactState> v(static_cast<std::size_t>(mode.size()));
  for (Index i = 0; i < mode.size(); ++i) v[static_cast<std::size_t>(i)] = mode[i];
  return v;
}

/// A Python list of ContactState as a DamperStates.
Mode to_mode(const std::vector<ContactState>& states) {
  Mode mode(static_cast<Index>(states.size()));
  for (std::size_t i = 0; i < states.size(); ++i) mode[static_cast<Index>(i)] = states[i];
  return mode;
}

/// A Python CoulombLaw, StribeckLaw or RegularisedLaw as the law variant (else ValueError naming
/// `where` and law).
Law to_law(const py::handle& law, const std::string& where = "PointDamper") {
  if (py::isinstance<CoulombLaw<double>>(law)) return law.cast<CoulombLaw<double>>();
  if (py::isinstance<StribeckLaw<double>>(law)) return law.cast<StribeckLaw<double>>();
  if (py::isinstance<RegularisedLaw<double>>(law)) return law.cast<RegularisedLaw<double>>();
  throw std::invalid_argument(where + ": law must be a CoulombLaw, StribeckLaw or RegularisedLaw");
}

template <class T>
T cast_as(const py::handle& h, const std::string& what);

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

/// A Python argument or callable result as T, else TypeError "<what>, got <its type[ and shape]>"
/// (what: the parameter and what it must be), instead of pybind11's RuntimeError.
template <class T>
T cast_as(const py::handle& h, const std::string& what) {
  try {
    return h.cast<T>();
  } catch (const py::cast_error&) {
  } catch (const py::reference_cast_error&) {
  }
  std::string got = py::str(py::type::of(h).attr("__name__"));
  if (py::hasattr(h, "shape")) got += " of shape " + std::string(py::str(h.attr("shape")));
  throw py::type_error(what + ", got " + got);
}

/// Checks a run's start: x0 of state_size() entries (ValueError naming x0, with both sizes), then
/// its mode (validate_state: num_dampers() states, ...).
template <class Sys>
void check_start(const Sys& system, const Mode& mode, const State& x, const std::string& where) {
  if (x.size() != system.state_size())
    throw std::invalid_argument(where + ": x0 has size " + std::to_string(x.size()) +
                                ", expected state_size() = " + std::to_string(system.state_size()));
  system.validate_state(mode, x, where.c_str());
}

/// A point of the frame whose displacement simulate() records at every sample:
/// point_shape(member, coordinate, direction)^T q.
struct Probe {
  MemberId member = 0;
  double coordinate = 0;
  LoadDirection direction = LoadDirection::GlobalX;
};

/// One transition seen by simulate()'s observer (the stepper's record: every damper's state).
struct Transition {
  double t = 0;
  std::vector<ContactState> from, to;
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
  std::optional<CSystem::EnergyBalance> contact_energy;  // a ContactSystem's audit
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
double start_energy(CSystem& system, const Mode&, double, const State& x) { return system.mechanical_energy(x); }

/// simulate() from (mode, t0, x0) - by default the system's initial state made consistent - to
/// t_end, recording as asked. The GIL is released and the system's lock held while the stepper
/// runs; Ctrl-C stops it (KeyboardInterrupt). Py: PySystem or PyContactSystem (no probes nor
/// statistics: ValueError naming them).
template <class Py>
Run run_simulation(Py& py_system, double t_end, const RunOptions<double>& options, double t0,
                   std::optional<State> x0, std::optional<std::vector<ContactState>> mode0,
                   const std::vector<Probe>& probes, bool record_states, double evaluate_from,
                   std::optional<StatisticsWindow<double>> window, bool consistent) {
  constexpr bool kContacts = std::is_same_v<Py, PyContactSystem>;
  using Sys = std::conditional_t<kContacts, CSystem, System>;
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
  py::class_<SectionProperties<double>>(m, "SectionProperties", "Beam section: E [Pa], rho [kg/m^3], A [m^2], I [m^4].")
      .def(py::init([](double E, double rho, double A, double I) { return SectionProperties<double>{E, rho, A, I}; }),
           py::arg("E"), py::arg("rho"), py::arg("A"), py::arg("I"))
      .def_readwrite("E", &SectionProperties<double>::E)
      .def_readwrite("rho", &SectionProperties<double>::rho)
      .def_readwrite("A", &SectionProperties<double>::A)
      .def_readwrite("I", &SectionProperties<double>::I);
  py::enum_<Dof>(m, "Dof").value("X", Dof::X).value("Y", Dof::Y).value("Rz", Dof::Rz);
  py::enum_<MassType>(m, "MassType").value("Consistent", MassType::Consistent).value("Lumped", MassType::Lumped);
  using Frame = FrameModel<double>;
  py::class_<Frame>(m, "FrameModel", "A plane frame of Euler-Bernoulli members (docs/beam.md).")
      .def(py::init<>())
      .def("add_node", &Frame::add_node, py::arg("x"), py::arg("y"), "Adds a node at (x, y) [m]; returns its id.")
      .def("add_member", py::overload_cast<NodeId, NodeId, const Frame::Section&, Index>(&Frame::add_member),
           py::arg("node_a"), py::arg("node_b"), py::arg("section"), py::arg("elements"),
           "Adds a member of `elements` equal elements; returns its id.")
      .def("add_member",
           py::overload_cast<NodeId, NodeId, const Frame::Section&, std::vector<double>>(&Frame::add_member),
           py::arg("node_a"), py::arg("node_b"), py::arg("section"), py::arg("stations"))
      .def("clamp", &Frame::clamp, py::arg("node"))
      .def("pin", &Frame::pin, py::arg("node"))
      .def("fix", &Frame::fix, py::arg("node"), py::arg("dof"))
      .def("add_point_mass", &Frame::add_point_mass, py::arg("node"), py::arg("m"))
      .def("add_rotary_inertia", &Frame::add_rotary_inertia, py::arg("node"), py::arg("J"))
      .def("add_spring", &Frame::add_spring, py::arg("node"), py::arg("dof"), py::arg("k"))
      .def("member_nodes", [](const Frame& f, MemberId id) { return f.member(id).nodes; }, py::arg("member"),
           "Node ids along the member, a ... b.")
      .def("member_length", [](const Frame& f, MemberId id) { return f.member(id).length; }, py::arg("member"))
      .def("node_position", [](const Frame& f, NodeId n) { return f.node_position(n); }, py::arg("node"));

  py::class_<ModalBasis<double>>(m, "ModalBasis", "Mass-normalised modes of a frame (docs/modal.md).")
      .def_property_readonly("omega", &ModalBasis<double>::omega, "natural frequencies [rad/s], ascending")
      .def_property_readonly("frequencies_hz", &ModalBasis<double>::frequencies_hz)
      .def_property_readonly("phi", &ModalBasis<double>::phi)
      .def_property_readonly("damping_ratios", &ModalBasis<double>::damping_ratios)
      .def("__len__", [](const ModalBasis<double>& b) { return b.size(); })
      .def("truncated", &ModalBasis<double>::truncated, py::arg("n"))
      .def("with_modal_damping", &ModalBasis<double>::with_modal_damping, py::arg("ratios"))
      .def("with_rayleigh_damping", &ModalBasis<double>::with_rayleigh_damping, py::arg("alpha"), py::arg("beta"));
  m.def(
      "compute_modes",
      [](const Frame& frame, Index num_modes, double max_omega, MassType mass) {
        ModalOptions<double> o;
        o.num_modes = num_modes;
        o.max_omega = max_omega;
        return compute_modes(frame.assemble(mass), o);
      },
      py::arg("frame"), py::arg("num_modes") = 10, py::arg("max_omega") = std::numeric_limits<double>::infinity(),
      py::arg("mass") = MassType::Consistent, "The lowest num_modes modes of the assembled frame.");
}

void bind_dampers(py::module_& m) {
  py::enum_<ContactState>(m, "ContactState")
      .value("Stick", ContactState::Stick)
      .value("SlipPositive", ContactState::SlipPositive)
      .value("SlipNegative", ContactState::SlipNegative)
      .value("LiftOff", ContactState::LiftOff)
      .value("Separated", ContactState::Separated);
  py::enum_<MemberEnd>(m, "MemberEnd")
      .value("Default", MemberEnd::Default)
      .value("Stop", MemberEnd::Stop)
      .value("Extend", MemberEnd::Extend)
      .value("Wall", MemberEnd::Wall);
  py::enum_<Separation>(m, "Separation")
      .value("Stop", Separation::Stop)
      .value("Separate", Separation::Separate);
  py::enum_<LoadDirection>(m, "LoadDirection")
      .value("GlobalX", LoadDirection::GlobalX)
      .value("GlobalY", LoadDirection::GlobalY)
      .value("Axial", LoadDirection::Axial)
      .value("Transverse", LoadDirection::Transverse)
      .value("Moment", LoadDirection::Moment);
  py::enum_<NormalLoad>(m, "NormalLoad").value("Constant", NormalLoad::Constant).value("Inertial", NormalLoad::Inertial);
  py::enum_<ContactPoint>(m, "ContactPoint").value("Fixed", ContactPoint::Fixed).value("Moving", ContactPoint::Moving);
  py::enum_<EndPolicy>(m, "EndPolicy")
      .value("Throw", EndPolicy::Throw)
      .value("Clamp", EndPolicy::Clamp)
      .value("Extrapolate", EndPolicy::Extrapolate);
  py::class_<CoulombLaw<double>>(m, "CoulombLaw", "Coulomb friction with static mu_s >= kinetic mu_k.")
      .def(py::init<double, double>(), py::arg("mu_s"), py::arg("mu_k"));
  py::class_<StribeckLaw<double>>(m, "StribeckLaw")
      .def(py::init<double, double, double, double>(), py::arg("mu_s"), py::arg("mu_k"), py::arg("v_s"),
           py::arg("exponent") = 2.0);
  py::class_<RegularisedLaw<double>>(m, "RegularisedLaw", "tanh-regularised friction mu tanh(v / v_eps).")
      .def(py::init([](double mu, double v_eps) { return RegularisedLaw<double>(mu, v_eps); }), py::arg("mu"),
           py::arg("v_eps"));

  using Damper = System::Damper;
  py::class_<Damper>(m, "PointDamper", "A point-contact friction damper on a member (docs/model.md).")
      .def(py::init([](MemberId member, double coordinate, double mass, double stiffness, double preload,
                       const py::object& law, double share) {
             return Damper(member, coordinate, mass, stiffness, preload, to_law(law), share);
           }),
           py::arg("member"),
           py::arg("contact_coordinate"), py::arg("mass"), py::arg("stiffness"), py::arg("preload"), py::arg("law"),
           py::arg("share") = 1.0)
      .def_readwrite("member", &Damper::member)
      .def_readwrite("contact_coordinate", &Damper::contact_coordinate)
      .def_readwrite("mass", &Damper::mass)
      .def_readwrite("stiffness", &Damper::stiffness)
      .def_readwrite("preload", &Damper::preload)
      .def_readwrite("share", &Damper::share)
      .def_readwrite("side", &Damper::side)
      .def_readwrite("initial_state", &Damper::initial_state)
      .def_readwrite("normal_load", &Damper::normal_load)
      .def_readwrite("contact_point", &Damper::contact_point)
      .def_readwrite("separation", &Damper::separation)
      .def_readwrite("restitution", &Damper::restitution)
      .def_readwrite("landing_speed", &Damper::landing_speed)
      .def_readwrite("start_end", &Damper::start_end)
      .def_readwrite("finish_end", &Damper::finish_end)
      .def_readwrite("wall_restitution", &Damper::wall_restitution);
  using Load = System::Load;
  py::class_<Load>(m, "PointLoad", "A point load F(t) = amplitude sin(omega t + phase) + offset, or time_function(t).")
      .def(py::init([](MemberId member, double coordinate, LoadDirection direction, double amplitude, double omega,
                       double phase, double offset) {
             Load l = Load::harmonic(member, coordinate, direction, amplitude, omega, phase);
             l.offset = offset;
             return l;
           }),
           py::arg("member"), py::arg("coordinate"), py::arg("direction") = LoadDirection::GlobalX,
           py::arg("amplitude") = 0.0, py::arg("omega") = 0.0, py::arg("phase") = 0.0, py::arg("offset") = 0.0)
      .def_static("harmonic", &Load::harmonic, py::arg("member"), py::arg("coordinate"), py::arg("direction"),
                  py::arg("amplitude"), py::arg("omega"), py::arg("phase") = 0.0)
      .def_property(
          "time_function", [](const Load& l) { return l.time_function; },
          [](Load& l, const py::object& f) { l.time_function = python_time_function(f, "PointLoad", "F"); },
          "optional F(t) (a Python callable; slower)")
      .def("value", &Load::value, py::arg("t"));
  using Options = ModelOptions<double>;
  py::class_<Options>(m, "ModelOptions", "What a friction-damped scene models (docs/model.md).")
      .def(py::init<>())
      .def_readwrite("normal_load", &Options::normal_load)
      .def_readwrite("moving_contact", &Options::moving_contact)
      .def_readwrite("convective_terms", &Options::convective_terms)
      .def_readwrite("watch_lift_off", &Options::watch_lift_off)
      .def_readwrite("energy_audit", &Options::energy_audit)
      .def_readwrite("end_policy", &Options::end_policy)
      .def_readwrite("refine_stale_factorisation", &Options::refine_stale_factorisation);
}

/// A FrictionDampedSystem property of a PySystem (pybind11 does not adapt the base's noexcept
/// member functions to the derived class).
template <auto getter>
decltype(auto) system_getter(const PySystem& system) {
  return (static_cast<const System&>(system).*getter)();
}

void bind_system(py::module_& m) {
  py::class_<System::ContactEvent>(m, "ContactEvent", "One damper's contact switch.")
      .def_readonly("t", &System::ContactEvent::t)
      .def_readonly("damper", &System::ContactEvent::damper)
      .def_readonly("from_state", &System::ContactEvent::from)
      .def_readonly("to_state", &System::ContactEvent::to);
  py::class_<System::EnergyBalance>(m, "EnergyBalance", "E(t) - E0 = W_ext - D_visc - D_fric + W_slope - D_imp + residual.")
      .def_readonly("mechanical", &System::EnergyBalance::mechanical)
      .def_readonly("external_work", &System::EnergyBalance::external_work)
      .def_readonly("viscous_dissipation", &System::EnergyBalance::viscous_dissipation)
      .def_readonly("friction_dissipation", &System::EnergyBalance::friction_dissipation)
      .def_readonly("slope_work", &System::EnergyBalance::slope_work)
      .def_readonly("impact_loss", &System::EnergyBalance::impact_loss)
      .def_readonly("residual", &System::EnergyBalance::residual);
  py::enum_<System::StopReason>(m, "StopReason")
      .value("None_", System::StopReason::None)
      .value("LiftOff", System::StopReason::LiftOff)
      .value("LeftMember", System::StopReason::LeftMember)
      .value("NoConsistentState", System::StopReason::NoConsistentState)
      .value("NonFiniteLoad", System::StopReason::NonFiniteLoad);
  // PySystem: the system and the lock of the calls that run or evaluate it (call_guard.hpp).
  py::class_<PySystem>(m, "FrictionDampedSystem",
                       "Frame modes + friction dampers + loads (paper eqs 26-29). Calls that run or evaluate one "
                       "system from several threads run one after the other (docs/python.md).")
      .def(py::init<const FrameModel<double>&, const ModalBasis<double>&, std::vector<System::Damper>,
                    std::vector<System::Load>, const ModelOptions<double>&>(),
           py::arg("frame"), py::arg("basis"), py::arg("dampers"), py::arg("loads") = std::vector<System::Load>{},
           py::arg("options") = ModelOptions<double>{})
      .def_property_readonly("num_modes", &system_getter<&System::num_modes>)
      .def_property_readonly("num_dampers", &system_getter<&System::num_dampers>)
      .def_property_readonly("state_size", &system_getter<&System::state_size>)
      .def_property_readonly("q_offset", &system_getter<&System::q_offset>)
      .def_property_readonly("qd_offset", &system_getter<&System::qd_offset>)
      .def_property_readonly("x_offset", &system_getter<&System::x_offset>)
      .def_property_readonly("xd_offset", &system_getter<&System::xd_offset>)
      .def_property_readonly("contact_offset", &system_getter<&System::contact_offset>)
      .def_property_readonly("flight_offset", &system_getter<&System::flight_offset>)
      .def_property_readonly("num_separable", &system_getter<&System::num_separable>)
      .def_property_readonly("energy_offset", &system_getter<&System::energy_offset>)
      .def_property_readonly("options", &system_getter<&System::options>)
      .def_property_readonly("dampers", &system_getter<&System::dampers>)
      .def_property_readonly("omega_squared", &system_getter<&System::omega_squared>)
      .def("point_shape", &System::point_shape, py::arg("member"), py::arg("coordinate"), py::arg("direction"),
           "Row psi with psi^T q the displacement of the point along `direction`.")
      .def("initial_state", &System::initial_state)
      .def("requested_mode", [](const PySystem& s) { return to_list(s.requested_mode()); })
      .def(
          "make_consistent",
          [](PySystem& s, std::vector<ContactState> mode, double t, State x) {
            Mode md = to_mode(mode);
            const bool ok = with_system(s, [&](SignalCheck&) { return s.make_consistent(md, t, x); });
            return py::make_tuple(ok, to_list(md), x);
          },
          py::arg("mode"), py::arg("t"), py::arg("x"), "(ok, mode, x) made consistent at t.")
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
            d["slope"] = e.slope, d["y"] = e.y;
            return d;
          },
          py::arg("mode"), py::arg("t"), py::arg("x"), "Forces and kinematics of the dampers (dict of arrays).")
      .def(
          "events",
          [](const PySystem& s) { return with_system(s, [&](SignalCheck&) { return s.events(); }); },
          "Contact switches logged since construction or clear_events().")
      .def("clear_events", [](PySystem& s) { with_system(s, [&](SignalCheck&) { s.clear_events(); }); })
      .def_property_readonly(
          "stop_reason", [](const PySystem& s) { return with_system(s, [&](SignalCheck&) { return s.stop_reason(); }); })
      .def_property_readonly(
          "stop_damper", [](const PySystem& s) { return with_system(s, [&](SignalCheck&) { return s.stop_damper(); }); })
      .def(
          "mechanical_energy",
          [](PySystem& s, const std::vector<ContactState>& mode, double t, const State& x) {
            const Mode md = to_mode(mode);
            return with_system(s, [&](SignalCheck&) {
              s.validate_state(md, x, "FrictionDampedSystem.mechanical_energy");
              return s.mechanical_energy(md, t, x);
            });
          },
          py::arg("mode"), py::arg("t"), py::arg("x"))
      .def(
          "energy_balance",
          [](PySystem& s, const std::vector<ContactState>& mode, double t, const State& x, double E0) {
            const Mode md = to_mode(mode);
            return with_system(s, [&](SignalCheck&) {
              s.validate_state(md, x, "FrictionDampedSystem.energy_balance");
              return s.energy_balance(md, t, x, E0);
            });
          },
          py::arg("mode"), py::arg("t"), py::arg("x"), py::arg("E0"));
}

/// Evaluation of a ContactSystem as a dict of arrays.
py::dict to_dict(const CSystem::Evaluation& e) {
  py::dict d;
  d["qdd"] = e.qdd, d["f"] = e.f, d["v"] = e.v, d["N"] = e.N, d["finite"] = e.finite;
  return d;
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
           py::arg("coordinate"))
      .def_readwrite("member", &Point::member, "member the point lies on")
      .def_readwrite("coordinate", &Point::coordinate, "position along the member [m]")
      .def("__repr__", [](const Point& p) {
        return "StructurePoint(member=" + std::to_string(p.member.value) + ", coordinate=" +
               std::string(py::str(py::float_(p.coordinate))) + ")";
      });
  py::class_<Direction>(m, "PlaneDirection",
                        "An in-plane direction (x, y) in global components; a contact needs a unit vector (|d| = 1 "
                        "to 1e-9, checked by ContactSystem: ValueError naming direction).")
      .def(py::init([](double x, double y) { return Direction{x, y}; }), py::arg("x") = 1.0, py::arg("y") = 0.0)
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
           py::arg("value") = 1.0, py::arg("time_function") = py::none())
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
      .def(py::init<>())
      .def_readwrite("energy_audit", &COptions::energy_audit,
                     "carry the audit integrals W_ext, D_visc, D_fric as three extra states (default True)")
      .def_readwrite("velocity_tolerance", &COptions::velocity_tolerance,
                     "|v| [m/s] at or below which v counts as 0 where a contact's state is decided");

  py::class_<PyContactSystem> cls(
      m, "ContactSystem",
      "A frame's retained modes + friction contacts at structure points (PointContact) + point loads: q'' = r + "
      "sum_i w_i f_i with contact rows w_i (s_i = w_i . q) (docs/contacts.md). State [q, q', W_ext, D_visc, "
      "D_fric] (the last three with the energy audit). Calls that run or evaluate one system from several threads "
      "run one after the other (docs/python.md).");
  py::class_<CSystem::ContactEvent>(cls, "ContactEvent", "One contact's switch.")
      .def_readonly("t", &CSystem::ContactEvent::t, "time of the switch [s]")
      .def_readonly("contact", &CSystem::ContactEvent::contact, "which contact switched")
      .def_readonly("from_state", &CSystem::ContactEvent::from, "its state before")
      .def_readonly("to_state", &CSystem::ContactEvent::to, "its state after");
  using Balance = CSystem::EnergyBalance;
  py::class_<Balance>(cls, "EnergyBalance", "The energy audit: (E - E0) - (W_ext - D_visc - D_fric) = residual [J].")
      .def_readonly("mechanical", &Balance::mechanical, "E = q'.q'/2 + sum omega_j^2 q_j^2 / 2 [J]")
      .def_readonly("external_work", &Balance::external_work, "W_ext [J]")
      .def_readonly("viscous_dissipation", &Balance::viscous_dissipation, "D_visc [J]")
      .def_readonly("friction_dissipation", &Balance::friction_dissipation, "D_fric [J]")
      .def_readonly("residual", &Balance::residual, "(E - E0) - (W_ext - D_visc - D_fric) [J]")
      .def_readonly("scale", &Balance::scale, "largest magnitude of the terms [J]")
      .def("relative_residual", &Balance::relative_residual, "|residual| / scale (0 when every term is 0).");
  cls.def(py::init<const FrameModel<double>&, const ModalBasis<double>&, std::vector<Contact>,
                   std::vector<PointLoad<double>>, COptions>(),
          py::arg("frame"), py::arg("basis"), py::arg("contacts"), py::arg("loads") = std::vector<PointLoad<double>>{},
          py::arg("options") = COptions{},
          "Assembles each contact's row from `frame` and `basis` (a basis of that frame). ValueError naming the "
          "contact and the parameter: a side off its member (coordinate), a non-unit direction, a non-positive "
          "normal.value, a contact that cannot slip (zero row), ...")
      .def_property_readonly("num_modes", [](const PyContactSystem& s) { return s.num_modes(); }, "n, retained modes")
      .def_property_readonly("num_contacts", [](const PyContactSystem& s) { return s.num_contacts(); }, "D, contacts")
      .def_property_readonly("state_size", [](const PyContactSystem& s) { return s.state_size(); },
                             "2n (+ 3 with the energy audit)")
      .def_property_readonly("audit_offset", [](const PyContactSystem& s) { return s.audit_offset(); },
                             "index of the first audit integral (W_ext, D_visc, D_fric)")
      .def_property_readonly("contacts", [](const PyContactSystem& s) { return s.contacts(); },
                             "the contacts (copies of the PointContacts)")
      .def_property_readonly("loads", [](const PyContactSystem& s) { return s.loads(); }, "the point loads (copies)")
      .def_property_readonly("options", [](const PyContactSystem& s) { return s.options(); },
                             "the ContactSystemOptions (a copy)")
      .def(
          "contact_row",
          [](const PyContactSystem& s, Index i) {
            if (i < 0 || i >= s.num_contacts())
              detail::throw_invalid("ContactSystem.contact_row",
                                    "i must be in [0, num_contacts() = " + std::to_string(s.num_contacts()) + ")", i);
            return Eigen::VectorXd(s.contact_row(i));
          },
          py::arg("i"), "Row w_i of contact i: its slip s_i = w_i . q [m], v_i = w_i . q' [m/s].")
      .def("initial_state", &PyContactSystem::initial_state, "Rest: q = q' = 0, audit integrals 0.")
      .def("requested_mode", [](const PyContactSystem& s) { return to_list(s.requested_mode()); },
           "Each contact's initial_state.")
      .def(
          "make_consistent",
          [](PyContactSystem& s, std::vector<ContactState> mode, double t, State x) {
            Mode md = to_mode(mode);
            const bool ok = with_system(s, [&](SignalCheck&) {
              s.validate_state(md, x, "ContactSystem.make_consistent");
              return s.make_consistent(md, t, x);
            });
            return py::make_tuple(ok, to_list(md), x);
          },
          py::arg("mode"), py::arg("t"), py::arg("x"),
          "(ok, mode, x) made consistent at t [s]: a contact with |v| above the velocity tolerance slides in sgn(v), "
          "one at rest sticks unless its force exceeds mu_s N; stuck velocities are projected to 0.")
      .def(
          "evaluate",
          [](PyContactSystem& s, const std::vector<ContactState>& mode, double t, const State& x) {
            const Mode md = to_mode(mode);
            const CSystem::Evaluation e = with_system(s, [&](SignalCheck&) {
              s.validate_state(md, x, "ContactSystem.evaluate");
              return s.evaluate(md, t, x);  // a copy, made under the lock
            });
            return to_dict(e);
          },
          py::arg("mode"), py::arg("t"), py::arg("x"),
          "Forces and kinematics at (mode, t, x): dict of qdd, f (friction force on side a along d [N]), v (sliding "
          "velocity [m/s]), N (normal force [N]) and finite.")
      .def(
          "events", [](const PyContactSystem& s) { return with_system(s, [&](SignalCheck&) { return s.events(); }); },
          "The contact switches (ContactSystem.ContactEvent) logged since construction or clear_events().")
      .def("clear_events", [](PyContactSystem& s) { with_system(s, [&](SignalCheck&) { s.clear_events(); }); },
           "Forgets the logged switches.")
      .def(
          "mechanical_energy",
          [](const PyContactSystem& s, const State& x) {
            return with_system(s, [&](SignalCheck&) {
              s.validate_state(s.requested_mode(), x, "ContactSystem.mechanical_energy");
              return s.mechanical_energy(x);
            });
          },
          py::arg("x"), "E = q'.q'/2 + sum omega_j^2 q_j^2 / 2 [J].")
      .def(
          "energy_balance",
          [](const PyContactSystem& s, const State& x, double E0) {
            return with_system(s, [&](SignalCheck&) {
              s.validate_state(s.requested_mode(), x, "ContactSystem.energy_balance");
              return s.energy_balance(x, E0);
            });
          },
          py::arg("x"), py::arg("E0"),
          "The energy audit at x from the start's energy E0 [J] (ValueError when options.energy_audit is off).");
}

/// simulate() for one system type (Py: PySystem or PyContactSystem).
template <class Py>
void def_simulate(py::module_& m, const char* doc) {
  m.def("simulate", &run_simulation<Py>, py::arg("system"), py::arg("t_end"), py::arg("options") = RunOptions<double>{},
        py::arg("t0") = 0.0, py::arg("x0") = py::none(), py::arg("mode") = py::none(),
        py::arg("probes") = std::vector<Probe>{}, py::arg("record_states") = true,
        py::arg("evaluate_from") = std::numeric_limits<double>::infinity(), py::arg("statistics") = py::none(),
        py::arg("consistent") = true, doc);
}

void bind_simulate(py::module_& m) {
  py::enum_<Integrator>(m, "Integrator")
      .value("RungeKutta4", Integrator::RungeKutta4)
      .value("DormandPrince54", Integrator::DormandPrince54)
      .value("Rosenbrock23", Integrator::Rosenbrock23)
      .value("Exponential", Integrator::Exponential);
  py::enum_<EventLocation>(m, "EventLocation")
      .value("DenseRootFinding", EventLocation::DenseRootFinding)
      .value("Bisection", EventLocation::Bisection);
  py::enum_<Status>(m, "Status")
      .value("Success", Status::Success)
      .value("StepSizeUnderflow", Status::StepSizeUnderflow)
      .value("MaxSteps", Status::MaxSteps)
      .value("NonFiniteState", Status::NonFiniteState)
      .value("ZenoGuard", Status::ZenoGuard)
      .value("StoppedByObserver", Status::StoppedByObserver)
      .value("StoppedBySystem", Status::StoppedBySystem);
  m.def("status_name", [](Status s) { return std::string(to_string(s)); }, py::arg("status"));
  py::class_<RunOptions<double>>(m, "RunOptions",
                                 "Integrator (rk4 | dopri5 | rosenbrock23 | exponential) and stepper options; "
                                 "keywords: the StepperOptions fields (docs/ode.md).")
      .def(py::init(&make_run_options), py::arg("integrator") = "dopri5")
      .def_property(
          "integrator", [](const RunOptions<double>& o) { return std::string(to_string(o.integrator)); },
          [](RunOptions<double>& o, const std::string& name) { o.integrator = parse_integrator(name); })
      .def_property(
          "rtol", [](const RunOptions<double>& o) { return o.stepper.rtol; },
          [](RunOptions<double>& o, double v) { o.stepper.rtol = v; })
      .def_property(
          "atol", [](const RunOptions<double>& o) { return o.stepper.atol; },
          [](RunOptions<double>& o, double v) { o.stepper.atol = v; })
      .def_property(
          "fixed_step", [](const RunOptions<double>& o) { return o.stepper.fixed_step; },
          [](RunOptions<double>& o, double v) { o.stepper.fixed_step = v; })
      .def_property(
          "output_interval", [](const RunOptions<double>& o) { return o.stepper.output_interval; },
          [](RunOptions<double>& o, double v) { o.stepper.output_interval = v; })
      .def_readwrite("check_stability_limit", &RunOptions<double>::check_stability_limit);

  py::class_<Probe>(m, "Probe", "A point whose displacement simulate() records: point_shape(member, coordinate, direction)^T q.")
      .def(py::init([](MemberId member, double coordinate, LoadDirection direction) {
             return Probe{member, coordinate, direction};
           }),
           py::arg("member"), py::arg("coordinate"), py::arg("direction") = LoadDirection::GlobalX)
      .def_readonly("member", &Probe::member)
      .def_readonly("coordinate", &Probe::coordinate)
      .def_readonly("direction", &Probe::direction);
  py::class_<StatisticsWindow<double>>(m, "StatisticsWindow", "Window [t_start, t_end] and period of DamperStatistics.")
      .def(py::init([](double t_start, double t_end, double period) {
             return StatisticsWindow<double>{t_start, t_end, period};
           }),
           py::arg("t_start"), py::arg("t_end"), py::arg("period"));
  py::enum_<DamperRegime>(m, "DamperRegime")
      .value("Stick", DamperRegime::Stick)
      .value("StickSlip", DamperRegime::StickSlip)
      .value("GrossSlip", DamperRegime::GrossSlip)
      .value("NotReached", DamperRegime::NotReached)
      .value("IntermittentContact", DamperRegime::IntermittentContact);
  m.def("regime_name", [](DamperRegime r) { return std::string(to_string(r)); }, py::arg("regime"));
  using Stats = DamperWindowStatistics<double>;
  py::class_<Stats>(m, "DamperWindowStatistics", "One damper's statistics over the window (DamperStatistics).")
      .def_readonly("observed_time", &Stats::observed_time)
      .def_readonly("stick_time", &Stats::stick_time)
      .def_readonly("stick_fraction", &Stats::stick_fraction)
      .def_readonly("switches", &Stats::switches)
      .def_readonly("switches_per_period", &Stats::switches_per_period)
      .def_readonly("separated_time", &Stats::separated_time)
      .def_readonly("separated_fraction", &Stats::separated_fraction)
      .def_readonly("bounces", &Stats::bounces)
      .def_readonly("landings", &Stats::landings)
      .def_readonly("wall_impacts", &Stats::wall_impacts)
      .def_readonly("wall_rests", &Stats::wall_rests)
      .def_readonly("wall_time", &Stats::wall_time)
      .def_readonly("regime", &Stats::regime);
  py::class_<StepperStats>(m, "StepperStats")
      .def_readonly("accepted_steps", &StepperStats::accepted_steps)
      .def_readonly("rejected_steps", &StepperStats::rejected_steps)
      .def_readonly("rhs_evaluations", &StepperStats::rhs_evaluations)
      .def_readonly("guard_evaluations", &StepperStats::guard_evaluations)
      .def_readonly("jacobian_evaluations", &StepperStats::jacobian_evaluations)
      .def_readonly("factorisations", &StepperStats::factorisations)
      .def_readonly("events", &StepperStats::events)
      .def_readonly("guard_sample_cuts", &StepperStats::guard_sample_cuts);
  py::class_<Transition>(m, "Transition", "One transition of the run: every damper's state before and after.")
      .def_readonly("t", &Transition::t)
      .def_readonly("from_mode", &Transition::from)
      .def_readonly("to_mode", &Transition::to);

  py::class_<Run>(m, "Run", "The result and histories of simulate().")
      .def_readonly("status", &Run::status)
      .def_property_readonly("ok", [](const Run& r) { return r.status == Status::Success; })
      .def_readonly("message", &Run::message)
      .def_readonly("t", &Run::t, "time reached")
      .def_readonly("x", &Run::x, "state at t")
      .def_readonly("mode", &Run::mode, "contact states at t")
      .def_readonly("stats", &Run::stats)
      .def_readonly("E0", &Run::E0, "mechanical energy at the (consistent) start")
      .def_property_readonly(
          "energy",
          [](const Run& r) -> py::object {
            if (r.energy) return py::cast(*r.energy);
            if (r.contact_energy) return py::cast(*r.contact_energy);
            return py::none();
          },
          "the energy audit at t: an EnergyBalance (a ContactSystem's: ContactSystem.EnergyBalance), None without "
          "the audit")
      .def_readonly("transitions", &Run::transitions)
      .def_readonly("damper_statistics", &Run::statistics)
      .def_property_readonly("sample_t", [](const Run& r) { return py::array_t<double>(py::cast(r.sample_t)); })
      .def_property_readonly("states",
                             [](const Run& r) {
                               const Index n = r.samples.empty() ? r.x.size() : r.samples.front().size();
                               return stack<double>(r.samples, n, [](const State& s, Index c) { return s[c]; });
                             })
      .def_property_readonly("sample_modes",
                             [](const Run& r) {
                               return stack<std::int8_t>(r.sample_modes, static_cast<Index>(r.mode.size()),
                                                         [](const std::vector<ContactState>& s, Index c) {
                                                           return static_cast<std::int8_t>(s[static_cast<std::size_t>(c)]);
                                                         });
                             })
      .def_property_readonly("probes",
                             [](const Run& r) {
                               const Index n = r.probe_values.empty() ? 0 : static_cast<Index>(r.probe_values[0].size());
                               return stack<double>(r.probe_values, n, [](const std::vector<double>& s, Index c) {
                                 return s[static_cast<std::size_t>(c)];
                               });
                             })
      .def_property_readonly("force_t", [](const Run& r) { return py::array_t<double>(py::cast(r.force_t)); })
      .def_property_readonly("forces", [](const Run& r) {
        py::dict d;
        const Index D = static_cast<Index>(r.mode.size());
        const auto get = [](const System::Vector& v, Index c) { return v[c]; };
        d["N"] = stack<double>(r.N, D, get), d["f"] = stack<double>(r.f, D, get), d["V"] = stack<double>(r.V, D, get);
        if (r.y.size() == r.N.size()) {  // a FrictionDampedSystem's run
          d["y"] = stack<double>(r.y, D, get), d["X"] = stack<double>(r.X, D, get);
        }
        return d;
      }, "per sample from evaluate_from on, one column per damper or contact: N, f, V (a ContactSystem's sliding "
         "velocity v) and, for a FrictionDampedSystem, y and X");

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
}

void bind_trade_study(py::module_& m) {
  using Row = TradeRow<double>;
  py::class_<Row>(m, "TradeRow", "One variant's cost and error against the reference.")
      .def_readonly("name", &Row::name)
      .def_readonly("started", &Row::started)
      .def_readonly("status", &Row::status)
      .def_readonly("message", &Row::message)
      .def_readonly("t_reached", &Row::t_reached)
      .def_readonly("cpu_seconds", &Row::cpu_seconds)
      .def_readonly("rhs_evaluations", &Row::rhs_evaluations)
      .def_readonly("events", &Row::events)
      .def_readonly("output_error_max", &Row::output_error_max)
      .def_readonly("output_error_rms", &Row::output_error_rms)
      .def_readonly("switch_time_error", &Row::switch_time_error)
      .def_readonly("missed_switches", &Row::missed_switches)
      .def_readonly("extra_switches", &Row::extra_switches)
      .def_readonly("energy_residual", &Row::energy_residual)
      .def_property_readonly("ok", &Row::ok);
  using Result = TradeStudyResult<double>;
  py::class_<Result>(m, "TradeStudyResult")
      .def_readonly("reference", &Result::reference)
      .def_readonly("validation", &Result::validation)
      .def_readonly("validation_method", &Result::validation_method)
      .def_readonly("rows", &Result::rows);
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
           py::arg("name"), py::arg("setup"), py::arg("run") = RunOptions<double>{})
      .def_readonly("name", &Variant::name);
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
      "Speed/accuracy of each variant against a validated tight reference (docs/model.md); each variant's "
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


/// A periodic orbit of Shooting<System>::forced as Python sees it.
struct PyOrbit {
  ShootingStatus status = ShootingStatus::NoConvergence;
  std::string message;
  double t0 = 0, period = 0, residual = 0;
  int iterations = 0;
  State x0;
  std::vector<ContactState> mode;
  Eigen::MatrixXd monodromy;
  Eigen::VectorXcd multipliers;
  double max_modulus = 0;
  bool stable = false;
  Instability instability = Instability::None;
  Eigen::VectorXd amplitudes;
  std::vector<Transition> events;
  std::vector<double> stick_fractions;  // per damper (orbit_contact_statistics)
  std::vector<int> switches;            // per damper
};

/// The C++ orbit as PyOrbit (no Python objects: callable with the GIL released).
template <class Sys>
PyOrbit to_py(const PeriodicOrbit<Sys>& orbit) {
  PyOrbit out;
  out.status = orbit.status;
  out.message = orbit.message;
  out.t0 = orbit.t0;
  out.period = orbit.period;
  out.residual = orbit.residual;
  out.iterations = orbit.iterations;
  out.x0 = orbit.x0;
  out.mode = to_list(orbit.mode);
  out.monodromy = orbit.monodromy;
  out.multipliers = orbit.floquet.multipliers;
  out.max_modulus = orbit.floquet.max_modulus;
  out.stable = orbit.floquet.stable;
  out.instability = orbit.floquet.instability;
  out.amplitudes = orbit.amplitudes;
  for (const auto& e : orbit.events) out.events.push_back(Transition{e.t, to_list(e.from), to_list(e.to)});
  for (Index i = 0; i < orbit.mode.size(); ++i) {
    const auto c = orbit_contact_statistics(orbit, i);
    out.stick_fractions.push_back(c.stick_fraction);
    out.switches.push_back(c.switches);
  }
  return out;
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

/// The run budget of the steady-state functions: max_steps step attempts per run (> 0).
long checked_max_steps(long max_steps, const std::string& where) {
  if (max_steps <= 0)
    detail::throw_invalid(where, "max_steps must be > 0 (step attempts allowed per run)", max_steps);
  return max_steps;
}

/// The periodic components the steady-state functions compare: `periodic` (ValueError naming it
/// when empty - C++'s "all", here the audit integrals too - or out of range) or by default q,
/// q', x_d, x_d' (the first 2n + 2D), not the contact coordinates X (a neutral direction) nor
/// the audit integrals.
/// The default periodic components: q, q', x_d, x_d' of a FrictionDampedSystem (2n + 2D), q, q' of
/// a ContactSystem (2n).
Index default_periodic_size(const System& system) { return 2 * system.num_modes() + 2 * system.num_dampers(); }
Index default_periodic_size(const CSystem& system) { return 2 * system.num_modes(); }

template <class Sys>
std::vector<Index> periodic_set(const Sys& system, const std::optional<std::vector<Index>>& periodic,
                                const std::string& where) {
  if (!periodic) return ShootingOptions<double>::first(default_periodic_size(system));
  if (periodic->empty())
    throw std::invalid_argument(where + ": periodic must not be empty (None: the default q, q', x_d, x_d')");
  detail::require_indices(where, "periodic", *periodic, system.state_size());
  return *periodic;
}

/// The shooting options of find_periodic_orbit and continue_orbits. Default periodic set: q, q',
/// x_d, x_d' (2n + 2D), i.e. not the contact coordinates X (a neutral direction) nor the energy
/// quadratures (docs/steady_state.md).
template <class Sys>
ShootingOptions<double> shooting_options(const Sys& system, const std::optional<std::vector<Index>>& periodic,
                                         const std::string& monodromy, double tolerance, int max_iterations,
                                         double rtol, double atol, long max_steps, const std::string& where) {
  ShootingOptions<double> opt;
  opt.stepper.rtol = rtol;
  opt.stepper.atol = atol;
  opt.stepper.max_steps = checked_max_steps(max_steps, where);
  opt.tolerance = tolerance;
  opt.max_iterations = max_iterations;
  if (monodromy == "finite_difference") opt.monodromy = MonodromyMethod::FiniteDifference;
  else if (monodromy != "variational")
    throw std::invalid_argument(where + ": monodromy must be 'variational' or 'finite_difference', got '" + monodromy +
                                "'");
  opt.periodic = periodic_set(system, periodic, where);
  return opt;
}

/// One point of continue_orbits' branch.
struct PyContinuationPoint {
  double parameter = 0, step = 0;
  bool stability_changed = false;
  PyOrbit orbit;
};

/// The C++ point as PyContinuationPoint (no Python objects).
PyContinuationPoint to_py(const ContinuationPoint<System>& pt) {
  return PyContinuationPoint{pt.parameter, pt.step, pt.stability_changed, to_py(pt.orbit)};
}

/// The C++ points of a branch as PyContinuationPoints.
std::vector<PyContinuationPoint> to_py(const std::vector<ContinuationPoint<System>>& points) {
  std::vector<PyContinuationPoint> out;
  out.reserve(points.size());
  for (const auto& pt : points) out.push_back(to_py(pt));
  return out;
}

/// One part of continue_orbits(parts = n > 1) (SplitContinuation's ContinuationPart).
struct PyContinuationPart {
  double start_parameter = 0;
  ContinuationStatus status = ContinuationStatus::Completed;
  std::string message;
  std::size_t points = 0, kept = 0;
  bool joined = false;
  double cpu_seconds = 0;
  std::vector<PyContinuationPoint> dropped;  // the part's own points when the branch does not hold them
};

/// What continue_orbits returns.
struct PyContinuation {
  ContinuationStatus status = ContinuationStatus::Completed;
  std::string message;
  std::vector<PyContinuationPoint> points;
  std::vector<PyContinuationPart> parts;  // empty for parts = 1
};

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

/// The Python callables of continue_orbits as Continuation's std::functions. They hold no
/// Python reference (the callables outlive the run: they are continue_orbits' arguments) and
/// re-acquire the GIL, which the run releases; a Python exception propagates as
/// py::error_already_set through Continuation::run (which catches nothing) to the caller.
struct ContinuationCallbacks {
  const py::object* parameter = nullptr;   // parameter(system, p) -> the system at p
  const py::object* period = nullptr;      // a float or period(p)
  const py::object* start_mode = nullptr;  // None or start_mode(system, t, x, mode) -> mode
  const py::object* on_point = nullptr;    // None or on_point(point)
  const py::object* start = nullptr;       // None or start(system, p) -> (mode, t0, x0) (parts > 1)

  // The continued systems are PySystems (continue_orbits' system and its copies for parts > 1),
  // passed to the callables as themselves.
  static py::object as_python(System& system) {
    return py::cast(static_cast<PySystem*>(&system), py::return_value_policy::reference);
  }

  void set(System& system, double p) const {
    py::gil_scoped_acquire gil;
    const py::object r = (*parameter)(as_python(system), p);
    if (!py::isinstance<PySystem>(r))
      throw py::type_error("continue_orbits: parameter(system, p) must return the FrictionDampedSystem at p, got " +
                           std::string(py::str(py::type::of(r).attr("__name__"))));
    const PySystem& next = r.cast<const PySystem&>();
    if (&next == &system) return;
    System copy = copy_of(next);  // under next's lock: another thread may be running it
    if (copy.state_size() != system.state_size() || copy.num_dampers() != system.num_dampers())
      throw std::invalid_argument("continue_orbits: parameter(system, p) returned a system of another state size (" +
                                  std::to_string(copy.state_size()) + " instead of " +
                                  std::to_string(system.state_size()) + ")");
    system = std::move(copy);
  }
  double period_of(double p) const {
    if (!PyCallable_Check(period->ptr())) return period->cast<double>();  // checked by continue_orbits
    py::gil_scoped_acquire gil;
    return cast_as<double>((*period)(p), "continue_orbits: period(p) must return a float");
  }
  Mode mode_of(System& system, double t, const State& x, const Mode& previous) const {
    py::gil_scoped_acquire gil;
    const py::object r = (*start_mode)(as_python(system), t, x, to_list(previous));
    const std::string what = "continue_orbits: start_mode(system, t, x, mode)";
    Mode mode = to_mode(cast_as<std::vector<ContactState>>(r, what + " must return a list of ContactState"));
    system.validate_state(mode, x, what.c_str());
    return mode;
  }
  void point(const ContinuationPoint<System>& pt) const {
    py::gil_scoped_acquire gil;
    (*on_point)(to_py(pt));
  }
  SplitContinuation<System>::Guess guess(System& system, double p) const {
    py::gil_scoped_acquire gil;
    const py::object r = (*start)(as_python(system), p);
    const std::string where = "continue_orbits: start(system, p)", what = where + " must return (mode, t0, x0)";
    const auto t = cast_as<std::tuple<py::object, py::object, py::object>>(r, what);
    SplitContinuation<System>::Guess g{
        to_mode(cast_as<std::vector<ContactState>>(std::get<0>(t), what + " with mode a list of ContactState")),
        cast_as<double>(std::get<1>(t), what + " with t0 a float"),
        cast_as<State>(std::get<2>(t), what + " with x0 a 1-D array of floats")};
    check_start(system, g.mode, g.x0, where);
    return g;
  }
};

/// find_periodic_orbit for one system type (Py: PySystem or PyContactSystem).
template <class Py>
void def_find_periodic_orbit(py::module_& m, const char* doc) {
  using Sys = std::conditional_t<std::is_same_v<Py, PyContactSystem>, CSystem, System>;
  m.def(
      "find_periodic_orbit",
      [](Py& system, double period, double t0, std::optional<State> x0, std::optional<std::vector<ContactState>> mode,
         std::optional<std::vector<Index>> periodic, const std::string& monodromy, double tolerance, int max_iterations,
         double rtol, double atol, long max_steps) {
        return with_system(system, [&](SignalCheck& signals) {
          ShootingOptions<double> opt = shooting_options(system, periodic, monodromy, tolerance, max_iterations, rtol,
                                                         atol, max_steps, "find_periodic_orbit");
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
      py::arg("max_steps") = StepperOptions<double>{}.max_steps, doc);
}

void bind_steady_state(py::module_& m) {
  py::enum_<ShootingStatus>(m, "ShootingStatus")
      .value("Converged", ShootingStatus::Converged)
      .value("NoConvergence", ShootingStatus::NoConvergence)
      .value("ModeNotPeriodic", ShootingStatus::ModeNotPeriodic)
      .value("IntegrationFailed", ShootingStatus::IntegrationFailed)
      .value("SingularJacobian", ShootingStatus::SingularJacobian);
  py::enum_<Instability>(m, "Instability")
      .value("Stable", Instability::None)  // "None" is a Python keyword
      .value("Fold", Instability::Fold)
      .value("PeriodDoubling", Instability::PeriodDoubling)
      .value("NeimarkSacker", Instability::NeimarkSacker);
  py::class_<PyOrbit>(m, "PeriodicOrbit", "A periodic orbit found by shooting (docs/steady_state.md).")
      .def_readonly("status", &PyOrbit::status)
      .def_property_readonly("ok", [](const PyOrbit& o) { return o.status == ShootingStatus::Converged; })
      .def_readonly("message", &PyOrbit::message)
      .def_readonly("t0", &PyOrbit::t0)
      .def_readonly("period", &PyOrbit::period)
      .def_readonly("residual", &PyOrbit::residual, "max |x_i(T) - x_i(0)| over the periodic components")
      .def_readonly("iterations", &PyOrbit::iterations, "orbit runs made")
      .def_readonly("x0", &PyOrbit::x0, "the orbit's state at t0")
      .def_readonly("mode", &PyOrbit::mode, "contact states at t0")
      .def_readonly("monodromy", &PyOrbit::monodromy, "dx_P(T)/dx_P(0) over the periodic components P")
      .def_readonly("multipliers", &PyOrbit::multipliers, "Floquet multipliers")
      .def_readonly("max_modulus", &PyOrbit::max_modulus)
      .def_readonly("stable", &PyOrbit::stable)
      .def_readonly("instability", &PyOrbit::instability)
      .def_readonly("amplitudes", &PyOrbit::amplitudes, "max |x_i| over the orbit (the periodic components)")
      .def_readonly("events", &PyOrbit::events, "the contact switches of one period")
      .def_readonly("stick_fractions", &PyOrbit::stick_fractions, "per damper: time stuck / T")
      .def_readonly("switches", &PyOrbit::switches, "per damper: its contact-state changes in one period");
  def_find_periodic_orbit<PySystem>(
      m,
      "Forced periodic orbit of the given period by shooting from (mode, t0, x0) (default: the system's initial "
      "state), with its monodromy and Floquet multipliers (Shooting::forced, docs/steady_state.md). periodic: the "
      "state indices that must repeat (default: q, q', x_d, x_d', the first 2n + 2D); max_steps: step attempts "
      "allowed per orbit run (a run beyond it fails: IntegrationFailed). The GIL is released; Ctrl-C stops the "
      "call (KeyboardInterrupt).");
  def_find_periodic_orbit<PyContactSystem>(
      m,
      "A ContactSystem's forced periodic orbit, as above; the default periodic components are q, q' (the first "
      "2n), not the audit integrals. stick_fractions and switches are per contact.");

  py::enum_<ContinuationStatus>(m, "ContinuationStatus")
      .value("Completed", ContinuationStatus::Completed)
      .value("MaxPoints", ContinuationStatus::MaxPoints)
      .value("StepTooSmall", ContinuationStatus::StepTooSmall)
      .value("StartFailed", ContinuationStatus::StartFailed)
      .value("Stopped", ContinuationStatus::Stopped)
      .value("Interrupted", ContinuationStatus::Interrupted);
  py::class_<PyContinuationPoint>(m, "ContinuationPoint", "One point of a branch (docs/steady_state.md).")
      .def_readonly("parameter", &PyContinuationPoint::parameter, "the parameter p")
      .def_readonly("step", &PyContinuationPoint::step, "the arclength step that reached it (0 at the start)")
      .def_readonly("stability_changed", &PyContinuationPoint::stability_changed,
                    "the orbit's stability differs from the previous point's")
      .def_readonly("orbit", &PyContinuationPoint::orbit, "the PeriodicOrbit at p");
  py::class_<PyContinuationPart>(m, "BranchPart", "One part of continue_orbits(parts > 1) (SplitContinuation).")
      .def_readonly("start_parameter", &PyContinuationPart::start_parameter, "the parameter of its start orbit")
      .def_readonly("status", &PyContinuationPart::status, "how the part's run ended (Stopped: it joined the next)")
      .def_readonly("message", &PyContinuationPart::message)
      .def_readonly("points", &PyContinuationPart::points, "points the part computed")
      .def_readonly("kept", &PyContinuationPart::kept, "of them in the joined branch")
      .def_readonly("joined", &PyContinuationPart::joined, "its branch ran into the next part's start")
      .def_readonly("cpu_seconds", &PyContinuationPart::cpu_seconds, "CPU time of the part's thread")
      .def_readonly("dropped", &PyContinuationPart::dropped,
                    "its own points when the joined branch does not hold them (an earlier part did not join)");
  py::class_<PyContinuation>(m, "Branch", "A branch computed by continue_orbits.")
      .def_readonly("status", &PyContinuation::status)
      .def_readonly("message", &PyContinuation::message, "why it ended early (empty when Completed)")
      .def_readonly("points", &PyContinuation::points)
      .def_readonly("parts", &PyContinuation::parts, "per part (parts > 1): what it did; empty for one part")
      .def_property_readonly("completed",
                             [](const PyContinuation& c) { return c.status == ContinuationStatus::Completed; })
      .def_property_readonly(
          "parameters",
          [](const PyContinuation& c) {
            std::vector<double> p;
            for (const auto& pt : c.points) p.push_back(pt.parameter);
            return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(p.data(), static_cast<Index>(p.size())));
          },
          "the points' parameters (numpy)");
  m.def(
      "continue_orbits",
      [](PySystem& system, const py::object& parameter, double p0, double p_end, const py::object& period, double t0,
         std::optional<State> x0, std::optional<std::vector<ContactState>> mode,
         std::optional<std::vector<Index>> periodic, const std::string& monodromy, double tolerance, int max_iterations,
         double rtol, double atol, double initial_step, double min_step, double max_step, int max_points,
         int max_corrector_iterations, int fast_iterations, double growth, double section_margin,
         int chord_iterations, const py::object& start_mode, const py::object& on_point, int parts,
         const py::object& start, long max_steps) {
        static const std::string where = "continue_orbits";
        if (parts < 1) detail::throw_invalid(where, "parts must be >= 1", parts);
        if (parts > max_split_parts())
          detail::throw_invalid(where,
                                "parts must be <= " + std::to_string(max_split_parts()) +
                                    " (4 x the hardware threads: each part is a thread and a copy of the system, "
                                    "and the speed-up is at most the number of cores)",
                                parts);
        if (!start.is_none() && !PyCallable_Check(start.ptr()))
          throw std::invalid_argument(where + ": start must be None or a callable start(system, p)");
        if (!PyCallable_Check(parameter.ptr()))
          throw std::invalid_argument(where + ": parameter must be a callable parameter(system, p)");
        if (!PyCallable_Check(period.ptr())) {
          const double T = cast_as<double>(period, where + ": period must be a float or a callable period(p)");
          detail::require_positive(where, "period", T);
        }
        if (!start_mode.is_none() && !PyCallable_Check(start_mode.ptr()))
          throw std::invalid_argument(where + ": start_mode must be None or a callable start_mode(system, t, x, mode)");
        if (!on_point.is_none() && !PyCallable_Check(on_point.ptr()))
          throw std::invalid_argument(where + ": on_point must be None or a callable on_point(point)");
        detail::require_finite(where, "p0", p0);
        detail::require_finite(where, "p_end", p_end);
        if (!(p_end != p0)) detail::throw_invalid(where, "p_end must differ from p0", p_end);
        ContinuationOptions<double> co;
        co.parameter_min = std::min(p0, p_end);
        co.parameter_max = std::max(p0, p_end);
        co.direction = p_end > p0 ? 1 : -1;
        co.initial_step = initial_step;
        co.min_step = min_step;
        co.max_step = max_step;
        co.max_points = max_points;
        co.max_corrector_iterations = max_corrector_iterations;
        co.fast_iterations = fast_iterations;
        co.growth = growth;
        co.section_margin = section_margin;
        co.chord_iterations = chord_iterations;
        const ContinuationCallbacks cb{&parameter, &period, &start_mode, &on_point, &start};
        ShootingOptions<double> opt;
        State x;
        Mode md;
        // parts > 1: the parts run on copies (made under the system's lock, destroyed with the GIL
        // held: a load's Python time_function is copied with them), not on `system`, which is
        // locked again at the end to take part 0's copy (the system at part 0's last point).
        std::vector<PySystem> copies;
        PyContinuation out = with_system(system, [&](SignalCheck& signals) {
          opt = shooting_options(system, periodic, monodromy, tolerance, max_iterations, rtol, atol, max_steps, where);
          x = x0 ? *x0 : system.initial_state();
          md = mode ? to_mode(*mode) : system.requested_mode();
          check_start(system, md, x, where);
          PyContinuation one;
          if (parts > 1) {
            copies.assign(static_cast<std::size_t>(parts), system);
            return one;
          }
          opt.interrupt = [&signals] { return signals(); };
          Continuation<System> cont(
              system, [&cb](System& s, double p) { cb.set(s, p); }, [&cb](double p) { return cb.period_of(p); }, opt,
              co);
          if (!start_mode.is_none())
            cont.start_mode(
                [&cb](System& s, double t, const State& xs, const Mode& prev) { return cb.mode_of(s, t, xs, prev); });
          if (!on_point.is_none()) cont.on_point([&cb](const ContinuationPoint<System>& pt) { cb.point(pt); });
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
          std::vector<System*> systems;
          for (PySystem& c : copies) systems.push_back(&c);
          SplitContinuation<System> split(
              systems, [&cb](System& s, double p) { cb.set(s, p); }, [&cb](double p) { return cb.period_of(p); },
              opt, co);
          if (!start_mode.is_none())
            split.start_mode(
                [&cb](System& s, double t, const State& xs, const Mode& prev) { return cb.mode_of(s, t, xs, prev); });
          if (!on_point.is_none())
            split.on_point([&cb](std::size_t, const ContinuationPoint<System>& pt) { cb.point(pt); });
          const auto result = split.run([&](System& s, double p) {
            if (start.is_none()) return SplitContinuation<System>::Guess{md, t0, x};
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
        with_system(system, [&](SignalCheck&) { static_cast<System&>(system) = copies.front(); });
        return out;
      },
      py::arg("system"), py::arg("parameter"), py::arg("p0"), py::arg("p_end"), py::arg("period"), py::arg("t0") = 0.0,
      py::arg("x0") = py::none(), py::arg("mode") = py::none(), py::arg("periodic") = py::none(),
      py::arg("monodromy") = "variational", py::arg("tolerance") = 1e-9, py::arg("max_iterations") = 30,
      py::arg("rtol") = 1e-10, py::arg("atol") = 1e-12, py::arg("initial_step") = 0.01, py::arg("min_step") = 1e-6,
      py::arg("max_step") = 0.1, py::arg("max_points") = 200, py::arg("max_corrector_iterations") = 8,
      py::arg("fast_iterations") = 3, py::arg("growth") = 1.5, py::arg("section_margin") = 0.0,
      py::arg("chord_iterations") = 0, py::arg("start_mode") = py::none(), py::arg("on_point") = py::none(),
      py::arg("parts") = 1, py::arg("start") = py::none(), py::arg("max_steps") = StepperOptions<double>{}.max_steps,
      "Pseudo-arclength continuation of forced periodic orbits in a parameter p from p0 towards p_end "
      "(Continuation, docs/steady_state.md): parameter(system, p) returns the FrictionDampedSystem at p (it replaces "
      "`system`, which is left at the last point's p); period is the forcing period, a float or period(p). The start "
      "orbit is shot from (mode, t0, x0) (default: the system's initial state). The arclength norm is Euclidean in "
      "(x_P, p): scale p so that both are of order one. section_margin > 0 moves the section t0 away from an "
      "event within that fraction of a period; chord_iterations > 0 lets the corrector first iterate on plain runs "
      "with the last point's Jacobian (ContinuationOptions). parts = n > 1 follows the branch in n parts at once "
      "(SplitContinuation: part k starts at the k-th of n equal cuts of [p0, p_end], on its own thread and a copy "
      "of the system, and the parts are joined where one runs into the next one's start); start(system, p) -> "
      "(mode, t0, x0) gives each part's start guess (default: mode, t0, x0 above), on_point is then called as the "
      "parts find their points (not in branch order) and Branch.parts tells what each part did; parts is at most "
      "4 x the hardware threads. max_steps: step attempts allowed per orbit run. A Python exception raised by a "
      "callable ends the run and propagates. The GIL is released during the run and re-acquired for each "
      "callable; Ctrl-C stops the call (KeyboardInterrupt).");

  py::enum_<PoincareStatus>(m, "PoincareStatus")
      .value("Periodic", PoincareStatus::Periodic)
      .value("NotPeriodic", PoincareStatus::NotPeriodic)
      .value("IntegrationFailed", PoincareStatus::IntegrationFailed)
      .value("Undecided", PoincareStatus::Undecided);
  py::class_<PyPoincare>(m, "PoincareSections", "Poincaré sections of a forced response (docs/steady_state.md).")
      .def_readonly("status", &PyPoincare::status)
      .def_property_readonly("periodic", [](const PyPoincare& p) { return p.status == PoincareStatus::Periodic; })
      .def_readonly("message", &PyPoincare::message, "why a run failed (empty otherwise)")
      .def_readonly("period", &PyPoincare::period, "k of a period-k response, 0 when not periodic")
      .def_readonly("recurrence", &PyPoincare::recurrence,
                    "per k = 1 .. max_period: max_n |x_P(n) - x_P(n - k)| / max_n |x_P(n)| over the record")
      .def_readonly("t0", &PyPoincare::t0, "time of the first section")
      .def_readonly("period_time", &PyPoincare::period_time, "the forcing period T")
      .def_readonly("states", &PyPoincare::states, "the sections x(t0 + nT), one row per n")
      .def_readonly("modes", &PyPoincare::modes, "the contact states at each section");
  m.def(
      "poincare_sections",
      [](PySystem& system, double period, double t0, std::optional<State> x0,
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
          const auto r = poincare_sections(static_cast<System&>(system), md, t0, x, period, opt);
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
      py::arg("max_steps") = StepperOptions<double>{}.max_steps,
      "Poincaré sections of the forced response from (mode, t0, x0) (default: the system's initial state): "
      "transient_periods whole periods, then the state at the next record_periods multiples of `period`, and the "
      "smallest k <= max_period with which they repeat to `tolerance` / 10 (relative, over the components "
      "`periodic`, default q, q', x_d, x_d'; the tolerance at least 100 (rtol + atol / scale)): a period-k "
      "response; within a factor 10 of the tolerance Undecided (period: the candidate k); else not periodic "
      "(quasi-periodic, chaotic or still transient). A periodic section is a guess for find_periodic_orbit with period k T (poincare_sections, "
      "docs/steady_state.md). record_periods is bounded by the record's memory (record_periods x state_size x 16 "
      "bytes <= 1 GiB); max_steps: step attempts allowed per period's run. The GIL is released; Ctrl-C stops the "
      "call (KeyboardInterrupt).");
}

}  // namespace

PYBIND11_MODULE(stickslip, m) {
  m.doc() = "stickslip: dynamics of beam frames damped by dry friction (docs/python.md)";
  m.attr("__version__") = STICKSLIP_VERSION_STRING;
  bind_frame(m);
  bind_dampers(m);
  bind_system(m);
  bind_contacts(m);
  bind_simulate(m);
  bind_trade_study(m);
  bind_steady_state(m);
}
