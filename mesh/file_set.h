// Several files that appear together or not at all (a fit.json and the fitted mesh, a phantom
// and its sidecar; issue 23).
#pragma once

#include <filesystem>
#include <functional>
#include <string_view>
#include <vector>

namespace glint {

/// add() writes each file completely under a temporary name beside its target (checked against
/// the process' inputs like write_atomically, mesh/output_guard.h); commit() renames them all.
/// A failure before commit, or the destructor without commit, removes every temporary; a
/// rename failing during commit (rare: same folder) also removes the targets this set already
/// moved in (a file they replaced is not restored).
class FileSet {
  public:
    FileSet() = default;
    ~FileSet();
    FileSet(const FileSet&) = delete;
    FileSet& operator=(const FileSet&) = delete;
    /// `write` receives a temporary path with the target's extension and must create it.
    void add(const std::filesystem::path& path,
             const std::function<void(const std::filesystem::path& temp)>& write);
    /// Text or bytes.
    void add(const std::filesystem::path& path, std::string_view contents);
    void commit();

  private:
    struct Staged {
        std::filesystem::path temp, target, path;
    };
    std::vector<Staged> staged_;
};

}  // namespace glint
