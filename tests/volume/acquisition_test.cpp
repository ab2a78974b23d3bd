// What a scanner adds to the object it images (volume/acquisition.h): a Gaussian point-spread
// blur that turns a sharp edge into the error function of its width, and noise with the asked σ
// per voxel, white or correlated over neighbours as the Gaussian that made it says.
#include "volume/acquisition.h"

#include "mesh/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace glint {
namespace {

Volume uniform(std::array<std::size_t, 3> size, Vec3d spacing, float value) {
    Volume v;
    v.geometry.size = size;
    v.geometry.spacing = spacing;
    v.voxels.assign(v.geometry.voxel_count(), value);
    return v;
}

struct Moments {
    double mean = 0, sd = 0, neighbour_correlation = 0;
};

// Mean, SD and the correlation of voxels one step apart along i, over the inner voxels (three
// kernel widths from every face, where the edge's repeated values do not reach).
Moments moments(const Volume& v, std::size_t skip) {
    const auto& n = v.geometry.size;
    double s = 0, s2 = 0, sxy = 0;
    std::size_t count = 0;
    for (std::size_t k = skip; k + skip < n[2]; ++k)
        for (std::size_t j = skip; j + skip < n[1]; ++j)
            for (std::size_t i = skip; i + skip + 1 < n[0]; ++i) {
                const double x = v.voxels[v.geometry.offset(i, j, k)];
                s += x;
                s2 += x * x;
                sxy += x * v.voxels[v.geometry.offset(i + 1, j, k)];
                ++count;
            }
    Moments m;
    m.mean = s / double(count);
    const double var = s2 / double(count) - m.mean * m.mean;
    m.sd = std::sqrt(var);
    m.neighbour_correlation = (sxy / double(count) - m.mean * m.mean) / var;
    return m;
}

TEST(Scanner, TheBlurTurnsASharpEdgeIntoTheErrorFunctionOfItsWidth) {
    // A step at x = 0 (between voxel centres −0.05 and +0.05) on 0.1 mm voxels, blurred with a
    // 0.6 mm FWHM: the profile is Φ(x / σ), σ = 0.6 / 2.3548 = 0.2548 mm.
    Volume v = uniform({80, 3, 3}, {0.1, 0.1, 0.1}, 0.0f);
    v.geometry.origin = {-3.95, 0, 0};
    for (std::size_t k = 0; k < 3; ++k)
        for (std::size_t j = 0; j < 3; ++j)
            for (std::size_t i = 40; i < 80; ++i) v.voxels[v.geometry.offset(i, j, k)] = 1000.0f;
    apply_scanner(v, {.psf_fwhm = 0.6});
    const double sigma = gaussian_sigma_from_fwhm(0.6);
    EXPECT_NEAR(sigma, 0.2548, 1e-4);
    for (std::size_t i = 30; i < 50; ++i) {
        const double x = v.geometry.physical_from_index(Vec3d(double(i), 1, 1)).x();
        const double expected = 1000.0 * 0.5 * std::erfc(-x / (sigma * std::sqrt(2.0)));
        EXPECT_NEAR(v.voxels[v.geometry.offset(i, 1, 1)], expected, 6.0) << "x " << x;
    }
    // The edge stays where it was: the middle value sits between the two central voxels.
    EXPECT_NEAR(
        0.5 * (v.voxels[v.geometry.offset(39, 1, 1)] + v.voxels[v.geometry.offset(40, 1, 1)]),
        500.0, 1e-3);
}

TEST(Scanner, AUniformVolumeStaysUniformUnderTheBlur) {
    Volume v = uniform({9, 7, 5}, {0.4, 0.4, 0.4}, 1040.0f);
    apply_scanner(v, {.psf_fwhm = 1.5});
    for (float x : v.voxels) EXPECT_NEAR(x, 1040.0f, 1e-3f);
}

TEST(Scanner, WhiteNoiseHasItsSigmaAndNoCorrelation) {
    Volume v = uniform({40, 40, 40}, {0.3, 0.3, 0.3}, 1000.0f);
    apply_scanner(v, {.noise_sigma = 50.0, .noise_seed = 4});
    const Moments m = moments(v, 0);
    EXPECT_NEAR(m.mean, 1000.0, 0.5);
    EXPECT_NEAR(m.sd, 50.0, 1.0);
    EXPECT_NEAR(m.neighbour_correlation, 0.0, 0.02);
    // Drawn voxel by voxel in storage order from the seed.
    std::mt19937 random(4);
    std::normal_distribution<double> noise(0.0, 50.0);
    for (std::size_t i = 0; i < 5; ++i)
        EXPECT_FLOAT_EQ(v.voxels[i], static_cast<float>(1000.0f + noise(random)));
}

TEST(Scanner, CorrelatedNoiseKeepsItsSigmaAndCorrelatesNeighboursAsItsGaussianSays) {
    // Correlation length c = 0.4 mm on 0.3 mm voxels: neighbours correlate by
    // exp(−0.3² / (4 · 0.4²)) = 0.869 (the discrete kernel differs from it by a little).
    Volume v = uniform({60, 60, 60}, {0.3, 0.3, 0.3}, 0.0f);
    apply_scanner(v, {.noise_sigma = 80.0, .noise_correlation = 0.4, .noise_seed = 9});
    const Moments m = moments(v, 5);
    EXPECT_NEAR(m.mean, 0.0, 4.0);
    EXPECT_NEAR(m.sd, 80.0, 4.0);
    EXPECT_NEAR(m.neighbour_correlation, std::exp(-0.09 / (4 * 0.16)), 0.03);
}

TEST(Scanner, EachSeedIsItsOwnRealisation) {
    Volume a = uniform({10, 10, 10}, {0.4, 0.4, 0.4}, 0.0f), b = a, c = a;
    apply_scanner(a, {.noise_sigma = 10.0, .noise_correlation = 0.3, .noise_seed = 1});
    apply_scanner(b, {.noise_sigma = 10.0, .noise_correlation = 0.3, .noise_seed = 1});
    apply_scanner(c, {.noise_sigma = 10.0, .noise_correlation = 0.3, .noise_seed = 2});
    EXPECT_EQ(a.voxels, b.voxels);
    EXPECT_NE(a.voxels, c.voxels);
}

TEST(Scanner, RefusesAWidthSigmaOrCorrelationThatIsNegativeOrNotFinite) {
    Volume v = uniform({4, 4, 4}, {1, 1, 1}, 0.0f);
    for (const ScannerModel& s :
         {ScannerModel{.psf_fwhm = -1.0}, ScannerModel{.noise_sigma = NAN},
          ScannerModel{.noise_sigma = 1.0, .noise_correlation = INFINITY}}) {
        EXPECT_THROW(apply_scanner(v, s), InputError);
        EXPECT_THROW(check_scanner(s), InputError);
    }
    try {
        apply_scanner(v, {.psf_fwhm = -1.0});
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("FWHM is -1"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace glint
