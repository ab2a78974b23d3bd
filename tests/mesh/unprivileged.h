// Runs a check as a user that file permissions bind. Root passes every permission check
// (CAP_DAC_OVERRIDE), so tests of "this user may not enter that folder" would skip there; here
// the check runs in a forked child that drops to user and group nobody (65534) first. Its
// answer (a string) comes back through a pipe. Not root: it runs in the test process itself.
#pragma once

#include <grp.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <string>

namespace glint::test {

/// A fresh folder under /tmp that user nobody may enter (the build tree need not be).
inline std::filesystem::path open_temp_folder(const std::string& name) {
    std::string pattern = "/tmp/glint_" + name + ".XXXXXX";
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    std::filesystem::permissions(
        pattern, std::filesystem::perms::owner_all | std::filesystem::perms::group_read |
                     std::filesystem::perms::group_exec | std::filesystem::perms::others_read |
                     std::filesystem::perms::others_exec);
    return pattern;
}

/// `check()`'s string as an unprivileged user sees it; "exception: <what>" when it threw
/// something other than what it catches itself, "child failed" when the child died.
inline std::string as_unprivileged(const std::function<std::string()>& check) {
    auto guarded = [&]() -> std::string {
        try {
            return check();
        } catch (const std::exception& e) {
            return std::string("exception: ") + e.what();
        }
    };
    if (::geteuid() != 0) return guarded();
    int fds[2];
    if (::pipe(fds) != 0) return "child failed: pipe";
    const pid_t pid = ::fork();
    if (pid < 0) return "child failed: fork";
    if (pid == 0) {
        ::close(fds[0]);
        const bool dropped = ::setgroups(0, nullptr) == 0 &&
                             ::setresgid(65534, 65534, 65534) == 0 &&
                             ::setresuid(65534, 65534, 65534) == 0;
        const std::string answer = dropped ? guarded() : "child failed: cannot drop to nobody";
        std::size_t done = 0;
        while (done < answer.size()) {
            const ssize_t n = ::write(fds[1], answer.data() + done, answer.size() - done);
            if (n <= 0) break;
            done += static_cast<std::size_t>(n);
        }
        ::_exit(0);
    }
    ::close(fds[1]);
    std::string answer;
    char buf[4096];
    for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;)
        answer.append(buf, static_cast<std::size_t>(n));
    ::close(fds[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (!WIFEXITED(status)) return "child failed: died";
    return answer;
}

}  // namespace glint::test
