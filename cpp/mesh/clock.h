#pragma once
// The steady clock the stage timings use (the solver, the handle deformer, a grab frame, a session's
// reports), and the milliseconds since one of its time points.
#include <chrono>

namespace adasculpt {

using Clock = std::chrono::steady_clock;
inline double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

}  // namespace adasculpt
