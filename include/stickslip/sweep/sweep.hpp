#pragma once
/// \file sweep.hpp
/// \brief Sweeps of independent work items (design studies: preload x frequency x ...): each
/// item k of 0 .. count - 1 becomes one row of text; run serially or on a pool of std::threads
/// with dynamic load balancing; an item that throws becomes a row with the error and the sweep
/// goes on. The MPI backend is in sweep_mpi.hpp (docs/sweeps.md).

#include "stickslip/detail/validate.hpp"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

namespace stickslip {

/// What became of one work item of a sweep.
struct SweepOutcome {
  bool ok = false;    ///< the item's function returned (false: it threw, see error)
  std::string row;    ///< the row it returned (empty when it threw)
  std::string error;  ///< the exception's what() when it threw
};

/// The work of a sweep: row text of item k (0 <= k < count). Throwing marks the item failed.
using SweepItem = std::function<std::string(std::size_t)>;

/// Progress report after each finished item: (items done, count, the item, its outcome). It must
/// not throw (it runs on the worker threads, or on MPI rank 0 while the other ranks wait).
using SweepProgress = std::function<void(std::size_t, std::size_t, std::size_t, const SweepOutcome&)>;

/// Runs item k and catches what it throws: the one place where an item's failure becomes a row.
inline SweepOutcome run_sweep_item(const SweepItem& item, std::size_t k) {
  SweepOutcome o;
  try {
    o.row = item(k);
    o.ok = true;
  } catch (const std::exception& e) {
    o.error = e.what();
  } catch (...) {
    o.error = "unknown exception";
  }
  return o;
}

/// Runs items 0 .. count - 1 in order in this thread; outcome k belongs to item k.
/// \throws std::invalid_argument when `item` is empty
inline std::vector<SweepOutcome> run_sweep_serial(std::size_t count, const SweepItem& item,
                                                  const SweepProgress& progress = {}) {
  if (!item) detail::throw_invalid("run_sweep_serial", "item must be set", "empty");
  std::vector<SweepOutcome> out(count);
  for (std::size_t k = 0; k < count; ++k) {
    out[k] = run_sweep_item(item, k);
    if (progress) progress(k + 1, count, k, out[k]);
  }
  return out;
}

/// Runs items 0 .. count - 1 on `threads` std::threads (0: std::thread::hardware_concurrency()),
/// each taking the next unclaimed item when it finishes one (dynamic load balancing: cheap and
/// expensive items mix). `item` must be safe to call concurrently for different k. Outcome k
/// belongs to item k whatever the thread, so the rows equal run_sweep_serial's whenever each
/// row depends on k alone. `progress` is called under a lock, one call at a time.
/// \throws std::invalid_argument when `item` is empty
inline std::vector<SweepOutcome> run_sweep_threads(std::size_t count, const SweepItem& item,
                                                   unsigned threads = 0, const SweepProgress& progress = {}) {
  if (!item) detail::throw_invalid("run_sweep_threads", "item must be set", "empty");
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(count, 1)));
  std::vector<SweepOutcome> out(count);
  std::atomic<std::size_t> next{0};
  std::size_t done = 0;
  std::mutex report;
  auto worker = [&] {
    for (std::size_t k = next++; k < count; k = next++) {
      out[k] = run_sweep_item(item, k);
      std::lock_guard<std::mutex> lock(report);
      ++done;
      if (progress) progress(done, count, k, out[k]);
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
  return out;
}

/// Quotes a CSV cell: "text" with every " doubled (RFC 4180).
inline std::string csv_quoted(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

/// Cells naming item k (e.g. its parameters), written first on its row whether it failed or not.
using SweepKey = std::function<std::string(std::size_t)>;

/// Writes a sweep as CSV: the line `key_header`,`header`,error, then per item k in order
/// key(k), its row and an empty error cell, or, for a failed item, key(k), as many empty cells as
/// `header` has columns (its commas + 1) and the quoted error. The same outcomes give the same
/// bytes whatever backend ran them.
/// \throws std::invalid_argument when `key` is empty
inline void write_sweep_csv(std::ostream& os, const std::string& key_header, const SweepKey& key,
                            const std::string& header, const std::vector<SweepOutcome>& outcomes) {
  if (!key) detail::throw_invalid("write_sweep_csv", "key must be set", "empty");
  const std::size_t columns = static_cast<std::size_t>(std::count(header.begin(), header.end(), ',')) + 1;
  os << key_header << ',' << header << ",error\n";
  for (std::size_t k = 0; k < outcomes.size(); ++k) {
    const SweepOutcome& o = outcomes[k];
    os << key(k) << ',';
    if (o.ok)
      os << o.row << ",\n";
    else
      os << std::string(columns, ',') << csv_quoted(o.error) << '\n';
  }
}

}  // namespace stickslip
