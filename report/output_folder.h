// An output folder that appears complete or not at all.
//
// Files are written into a staging folder beside the target ("<out>.partial-<pid>"); commit()
// renames it into place (an existing folder of that name, when the caller allows replacing
// it, is moved aside first and removed after the rename: the old results stay whole until
// the new ones are complete). If the run fails or is interrupted before commit(), the destructor
// removes the staging folder: no half-written atlas is ever left under the target name.
#pragma once

#include <filesystem>

namespace glint {

class OutputFolder {
  public:
    /// `replace_existing`: an existing target folder is replaced on commit(); otherwise
    /// InputError names it (the CLI's --force). \throw IoError when the parent folder does
    /// not exist or is not writable; \throw InputError when the target exists and is not a
    /// folder, or exists and may not be replaced.
    explicit OutputFolder(std::filesystem::path target, bool replace_existing = false);
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
