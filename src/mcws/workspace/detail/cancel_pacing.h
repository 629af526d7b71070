#pragma once
/// \file
/// \brief Checks for cancelling (CancelCheck) from inside the OpenMP loops of the workspace module,
/// on the calling thread only. Private to mcws_workspace (namespace mcws::detail).

#include <omp.h>

#include "mcws/core/cancel_check.h"

namespace mcws::detail {

/// Items between two checks for cancelling in a loop over points (a neighbour search, a star's
/// small triangulation: a few milliseconds of work on the calling thread).
constexpr unsigned kPointCancelStride = 4096;

/// \brief A CancelPacer for the thread that runs it in an OpenMP team: thread 0, the thread that
/// called the library (the only one CancelCheck may be called on), calls `check` every `stride`
/// steps; the other threads never do. Step inside a FirstError's run(), so that what `check`
/// throws ends the loop (the other threads skip the items not yet started) and is rethrown after
/// it.
inline CancelPacer callingThreadPacer(const CancelCheck& check, unsigned stride) {
  static const CancelCheck kNever;
  return CancelPacer(omp_get_thread_num() == 0 ? check : kNever, stride);
}

}  // namespace mcws::detail
