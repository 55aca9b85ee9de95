// The blade example's preload sweep over MPI ranks (stickslip/sweep/sweep_mpi.hpp): rank 0
// hands out the preloads one at a time, gathers the rows and writes OUT/sweep.csv and
// OUT/sweep.json as `blade_damper --sweep` does (the representatives are chosen, not re-run).
//   mpirun -np 4 blade_sweep_mpi --sweep 0.5:40:32 --duration 20 --out out
// --backend threads|serial runs the same items without MPI ranks (for comparison). Each finished
// row is appended to OUT/sweep.journal as it arrives; --resume runs only the items the journal
// lacks (docs/sweeps.md, "Keeping and resuming").
#include "blade_sweep.hpp"

#include <stickslip/sweep/sweep_journal.hpp>
#include <stickslip/sweep/sweep_mpi.hpp>

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

const char* kHelp = R"(blade_sweep_mpi - the blade example's preload sweep over MPI ranks

Usage: mpirun -np N blade_sweep_mpi [options]
  --sweep lo:hi:count     log-spaced preloads [N] (default 0.5:40:32; linear with --sweep-linear)
  --sweep-linear          linearly spaced preloads
  --sweep-preloads a,b,.. these preloads [N] instead (numbers; one that is not > 0 fails its item only)
  --duration T            simulated time of each run [s], in (0.5, 1000] (default 20)
  --modes n               retained modes (default 6)
  --backend name          mpi (default) | threads | serial
  --threads n             threads of the threads backend (default 0: all cores)
  --out DIR               output folder (default out)
  --resume                keep the rows of OUT/sweep.journal (an earlier run of this sweep that
                          ended early) and run only the other preloads
  --abort-after k         (testing) end the process abruptly once k rows are in the journal, as a
                          killed job would
)";

/// Durations: E is averaged over [T - 1, T - 0.5] s clamped at 0, so a run must last more than
/// 0.5 s to have a window; the runs' step budget (10^8 steps, ~5e4 steps per second of a
/// stick-slip run) lasts ~2000 s, so 1000 s is the longest run a sweep asks for.
constexpr double kMinDuration = 0.5, kMaxDuration = 1000;

struct Options {
  std::vector<double> preloads;
  double duration = 20;
  int modes = 6;
  std::string backend = "mpi";
  unsigned threads = 0;
  std::string out = "out";
  bool resume = false;
  long long abort_after = 0;  ///< > 0: std::_Exit after that many rows are journalled (tests)
  bool help = false;  ///< --help: print the usage (rank 0) and end normally, MPI finalised
};

Options parse(int argc, char** argv) {
  Options o;
  double lo = 0.5, hi = 40;
  int count = 32;
  bool log_spaced = true;
  auto need = [&](int& i) { return blade::next_argument(argc, argv, i); };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      o.help = true;
      return o;
    } else if (a == "--sweep") {
      blade::parse_sweep_range(need(i), lo, hi, count);
    } else if (a == "--sweep-linear") {
      log_spaced = false;
    } else if (a == "--sweep-preloads") {
      o.preloads = blade::parse_list(need(i), "--sweep-preloads");
      if (static_cast<long long>(o.preloads.size()) > blade::kMaxSweepCount)
        throw std::invalid_argument("--sweep-preloads takes at most " + std::to_string(blade::kMaxSweepCount) +
                                    " preloads (each is a run), got " + std::to_string(o.preloads.size()));
    } else if (a == "--duration") {
      o.duration = blade::parse_number(need(i), "--duration");
      if (!(o.duration > kMinDuration && o.duration <= kMaxDuration))
        throw std::invalid_argument("--duration must be in (0.5, 1000] s (E is averaged over [T - 1, T - 0.5] s: a "
                                    "shorter run has no energy window; 1000 s is half the runs' step budget), got " +
                                    blade::fmt(o.duration));
    } else if (a == "--modes") {
      o.modes = static_cast<int>(blade::parse_integer(need(i), "--modes", 1, std::numeric_limits<int>::max(), ""));
    } else if (a == "--resume") {
      o.resume = true;
    } else if (a == "--abort-after") {
      o.abort_after = blade::parse_integer(need(i), "--abort-after", 1, blade::kMaxSweepCount, "");
    } else if (a == "--backend") {
      o.backend = need(i);
      if (o.backend != "mpi" && o.backend != "threads" && o.backend != "serial")
        throw std::invalid_argument("--backend expects mpi, threads or serial, got " + o.backend);
    } else if (a == "--threads") {
      o.threads = static_cast<unsigned>(blade::parse_integer(need(i), "--threads", 0, 1024, "0: all cores"));
    } else if (a == "--out") {
      o.out = need(i);
    } else {
      throw std::invalid_argument("unknown option " + a + " (see --help)");
    }
  }
  if (o.preloads.empty()) o.preloads = blade::sweep_preloads(lo, hi, count, log_spaced);
  return o;
}

