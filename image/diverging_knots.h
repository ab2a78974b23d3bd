// The knots of glint's diverging map of signed shape change: ColorBrewer's RdBu with 9 classes
// (colorbrewer2.org) as 0…1 values, blue (loss) first, for ImageBufAlgo::color_map. In a header
// of their own so that the build-time sampler (tables/sample_colour_maps.cpp) and the run's
// pictures use the same numbers.
#pragma once

#include <array>

namespace glint {

inline constexpr std::array<float, 27> kDivergingKnots = {
    33 / 255.f,  102 / 255.f, 172 / 255.f,  // #2166ac
    67 / 255.f,  147 / 255.f, 195 / 255.f,  // #4393c3
    146 / 255.f, 197 / 255.f, 222 / 255.f,  // #92c5de
    209 / 255.f, 229 / 255.f, 240 / 255.f,  // #d1e5f0
    247 / 255.f, 247 / 255.f, 247 / 255.f,  // #f7f7f7
    253 / 255.f, 219 / 255.f, 199 / 255.f,  // #fddbc7
    244 / 255.f, 165 / 255.f, 130 / 255.f,  // #f4a582
    214 / 255.f, 96 / 255.f,  77 / 255.f,   // #d6604d
    178 / 255.f, 24 / 255.f,  43 / 255.f,   // #b2182b
};

}  // namespace glint
