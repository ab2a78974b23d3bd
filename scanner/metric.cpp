#include "scanner/metric.h"

#include "mesh/error.h"
#include "mesh/mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace glint {

namespace {

void angle_values(const FrameView&, const FrameView&, std::span<const float> angle,
                  std::span<float> value) {
    std::copy(angle.begin(), angle.end(), value.begin());
}

// The 8-bit normal colour of one channel (rgb = 0.5·n + 0.5, quantised as the paper saved it).
int paper_colour(float n) {
    const float v = std::isfinite(n) ? n : 0.0f;
    return static_cast<int>(std::lround(std::clamp(0.5f * v + 0.5f, 0.0f, 1.0f) * 255.0f));
}

// note: a per-pixel loop, not ImageBufAlgo::absdiff, so the sweep never maps OpenImageIO
// (start-up: image/image_ops.h). The arithmetic is what absdiff on 8-bit images handed back
// (each channel's |Δ| scaled by 1/255 as OpenImageIO converts 8-bit values, then
// 255 · (r + g + b) / 3), kept to the bit: the GPU sweep's shader (atlas_pixels.comp
// rgb_value) computes the same and its tests compare the two to 1 ulp.
void rgb_values(const FrameView& ref, const FrameView& exa, std::span<const float> angle,
                std::span<float> value) {
    constexpr float kToFloat = 1.0f / 255.0f;
    const std::size_t n = angle.size();
    for (std::size_t i = 0; i < n; ++i) {
        if (std::isnan(angle[i])) {
            value[i] = kNaN;
            continue;
        }
        float d[3];
        for (std::size_t c = 0; c < 3; ++c)
            d[c] = static_cast<float>(std::abs(paper_colour(ref.normal[3 * i + c]) -
                                               paper_colour(exa.normal[3 * i + c]))) *
                   kToFloat;
        value[i] = 255.0f * ((d[0] + d[1]) + d[2]) / 3.0f;
    }
}

// note: the histogram and colour ranges are the ranges a damage shows in: the angle's 90°
// bin collects missing surface; the rgb colour scale's 64 units are what a ~15° tilt moves
// an 8-bit normal colour by (measured on the phantom dent tests), as 20° is for the angle.
constexpr std::array<MetricDescriptor, 2> kMetrics{{
    {Metric::AngleDeg, "angle", "deg", "°", "angle deviation",
     "angle between the reference and the examined normal, degrees", 90.0f, 180.0, 90.0, 1.0, 20.0,
     angle_values},
    {Metric::RgbAbs, "rgb", "rgb", " rgb", "RGB difference",
     "the paper's metric: mean |dR|, |dG|, |dB| of the 8-bit normal colours, 0-255", 255.0f, 255.0,
     256.0, 4.0, 64.0, rgb_values},
}};

}  // namespace

std::span<const MetricDescriptor> metrics() { return kMetrics; }

const MetricDescriptor& describe(Metric metric) {
    for (const auto& m : kMetrics)
        if (m.id == metric) return m;
    GLINT_ASSERT(false, "metric without a descriptor");
    return kMetrics[0];
}

Metric parse_metric(std::string_view name) {
    std::string names;
    for (const auto& m : kMetrics) {
        if (m.name == name) return m.id;
        names += (names.empty() ? "" : " or ") + std::string(m.name);
    }
    throw InputError("metric \"" + std::string(name) + "\": expected " + names);
}

std::string to_string(Metric metric) { return std::string(describe(metric).name); }

DeviationMap compare_frames(const FrameView& reference, const FrameView& examined,
                            const CompareOptions& options, Metric metric) {
    DeviationMap d = compare_frames(reference, examined, options);
    d.value.resize(d.angle_deg.size());
    describe(metric).compute(reference, examined, d.angle_deg, d.value);
    return d;
}

}  // namespace glint
