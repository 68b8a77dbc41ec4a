// shadelab plot ticks: where an axis puts its tick marks and what their labels say. Pure functions, no
// drawing; the plot renderer (plot.h) calls them with a tick count that fits the axis length in pixels.
//
// Contract:
// - linear_ticks(lo, hi, max_count, ...): major ticks at the multiples of a "nice" step, 1, 2 or 5 x 10^k,
//   the smallest such step that gives at most max_count ticks in the range (at least 2 ticks when the
//   range allows). With expand_lo / expand_hi the range end is first widened to the next multiple of the
//   step (0.03..0.97 becomes 0..1); an end that is not expanded is kept exactly. Values are computed as
//   k * step in one rounding (never by accumulation), so 0 is exactly +0.
//   Labels share one number of decimals (0.0, 0.2, ..., 1.0). When the largest magnitude is >= 1e6 or
//   below 1e-4, labels are "m×10^e" with one e for the axis, that of the largest magnitude (0.5×10^7,
//   1.0×10^7; the renderer draws e as a superscript; 0 stays "0").
// - log_ticks(lo, hi, max_count, ...): needs 0 < lo < hi. Major ticks at decades 10^k, every d-th decade
//   with d from 1, 2, 5, 10, 20, ... so that at most max_count decades are labelled; with d = 1 the minor
//   ticks 2..9 x 10^k are added (unlabelled, minor = true). Expanding widens an end to its decade. When a
//   range holds fewer than two decades, the ticks are 1, 2, 5 x 10^k; when it holds fewer than two of
//   those, linear ticks. Decade labels are plain numbers (0.001 ... 10000) when every decade lies in
//   [1e-3, 1e4], else "10^k".
// - lo and hi must be finite with lo < hi (and lo > 0 for log); max_count is clamped to at least 2.
//   Callers widen a degenerate range (lo == hi) before asking (plot.cpp does). Violations give an empty
//   TickSet with min == lo and max == hi, never a crash.
// - Labels are ASCII except the "×" of the scientific form; minus signs are ASCII '-' (the renderer
//   typesets them as U+2212). Formatting does not depend on the C or C++ locale (std::to_chars).
#pragma once

#include <string>
#include <vector>

namespace shadelab {

struct Tick {
  double value = 0.0;
  std::string label;   // empty for minor ticks
  bool minor = false;  // minor ticks get a lighter grid line and no label
};

struct TickSet {
  double min = 0.0;  // the axis range after any expansion
  double max = 1.0;
  double step = 0.0;  // linear: the major step; log: the major step in decades (0 for 1-2-5 / linear fallback)
  std::vector<Tick> ticks;  // ascending
};

// 1, 2 or 5 x 10^k: the smallest such value >= raw, for raw in (1e-300, 1e300); otherwise 1.
double nice_step(double raw);

TickSet linear_ticks(double lo, double hi, int max_count, bool expand_lo = false, bool expand_hi = false);

TickSet log_ticks(double lo, double hi, int max_count, bool expand_lo = false, bool expand_hi = false);

// `value` with `decimals` digits after the point, locale-independent; -0 prints as "0".
std::string format_fixed(double value, int decimals);

}  // namespace shadelab
