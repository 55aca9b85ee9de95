// Peer benchmark: the stick-slip oscillators of peer_problems.hpp integrated by the
// library (HybridStepper), by Boost.Odeint and by SUNDIALS CVODE, each "as its users write it".
// For each problem x implementation x target final-state error (1e-6, 1e-9) it finds the loosest
// tolerance setting that reaches the target with the reference's event sequence, times it (median
// of repeats, CPU time) and writes peers.csv, peers.json and peers.md to --out.
//
//   peer_benchmark [--out DIR] [--repeats R] [--min-seconds S] [--only NAME,NAME...]
//   (--only: the implementations of implementations() to run, by name; default all)

#include <stickslip/ode.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "peers/peer_cvode.hpp"
#include "peers/peer_library.hpp"
#include "peers/peer_odeint.hpp"
#include "peers/peer_problems.hpp"
#include "peers/peer_reference.hpp"
#include "peers/peer_run.hpp"

namespace peers {
namespace {

/// The implementations compared. Hook: the lead adds the library's modal-exact method here.
std::vector<Implementation> implementations() {
  return {
      {"library_dormand_prince54", "library", &run_library<stickslip::DormandPrince54>},
      {"library_rosenbrock23", "library", &run_library<stickslip::Rosenbrock23>},
      {"library_modal_exact", "library", &run_library<ModalExact>},
      {"odeint_dopri5", "odeint", &run_odeint},
      {"cvode_adams", "cvode", &run_cvode},
  };
}

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// ---------------------------------------------------------------- reference validation

/// Events `a` against `b`: same number and kinds (from -> to), largest time difference over the
/// common prefix.
struct SequenceComparison {
  bool matches = true;
  double max_time_error = 0;
  long compared = 0;
};

SequenceComparison compare_events(const std::vector<Event>& a, const std::vector<Event>& b) {
  SequenceComparison c;
  c.matches = a.size() == b.size();
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    c.matches = c.matches && a[i].from == b[i].from && a[i].to == b[i].to;
    c.max_time_error = std::max(c.max_time_error, std::abs(a[i].t - b[i].t));
    ++c.compared;
  }
  return c;
}

struct Validation {
  std::string problem, against;
  double event_time_error = 0, state_error = 0;
  long events_compared = 0;
  bool sequence_matches = true;
};

// Closed form of the belt problem (m = k = N = 1, from stick at x = 0 with v = v_b): stick until
// x = mu_s; each slip is a half circle about x = mu_k of radius sqrt(a^2 + v_b^2), a = mu_s -
// mu_k, lasting 2 pi - 2 atan(a / v_b) and ending at x = mu_k - a; the next stick lasts 2a / v_b.
Validation validate_belt(const ChainParameters& p, const ReferenceSolution& ref) {
  Validation v{p.name, "closed-form stick-slip cycle"};
  const double vb = p.belt_speed, a = p.mu_s - p.mu_k;
  const double slip = 2.0 * kPi - 2.0 * std::atan(a / vb), stick = 2.0 * a / vb;
  double t = p.mu_s / vb;  // first stick: x from 0 to mu_s
  std::vector<Event> exact;
  Eigen::Vector2d final_state;
  bool sticking = true;
  double start = 0.0;
  while (t < p.t_end) {
    exact.push_back({t, sticking ? ContactState::Stick : ContactState::SlipNegative,
                     sticking ? ContactState::SlipNegative : ContactState::Stick});
    start = t;
    sticking = !sticking;
    t += sticking ? stick : slip;
  }
  const double tau = p.t_end - start;
  if (exact.empty()) {
    final_state = {vb * p.t_end, vb};
  } else if (sticking) {
    final_state = {p.mu_k - a + vb * tau, vb};
  } else {  // y = x - mu_k = a cos tau + v_b sin tau
    final_state = {p.mu_k + a * std::cos(tau) + vb * std::sin(tau),
                   -a * std::sin(tau) + vb * std::cos(tau)};
  }
  const SequenceComparison c = compare_events(exact, ref.events);
  v.sequence_matches = c.matches;
  v.event_time_error = c.max_time_error;
  v.events_compared = c.compared;
  v.state_error = (ref.final_state - final_state).cwiseAbs().maxCoeff();
  return v;
}

// Den Hartog's non-stop motion: reversals at t = k pi / omega, alternating slip directions, the
// closed-form state DenHartogSteadyState::state(t_end).
Validation validate_den_hartog(const ChainParameters& p, const ReferenceSolution& ref) {
  Validation v{p.name, "Den Hartog closed-form non-stop steady state"};
  const DenHartogSteadyState ss(p.force_amplitude[0], p.force_frequency, p.mu_k * p.normal_force);
  const double half = kPi / p.force_frequency;
  std::vector<Event> exact;
  for (long k = 1; static_cast<double>(k) * half < p.t_end; ++k) {
    const bool odd = k % 2 == 1;  // the slip that ends at reversal k is positive for odd k
    exact.push_back({static_cast<double>(k) * half,
                     odd ? ContactState::SlipPositive : ContactState::SlipNegative,
                     odd ? ContactState::SlipNegative : ContactState::SlipPositive});
  }
  const SequenceComparison c = compare_events(exact, ref.events);
  v.sequence_matches = c.matches;
  v.event_time_error = c.max_time_error;
  v.events_compared = c.compared;
  v.state_error = (ref.final_state - ss.state(p.t_end)).cwiseAbs().maxCoeff();
  return v;
}

// No closed form: the reference against itself with a 4x finer sample spacing (catches a
// missed pair of crossings inside one sample interval; not an independent check).
Validation validate_self(const ChainParameters& p, const ReferenceSolution& ref) {
  Validation v{p.name, "reference with 4x finer sampling (self-consistency only)"};
  ReferenceOptions fine;
  fine.sample /= 4.0;
  const ReferenceSolution r = solve_reference(p, fine);
  const SequenceComparison c = compare_events(r.events, ref.events);
  v.sequence_matches = c.matches;
  v.event_time_error = c.max_time_error;
  v.events_compared = c.compared;
  v.state_error = (ref.final_state - r.final_state).cwiseAbs().maxCoeff();
  return v;
}

Validation validate(const ChainParameters& p, const ReferenceSolution& ref) {
  if (p.name == "belt") return validate_belt(p, ref);
  if (p.name == "den_hartog_nonstop") return validate_den_hartog(p, ref);
  return validate_self(p, ref);
}

// ---------------------------------------------------------------- sweep and timing

struct Check {
  bool pass = false;
  bool sequence_matches = false;
  double final_error = std::numeric_limits<double>::infinity();
  double event_time_error = std::numeric_limits<double>::infinity();
};

Check check(const RunOutcome& r, const ReferenceSolution& ref, double target) {
  Check c;
  if (!r.ok) return c;
  const SequenceComparison e = compare_events(r.events, ref.events);
  c.sequence_matches = e.matches;
  c.event_time_error = e.matches ? e.max_time_error : std::numeric_limits<double>::infinity();
  c.final_error = (r.final_state - ref.final_state).cwiseAbs().maxCoeff();
  c.pass = c.sequence_matches && c.final_error <= target;
  return c;
}

struct Row {
  std::string problem, implementation, family;
  double target = 0, setting = std::numeric_limits<double>::quiet_NaN();
  bool reached = false;
  double cpu_seconds = std::numeric_limits<double>::quiet_NaN();
  long rhs_evaluations = 0, steps = 0, events = 0;
  long event_state_rhs = -1, restart_rhs = -1;  // RunOutcome's (library HybridStepper only)
  double final_error = std::numeric_limits<double>::quiet_NaN();
  double event_time_error = std::numeric_limits<double>::quiet_NaN();
  double ratio_odeint = std::numeric_limits<double>::quiet_NaN();
  double ratio_cvode = std::numeric_limits<double>::quiet_NaN();
  std::string note{};
};

// Tolerance grid 10^-3, 10^-3.5, ..., 10^-13 (loose to tight). A setting counts when it and the
// next tighter one both pass (one lucky cancellation of errors does not set the result). A
// sweep stops once a single run costs more than kSweepBudget CPU seconds.
constexpr double kSweepBudget = 3.0;

std::vector<double> tolerance_grid() {
  std::vector<double> g;
  for (int k = 6; k <= 26; ++k) g.push_back(std::pow(10.0, -0.5 * static_cast<double>(k)));
  return g;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Median over `repeats` of the CPU time per run, each repeat running until min_seconds.
double time_run(const Implementation& impl, const ChainParameters& p, double tol, int repeats,
                double min_seconds) {
  std::vector<double> per_run;
  for (int r = 0; r < repeats; ++r) {
    long runs = 0;
    const double start = cpu_seconds();
    double elapsed = 0;
    do {
      const RunOutcome o = impl.run(p, tol);
      if (!o.ok) throw std::runtime_error("a timed run failed: " + o.message);
      ++runs;
      elapsed = cpu_seconds() - start;
    } while (elapsed < min_seconds);
    per_run.push_back(elapsed / static_cast<double>(runs));
  }
  return median(per_run);
}

Row measure(const Implementation& impl, const ChainParameters& p, const ReferenceSolution& ref,
            double target, int repeats, double min_seconds) {
  Row row{p.name, impl.name, impl.family, target};
  const auto grid = tolerance_grid();
  std::vector<Check> checks;
  std::vector<RunOutcome> outcomes;
  std::size_t chosen = grid.size();
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const double t0 = cpu_seconds();
    outcomes.push_back(impl.run(p, grid[i]));
    const double cost = cpu_seconds() - t0;
    checks.push_back(check(outcomes.back(), ref, target));
    if (i >= 1 && checks[i - 1].pass && checks[i].pass) {
      chosen = i - 1;
      break;
    }
    if (cost > kSweepBudget) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "sweep stopped at rtol=atol=%.1e (run cost %.2f s)", grid[i],
                    cost);
      row.note = buf;
      break;
    }
  }
  if (chosen == grid.size()) {
    if (row.note.empty()) row.note = "target not reached down to rtol=atol=1e-13";
    const RunOutcome& last = outcomes.back();
    char buf[160];
    std::snprintf(buf, sizeof buf, "; tightest run: %s, %zu of %zu events, final error %.2e",
                  last.ok ? "ok" : last.message.c_str(), last.events.size(), ref.events.size(),
                  checks.back().final_error);
    row.note += buf;
    return row;
  }
  const RunOutcome& o = outcomes[chosen];
  row.reached = true;
  row.setting = grid[chosen];
  row.rhs_evaluations = o.rhs_evaluations;
  row.steps = o.steps;
  row.events = static_cast<long>(o.events.size());
  row.event_state_rhs = o.event_state_rhs;
  row.restart_rhs = o.restart_rhs;
  row.final_error = checks[chosen].final_error;
  row.event_time_error = checks[chosen].event_time_error;
  row.cpu_seconds = time_run(impl, p, row.setting, repeats, min_seconds);
  return row;
}

