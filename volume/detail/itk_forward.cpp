// itk_io.h's reads and writes, answered by the plugin (volume/detail/volume_plugin.h), which
// is loaded by the first of them.
#include "volume/detail/itk_io.h"
#include "volume/detail/volume_plugin.h"

namespace glint::detail {

RawVolume itk_read(const std::filesystem::path& path, std::size_t max_voxels) {
    RawVolume volume;
    call_volume_io([&](const VolumeIoTable& io, std::string& message) {
        return io.read(path, max_voxels, volume, message);
    });
    return volume;
}

void itk_write(const RawVolume& volume, const std::filesystem::path& path) {
    call_volume_io([&](const VolumeIoTable& io, std::string& message) {
        return io.write(volume, path, message);
    });
}

void itk_write_dicom(const RawVolume& volume, const std::filesystem::path& folder) {
    call_volume_io([&](const VolumeIoTable& io, std::string& message) {
        return io.write_dicom(volume, folder, message);
    });
}

}  // namespace glint::detail
