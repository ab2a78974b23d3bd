#include "volume/acquisition.h"

#include "mesh/cancel.h"
#include "mesh/error.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

namespace glint {

double gaussian_sigma_from_fwhm(double fwhm) {
    return fwhm / (2.0 * std::sqrt(2.0 * std::numbers::ln2));
}

namespace {

// A normalised Gaussian kernel of σ `sigma` voxels, cut at 3σ (at least one tap each side).
std::vector<double> gaussian_kernel(double sigma) {
    const int half = std::max(1, static_cast<int>(std::ceil(3.0 * sigma)));
    std::vector<double> k(static_cast<std::size_t>(2 * half + 1));
    double sum = 0.0;
    for (int i = -half; i <= half; ++i)
        sum += k[static_cast<std::size_t>(i + half)] = std::exp(-0.5 * i * i / (sigma * sigma));
    for (double& w : k) w /= sum;
    return k;
}

// One pass along grid axis `axis`; outer values repeat beyond the edge.
void smooth_axis(Volume& v, std::size_t axis, const std::vector<double>& kernel) {
    const auto& n = v.geometry.size;
    const long half = static_cast<long>(kernel.size() / 2);
    const std::size_t stride = axis == 0 ? 1 : axis == 1 ? n[0] : n[0] * n[1];
    const long length = static_cast<long>(n[axis]);
    std::vector<double> line(n[axis]);
    // Every line along `axis`: its first voxel runs over the other two axes.
    const std::size_t a = axis == 0 ? 1 : 0, b = axis == 2 ? 1 : 2;
    for (std::size_t q = 0; q < n[b]; ++q) {
        throw_if_cancelled();
        for (std::size_t p = 0; p < n[a]; ++p) {
            std::array<std::size_t, 3> start{0, 0, 0};
            start[a] = p;
            start[b] = q;
            const std::size_t first = v.geometry.offset(start[0], start[1], start[2]);
            for (long i = 0; i < length; ++i) {
                double s = 0.0;
                for (long t = -half; t <= half; ++t) {
                    const long j = std::clamp(i + t, 0L, length - 1);
                    s += kernel[static_cast<std::size_t>(t + half)] *
                         v.voxels[first + static_cast<std::size_t>(j) * stride];
                }
                line[static_cast<std::size_t>(i)] = s;
            }
            for (long i = 0; i < length; ++i)
                v.voxels[first + static_cast<std::size_t>(i) * stride] =
                    static_cast<float>(line[static_cast<std::size_t>(i)]);
        }
    }
}

void check(double x, const char* what) {
    if (!(x >= 0) || !std::isfinite(x))
        throw InputError(std::string("scanner model: ") + what + " is " + std::to_string(x) +
                         "; expected a finite value ≥ 0");
}

}  // namespace

void gaussian_smooth(Volume& volume, double sigma_mm) {
    for (std::size_t d = 0; d < 3; ++d) {
        const double sigma = sigma_mm / volume.geometry.spacing[static_cast<Eigen::Index>(d)];
        if (sigma < 0.01 || volume.geometry.size[d] < 2) continue;
        smooth_axis(volume, d, gaussian_kernel(sigma));
    }
}

void check_scanner(const ScannerModel& s) {
    check(s.psf_fwhm, "the point-spread function's FWHM");
    check(s.noise_sigma, "the noise σ");
    check(s.noise_correlation, "the noise's correlation length");
}

void apply_scanner(Volume& volume, const ScannerModel& s) {
    check_scanner(s);
    if (s.psf_fwhm > 0) gaussian_smooth(volume, gaussian_sigma_from_fwhm(s.psf_fwhm));
    if (!(s.noise_sigma > 0)) return;
    std::mt19937 random(s.noise_seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    if (!(s.noise_correlation > 0)) {
        std::normal_distribution<double> noise(0.0, s.noise_sigma);
        for (float& x : volume.voxels) x = static_cast<float>(x + noise(random));
        return;
    }
    // Correlated: white unit noise smoothed, then scaled so that each voxel's σ is the asked
    // one: a separable kernel k scales the variance by Π_axes Σ k².
    Volume noise;
    noise.geometry = volume.geometry;
    noise.voxels.resize(volume.voxels.size());
    for (float& x : noise.voxels) x = static_cast<float>(normal(random));
    double variance = 1.0;
    for (std::size_t d = 0; d < 3; ++d) {
        const double sigma =
            s.noise_correlation / volume.geometry.spacing[static_cast<Eigen::Index>(d)];
        if (sigma < 0.01 || volume.geometry.size[d] < 2) continue;
        const std::vector<double> kernel = gaussian_kernel(sigma);
        double squares = 0.0;
        for (double w : kernel) squares += w * w;
        variance *= squares;
        smooth_axis(noise, d, kernel);
    }
    const double scale = s.noise_sigma / std::sqrt(variance);
    for (std::size_t i = 0; i < volume.voxels.size(); ++i)
        volume.voxels[i] = static_cast<float>(volume.voxels[i] + scale * noise.voxels[i]);
}

}  // namespace glint
