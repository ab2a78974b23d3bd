// Volumes: conversion between glint's Volume and the ITK side (detail/itk_io.h), staging of
// written files, the volume-or-mesh test.
#include "volume/volume.h"

#include "mesh/atomic_file.h"
#include "mesh/error.h"
#include "mesh/input_path.h"
#include "mesh/output_guard.h"
#include "volume/detail/isolated_read.h"
#include "volume/detail/itk_io.h"
#include "volume/detail/volume_plugin.h"

#include <algorithm>
#include <cmath>

namespace glint {

namespace fs = std::filesystem;

namespace {

detail::RawVolume to_raw(const Volume& v) {
    detail::RawVolume r;
    const VolumeGeometry& g = v.geometry;
    r.size = g.size;
    for (int d = 0; d < 3; ++d) {
        r.spacing[static_cast<std::size_t>(d)] = g.spacing[d];
        r.origin[static_cast<std::size_t>(d)] = g.origin[d];
        for (int c = 0; c < 3; ++c)
            r.direction[static_cast<std::size_t>(3 * d + c)] = g.direction(d, c);
    }
    r.voxels = v.voxels;
    if (r.voxels.size() != g.voxel_count())
        throw InputError("volume: " + std::to_string(r.voxels.size()) +
                         " voxels, the geometry needs " + std::to_string(g.voxel_count()));
    return r;
}

}  // namespace

Vec3d VolumeGeometry::physical_from_index(const Vec3d& index) const {
    return origin + direction * spacing.cwiseProduct(index);
}

Vec3d VolumeGeometry::index_from_physical(const Vec3d& p) const {
    return (direction.inverse() * (p - origin)).cwiseQuotient(spacing);
}

std::array<float, 2> Volume::range() const {
    if (voxels.empty()) return {0.0f, 0.0f};
    const auto [lo, hi] = std::minmax_element(voxels.begin(), voxels.end());
    return {*lo, *hi};
}

bool is_volume_path(const fs::path& path) {
    std::error_code ec;
    return fs::is_directory(path, ec) || !detail::volume_format(path).empty();
}

Volume read_volume(const fs::path& path, std::size_t max_voxels) {
    std::error_code ec;
    if (!reachable_input(path, quoted_volume(path.string())))
        throw InputError(quoted_volume(path.string()) + ": no such file or folder");
    for (const fs::path& f : input_files(path)) protect_input(f);  // never an output
    // DICOM goes through GDCM, which may crash on files the pre-check cannot foresee: its read
    // runs in a child process (detail/isolated_read.h).
    auto read = [&] { return detail::itk_read(path, max_voxels); };
    const bool isolated = fs::is_directory(path, ec) || detail::volume_format(path) == "dicom";
    // The plugin is loaded here, not in each child: what a child loads dies with it.
    if (isolated) (void)detail::volume_io_plugin();
    detail::RawVolume raw = isolated ? detail::read_in_child(path, read) : read();
    Volume v;
    v.path = path;
    v.format = std::move(raw.format);
    v.stored_type = std::move(raw.stored_type);
    VolumeGeometry& g = v.geometry;
    g.size = raw.size;
    for (int d = 0; d < 3; ++d) {
        g.spacing[d] = raw.spacing[static_cast<std::size_t>(d)];
        g.origin[d] = raw.origin[static_cast<std::size_t>(d)];
        for (int c = 0; c < 3; ++c)
            g.direction(d, c) = raw.direction[static_cast<std::size_t>(3 * d + c)];
    }
    if (!(g.spacing.array() > 0).all())
        throw InputError(quoted_volume(path.string()) + ": spacing (" +
                         std::to_string(g.spacing.x()) + ", " + std::to_string(g.spacing.y()) +
                         ", " + std::to_string(g.spacing.z()) + ") mm, expected every spacing > 0");
    if (std::abs(std::abs(g.direction.determinant()) - 1.0) > 1e-3)
        throw InputError(
            quoted_volume(path.string()) + ": direction matrix is not orthonormal (determinant " +
            std::to_string(g.direction.determinant()) + "), expected direction cosines");
    v.voxels = std::move(raw.voxels);
    for (std::size_t n = 0; n < v.voxels.size(); ++n)
        if (!std::isfinite(v.voxels[n]))
            throw InputError(quoted_volume(path.string()) + ": voxel " + std::to_string(n) +
                             " is not finite, expected finite values");
    return v;
}

void write_volume(const Volume& volume, const fs::path& path) {
    const std::string format = detail::volume_format(path);
    if (format.empty() || format == "dicom")
        throw InputError(
            quoted_volume(path.string()) +
            ": cannot write this extension, expected .mha .mhd .nii .nii.gz .nrrd .nhdr");
    const detail::RawVolume raw = to_raw(volume);
    const std::string name = path.filename().string();
    auto has_suffix = [&](const std::string& s) {
        return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
    };
    if (has_suffix(".mhd") || has_suffix(".nhdr")) {
        // note: a header names its data file, so the pair is written under its final names
        // (not atomically).
        detail::itk_write(raw, path);
    } else if (has_suffix(".nii.gz")) {
        write_atomically_to_path(path, [&](const fs::path& temp) {
            fs::path staged = temp;
            staged.replace_extension(".nii.gz");
            detail::itk_write(raw, staged);
            fs::rename(staged, temp);
        });
    } else {
        write_atomically_to_path(path, [&](const fs::path& temp) { detail::itk_write(raw, temp); });
    }
}

void write_dicom_series(const Volume& volume, const fs::path& folder) {
    std::error_code ec;
    if (fs::exists(folder, ec))
        throw IoError("DICOM folder \"" + folder.string() + "\": exists already");
    fs::create_directories(folder, ec);
    if (ec)
        throw IoError("DICOM folder \"" + folder.string() + "\": cannot create: " + ec.message());
    detail::itk_write_dicom(to_raw(volume), folder);
}

}  // namespace glint
