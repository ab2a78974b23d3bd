#include "image/sampled_maps.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace glint {

namespace {
#include "image/sampled_maps.inc"

static_assert(std::size(k_diverging_samples) == 3 * (kSampledIntervals + 1),
              "the generated diverging map has the size image/sampled_map_size.h names");
static_assert(std::size(k_inferno_samples) == 3 * (kSampledIntervals + 1),
              "the generated inferno map has the size image/sampled_map_size.h names");
}  // namespace

std::span<const float> sampled_map(SampledMap map) {
    return map == SampledMap::Diverging ? std::span<const float>(k_diverging_samples)
                                        : std::span<const float>(k_inferno_samples);
}

Rgb sampled_colour(SampledMap map, double t) {
    const std::span<const float> rgb = sampled_map(map);
    const double x = (std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0)) * kSampledIntervals;
    const int i = std::min(static_cast<int>(x), kSampledIntervals - 1);
    const auto f = static_cast<float>(x - i);
    const float* a = &rgb[3 * static_cast<std::size_t>(i)];
    return {a[0] + f * (a[3] - a[0]), a[1] + f * (a[4] - a[1]), a[2] + f * (a[5] - a[2])};
}

}  // namespace glint
