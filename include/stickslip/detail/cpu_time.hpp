#pragma once
/// \file cpu_time.hpp
/// \brief CPU time of the calling thread (internal): what a run costs when several runs share the
/// process on threads (trade_study(), the blade example's sweep), which std::clock(), the
/// process's CPU time, does not tell.

#include <ctime>

#include <time.h>  // clock_gettime, CLOCK_THREAD_CPUTIME_ID (POSIX)

namespace stickslip::detail {

/// CPU seconds consumed so far by the calling thread (POSIX CLOCK_THREAD_CPUTIME_ID). Where that
/// clock does not exist or fails, the process's CPU time std::clock() / CLOCKS_PER_SEC, which
/// counts every thread of the process.
inline double thread_cpu_seconds() noexcept {
#if defined(CLOCK_THREAD_CPUTIME_ID)
  timespec ts{};
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) == 0)
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
#endif
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

}  // namespace stickslip::detail
