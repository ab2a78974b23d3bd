// An output folder that appears complete or not at all, and never costs the user anything else.
//
// Files are written into a staging folder beside the target: "<out>.partial-<pid>/out", the
// wrapper "<out>.partial-<pid>" holding a marker file (kStagingMarker: glint, host, pid) that
// recognises it as glint's. commit() moves "out" into place:
// - without replace_existing, with renameat2(RENAME_NOREPLACE): a target that appeared during
//   the run (another run, the user) is refused and kept, never deleted;
// - with it, with renameat2(RENAME_EXCHANGE): the old and new results swap in one step, so the
//   target never disappears; the old ones, now inside the wrapper, are removed after.
// Where the filesystem has no renameat2 flags (EINVAL: some network and FUSE filesystems), the
// fallback is rename(2): without replace_existing it still refuses a non-empty folder that
// appeared (an empty one is replaced); with it the old target is first moved into the
// wrapper, so for that moment the target is absent (the old results are then whole under
// the wrapper and put back if the move of the new ones fails).
// A staging wrapper is never taken over: an existing name gets a numbered sibling. Wrappers of
// earlier runs carrying the marker, of this host, whose process is gone (killed runs) are
// removed when the next run into the same target starts; anything without the marker is left.
// The output is checked against the process' inputs (mesh/output_guard.h) before anything is made.
#pragma once

#include <filesystem>
#include <string_view>

namespace glint {

/// Name of the marker file inside a staging wrapper.
inline constexpr std::string_view kStagingMarker = ".glint-staging";

class OutputFolder {
  public:
    /// `replace_existing`: an existing target folder is replaced on commit(); otherwise
    /// InputError names it (the CLI's --force). \throw IoError when the parent folder does
    /// not exist or is not writable; \throw InputError when the target exists and is not a
    /// folder, exists and may not be replaced, or is, holds or lies inside an input.
    explicit OutputFolder(std::filesystem::path target, bool replace_existing = false);
    ~OutputFolder();
    OutputFolder(const OutputFolder&) = delete;
    OutputFolder& operator=(const OutputFolder&) = delete;

    /// Path of a file inside the staging folder (sub-folders are created on demand).
    [[nodiscard]] std::filesystem::path file(const std::filesystem::path& relative) const;
    [[nodiscard]] const std::filesystem::path& staging() const { return staging_; }
    [[nodiscard]] const std::filesystem::path& target() const { return target_; }
    /// Moves the staging folder into place. \throw InputError when the target appeared during
    /// the run and may not be replaced (it is kept as found); IoError.
    void commit();

  private:
    void commit_new();
    void commit_replacing();
    std::filesystem::path target_;
    std::filesystem::path wrapper_;  ///< "<out>.partial-<pid>": the marker and staging_
    std::filesystem::path staging_;  ///< wrapper_ / "out"
    bool replace_existing_ = false;
};

}  // namespace glint
