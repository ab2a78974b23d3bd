// DICOM checked before GDCM sees it (issue 23): GDCM asserts (SIGABRT) on some malformed files,
// a 4-byte file in a series folder among them, and a folder such as /proc holds files that
// block or lie about their size. Only regular files that pass a structural check of the DICOM
// Part 10 layout reach GDCM.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace glint::detail {

/// Empty when `path` is a regular file laid out as DICOM Part 10: the 128-byte preamble and
/// "DICM", a file meta group (0002) of explicit-VR elements that fit the file, then data
/// elements that fit the file (walked up to the first undefined length; deflated and
/// big-endian data sets are checked as far as their meta group). Otherwise what is wrong, in
/// words ("4 bytes, expected at least 132 (preamble and \"DICM\")"). Opened without blocking.
[[nodiscard]] std::string dicom_file_problem(const std::filesystem::path& path);

/// The files of a folder (not its sub-folders) GDCM may read, and what the rest are.
struct DicomFolderScan {
    std::vector<std::filesystem::path> accepted;
    std::size_t rejected = 0;
    std::string first_rejection;  ///< "\"name\": problem"
};
[[nodiscard]] DicomFolderScan scan_dicom_folder(const std::filesystem::path& folder);

/// The folder GDCM reads for `folder`: the folder itself when every file in it passes, else a
/// temporary folder of symbolic links to the files that pass (removed with this object).
/// \throw InputError when no file passes: "a folder with no DICOM series in it", with the
/// count and the first rejected file and why.
class CheckedDicomFolder {
  public:
    explicit CheckedDicomFolder(const std::filesystem::path& folder);
    ~CheckedDicomFolder();
    CheckedDicomFolder(const CheckedDicomFolder&) = delete;
    CheckedDicomFolder& operator=(const CheckedDicomFolder&) = delete;
    [[nodiscard]] const std::filesystem::path& path() const { return path_; }

  private:
    std::filesystem::path path_;
    bool temporary_ = false;
};

}  // namespace glint::detail
