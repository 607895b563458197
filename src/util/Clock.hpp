// Wall and CPU clocks: seconds between steady-clock instants, and the
// process's CPU time (all threads, the driver's workers included: on a
// shared machine a steadier measure of the work than wall time).
#pragma once

#include <chrono>
#include <ctime>

namespace rt {

using SteadyClock = std::chrono::steady_clock;

inline double secondsBetween(SteadyClock::time_point from, SteadyClock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

inline double secondsSince(SteadyClock::time_point start) {
  return secondsBetween(start, SteadyClock::now());
}

inline double processCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return double(now.tv_sec) + double(now.tv_nsec) * 1e-9;
}

}  // namespace rt
