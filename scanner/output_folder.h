// An output folder that appears complete or not at all.
//
// Files are written into a staging folder beside the target ("<out>.partial-<pid>"); commit()
// renames it into place (an existing folder of that name is moved aside first and removed
// after the rename). If the run fails or is interrupted before commit(), the destructor
// removes the staging folder: no half-written atlas is ever left under the target name.
#pragma once

#include <filesystem>

namespace glint {

class OutputFolder {
public:
    /// \throw IoError when the parent folder does not exist or is not writable;
    /// \throw InputError when the target exists and is not a folder.
    explicit OutputFolder(std::filesystem::path target);
    ~OutputFolder();
    OutputFolder(const OutputFolder&) = delete;
    OutputFolder& operator=(const OutputFolder&) = delete;

    /// Path of a file inside the staging folder (sub-folders are created on demand).
    [[nodiscard]] std::filesystem::path file(const std::filesystem::path& relative) const;
    [[nodiscard]] const std::filesystem::path& staging() const { return staging_; }
    [[nodiscard]] const std::filesystem::path& target() const { return target_; }
    /// Moves the staging folder into place. \throw IoError.
    void commit();

private:
    std::filesystem::path target_;
    std::filesystem::path staging_;
    bool committed_ = false;
};

}  // namespace glint
