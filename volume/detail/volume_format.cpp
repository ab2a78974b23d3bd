// The volume format for a file name: pure string work, so the program answers it without
// loading the ITK plugin (volume/io.cpp asks it for every path it is given).
#include "volume/detail/itk_io.h"

#include <algorithm>
#include <cctype>

namespace glint::detail {

namespace {
bool ends_with_ignoring_case(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() &&
           std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(), [](char a, char b) {
               return std::tolower(static_cast<unsigned char>(a)) ==
                      std::tolower(static_cast<unsigned char>(b));
           });
}
}  // namespace

std::string volume_format(const std::filesystem::path& path) {
    const std::string name = path.filename().string();
    const auto is = [&](const char* suffix) { return ends_with_ignoring_case(name, suffix); };
    if (is(".mha") || is(".mhd")) return "metaimage";
    if (is(".nii") || is(".nii.gz")) return "nifti";
    if (is(".nrrd") || is(".nhdr")) return "nrrd";
    if (is(".dcm")) return "dicom";
    return "";
}

}  // namespace glint::detail