// ---------------------------------------------------------------- output

std::string machine_description() {
  std::ifstream cpu("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  long cores = 0;
  while (std::getline(cpu, line)) {
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      ++cores;
    }
  }
  std::ostringstream s;
  s << model << ", " << cores << " logical CPUs, gcc " << __VERSION__;
  return s.str();
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return buf;
}

std::string num(double x) {
  if (std::isnan(x)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

std::string ratio_text(double r) {
  if (std::isnan(r)) return "–";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", r);
  return buf;
}

void write_outputs(const std::string& dir, const std::vector<Row>& rows,
                   const std::vector<Validation>& validations,
                   const std::vector<ChainParameters>& problems, const std::string& when,
                   const std::string& machine, int repeats) {
  std::ofstream csv(dir + "/peers.csv");
  csv << "problem,implementation,family,target,reached,setting,cpu_seconds,rhs_evaluations,steps,"
         "events,final_error,max_event_time_error,time_over_odeint,time_over_cvode,note\n";
  for (const auto& r : rows)
    csv << r.problem << ',' << r.implementation << ',' << r.family << ',' << num(r.target) << ','
        << (r.reached ? 1 : 0) << ',' << num(r.setting) << ',' << num(r.cpu_seconds) << ','
        << r.rhs_evaluations << ',' << r.steps << ',' << r.events << ',' << num(r.final_error)
        << ',' << num(r.event_time_error) << ',' << num(r.ratio_odeint) << ','
        << num(r.ratio_cvode) << ",\"" << r.note << "\"\n";

  std::ofstream js(dir + "/peers.json");
  js << "{\n  \"date\": \"" << when << "\",\n  \"machine\": \"" << machine
     << "\",\n  \"repeats\": " << repeats << ",\n  \"problems\": [\n";
  for (std::size_t i = 0; i < problems.size(); ++i)
    js << "    {\"name\": \"" << problems[i].name << "\", \"description\": \""
       << problems[i].description << "\", \"t_end\": " << problems[i].t_end << "}"
       << (i + 1 < problems.size() ? ",\n" : "\n");
  js << "  ],\n  \"reference_validation\": [\n";
  for (std::size_t i = 0; i < validations.size(); ++i) {
    const auto& v = validations[i];
    js << "    {\"problem\": \"" << v.problem << "\", \"against\": \"" << v.against
       << "\", \"events_compared\": " << v.events_compared << ", \"sequence_matches\": "
       << (v.sequence_matches ? "true" : "false")
       << ", \"max_event_time_error\": " << num(v.event_time_error)
       << ", \"final_state_error\": " << num(v.state_error) << "}"
       << (i + 1 < validations.size() ? ",\n" : "\n");
  }
  js << "  ],\n  \"rows\": [\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    js << "    {\"problem\": \"" << r.problem << "\", \"implementation\": \"" << r.implementation
       << "\", \"family\": \"" << r.family << "\", \"target\": " << num(r.target)
       << ", \"reached\": " << (r.reached ? "true" : "false") << ", \"setting\": "
       << num(r.setting) << ", \"cpu_seconds\": " << num(r.cpu_seconds)
       << ", \"rhs_evaluations\": " << r.rhs_evaluations << ", \"steps\": " << r.steps
       << ", \"events\": " << r.events << ", \"final_error\": " << num(r.final_error)
       << ", \"max_event_time_error\": " << num(r.event_time_error)
       << ", \"time_over_odeint\": " << num(r.ratio_odeint)
       << ", \"time_over_cvode\": " << num(r.ratio_cvode) << ", \"note\": \"" << r.note << "\"}"
       << (i + 1 < rows.size() ? ",\n" : "\n");
  }
  js << "  ]\n}\n";

  std::ofstream md(dir + "/peers.md");
  md << "Run " << when << " on " << machine << "; CPU time per run, median of " << repeats
     << " repeats.\n\n";
  md << "| problem | target | implementation | rtol = atol | CPU time | RHS evals | steps | events "
        "| final error | time / odeint | time / CVODE |\n";
  md << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    char t[32];
    if (r.reached) {
      std::snprintf(t, sizeof t, "%.3g ms", 1e3 * r.cpu_seconds);
    } else {
      std::snprintf(t, sizeof t, "not reached");
    }
    md << "| " << r.problem << " | " << num(r.target) << " | " << r.implementation << " | "
       << (r.reached ? num(r.setting) : "–") << " | " << t << " | "
       << (r.reached ? std::to_string(r.rhs_evaluations) : "–") << " | "
       << (r.reached ? std::to_string(r.steps) : "–") << " | "
       << (r.reached ? std::to_string(r.events) : "–") << " | "
       << (r.reached ? num(r.final_error) : "–") << " | " << ratio_text(r.ratio_odeint) << " | "
       << ratio_text(r.ratio_cvode) << " |\n";
  }
  md << "\nReference validation:\n\n| problem | against | events | sequence | max event-time "
        "error | final-state error |\n|---|---|---|---|---|---|\n";
  for (const auto& v : validations)
    md << "| " << v.problem << " | " << v.against << " | " << v.events_compared << " | "
       << (v.sequence_matches ? "matches" : "DIFFERS") << " | " << num(v.event_time_error)
       << " s | " << num(v.state_error) << " |\n";
}

int run_main(int argc, char** argv) {
  std::string out = "build/peers-out";
  int repeats = 5;
  double min_seconds = 0.02;
  std::string only;  // comma-separated implementation names; empty: all
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--out" && i + 1 < argc) {
      out = argv[++i];
    } else if (a == "--repeats" && i + 1 < argc) {
      repeats = std::stoi(argv[++i]);
    } else if (a == "--min-seconds" && i + 1 < argc) {
      min_seconds = std::stod(argv[++i]);
    } else if (a == "--only" && i + 1 < argc) {
      only = argv[++i];
    } else {
      std::fprintf(stderr, "usage: peer_benchmark [--out DIR] [--repeats R] [--min-seconds S] "
                           "[--only NAME,NAME...]\n");
      return 2;
    }
  }
  if (repeats < 1) throw std::invalid_argument("peer_benchmark: --repeats must be >= 1");
  const std::string when = utc_now(), machine = machine_description();
  const auto problems = make_problems();
  std::vector<Implementation> impls;
  for (const auto& impl : implementations())
    if (only.empty() || ("," + only + ",").find("," + std::string(impl.name) + ",") != std::string::npos)
      impls.push_back(impl);
  if (impls.empty()) throw std::invalid_argument("peer_benchmark: --only names no implementation");
  std::vector<Row> rows;
  std::vector<Validation> validations;
  for (const auto& p : problems) {
    const double t0 = cpu_seconds();
    const ReferenceSolution ref = solve_reference(p);
    std::printf("%s: reference %zu events, %.2f s CPU\n", p.name.c_str(), ref.events.size(),
                cpu_seconds() - t0);
    validations.push_back(validate(p, ref));
    const auto& v = validations.back();
    std::printf("  validation against %s: sequence %s, max event-time error %.2e s, final-state "
                "error %.2e\n",
                v.against.c_str(), v.sequence_matches ? "matches" : "DIFFERS", v.event_time_error,
                v.state_error);
    for (double target : {1e-6, 1e-9}) {
      const std::size_t first = rows.size();
      for (const auto& impl : impls) {
        rows.push_back(measure(impl, p, ref, target, repeats, min_seconds));
        const Row& r = rows.back();
        std::printf("  %-26s target %.0e: %s rtol=atol=%.1e, %.3g ms, %ld RHS, error %.2e %s\n",
                    r.implementation.c_str(), target, r.reached ? "reached" : "NOT reached",
                    r.setting, 1e3 * r.cpu_seconds, r.rhs_evaluations, r.final_error,
                    r.note.c_str());
        if (r.reached && r.event_state_rhs >= 0)
          std::printf("    %ld steps, %ld events: %ld RHS for event states, %ld for restarts\n",
                      r.steps, r.events, r.event_state_rhs, r.restart_rhs);
        std::fflush(stdout);
      }
      auto family_time = [&](const char* fam) {
        for (std::size_t i = first; i < rows.size(); ++i)
          if (rows[i].family == fam) return rows[i].cpu_seconds;
        return std::numeric_limits<double>::quiet_NaN();
      };
      const double odeint = family_time("odeint"), cvode = family_time("cvode");
      for (std::size_t i = first; i < rows.size(); ++i) {
        if (rows[i].family != "library") continue;
        rows[i].ratio_odeint = rows[i].cpu_seconds / odeint;
        rows[i].ratio_cvode = rows[i].cpu_seconds / cvode;
      }
    }
  }
  write_outputs(out, rows, validations, problems, when, machine, repeats);
  std::printf("peer_benchmark: wrote %s/peers.csv, peers.json, peers.md\n", out.c_str());
  // The reference must be two orders of magnitude below the tightest target (1e-9) to rank
  // anything at that target: event times and final states within 1e-11.
  for (const auto& v : validations) {
    if (!v.sequence_matches || !(v.event_time_error <= 1e-11) || !(v.state_error <= 1e-11)) {
      std::fprintf(stderr, "peer_benchmark: reference validation FAILED for %s\n", v.problem.c_str());
      return 3;
    }
  }
  return 0;
}

}  // namespace
}  // namespace peers

int main(int argc, char** argv) {
  try {
    return peers::run_main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "peer_benchmark: %s\n", e.what());
    return 1;
  }
}
