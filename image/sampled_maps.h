// Colour maps sampled by OpenImageIO when glint was built (tables/sample_colour_maps.cpp runs
// ImageBufAlgo::color_map at kSampledIntervals + 1 evenly spaced points): the atlas files'
// vertex colours, report.html's colour scales and the pictures' per-pixel colours come from
// these samples, so a run that draws no picture (--no-pictures) never loads the image library.
// The diverging map is linear between knots that fall on samples, so interpolating the samples
// gives OpenImageIO's own colours to float rounding.
#pragma once

#include "image/canvas.h"
#include "image/sampled_map_size.h"

#include <span>

namespace glint {

enum class SampledMap {
    Diverging,  ///< image/diverging_knots.h: blue (loss) → near white → red (gain)
    Inferno,    ///< OpenImageIO's "inferno": black → purple → orange → pale yellow
};

/// The map's samples, (kSampledIntervals + 1) × 3 floats, sample i at t = i / kSampledIntervals.
[[nodiscard]] std::span<const float> sampled_map(SampledMap map);

/// The map's colour at t (clamped to [0, 1]; NaN is 0), linear between samples.
[[nodiscard]] Rgb sampled_colour(SampledMap map, double t);

}  // namespace glint
