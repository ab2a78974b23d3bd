// Whole processes for benchmarks that time a run as a user starts it (peers_bench.cpp,
// startup_bench.cpp): wall time from spawn to exit and the peak resident memory (wait4).
#pragma once

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace glint::bench {

struct ProcessRun {
    double seconds = 0.0;
    double peak_mib = 0.0;
};

/// Runs argv[0] with stdout into `stdout_file` (empty: /dev/null) and stderr kept; waits.
inline ProcessRun run_process(const std::vector<std::string>& argv,
                              const std::filesystem::path& stdout_file) {
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    const std::string out = stdout_file.empty() ? "/dev/null" : stdout_file.string();
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const auto t0 = std::chrono::steady_clock::now();
    pid_t pid = 0;
    const int err = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (err != 0) throw std::runtime_error("cannot start " + argv[0]);
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    ProcessRun r;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.peak_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw std::runtime_error(argv[0] + " " + argv[1] + " failed (status " +
                                 std::to_string(status) + ")");
    return r;
}

}  // namespace glint::bench
