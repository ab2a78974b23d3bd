#include "report/output_folder.h"

#include "mesh/cancel.h"
#include "mesh/error.h"
#include "mesh/fault_injection.h"
#include "mesh/front_end.h"
#include "mesh/output_guard.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>  // renameat2, RENAME_EXCHANGE, RENAME_NOREPLACE (glibc 2.28)
#include <unistd.h>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

namespace glint {

namespace fs = std::filesystem;

namespace {

std::string host_name() {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
    return name;
}

std::string marker_text(pid_t pid) {
    return "glint staging folder\nhost " + host_name() + "\npid " + std::to_string(pid) + "\n";
}

// The pid a staging wrapper's marker names when it is glint's, of this host; otherwise 0.
pid_t marker_pid(const fs::path& wrapper) {
    std::ifstream in(wrapper / kStagingMarker);
    std::string title, host_key, host, pid_key;
    long pid = 0;
    if (!std::getline(in, title) || title != "glint staging folder") return 0;
    if (!(in >> host_key >> host >> pid_key >> pid) || host_key != "host" || pid_key != "pid")
        return 0;
    return host == host_name() && pid > 0 ? static_cast<pid_t>(pid) : 0;
}

// Removes a staging wrapper with its marker last: a run killed while removing it (after a
// commit, or unwinding) leaves a wrapper that is still recognised as glint's and removed by
// the next run, never an unmarked folder that looks like the user's.
void remove_wrapper(const fs::path& wrapper) {
    std::error_code ec;
    for (fs::directory_iterator it(wrapper, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().filename() != kStagingMarker) {
            std::error_code ignored;
            fs::remove_all(it->path(), ignored);
        }
    fs::remove_all(wrapper, ec);
}

// The pid a wrapper's name carries ("<out>.partial-<pid>[-n]" after `prefix`), or 0.
pid_t named_pid(const std::string& name, const std::string& prefix) {
    long pid = 0;
    std::size_t at = prefix.size();
    for (; at < name.size() && std::isdigit(static_cast<unsigned char>(name[at])) && pid < 1L << 30;
         ++at)
        pid = 10 * pid + (name[at] - '0');
    const bool whole = at == name.size() || name[at] == '-';
    return whole && at > prefix.size() ? static_cast<pid_t>(pid) : 0;
}

bool gone(pid_t pid) {
    return pid > 0 && pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH;
}

// Removes the staging wrappers of killed runs into `target`: marked as glint's, of this host,
// their process gone. A folder without the marker is the user's and is left alone, but for an
// empty one whose name carries a pid that is gone: a run killed between making its wrapper and
// writing the marker left it, and an empty folder holds nothing to lose (only an empty folder
// is removed: fs::remove refuses any other).
void remove_leftovers(const fs::path& target) {
    const std::string prefix = target.filename().string() + ".partial-";
    std::error_code ec;
    for (fs::directory_iterator it(target.parent_path(), ec), end; !ec && it != end;
         it.increment(ec)) {
        const fs::path p = it->path();
        const std::string name = p.filename().string();
        if (name.compare(0, prefix.size(), prefix) != 0 || it->is_symlink(ec) ||
            !it->is_directory(ec))
            continue;
        const pid_t pid = marker_pid(p);
        if (pid == 0) {
            std::error_code ignored;
            if (gone(named_pid(name, prefix)) && fs::is_empty(p, ignored)) fs::remove(p, ignored);
            continue;
        }
        if (!gone(pid)) continue;  // alive, ours, or not ours to judge
        remove_wrapper(p);
    }
}

// A new wrapper beside the target, never an existing folder: "<out>.partial-<pid>[-n]".
fs::path make_wrapper(const fs::path& target) {
    const std::string base = target.filename().string() + ".partial-" + std::to_string(::getpid());
    for (int n = 0; n < 100; ++n) {
        const fs::path w = target.parent_path() / (n == 0 ? base : base + "-" + std::to_string(n));
        std::error_code ec;
        if (fs::create_directory(w, ec)) return w;
        if (ec)
            throw IoError("output folder \"" + target.string() + "\": cannot create \"" +
                          w.string() + "\": " + ec.message());
    }
    throw IoError("output folder \"" + target.string() + "\": 100 folders named \"" + base +
                  "*\" exist beside it; expected a free staging name");
}

int rename2(const fs::path& from, const fs::path& to, unsigned flags) {
    return ::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), flags) == 0 ? 0 : errno;
}

bool no_flags_here(int err) { return err == EINVAL || err == ENOSYS || err == ENOTSUP; }

// Whether an existing folder may be replaced by --force: it is empty, or it is a result glint
// wrote (its report.json names the glint version that wrote it). Anything else is the user's:
// "-o . --force" in a home folder, "-o .." (issue 52).
bool is_glint_result(const fs::path& folder) {
    std::error_code ec;
    if (fs::is_empty(folder, ec) && !ec) return true;
    const fs::path report = folder / "report.json";
    if (!fs::is_regular_file(fs::symlink_status(report, ec))) return false;
    // note: report.json's keys are sorted, so "glint_version" may follow the regions; read in
    // blocks, keeping the tail of each so a key across two blocks is still found.
    const std::string key = "\"glint_version\"";
    std::ifstream in(report, std::ios::binary);
    std::string block(1 << 16, '\0'), tail;
    while (in) {
        in.read(block.data(), static_cast<std::streamsize>(block.size()));
        const std::string text = tail + block.substr(0, static_cast<std::size_t>(in.gcount()));
        if (text.find(key) != std::string::npos) return true;
        tail = text.size() > key.size() ? text.substr(text.size() - key.size()) : text;
    }
    return false;
}

void refuse_foreign_folder(const fs::path& target) {
    std::error_code ec;
    if (fs::is_directory(fs::symlink_status(target, ec)) && !is_glint_result(target))
        throw InputError("output folder \"" + target.string() +
                         "\" exists and holds files glint did not write (no report.json of a glint "
                         "run); expected an empty folder or an earlier glint result (nothing was "
                         "replaced, " +
                         spell_flag("force") + " or not: choose another output folder)");
}

}  // namespace

