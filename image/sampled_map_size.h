// How finely the build samples the colour maps of image/sampled_maps.h.
#pragma once

namespace glint {

/// Intervals between samples: the diverging map's 9 knots fall on samples (a multiple of 8),
/// and so do the 17 evenly spaced colours report.html's scales take (a multiple of 16).
inline constexpr int kSampledIntervals = 1024;
static_assert(kSampledIntervals % 16 == 0,
              "knots and the page's scale points must fall on samples");

}  // namespace glint
