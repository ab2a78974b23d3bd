// glint volume-edit IN -o OUT.mha [--erode x,y,z,r]… [--erode-to V] [--pose rx,ry,rz,tx,ty,tz]
//                   [--voxel-size x,y,z] [--psf-fwhm mm] [--noise σ --noise-seed N
//                   --noise-correlation mm]
// [--pivot x,y,z]: a longitudinal "after" scan with a known change (volume/edit.h), and
// OUT.json beside it with the ground truth.
#include "mesh/atomic_file.h"
#include "mesh/damage.h"
#include "mesh/error.h"
#include "mesh/json_text.h"
#include "mesh/output_guard.h"
#include "tools/command.h"
#include "volume/edit.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace glint::cli::volume_edit_command {
namespace {

struct EditArgs {
    std::string input;
    std::string output;
    std::vector<std::string> erode;
    std::optional<double> erode_to;
    std::string pose = "0,0,0,0,0,0";
    std::string pivot = "0,0,0";
    std::string voxel_size;
    double noise = 0.0;
    std::uint32_t noise_seed = 1;
    double noise_correlation = 0.0;
    double psf_fwhm = 0.0;
};

std::vector<double> numbers(const std::string& text, const char* flag, std::size_t count) {
    std::vector<double> out;
    std::istringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        try {
            std::size_t used = 0;
            out.push_back(std::stod(item, &used));
            if (used != item.size()) throw std::invalid_argument(item);
        } catch (const std::exception&) {
            throw InputError(std::string(flag) + " \"" + text + "\": \"" + item +
                             "\" is not a number");
        }
    }
    if (out.size() != count)
        throw InputError(std::string(flag) + " \"" + text + "\": expected " +
                         std::to_string(count) + " numbers, found " + std::to_string(out.size()));
    return out;
}

void run(const EditArgs& a) {
    guard_outputs({a.output, a.output + ".json"}, {a.input});
    VolumeEdit edit;
    const auto p = numbers(a.pivot, "--pivot", 3);
    edit.moved_from_original = motion_about(parse_pose_spec(a.pose), Vec3d(p[0], p[1], p[2]));
    const Volume input = read_volume(a.input);
    const float lowest = input.range()[0];
    for (const auto& e : a.erode) {
        const auto v = numbers(e, "--erode", 4);
        if (!(v[3] > 0)) throw InputError("--erode \"" + e + "\": radius must be > 0 mm");
        edit.erosions.push_back(
            {Vec3d(v[0], v[1], v[2]), v[3], static_cast<float>(a.erode_to.value_or(lowest))});
    }
    if (!a.voxel_size.empty()) {
        const auto v = numbers(a.voxel_size, "--voxel-size", 3);
        edit.spacing = Vec3d(v[0], v[1], v[2]);
    }
    if (!(a.noise >= 0) || !std::isfinite(a.noise))
        throw InputError("--noise " + std::to_string(a.noise) + ": expected a σ ≥ 0");
    edit.noise_sigma = a.noise;
    edit.noise_seed = a.noise_seed;
    for (const auto& [x, flag] : {std::pair{a.noise_correlation, "--noise-correlation"},
                                  std::pair{a.psf_fwhm, "--psf-fwhm"}})
        if (!(x >= 0) || !std::isfinite(x))
            throw InputError(std::string(flag) + " " + std::to_string(x) +
                             ": expected a length ≥ 0 mm");
    edit.noise_correlation = a.noise_correlation;
    edit.psf_fwhm = a.psf_fwhm;
    const Volume out = edit_volume(input, edit);
    write_volume(out, a.output);
    const std::string truth = a.output + ".json";
    write_file_atomically(truth, edit_json(edit));
    if (global_flags().json)
        std::cout << json_text(nlohmann::json{{"output", absolute_output(a.output)},
                                              {"truth", absolute_output(truth)}},
                               2)
                  << '\n';
    else std::printf("wrote %s and %s (ground truth)\n", a.output.c_str(), truth.c_str());
}

void setup(CLI::App& app) {
    static EditArgs a;
    auto* cmd =
        app.add_subcommand("volume-edit",
                           "Resample a volume under a known rigid motion with local erosions "
                           "(a longitudinal pair with ground truth)");
    cmd->add_option("IN", a.input, "Volume (.mhd .mha .nii .nii.gz .nrrd .nhdr or a DICOM folder)")
        ->required();
    cmd->add_option("-o,--output", a.output,
                    "Edited volume (.mha .mhd .nii .nii.gz .nrrd .nhdr); truth in OUTPUT.json")
        ->required();
    cmd->add_option("--erode", a.erode,
                    "x,y,z,r (mm, before the motion): lower values inside this ball; repeatable");
    cmd->add_option_function<double>(
        "--erode-to", [](double v) { a.erode_to = v; },
        "Value eroded material takes (default: the volume's lowest)");
    cmd->add_option("--pose", a.pose, "Rigid motion rx,ry,rz,tx,ty,tz (degrees, mm) about --pivot")
        ->capture_default_str();
    cmd->add_option("--pivot", a.pivot, "Centre of the rotation x,y,z (mm)")->capture_default_str();
    cmd->add_option("--voxel-size", a.voxel_size,
                    "x,y,z (mm): resample onto this voxel size over the same extent, each voxel "
                    "the mean over its own extent (another scanner's grid)");
    cmd->add_option("--noise", a.noise,
                    "Gaussian noise σ added to every voxel, in the volume's values (an "
                    "acquisition's own noise)");
    cmd->add_option("--noise-seed", a.noise_seed, "Seed of the noise realisation")
        ->capture_default_str();
    cmd->add_option("--noise-correlation", a.noise_correlation,
                    "mm: the noise correlated over neighbouring voxels as a cone-beam "
                    "reconstruction makes it (white noise smoothed by a Gaussian of this σ, "
                    "scaled back to --noise per voxel); 0: white")
        ->capture_default_str();
    cmd->add_option("--psf-fwhm", a.psf_fwhm,
                    "mm: the scanner's point-spread blur, a Gaussian of this full width at half "
                    "maximum applied before the noise; 0: none")
        ->capture_default_str();
    cmd->callback([] { run(a); });
}

const CommandRegistrar registrar(16, setup);

}  // namespace
}  // namespace glint::cli::volume_edit_command
