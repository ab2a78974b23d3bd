#include "scenario/detail/ct_acquisition.h"

#include "scenario/ct_of_mesh.h"

#include <sstream>

namespace glint::detail {

Acquisition inherited(const Acquisition& reference) {
    Acquisition a = reference;
    a.noise_seed = reference.noise_seed + 1;
    return a;
}

Acquisition read_acquisition(TableReader& r, bool volume, const Acquisition* inherit) {
    Acquisition a = inherit ? inherited(*inherit) : Acquisition{};
    if (auto v = r.optional<double>("volume_noise", "a number (σ, the volume's values)")) {
        if (!(*v >= 0)) r.fail(r.get("volume_noise"), "volume_noise", "must be ≥ 0");
        a.noise = *v;
    }
    if (auto v = r.integer("volume_noise_seed", 0, 4294967295))
        a.noise_seed = static_cast<std::uint32_t>(*v);
    if (auto v = r.numbers("voxel_size", 3, 3)) {
        for (double x : *v)
            if (!(x > 0)) r.fail(r.get("voxel_size"), "voxel_size", "every size must be > 0 mm");
        a.voxel_size = Vec3d((*v)[0], (*v)[1], (*v)[2]);
    }
    for (const char* key : {"psf_fwhm", "noise_correlation"})
        if (auto v = r.optional<double>(key, "a number (mm)")) {
            if (!(*v >= 0)) r.fail(r.get(key), key, "must be ≥ 0 mm");
            (std::string(key) == "psf_fwhm" ? a.psf_fwhm : a.noise_correlation) = *v;
        }
    for (const char* key :
         {"volume_noise", "volume_noise_seed", "voxel_size", "psf_fwhm", "noise_correlation"})
        if (r.has(key) && !volume)
            r.fail(r.get(key), key,
                   "needs a volume reference (mesh = \"scan.nii.gz\") or a mesh scanned as CT "
                   "([reference] scan_as_ct = true)");
    return a;
}

Volume acquire(const Volume& volume, VolumeEdit edit, const Acquisition& acquisition,
               bool noiseless) {
    if (!acquisition.any() && edit.erosions.empty() &&
        edit.moved_from_original.matrix() == Rigid::Identity().matrix())
        return volume;
    edit.spacing = acquisition.voxel_size;
    edit.noise_sigma = noiseless ? 0.0 : acquisition.noise;
    edit.noise_seed = acquisition.noise_seed;
    edit.noise_correlation = acquisition.noise_correlation;
    edit.psf_fwhm = acquisition.psf_fwhm;
    return edit_volume(volume, edit);
}

Volume acquire(const Mesh& object, const VolumeEdit& edit, const Acquisition& acquisition,
               float background, float inside, bool noiseless) {
    MeshScan scan;
    scan.voxel_size = acquisition.voxel_size.value_or(Vec3d::Constant(0.4));
    scan.background = background;
    scan.object = inside;
    scan.moved_from_original = edit.moved_from_original;
    scan.erosions = edit.erosions;
    scan.scanner = {acquisition.psf_fwhm, noiseless ? 0.0 : acquisition.noise,
                    acquisition.noise_correlation, acquisition.noise_seed};
    return scan_mesh(object, scan);
}

std::string describe(const Acquisition& a) {
    if (!a.any()) return "as stored";
    std::ostringstream s;
    if (a.noise > 0) s << "noise σ " << a.noise << " (seed " << a.noise_seed << ")";
    if (a.noise > 0 && a.noise_correlation > 0)
        s << ", correlated over " << a.noise_correlation << " mm";
    if (a.voxel_size)
        s << (a.noise > 0 ? ", " : "") << "voxels " << a.voxel_size->x() << " × "
          << a.voxel_size->y() << " × " << a.voxel_size->z() << " mm";
    if (a.psf_fwhm > 0)
        s << (a.noise > 0 || a.voxel_size ? ", " : "") << "blur " << a.psf_fwhm << " mm FWHM";
    return s.str();
}

}  // namespace glint::detail
