#pragma once
// The numbers a front end gives a render (`kasha render` and `kasha compare`'s options, the
// keyword arguments of Python's kasha.render) and the rule each keeps (core/number_check.h): one
// table, so that the command line and Python refuse the same values.
#include "core/number_check.h"

namespace kasha::render_numbers {

// What an int holds; a scene file's /render/seed is one, so a seed may not exceed it either.
constexpr double kMaxInt = 2147483647.0;

constexpr NumberRule kSpp{Sign::Positive, true, kMaxInt};
constexpr NumberRule kTime{Sign::NonNegative, false};  // seconds; 0: no time budget
constexpr NumberRule kSeed{Sign::NonNegative, true, kMaxInt};
constexpr NumberRule kThreads{Sign::NonNegative, true, 4096};  // 0: all cores
constexpr NumberRule kStrategyDepth{Sign::NonNegative, true, 64};

}  // namespace kasha::render_numbers
