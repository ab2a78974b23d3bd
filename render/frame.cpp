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

}  // namespace glint
