#include "tests/render/render_test_util.h"

namespace glint::test {

double quantile(std::vector<double> values, double q) {
    if (values.empty()) return 0.0;
    const auto k =
        static_cast<std::size_t>(std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    return values[k];
}

}  // namespace glint::test

#if defined(__SANITIZE_ADDRESS__)
// Leak checking is off for the render suite only; ASan's other checks stay on. Vulkan drivers
// (lavapipe's LLVM JIT) allocate for the life of the process, and glint keeps one anchor
// instance (render/vulkan_backend.cpp); with the fast unwinding the JIT needs (the slow
// unwinder deadlocks inside it on libgcc's FDE lock), their stacks stop at the driver and
// cannot be told from ours, so suppressions by library cannot work here.
extern "C" const char* __asan_default_options() { return "detect_leaks=0"; }
#endif
