// The blade example's preload sweep over MPI ranks (stickslip/sweep/sweep_mpi.hpp): rank 0
// hands out the preloads one at a time, gathers the rows and writes OUT/sweep.csv and
// OUT/sweep.json as `blade_damper --sweep` does (the representatives are chosen, not re-run).
//   mpirun -np 4 blade_sweep_mpi --sweep 0.5:40:32 --duration 20 --out out
// --backend threads|serial runs the same items without MPI ranks (for comparison).
#include "blade_sweep.hpp"

#include <stickslip/sweep/sweep_mpi.hpp>

#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

const char* kHelp = R"(blade_sweep_mpi - the blade example's preload sweep over MPI ranks

Usage: mpirun -np N blade_sweep_mpi [options]
  --sweep lo:hi:count     log-spaced preloads [N] (default 0.5:40:32; linear with --sweep-linear)
  --sweep-linear          linearly spaced preloads
  --sweep-preloads a,b,.. these preloads [N] instead (any values: a bad one fails its item only)
  --duration T            simulated time of each run [s] (default 20)
  --modes n               retained modes (default 6)
  --backend name          mpi (default) | threads | serial
  --threads n             threads of the threads backend (default: all cores)
  --out DIR               output folder (default out)
)";

struct Options {
  std::vector<double> preloads;
  double duration = 20;
  int modes = 6;
  std::string backend = "mpi";
  unsigned threads = 0;
  std::string out = "out";
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
      o.preloads = blade::parse_list(need(i));
    } else if (a == "--duration") {
      o.duration = std::stod(need(i));
    } else if (a == "--modes") {
      o.modes = std::stoi(need(i));
    } else if (a == "--backend") {
      o.backend = need(i);
      if (o.backend != "mpi" && o.backend != "threads" && o.backend != "serial")
        throw std::invalid_argument("--backend expects mpi, threads or serial, got " + o.backend);
    } else if (a == "--threads") {
      o.threads = static_cast<unsigned>(std::stoi(need(i)));
    } else if (a == "--out") {
      o.out = need(i);
    } else {
      throw std::invalid_argument("unknown option " + a + " (see --help)");
    }
  }
  if (!(o.duration > 0)) throw std::invalid_argument("--duration must be > 0");
  if (o.preloads.empty()) o.preloads = blade::sweep_preloads(lo, hi, count, log_spaced);
  return o;
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
    const blade::RunSettings settings = blade::settings_for_duration(blade::default_settings(), o.duration);
    const auto item = [&](std::size_t k) { return blade::sweep_item(base, settings, o.preloads[k]); };
    const auto progress = [&](std::size_t done, std::size_t n, std::size_t k, const stickslip::SweepOutcome& out) {
      blade::print_sweep_progress("sweep", done, n, o.preloads[k], out);
    };
    std::vector<stickslip::SweepOutcome> outcomes;
    if (o.backend == "mpi")
      outcomes = stickslip::run_sweep_mpi(o.preloads.size(), item, MPI_COMM_WORLD, progress);
    else if (rank == 0)
      outcomes = o.backend == "threads" ? stickslip::run_sweep_threads(o.preloads.size(), item, o.threads, progress)
                                        : stickslip::run_sweep_serial(o.preloads.size(), item, progress);
    if (rank == 0) {
      std::printf("blade_sweep_mpi: %zu preloads on %s (%d rank(s)), %g s each\n", o.preloads.size(),
                  o.backend.c_str(), size, o.duration);
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
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "blade_sweep_mpi (rank %d): %s\n", rank, e.what());
    rc = 1;
  }
  MPI_Finalize();
  return rc;
}
