// A 3D scalar volume (CT, CBCT, MRI) in physical coordinates, read from the formats the field
// uses: MetaImage (.mhd/.raw, .mha), NIfTI (.nii, .nii.gz), NRRD (.nrrd, .nhdr) and a DICOM
// series folder. Reading and writing go through ITK (with GDCM for DICOM); no ITK type
// appears here.
//
// Frames: voxel index i = (i, j, k) maps to the physical point (mm, the scanner's LPS frame
// as ITK reports it)
//     p = origin + direction · diag(spacing) · i
// so two scans of one patient stay in the scanner's frame.
#pragma once

#include "mesh/mesh.h"

#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace glint {

/// Where the voxels of a volume sit in physical space.
struct VolumeGeometry {
    std::array<std::size_t, 3> size{0, 0, 0};  ///< voxels along i, j, k
    Vec3d spacing{1, 1, 1};                    ///< mm between voxel centres along i, j, k
    Vec3d origin{0, 0, 0};                     ///< physical position of voxel (0, 0, 0), mm
    Eigen::Matrix3d direction = Eigen::Matrix3d::Identity();  ///< columns: unit axes i, j, k

    /// p = origin + direction · diag(spacing) · index (index may be fractional).
    [[nodiscard]] Vec3d physical_from_index(const Vec3d& index) const;
    /// The inverse of physical_from_index.
    [[nodiscard]] Vec3d index_from_physical(const Vec3d& p) const;
    [[nodiscard]] std::size_t voxel_count() const { return size[0] * size[1] * size[2]; }
    /// Linear offset of voxel (i, j, k): i fastest.
    [[nodiscard]] std::size_t offset(std::size_t i, std::size_t j, std::size_t k) const {
        return i + size[0] * (j + size[1] * k);
    }
};

/// A scalar volume: voxel values as float, i fastest, then j, then k.
struct Volume {
    VolumeGeometry geometry;
    std::vector<float> voxels;
    std::filesystem::path path;  ///< where it was read from (empty when generated)
    std::string format;          ///< "metaimage", "nifti", "nrrd", "dicom", or "" when generated
    std::string stored_type;     ///< pixel type as stored ("short", "float", …)

    /// Smallest and largest voxel value (NaN-free volumes only).
    [[nodiscard]] std::array<float, 2> range() const;
};

/// Whether a path names a volume rather than a mesh: a known volume extension
/// (.mhd .mha .nii .nii.gz .nrrd .nhdr .dcm) or a directory.
[[nodiscard]] bool is_volume_path(const std::filesystem::path& path);

/// The voxel budget of read_volume: 2·10⁹ voxels (8 GB as float, the 1000³-voxel scans of
/// today's CBCT twice over).
inline constexpr std::size_t kDefaultMaxVoxels = 2'000'000'000;

/// Reads a 3D scalar volume (MetaImage, NIfTI, NRRD, or a folder holding one DICOM series).
/// A 4D image with one time point is read as 3D.
/// \throw IoError missing file or folder. \throw InputError unknown format, truncated or
/// inconsistent data, a 2D or 4D image, a vector image, a folder with no DICOM series,
/// non-finite voxels; every message is one line naming the file.
/// A header declaring more than `max_voxels` voxels, or more voxel bytes than its file can
/// hold (compressed: at zlib's best ratio), is refused before anything is allocated.
[[nodiscard]] Volume read_volume(const std::filesystem::path& path,
                                 std::size_t max_voxels = kDefaultMaxVoxels);

/// Writes a volume; the format follows the extension (.mha, .mhd (+ .raw beside it), .nii,
/// .nii.gz, .nrrd, .nhdr (+ .raw.gz beside it)). Single-file formats are written atomically.
/// \throw InputError unknown extension. \throw IoError the write failed.
void write_volume(const Volume& volume, const std::filesystem::path& path);

/// Writes a volume as a DICOM CT series (one file per slice k, values rounded to 16-bit
/// integers, position and orientation of every slice from the geometry) into a new folder.
/// \throw IoError the folder exists or the write failed.
void write_dicom_series(const Volume& volume, const std::filesystem::path& folder);

}  // namespace glint
