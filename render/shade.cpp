#include "render/shade.h"

#include "mesh/error.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace glint {

ShadeMode parse_shade_mode(const std::string& text) {
    if (text == "normal") return ShadeMode::Normal;
    if (text == "reflection") return ShadeMode::Reflection;
    if (text == "zebra") return ShadeMode::Zebra;
    if (text == "paper8") return ShadeMode::Paper8;
    if (text == "depth") return ShadeMode::Depth;
    throw InputError("mode \"" + text + "\": expected normal, reflection, zebra, paper8 or depth");
}

std::string to_string(ShadeMode mode) {
    switch (mode) {
        case ShadeMode::Normal: return "normal";
        case ShadeMode::Reflection: return "reflection";
        case ShadeMode::Zebra: return "zebra";
        case ShadeMode::Paper8: return "paper8";
        case ShadeMode::Depth: return "depth";
    }
    return "?";
}

Vec3f normal_in_camera(const Frame& frame, const View& view, std::size_t pixel) {
    const Vec3f n(frame.normal[3 * pixel], frame.normal[3 * pixel + 1],
                  frame.normal[3 * pixel + 2]);
    if (frame.normal_space == NormalSpace::View) return n;
    return view.camera.world_from_camera.linear().transpose().cast<float>() * n;
}

RgbaImage shade(const Frame& frame, const View& view, const ShadeOptions& options) {
    RgbaImage image;
    image.width = frame.width;
    image.height = frame.height;
    const std::size_t n = frame.pixel_count();
    image.pixels.assign(4 * n, 0.0f);
    const Vec3f light = options.light_in_camera.normalized().cast<float>();
    float depth_min = std::numeric_limits<float>::max();
    float depth_max = -std::numeric_limits<float>::max();
    if (options.mode == ShadeMode::Depth) {
        for (std::size_t p = 0; p < n; ++p) {
            if (!frame.is_covered(p)) continue;
            depth_min = std::min(depth_min, frame.depth[p]);
            depth_max = std::max(depth_max, frame.depth[p]);
        }
    }
    const Camera& cam = view.camera;
    const double tan_half = std::tan(0.5 * cam.fov_y_rad);
    const double aspect = static_cast<double>(cam.width) / cam.height;
    for (std::size_t p = 0; p < n; ++p) {
        float* out = &image.pixels[4 * p];
        if (!frame.is_covered(p)) continue;
        out[3] = frame.coverage[p];
        switch (options.mode) {
            case ShadeMode::Normal:
            case ShadeMode::Paper8:
                for (int c = 0; c < 3; ++c) {
                    float v = 0.5f * frame.normal[3 * p + static_cast<std::size_t>(c)] + 0.5f;
                    // Paper8: the 8-bit value the paper's images store.
                    if (options.mode == ShadeMode::Paper8) v = std::round(255.0f * v) / 255.0f;
                    out[c] = v;
                }
                break;
            case ShadeMode::Reflection: {
                const float g = std::max(0.0f, normal_in_camera(frame, view, p).dot(light));
                out[0] = out[1] = out[2] = g;
                break;
            }
            case ShadeMode::Zebra: {
                // Reflected view direction r = d − 2(d·n)n (camera frame); stripes of the angle
                // between r and the camera's up axis: on a smooth surface they run smoothly, a
                // bump or a crease bends or breaks them.
                Vec3f d(0.0f, 0.0f, -1.0f);
                if (cam.projection == Projection::Perspective) {
                    const double x =
                        static_cast<double>(p % static_cast<std::size_t>(cam.width)) + 0.5;
                    const double y =
                        static_cast<double>(p / static_cast<std::size_t>(cam.width)) + 0.5;
                    const double xn = 2.0 * x / cam.width - 1.0;
                    const double yn = 1.0 - 2.0 * y / cam.height;
                    d = Vec3d(xn * tan_half * aspect, yn * tan_half, -1.0)
                            .normalized()
                            .cast<float>();
                }
                const Vec3f nc = normal_in_camera(frame, view, p);
                const Vec3f r = d - 2.0f * d.dot(nc) * nc;
                const double angle = std::acos(std::clamp(static_cast<double>(r.y()), -1.0, 1.0));
                const auto band = static_cast<long>(
                    std::floor(angle / std::numbers::pi * 2.0 * options.zebra_stripes));
                const float g = (band % 2 == 0) ? 1.0f : 0.0f;
                out[0] = out[1] = out[2] = g;
                break;
            }
            case ShadeMode::Depth: {
                const float range = depth_max - depth_min;
                const float g = range > 0.0f ? 1.0f - (frame.depth[p] - depth_min) / range : 1.0f;
                out[0] = out[1] = out[2] = g;
                break;
            }
        }
    }
    return image;
}

}  // namespace glint
