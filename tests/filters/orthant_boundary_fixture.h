#pragma once
// Shared by the orthant boundary filter's tests: the paper's test alone and every frame set.

#include <cmath>

#include "mcws/filters/orthant_boundary.h"

namespace mcws::test {

/// The paper's test alone, as the filter ran before its recommended settings: a 90-degree gap
/// (in 2-D) and no hull-depth stage. The tests of the test itself start from it.
template <typename Filter>
void paperTestOnly(Filter& filter) {
  filter.setMinimumGap(M_PI / 2);
  filter.setHullDepth(0.0);
}

inline const OrthantFrames kEveryFrameSet[] = {OrthantFrame::kAxis, OrthantFrame::kOutward,
                                               OrthantFrame::kAnyRotation, OrthantFrames()};

}  // namespace mcws::test
