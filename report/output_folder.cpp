#include "report/output_folder.h"

#include "mesh/error.h"

#include <unistd.h>
#include <system_error>

namespace glint {

namespace fs = std::filesystem;

OutputFolder::OutputFolder(fs::path target, bool replace_existing)
    : target_(fs::absolute(std::move(target)).lexically_normal()) {
    if (target_.filename().empty()) target_ = target_.parent_path();
    std::error_code ec;
    const fs::path parent = target_.parent_path();
    if (!fs::is_directory(parent, ec))
        throw IoError("output folder \"" + target_.string() + "\": parent folder \"" +
                      parent.string() + "\" does not exist");
    if (fs::exists(target_, ec) && !fs::is_directory(target_, ec))
        throw InputError("output \"" + target_.string() + "\" exists and is not a folder");
    if (!replace_existing && fs::exists(target_, ec))
        throw InputError("output folder \"" + target_.string() +
                         "\" exists; give --force to replace it");
    staging_ = parent / (target_.filename().string() + ".partial-" + std::to_string(::getpid()));
    fs::remove_all(staging_, ec);
    fs::create_directories(staging_, ec);
    if (ec || ::access(staging_.c_str(), W_OK) != 0)
        throw IoError("output folder \"" + target_.string() + "\": cannot create \"" +
                      staging_.string() + "\"" +
                      (ec ? ": " + ec.message() : std::string(": not writable")));
}

OutputFolder::~OutputFolder() {
    if (committed_) return;
    std::error_code ec;
    fs::remove_all(staging_, ec);  // destructors never throw; a leftover is harmless
}

fs::path OutputFolder::file(const fs::path& relative) const {
    const fs::path p = staging_ / relative;
    std::error_code ec;
    fs::create_directories(p.parent_path(), ec);
    if (ec)
        throw IoError("cannot create folder \"" + p.parent_path().string() + "\": " + ec.message());
    return p;
}

void OutputFolder::commit() {
    std::error_code ec;
    fs::path aside;
    if (fs::exists(target_, ec)) {
        aside = target_.parent_path() /
                (target_.filename().string() + ".old-" + std::to_string(::getpid()));
        fs::remove_all(aside, ec);
        fs::rename(target_, aside, ec);
        if (ec) throw IoError("cannot replace \"" + target_.string() + "\": " + ec.message());
    }
    fs::rename(staging_, target_, ec);
    if (ec) {
        std::error_code ec2;
        if (!aside.empty()) fs::rename(aside, target_, ec2);  // put the old results back
        throw IoError("cannot move results into \"" + target_.string() + "\": " + ec.message());
    }
    committed_ = true;
    if (!aside.empty()) fs::remove_all(aside, ec);
}

}  // namespace glint
