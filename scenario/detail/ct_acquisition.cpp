#include "scenario/detail/ct_acquisition.h"

#include <sstream>

namespace glint::detail {

Acquisition read_acquisition(TableReader& r, bool volume) {
    Acquisition a;
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
    for (const char* key : {"volume_noise", "volume_noise_seed", "voxel_size"})
        if (r.has(key) && !volume)
            r.fail(r.get(key), key, "needs a volume reference (mesh = \"scan.nii.gz\")");
    return a;
}

Volume acquire(const Volume& volume, VolumeEdit edit, const Acquisition& acquisition) {
    if (!acquisition.any() && edit.erosions.empty() &&
        edit.moved_from_original.matrix() == Rigid::Identity().matrix())
        return volume;
    edit.spacing = acquisition.voxel_size;
    edit.noise_sigma = acquisition.noise;
    edit.noise_seed = acquisition.noise_seed;
    return edit_volume(volume, edit);
}

std::string describe(const Acquisition& a) {
    if (!a.any()) return "as stored";
    std::ostringstream s;
    if (a.noise > 0) s << "noise σ " << a.noise << " (seed " << a.noise_seed << ")";
    if (a.voxel_size)
        s << (a.noise > 0 ? ", " : "") << "voxels " << a.voxel_size->x() << " × "
          << a.voxel_size->y() << " × " << a.voxel_size->z() << " mm";
    return s.str();
}

}  // namespace glint::detail
