// The ITK side of the volume module (internal). ITK 5.2 bundles its own Eigen 3.3, which
// cannot share a translation unit with the system Eigen 3.4 that mesh/mesh.h includes, so
// this wall speaks plain arrays: the files that include ITK include no glint header that
// brings Eigen, and volume/io.cpp converts.
//
// itk_read and the writes run in the plugin libglint_volume_io.so (volume/plugin/itk_io.cpp),
// loaded by the first of them (volume/detail/volume_plugin.h): where it is missing they throw
// IoError saying so. volume_format is string work and needs no plugin.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace glint::detail {

/// A volume as ITK gives it: geometry in plain arrays, voxels i fastest.
struct RawVolume {
    std::array<std::size_t, 3> size{0, 0, 0};
    std::array<double, 3> spacing{1, 1, 1};
    std::array<double, 3> origin{0, 0, 0};
    std::array<double, 9> direction{1, 0, 0, 0, 1,
                                    0, 0, 0, 1};  ///< row-major, columns = axes i, j, k
    std::vector<float> voxels;
    std::string format;       ///< metaimage, nifti, nrrd, dicom
    std::string stored_type;  ///< as stored ("short", "float", …)
};

/// Reads a volume file or a DICOM folder of at most `max_voxels` voxels.
/// \throw InputError (one line naming the file).
[[nodiscard]] RawVolume itk_read(const std::filesystem::path& path, std::size_t max_voxels);

/// The format name for a file's extension, or "" when it is none of glint's volume formats.
[[nodiscard]] std::string volume_format(const std::filesystem::path& path);

/// Writes one file (format by extension) under `path` exactly (the caller stages it).
/// \throw IoError.
void itk_write(const RawVolume& volume, const std::filesystem::path& path);

/// Writes a DICOM CT series into an existing empty folder. \throw IoError.
void itk_write_dicom(const RawVolume& volume, const std::filesystem::path& folder);

}  // namespace glint::detail
