// The ITK/GDCM side inside the plugin (the program reaches it through volume/detail/itk_io.h,
// where the behaviour is documented). Names differ from itk_io.h's forwarders so that the
// plugin's definitions and the program's never share a symbol.
#pragma once

#include "volume/detail/itk_io.h"

namespace glint::detail::itk_side {

[[nodiscard]] RawVolume read(const std::filesystem::path& path, std::size_t max_voxels);
void write(const RawVolume& volume, const std::filesystem::path& path);
void write_dicom(const RawVolume& volume, const std::filesystem::path& folder);

}  // namespace glint::detail::itk_side
