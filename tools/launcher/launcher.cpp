// `glint`: the first few hundred microseconds of the command line (issue 23 item 16).
//
// The program (glint-program) maps ~40 shared libraries before any code of its own runs; a
// SIGINT or SIGTERM in those ~25 ms ended it by the default action (exit 143, no word). This
// launcher maps only the C library: it blocks the two signals, then executes the program. The
// mask survives exec, so a signal sent meanwhile stays pending until the program has installed
// its handlers (tools/interrupts.cpp, from .preinit_array) and unblocks them: it is then seen as
// any other request to stop (exit 130, one line, nothing left half-written).
//
// GLINT_UNBLOCK_SIGNALS tells the program which of the two it should unblock: those that were
// not blocked when the launcher started (a caller's own mask is kept). The program removes the
// variable, so what it starts inherits nothing of it.
//
// Where the program lies: beside the launcher (the build tree), else at the install layout's
// path relative to the launcher's folder (GLINT_PROGRAM_FROM_BINDIR, set by CMake).
//
// note: plain C library calls only, and no C++ library: nothing here may map more than libc.
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <unistd.h>

#ifndef GLINT_PROGRAM_FROM_BINDIR
#define GLINT_PROGRAM_FROM_BINDIR "../lib/glint/glint-program"
#endif

namespace {

constexpr int kExitDeviceOrIo = 3;  // tools/command.h: kExitDeviceOrIo

// The folder of this executable, with a trailing '/', or "" when /proc is not mounted.
bool own_folder(char (&folder)[PATH_MAX]) {
    const ssize_t n = ::readlink("/proc/self/exe", folder, sizeof folder - 1);
    if (n <= 0) return false;
    folder[n] = '\0';
    char* slash = std::strrchr(folder, '/');
    if (slash == nullptr) return false;
    slash[1] = '\0';
    return true;
}

bool join(char (&out)[PATH_MAX], const char* folder, const char* name) {
    return std::snprintf(out, sizeof out, "%s%s", folder, name) < static_cast<int>(sizeof out);
}

}  // namespace

int main(int argc, char** argv) {
    (void)argc;
    sigset_t stop{};
    sigset_t before{};
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    sigprocmask(SIG_BLOCK, &stop, &before);
    char unblock[8] = "";
    if (!sigismember(&before, SIGINT)) std::strcat(unblock, "I");
    if (!sigismember(&before, SIGTERM)) std::strcat(unblock, "T");
    setenv("GLINT_UNBLOCK_SIGNALS", unblock, 1);

    char folder[PATH_MAX];
    char program[PATH_MAX] = "";
    if (own_folder(folder)) {
        char beside[PATH_MAX];
        if (join(beside, folder, "glint-program") && ::access(beside, X_OK) == 0)
            std::strcpy(program, beside);
        else if (join(beside, folder, GLINT_PROGRAM_FROM_BINDIR)) std::strcpy(program, beside);
    }
    if (program[0] != '\0') ::execv(program, argv);
    const int err = errno;
    sigprocmask(SIG_SETMASK, &before, nullptr);
    std::fprintf(stderr,
                 "glint: error: cannot start the glint program \"%s\": %s; expected it beside "
                 "this launcher or at %s from it (reinstall glint)\n",
                 program[0] != '\0' ? program : "glint-program",
                 program[0] != '\0' ? std::strerror(err) : "/proc/self/exe cannot be read",
                 GLINT_PROGRAM_FROM_BINDIR);
    return kExitDeviceOrIo;
}
