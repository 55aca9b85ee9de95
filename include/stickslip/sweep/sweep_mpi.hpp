#pragma once
/// \file sweep_mpi.hpp
/// \brief The MPI backend of sweep.hpp: rank 0 hands out work items one at a time to the other
/// ranks as they become free (dynamic load balancing) and gathers their rows; needs <mpi.h>
/// (link MPI::MPI_CXX; built by stickslip when STICKSLIP_MPI is ON, docs/sweeps.md).

#include "stickslip/sweep/sweep.hpp"

#include <mpi.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace stickslip {

namespace detail {

/// Message tags of the MPI sweep: a worker's request (with the outcome of its last item, if any),
/// the master's next item index, the master's stop.
enum SweepTag : int { kSweepResult = 7101, kSweepWork = 7102, kSweepStop = 7103 };

/// Outcome of item k as bytes: 8-byte item index (or ~0 for "none yet"), 1 byte ok, the text.
inline std::vector<char> pack_sweep_outcome(std::uint64_t k, const SweepOutcome& o) {
  const std::string& text = o.ok ? o.row : o.error;
  std::vector<char> buf(sizeof k + 1 + text.size());
  std::memcpy(buf.data(), &k, sizeof k);
  buf[sizeof k] = o.ok ? 1 : 0;
  std::memcpy(buf.data() + sizeof k + 1, text.data(), text.size());
  return buf;
}

/// Inverse of pack_sweep_outcome: the item index, and the outcome in `o`.
inline std::uint64_t unpack_sweep_outcome(const std::vector<char>& buf, SweepOutcome& o) {
  std::uint64_t k = 0;
  STICKSLIP_ASSERT(buf.size() >= sizeof k + 1 && "sweep message shorter than its header");
  std::memcpy(&k, buf.data(), sizeof k);
  o.ok = buf[sizeof k] != 0;
  std::string text(buf.begin() + static_cast<std::ptrdiff_t>(sizeof k + 1), buf.end());
  (o.ok ? o.row : o.error) = std::move(text);
  return k;
}

}  // namespace detail

/// Runs items 0 .. count - 1 over the ranks of `comm` (MPI must be initialised; every rank calls
/// this with the same count). With one rank it is run_sweep_serial. With more, rank 0 only
/// dispatches: each other rank asks for an item, runs it, sends its outcome back with the next
/// request, and rank 0 answers with the next unclaimed item or a stop, so a rank that drew cheap
/// items takes more of them. Returns, on rank 0, outcome k of every item k (identical to the
/// serial sweep's whenever each row depends on k alone) and calls `progress` there as outcomes
/// arrive; other ranks return an empty vector. An item that throws becomes a failed outcome on
/// its rank and the sweep goes on.
/// \throws std::invalid_argument when `item` is empty
inline std::vector<SweepOutcome> run_sweep_mpi(std::size_t count, const SweepItem& item, MPI_Comm comm,
                                               const SweepProgress& progress = {}) {
  if (!item) detail::throw_invalid("run_sweep_mpi", "item must be set", "empty");
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (size == 1) return run_sweep_serial(count, item, progress);
  constexpr std::uint64_t none = ~std::uint64_t(0);
  if (rank != 0) {
    std::vector<char> request = detail::pack_sweep_outcome(none, SweepOutcome{});
    for (;;) {
      MPI_Send(request.data(), static_cast<int>(request.size()), MPI_CHAR, 0, detail::kSweepResult, comm);
      std::uint64_t k = 0;
      MPI_Status status;
      MPI_Recv(&k, 1, MPI_UINT64_T, 0, MPI_ANY_TAG, comm, &status);
      if (status.MPI_TAG == detail::kSweepStop) return {};
      request = detail::pack_sweep_outcome(k, run_sweep_item(item, static_cast<std::size_t>(k)));
    }
  }
  std::vector<SweepOutcome> out(count);
  std::size_t next = 0, done = 0;
  int active = size - 1;
  std::vector<char> buf;
  while (active > 0) {
    // Polls (1 ms naps) instead of a blocking MPI_Probe, which busy-waits in Open MPI and would
    // take a core from the workers when the ranks oversubscribe the machine.
    MPI_Status status;
    for (int flag = 0;;) {
      MPI_Iprobe(MPI_ANY_SOURCE, detail::kSweepResult, comm, &flag, &status);
      if (flag) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    int bytes = 0;
    MPI_Get_count(&status, MPI_CHAR, &bytes);
    buf.resize(static_cast<std::size_t>(bytes));
    MPI_Recv(buf.data(), bytes, MPI_CHAR, status.MPI_SOURCE, detail::kSweepResult, comm, MPI_STATUS_IGNORE);
    SweepOutcome o;
    const std::uint64_t k = detail::unpack_sweep_outcome(buf, o);
    if (k != none) {
      STICKSLIP_ASSERT(k < count && "sweep result for an item that was never handed out");
      out[static_cast<std::size_t>(k)] = std::move(o);
      ++done;
      if (progress) progress(done, count, static_cast<std::size_t>(k), out[static_cast<std::size_t>(k)]);
    }
    if (next < count) {
      const std::uint64_t give = next++;
      MPI_Send(&give, 1, MPI_UINT64_T, status.MPI_SOURCE, detail::kSweepWork, comm);
    } else {
      const std::uint64_t stop = none;
      MPI_Send(&stop, 1, MPI_UINT64_T, status.MPI_SOURCE, detail::kSweepStop, comm);
      --active;
    }
  }
  return out;
}

}  // namespace stickslip
