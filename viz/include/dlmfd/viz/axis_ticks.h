// Ticks of chart axes and colour bars: where the marks go and how their labels read.
//
// Method: on a linear axis the multiples of a 1-2-5 step (1, 2 or 5 times a power of ten) inside
// the range, the step the smallest giving no more than the wanted count; on a log axis the 1, 2
// and 5 multiples of the decades when the range holds fewer than three decades and those are not
// too many, else the decades inside the range (every k-th decade when there are many), or linear
// 1-2-5 ticks when the range holds fewer than two decades and fewer than three 1-2-5 multiples
// (a range of less than a decade still gets three or more readable marks, never one or two).
// Labels: fixed decimals as the step needs, scientific notation for very large or small values;
// on a log axis one notation for every tick (plain digits from 0.001 to 50000, else "1e5").
// References: P. Heckbert, "Nice numbers for graph labels", Graphics Gems (1990).
#pragma once

#include <string>
#include <vector>

namespace dlmfd {

enum class AxisScale { kLinear, kLog10 };

struct AxisTicks {
  std::vector<double> values;  // increasing, inside the axis range
  std::vector<std::string> labels;
};

// Whether a value can be placed on an axis of this scale (finite, and > 0 on a log axis).
bool Usable(double value, AxisScale scale);
// 1-2-5 ticks inside [lo, hi] (lo < hi, finite), at most max(2, wanted) + 1 of them.
AxisTicks LinearTicks(double lo, double hi, int wanted);
// Ticks of a log axis on [lo, hi] (0 < lo < hi, finite), see the header block.
AxisTicks LogTicks(double lo, double hi, int wanted);
// LinearTicks or LogTicks by scale.
AxisTicks ScaleTicks(double lo, double hi, int wanted, AxisScale scale);

}  // namespace dlmfd
