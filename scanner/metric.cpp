#include "scanner/metric.h"

#include "mesh/error.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace glint {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

void angle_values(const FrameView&, const FrameView&, std::span<const float> angle,
                  std::span<float> value) {
    std::copy(angle.begin(), angle.end(), value.begin());
}

// The 8-bit normal colour image (rgb = 0.5·n + 0.5, quantised as the paper saved it).
OIIO::ImageBuf paper_colours(const FrameView& f) {
    OIIO::ImageBuf buf(OIIO::ImageSpec(f.width, f.height, 3, OIIO::TypeDesc::UINT8));
    std::vector<std::uint8_t> px(f.normal.size());
    for (std::size_t i = 0; i < px.size(); ++i) {
        const float n = std::isfinite(f.normal[i]) ? f.normal[i] : 0.0f;
        px[i] = static_cast<std::uint8_t>(
            std::lround(std::clamp(0.5f * n + 0.5f, 0.0f, 1.0f) * 255.0f));
    }
    buf.set_pixels(OIIO::ROI(0, f.width, 0, f.height, 0, 1, 0, 3), OIIO::TypeDesc::UINT8,
                   px.data());
    return buf;
}

void rgb_values(const FrameView& ref, const FrameView& exa, std::span<const float> angle,
                std::span<float> value) {
    const OIIO::ImageBuf diff = OIIO::ImageBufAlgo::absdiff(paper_colours(ref), paper_colours(exa));
    if (diff.has_error()) throw IoError("RGB difference: " + diff.geterror());
    const std::size_t n = angle.size();
    std::vector<float> px(3 * n);
    if (!diff.get_pixels(OIIO::ROI(0, ref.width, 0, ref.height, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT,
                         px.data()))
        throw IoError("RGB difference: " + diff.geterror());
    for (std::size_t i = 0; i < n; ++i)
        value[i] = std::isnan(angle[i])
                       ? kNaN
                       : 255.0f * (px[3 * i] + px[3 * i + 1] + px[3 * i + 2]) / 3.0f;
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
