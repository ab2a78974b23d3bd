#include "render/frame.h"

#include <algorithm>

namespace glint {

std::size_t Frame::covered_count() const {
    return static_cast<std::size_t>(
        std::count_if(coverage.begin(), coverage.end(), [](float c) { return c > 0.0f; }));
}

Frame make_empty_frame(int width, int height, NormalSpace space) {
    Frame frame;
    frame.width = width;
    frame.height = height;
    frame.normal_space = space;
    const std::size_t n = frame.pixel_count();
    frame.normal.assign(3 * n, 0.0f);
    frame.primitive_id.assign(n, kNoPrimitive);
    frame.depth.assign(n, kNoDepth);
    frame.coverage.assign(n, 0.0f);
    return frame;
}

FrameRows frame_rows(const Frame& f, int y0, int y1) {
    const auto w = static_cast<std::size_t>(f.width);
    const std::size_t first = static_cast<std::size_t>(y0) * w;
    const std::size_t count = static_cast<std::size_t>(y1 - y0) * w;
    return {f.width,
            y1 - y0,
            y0,
            f.normal_space,
            std::span<const float>(f.normal).subspan(3 * first, 3 * count),
            std::span<const std::uint32_t>(f.primitive_id).subspan(first, count),
            std::span<const float>(f.depth).subspan(first, count),
            std::span<const float>(f.coverage).subspan(first, count)};
}

}  // namespace glint
