// Helpers shared by the render tests: backends present, angles, statistics.
#pragma once

#include "render/frame.h"
#include "render/renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace glint::test {

/// Backends every render test runs on. lavapipe (Vulkan on the CPU) always runs; a
/// hardware GPU is picked automatically when present, since device choice prefers it.
inline std::vector<Backend> all_backends() { return {Backend::Vulkan, Backend::Embree}; }

inline std::string backend_name(const testing::TestParamInfo<Backend>& info) {
    return info.param == Backend::Vulkan ? "Vulkan" : "Embree";
}

/// Options for tests: validation on for Vulkan (any message fails the test, see
/// expect_no_validation_messages).
inline RenderOptions test_options(Backend backend, int supersample = 1) {
    RenderOptions o;
    o.backend = backend;
    o.supersample = supersample;
    o.validation = backend == Backend::Vulkan;
    return o;
}

inline void expect_no_validation_messages(const Renderer& renderer) {
    const auto messages = renderer.validation_messages();
    EXPECT_TRUE(messages.empty()) << messages.size() << " validation message(s), first: "
                                  << (messages.empty() ? "" : messages.front());
}

inline Vec3f pixel_normal(const Frame& f, std::size_t p) {
    return {f.normal[3 * p], f.normal[3 * p + 1], f.normal[3 * p + 2]};
}

inline double angle_deg(const Vec3d& a, const Vec3d& b) {
    const double c = std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0);
    return std::acos(c) * 180.0 / std::numbers::pi;
}

/// q-quantile (0…1) of values (nearest rank, lower).
// note: out of line: GCC 12 reports a false -Wfree-nonheap-object when this is inlined.
double quantile(std::vector<double> values, double q);

}  // namespace glint::test