OutputFolder::OutputFolder(fs::path target, bool replace_existing)
    : target_(fs::absolute(std::move(target)).lexically_normal()),
      replace_existing_(replace_existing) {
    if (target_.filename().empty()) target_ = target_.parent_path();
    refuse_output_over_inputs(target_);
    std::error_code ec;
    const fs::path parent = target_.parent_path();
    if (!fs::is_directory(parent, ec))
        throw IoError("output folder \"" + target_.string() + "\": parent folder \"" +
                      parent.string() + "\" does not exist");
    if (fs::exists(target_, ec) && !fs::is_directory(target_, ec))
        throw InputError("output \"" + target_.string() + "\" exists and is not a folder");
    if (fs::is_symlink(target_, ec))
        throw InputError("output \"" + target_.string() +
                         "\" is a symbolic link; expected a folder or no file at all (nothing was "
                         "written)");
    if (!replace_existing && fs::exists(target_, ec))
        throw InputError("output folder \"" + target_.string() + "\" exists; give " +
                         spell_flag("force") + " to replace it");
    if (replace_existing) refuse_foreign_folder(target_);
    remove_leftovers(target_);
    wrapper_ = make_wrapper(target_);
    track_staged(wrapper_);  // removed by the watchdog when a step never comes back
    staging_ = wrapper_ / "out";
    {
        std::ofstream marker(wrapper_ / kStagingMarker);
        marker << marker_text(::getpid());
    }
    fs::create_directory(staging_, ec);
    if (ec || ::access(staging_.c_str(), W_OK) != 0) {
        remove_wrapper(wrapper_);
        untrack_staged(wrapper_);
        throw IoError("output folder \"" + target_.string() + "\": cannot create \"" +
                      staging_.string() + "\"" +
                      (ec ? ": " + ec.message() : std::string(": not writable")));
    }
}

OutputFolder::~OutputFolder() {
    remove_wrapper(wrapper_);  // never throws; what a kill leaves is marked
    untrack_staged(wrapper_);
}

fs::path OutputFolder::file(const fs::path& relative) const {
    const fs::path p = staging_ / relative;
    std::error_code ec;
    fs::create_directories(p.parent_path(), ec);
    if (ec)
        throw IoError("cannot create folder \"" + p.parent_path().string() + "\": " + ec.message());
    return p;
}

void OutputFolder::commit_new() {
    int err = rename2(staging_, target_, RENAME_NOREPLACE);
    if (no_flags_here(err)) {
        // rename(2) replaces only an empty folder; a non-empty one fails with ENOTEMPTY.
        err = ::rename(staging_.c_str(), target_.c_str()) == 0 ? 0 : errno;
        if (err == ENOTEMPTY) err = EEXIST;
    }
    if (err == EEXIST)
        throw InputError("output folder \"" + target_.string() +
                         "\" appeared during the run (another run or program made it); kept as "
                         "found, expected it absent (give " +
                         spell_flag("force") + " to replace it)");
    if (err != 0)
        throw IoError("cannot move results into \"" + target_.string() +
                      "\": " + std::strerror(err));
}

void OutputFolder::commit_replacing() {
    for (int attempt = 0; attempt < 10; ++attempt) {
        int err = rename2(staging_, target_, RENAME_EXCHANGE);
        if (err == 0) return;  // the old results are now staging_, removed with the wrapper
        if (err == ENOENT) {   // no target (any more): a plain, non-replacing move
            err = rename2(staging_, target_, RENAME_NOREPLACE);
            if (err == 0) return;
            if (err == EEXIST) continue;  // appeared meanwhile: exchange with it
        }
        if (!no_flags_here(err))
            throw IoError("cannot move results into \"" + target_.string() +
                          "\": " + std::strerror(err));
        // No renameat2 flags on this filesystem: move the old results into the wrapper first
        // (the target is absent for that moment), put them back if the new ones cannot move.
        const fs::path old = wrapper_ / "old";
        std::error_code ec;
        if (fs::exists(target_, ec)) fs::rename(target_, old, ec);
        if (ec) throw IoError("cannot replace \"" + target_.string() + "\": " + ec.message());
        fs::rename(staging_, target_, ec);
        if (ec) {
            std::error_code ec2;
            if (fs::exists(old, ec2)) fs::rename(old, target_, ec2);
            throw IoError("cannot move results into \"" + target_.string() + "\": " + ec.message());
        }
        return;
    }
    throw IoError("cannot move results into \"" + target_.string() +
                  "\": it kept appearing and disappearing (10 attempts)");
}

void OutputFolder::commit() {
    fault_point("commit");
    // A signal that came while the last files were written stops the run here, before the
    // point of no return; one that comes after is reported by the command line (exit 130,
    // the results kept and complete).
    throw_if_cancelled();
    // Every file the run read is an input by now (the loaders register what they open: masks,
    // slices, buffers read after this folder was made): the results never replace one.
    refuse_output_over_inputs(target_);
    if (replace_existing_) {
        refuse_foreign_folder(target_);
        commit_replacing();
    } else {
        commit_new();
    }
    fault_point("committed");
    remove_wrapper(wrapper_);  // the marker, and with --force the replaced results
}

}  // namespace glint
