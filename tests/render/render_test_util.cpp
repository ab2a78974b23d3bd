#include "tests/render/render_test_util.h"

namespace glint::test {

double quantile(std::vector<double> values, double q) {
    if (values.empty()) return 0.0;
    const auto k = static_cast<std::size_t>(std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    return values[k];
}

}  // namespace glint::test
