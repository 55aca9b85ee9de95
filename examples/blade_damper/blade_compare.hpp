#pragma once
/// \file blade_compare.hpp
/// \brief `blade_damper --compare`: the speed/accuracy trade of model and integrator variants on
/// the blade scene, through the library's trade_study() (stickslip/model/trade_study.hpp).

#include "blade_scene.hpp"

#include <stickslip/stickslip.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace blade {

/// One variant of the comparison: the scene parameters and run options it changes.
struct CompareVariant {
  std::string name;                      ///< the spec as given, e.g. "integrator=rk4:1e-4"
  BladeParameters params;                ///< the base scene with the variant's change
  stickslip::RunOptions<double> run;     ///< the base run options with the variant's change
};

/// Applies one spec to (params, run): modes=N, rtol=R (atol = 1e-3 R), regularised=V,
/// constant-normal-load, fixed-contact, events=root|bisection, damping=Z,
/// elements=BLADE:PLATFORM, integrator=NAME[:X] (X: the step of rk4 or the rtol of the others).
/// Throws std::invalid_argument naming the spec.
inline CompareVariant parse_compare_variant(const std::string& spec, const BladeParameters& base,
                                            const stickslip::RunOptions<double>& base_run) {
  using namespace stickslip;
  CompareVariant v{spec, base, base_run};
  const auto eq = spec.find('=');
  const std::string key = spec.substr(0, eq);
  const std::string value = eq == std::string::npos ? std::string() : spec.substr(eq + 1);
  auto number = [&](const std::string& s) {
    std::size_t used = 0;
    double x = 0;
    try {
      x = std::stod(s, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != s.size() || !std::isfinite(x))
      throw std::invalid_argument("--compare: variant \"" + spec + "\": \"" + s + "\" is not a number");
    return x;
  };
  auto need_value = [&] {
    if (value.empty()) throw std::invalid_argument("--compare: variant \"" + spec + "\" needs a value (" + key + "=...)");
  };
  if (key == "modes") {
    need_value();
    v.params.modes = static_cast<int>(number(value));
  } else if (key == "rtol") {
    need_value();
    v.run.stepper.rtol = number(value);
    v.run.stepper.atol = 1e-3 * v.run.stepper.rtol;
  } else if (key == "regularised") {
    need_value();
    v.params.regularised_v_eps = number(value);
  } else if (key == "constant-normal-load" && value.empty()) {
    v.params.model.normal_load = NormalLoad::Constant;
  } else if (key == "fixed-contact" && value.empty()) {
    v.params.model.moving_contact = false;
  } else if (key == "damping") {
    need_value();
    v.params.damping_ratio = number(value);
  } else if (key == "events") {
    if (value == "root") v.run.stepper.event_location = EventLocation::DenseRootFinding;
    else if (value == "bisection") v.run.stepper.event_location = EventLocation::Bisection;
    else throw std::invalid_argument("--compare: variant \"" + spec + "\": events must be root or bisection");
  } else if (key == "elements") {
    const auto colon = value.find(':');
    if (colon == std::string::npos)
      throw std::invalid_argument("--compare: variant \"" + spec + "\": elements=BLADE:PLATFORM");
    v.params.blade_elements = static_cast<int>(number(value.substr(0, colon)));
    v.params.platform_elements = static_cast<int>(number(value.substr(colon + 1)));
    if (v.params.platform_elements % 2 != 0)
      throw std::invalid_argument("--compare: variant \"" + spec + "\": the platform needs an even number of elements");
  } else if (key == "integrator") {
    need_value();
    const auto colon = value.find(':');
    v.run.integrator = parse_integrator(value.substr(0, colon));
    if (colon != std::string::npos) {
      const double x = number(value.substr(colon + 1));
      if (v.run.integrator == Integrator::RungeKutta4) {
        v.run.stepper.fixed_step = x;
      } else {
        v.run.stepper.rtol = x;
        v.run.stepper.atol = 1e-3 * x;
      }
    }
  } else {
    throw std::invalid_argument("--compare: unknown variant \"" + spec +
                                "\" (modes=, rtol=, regularised=, constant-normal-load, fixed-contact, "
                                "events=, damping=, elements=B:P, integrator=NAME[:X])");
  }
  return v;
}

/// Splits "a,b,c" into variants of (base, base_run).
inline std::vector<CompareVariant> parse_compare_list(const std::string& list, const BladeParameters& base,
                                                      const stickslip::RunOptions<double>& base_run) {
  std::vector<CompareVariant> out;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(parse_compare_variant(item, base, base_run));
  if (out.empty()) throw std::invalid_argument("--compare needs at least one variant");
  return out;
}

/// The trade-study variant of a scene: builds the blade scene of `params` from rest, dampers in
/// their consistent initial states (as run_scene does).
inline stickslip::TradeVariant<BladeScene::System> trade_variant(std::string name, const BladeParameters& params,
                                                                 const stickslip::RunOptions<double>& run) {
  using System = BladeScene::System;
  stickslip::TradeVariant<System> v;
  v.name = std::move(name);
  v.run = run;
  v.setup = [params]() {
    BladeScene scene = make_blade_scene(params);
    System& sys = *scene.system;
    auto x0 = sys.initial_state();
    auto mode = sys.requested_mode();
    if (!sys.make_consistent(mode, 0.0, x0))
      throw std::runtime_error("inconsistent or lifted-off initial contact state at t = 0");
    return stickslip::TradeSetup<System>{std::move(sys), std::move(mode), std::move(x0)};
  };
  return v;
}

/// Options of the blade comparison: the compared output is the blade tip's lateral (global X)
/// displacement; the energy residual is the audit's closing error at the end of the run relative
/// to its largest term (NaN without the audit). Runs start from rest, where E0 = 0.
inline stickslip::TradeStudyOptions<BladeScene::System> compare_options(const BladeParameters& base, double duration,
                                                                       double sample_interval, int repeats) {
  using System = BladeScene::System;
  stickslip::TradeStudyOptions<System> o;
  o.t0 = 0;
  o.t_end = duration;
  o.output_interval = sample_interval;
  o.repeats = repeats;
  const double L1 = base.L1;
  o.output = [L1](const System& sys, double, const System::State& x) {
    // Member 1 is the blade (make_blade_scene adds the platform first); it carries the load.
    return sys.point_shape(1, L1, stickslip::LoadDirection::GlobalX).dot(x.head(sys.num_modes()));
  };
  o.energy_residual = [](System& sys, const stickslip::SimulationResult<System>& r) {
    if (!sys.options().energy_audit) return std::numeric_limits<double>::quiet_NaN();
    return sys.energy_balance(r.mode, r.t, r.x, 0.0).relative_residual();
  };
  return o;
}

}  // namespace blade