/// What the rows of a sweep depend on: the journal's settings line (a journal of other settings
/// is not resumed).
std::string journal_settings(const Options& o) {
  std::string s = "blade_sweep_mpi duration=" + blade::fmt(o.duration) + " modes=" + std::to_string(o.modes) +
                  " preloads=";
  for (std::size_t k = 0; k < o.preloads.size(); ++k) s += (k ? "," : "") + blade::fmt(o.preloads[k]);
  return s;
}

/// Rank 0: the items the journal holds (when resuming) into `outcomes`, and the journal opened
/// for appending the others. Throws std::invalid_argument naming --resume for another sweep's journal.
std::unique_ptr<stickslip::SweepJournal> open_journal(const Options& o, std::vector<stickslip::SweepOutcome>& outcomes,
                                                      std::vector<std::uint64_t>& pending) {
  const std::string path = o.out + "/sweep.journal", settings = journal_settings(o);
  std::vector<std::optional<stickslip::SweepOutcome>> done(o.preloads.size());
  if (o.resume) {
    try {
      done = stickslip::read_sweep_journal(path, settings, o.preloads.size());
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--resume: ") + e.what());
    }
  }
  outcomes.assign(o.preloads.size(), stickslip::SweepOutcome{});
  pending.clear();
  for (std::size_t k = 0; k < done.size(); ++k) {
    if (done[k]) outcomes[k] = *done[k];
    else pending.push_back(k);
  }
  std::filesystem::create_directories(o.out);
  return std::make_unique<stickslip::SweepJournal>(path, settings, o.resume);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  int rc = 0;
  try {
    const Options o = parse(argc, argv);
    if (o.help) {
      if (rank == 0) std::cout << kHelp;
      MPI_Finalize();
      return 0;
    }
    blade::BladeParameters base;
    base.modes = o.modes;
    try {  // the scene once, to name --modes when the frame has fewer modes (every item would fail)
      blade::make_blade_scene(base);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("--modes " + std::to_string(o.modes) + ": " + e.what());
    }
    const blade::RunSettings settings = blade::settings_for_duration(blade::default_settings(), o.duration);
    // Rank 0 reads the journal (--resume) and opens it; the items still to run (pending) go to
    // every rank of the MPI backend (-1: rank 0 failed, and says why).
    std::vector<stickslip::SweepOutcome> outcomes;
    std::vector<std::uint64_t> pending;
    std::unique_ptr<stickslip::SweepJournal> journal;
    std::string failure;
    if (rank == 0) {
      try {
        journal = open_journal(o, outcomes, pending);
      } catch (const std::exception& e) {
        failure = e.what();
      }
    }
    if (o.backend == "mpi") {
      long long n = failure.empty() ? static_cast<long long>(pending.size()) : -1;
      MPI_Bcast(&n, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
      if (n < 0 && rank != 0) throw std::runtime_error("rank 0 could not start the sweep");
      if (n >= 0) {
        pending.resize(static_cast<std::size_t>(n));
        MPI_Bcast(pending.data(), static_cast<int>(n), MPI_UINT64_T, 0, MPI_COMM_WORLD);
      }
    }
    if (!failure.empty()) throw std::invalid_argument(failure);
    const std::size_t kept = o.preloads.size() - pending.size();
    const auto item = [&](std::size_t j) { return blade::sweep_item(base, settings, o.preloads[pending[j]]); };
    // Called on rank 0 (or the one process), one call at a time: the row goes to the journal
    // (flushed) before anything else.
    long long journalled = 0;
    bool journal_failed = false;
    const auto progress = [&](std::size_t done, std::size_t n, std::size_t j, const stickslip::SweepOutcome& out) {
      const std::size_t k = static_cast<std::size_t>(pending[j]);
      try {
        journal->record(k, out);
      } catch (const std::exception& e) {
        if (!journal_failed) std::fprintf(stderr, "\nblade_sweep_mpi: %s (the sweep goes on)\n", e.what());
        journal_failed = true;
      }
      if (o.abort_after > 0 && ++journalled >= o.abort_after) {
        std::fflush(stdout);
        std::_Exit(3);
      }
      blade::print_sweep_progress("sweep", done, n, o.preloads[k], out);
    };
    std::vector<stickslip::SweepOutcome> fresh;
    if (o.backend == "mpi")
      fresh = stickslip::run_sweep_mpi(pending.size(), item, MPI_COMM_WORLD, progress);
    else if (rank == 0)
      fresh = o.backend == "threads" ? stickslip::run_sweep_threads(pending.size(), item, o.threads, progress)
                                     : stickslip::run_sweep_serial(pending.size(), item, progress);
    if (rank == 0)
      for (std::size_t j = 0; j < fresh.size(); ++j) outcomes[static_cast<std::size_t>(pending[j])] = std::move(fresh[j]);
    if (rank == 0) {
      std::printf("blade_sweep_mpi: %zu preloads on %s (%d rank(s)), %g s each", o.preloads.size(),
                  o.backend.c_str(), size, o.duration);
      if (o.resume) std::printf(" (%zu kept from %s/sweep.journal)", kept, o.out.c_str());
      std::printf("\n");
      std::filesystem::create_directories(o.out);
      std::ofstream j(o.out + "/sweep.json");
      blade::write_sweep_files(o.out, o.duration, o.preloads, outcomes, j);
      // The representatives are chosen as blade_damper chooses them (no re-run here).
      std::vector<std::optional<blade::Regime>> regimes;
      for (const auto& p : blade::sweep_points(o.preloads, outcomes)) regimes.push_back(p.common);
      const bool increasing =
          std::adjacent_find(o.preloads.begin(), o.preloads.end(), std::greater_equal<>()) == o.preloads.end();
      const auto chosen = increasing ? blade::choose_representatives(o.preloads, regimes)
                                     : std::vector<blade::Representative>{};  // bands need increasing preloads
      for (std::size_t k = 0; k < chosen.size(); ++k)
        j << (k ? ", " : "") << "{\"regime\": \"" << blade::to_string(chosen[k].regime) << "\", \"preload_N\": "
          << blade::jnum(chosen[k].preload) << "}";
      j << "]\n}\n";
      for (std::size_t k = 0; k < outcomes.size(); ++k)
        if (!outcomes[k].ok) std::fprintf(stderr, "N0 = %g N failed: %s\n", o.preloads[k], outcomes[k].error.c_str());
      if (std::none_of(outcomes.begin(), outcomes.end(), [](const stickslip::SweepOutcome& x) { return x.ok; })) {
        std::fprintf(stderr, "blade_sweep_mpi: every preload failed\n");
        rc = 1;
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "blade_sweep_mpi (rank %d): %s\n", rank, e.what());
    rc = 1;
  }
  MPI_Finalize();
  return rc;
}
