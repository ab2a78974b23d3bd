// Property test of OutputFolder (issue 23: the output-folder logic under random interleavings
// of runs, signals and user actions). Each run is a child process that stages an output,
// stops until told to commit, and commits with or without --force semantics; between its
// steps the test kills it (SIGKILL), asks it to stop (SIGTERM, as glint's handler does:
// request_cancel), or acts as a user: makes the target, writes into it, makes a folder named
// like a staging folder, removes things. A model of what must be on disk follows every step
// and the whole folder is compared with it after each one:
// - a user's files are never lost, unless a --force run replaced the target holding them;
// - the target is absent, the user's folder or one run's complete output, never half of one;
// - a run that reported success has its output in place until a later --force run or the
//   user replaced or removed it; a run refused (exit 2) changed nothing;
// - what killed runs leave is gone once the next run has started; nothing else is left.
// Seeds are fixed: a failure names the seed and the step, and reruns the same interleaving.
#include "report/output_folder.h"

#include "mesh/cancel.h"
#include "mesh/error.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace glint {
namespace {

namespace fs = std::filesystem;
using Files = std::map<std::string, std::string>;  // relative path → content

constexpr int kExitCancelled = 130;
// note: 150 interleavings of 14 steps fork about 1 000 runs, ~15 s of CPU (each fork of this
// test program, with its many libraries mapped, costs ~10 ms of system time).
constexpr unsigned kInterleavings = 150;
constexpr int kSteps = 14;

extern "C" void request_cancel_on_signal(int signal) { request_cancel(signal); }

// A run's complete output: four files, one of them in a sub-folder, each naming the run; its
// report.json names the glint version, as every glint result's does.
Files run_output(int run) {
    const std::string id = std::to_string(run);
    return {{"part1.txt", "run " + id + " part 1"},
            {"report.json", "{\"glint_version\": \"run " + id + "\"}"},
            {"run.txt", "run " + id},
            {"views/a.txt", "run " + id + " view a"}};
}

// Whether a --force run may replace the target: absent, empty, or a glint result (its
// report.json names the glint version); a folder of the user's is never replaced (issue 52).
bool replaceable(const std::optional<Files>& target) {
    if (!target || target->empty()) return true;
    const auto report = target->find("report.json");
    return report != target->end() && report->second.find("\"glint_version\"") != std::string::npos;
}

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

// What a child does: stage part of the output, report 'S', wait for one byte, stage the rest,
// commit. Exit 0 committed, 2 refused, 3 IO trouble, 130 stopped by SIGTERM, 4 anything else.
[[noreturn]] void child_run(const fs::path& target, bool force, int run, int report_fd, int go_fd) {
    struct sigaction action {};
    action.sa_handler = request_cancel_on_signal;  // no SA_RESTART: read() returns EINTR
    ::sigaction(SIGTERM, &action, nullptr);
    int code = 4;
    try {
        OutputFolder out(target, force);
        const Files files = run_output(run);
        write_text(out.file("part1.txt"), files.at("part1.txt"));
        if (::write(report_fd, "S", 1) != 1) ::_exit(5);
        char go = 0;
        while (::read(go_fd, &go, 1) < 0 && errno == EINTR) {
        }
        for (const auto& [name, text] : files)
            if (name != "part1.txt") write_text(out.file(name), text);
        out.commit();
        code = 0;
    } catch (const Cancelled&) {
        code = kExitCancelled;
    } catch (const InputError&) {
        code = 2;
    } catch (const IoError&) {
        code = 3;
    } catch (...) {
        code = 4;
    }
    ::_exit(code);
}

struct PendingRun {
    int id = 0;
    bool force = false;
    pid_t pid = 0;
    int go_fd = -1;
};

// Exit code, or 128 + signal for a killed process.
int wait_exit(pid_t pid) {
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

Files read_tree(const fs::path& root) {
    Files files;
    for (const auto& entry : fs::recursive_directory_iterator(root))
        if (entry.is_regular_file()) {
            std::ifstream in(entry.path());
            std::stringstream text;
            text << in.rdbuf();
            files[fs::relative(entry.path(), root).string()] = text.str();
        }
    return files;
}

std::string describe(const std::optional<Files>& files) {
    if (!files) return "absent";
    std::string text = "{";
    for (const auto& [name, content] : *files) text += " " + name + "=\"" + content + "\"";
    return text + " }";
}

// One interleaving: the folder, the model of what must be in it, the runs in flight.
class Interleaving {
  public:
    Interleaving(unsigned seed, const fs::path& dir) : random_(seed), dir_(dir) {
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    ~Interleaving() {
        for (const auto& run : pending_) {
            ::kill(run.pid, SIGKILL);
            (void)wait_exit(run.pid);
            ::close(run.go_fd);
        }
    }

    // Runs `steps` random steps, checking the folder against the model after each; stops at
    // the first mismatch (a failed expectation) with what was done so far in `log`.
    void run(int steps);
    const std::string& log() const { return log_; }

  private:
    int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(random_); }
    void step();
    void start_run();
    void commit_run(std::size_t index);
    void kill_run(std::size_t index, bool while_committing);
    void terminate_run(std::size_t index);
    void user_makes_target();
    void user_writes_into_target();
    void user_makes_decoy();
    void user_removes_something();
    void commit_outcome(const PendingRun& run, bool may_commit, int code);
    bool belongs_to_pending_run(const std::string& name) const;
    void check(const std::string& after);

    std::mt19937 random_;
    fs::path dir_;
    fs::path target() const { return dir_ / "out"; }
    std::optional<Files> expected_;    ///< the target's files; nullopt: no target
    std::set<std::string> decoys_;     ///< the user's folders named like staging folders
    std::set<std::string> leftovers_;  ///< killed runs' wrappers, until the next run starts
    std::vector<PendingRun> pending_;  ///< staged, waiting to commit
    int next_run_ = 1;
    int next_user_file_ = 1;
    pid_t last_pid_ = 0;
    std::string log_;
};

void Interleaving::run(int steps) {
    for (int i = 0; i < steps && !::testing::Test::HasFailure(); ++i) step();
    while (!pending_.empty() && !::testing::Test::HasFailure()) commit_run(0);
}

void Interleaving::step() {
    const auto any = [this] {
        return static_cast<std::size_t>(pick(static_cast<int>(pending_.size())));
    };
    const int action = pick(10);
    if (pending_.empty() && action < 6) return start_run();
    switch (action) {
        case 0:
        case 1: return pending_.size() < 3 ? start_run() : commit_run(any());
        case 2:
        case 3: return commit_run(any());
        case 4: return kill_run(any(), /*while_committing=*/pick(2) == 1);
        case 5: return terminate_run(any());
        case 6: return user_makes_target();
        case 7: return user_writes_into_target();
        case 8: return user_makes_decoy();
        default: return user_removes_something();
    }
}

void Interleaving::start_run() {
    const int id = next_run_++;
    const bool force = pick(2) == 1;
    int report[2], go[2];
    ASSERT_EQ(::pipe(report), 0);
    ASSERT_EQ(::pipe(go), 0);
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        ::close(report[0]);
        ::close(go[1]);
        child_run(target(), force, id, report[1], go[0]);
    }
    ::close(report[1]);
    ::close(go[0]);
    last_pid_ = pid;
    const std::string what = "run " + std::to_string(id) + (force ? " (force)" : "");
    char staged = 0;
    const bool started = ::read(report[0], &staged, 1) == 1;
    ::close(report[0]);
    const bool may_start = !expected_ || (force && replaceable(expected_));
    if (!started) {
        const int code = wait_exit(pid);
        ::close(go[1]);
        log_ += what + " refused at start, exit " + std::to_string(code) + "\n";
        EXPECT_FALSE(may_start) << what << " failed to start, exit " << code;
        EXPECT_EQ(code, 2) << what << ": a refusal is exit 2";
        return check("the refusal of " + what);
    }
    log_ += what + " staged (pid " + std::to_string(pid) + ")\n";
    EXPECT_TRUE(may_start) << what << " started over a target it may not replace";
    pending_.push_back({id, force, pid, go[1]});
    leftovers_.clear();  // the run started: the wrappers of killed runs must be gone
    check("the start of " + what);
}

// What a run that ended with `code` after being told to commit must have done.
void Interleaving::commit_outcome(const PendingRun& run, bool may_commit, int code) {
    const std::string what = "run " + std::to_string(run.id);
    log_ += what + " ended with exit " + std::to_string(code) + "\n";
    if (may_commit) {
        EXPECT_EQ(code, 0) << what << " should have committed";
        if (code == 0) expected_ = run_output(run.id);
    } else {
        EXPECT_EQ(code, 2) << what << " must refuse the target that appeared (without force, "
                           << "or a folder glint did not write)";
    }
}

void Interleaving::commit_run(std::size_t index) {
    const PendingRun run = pending_[index];
    pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(index));
    const bool may_commit = !expected_ || (run.force && replaceable(expected_));
    log_ += "commit run " + std::to_string(run.id) + "\n";
    const bool told = ::write(run.go_fd, "g", 1) == 1;
    ::close(run.go_fd);
    ASSERT_TRUE(told);
    commit_outcome(run, may_commit, wait_exit(run.pid));
    check("the commit of run " + std::to_string(run.id));
}

// SIGKILL while the run waits, or just after it was told to commit (then the commit may or
// may not have happened, but all of it or nothing).
void Interleaving::kill_run(std::size_t index, bool while_committing) {
    const PendingRun run = pending_[index];
    pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(index));
    const bool may_commit = !expected_ || (run.force && replaceable(expected_));
    log_ += "SIGKILL run " + std::to_string(run.id) +
            (while_committing ? " while committing\n" : " while staged\n");
    if (while_committing) {
        EXPECT_EQ(::write(run.go_fd, "g", 1), 1);
    }
    ::kill(run.pid, SIGKILL);
    const int code = wait_exit(run.pid);
    ::close(run.go_fd);
    if (code != 128 + SIGKILL) {
        EXPECT_TRUE(while_committing) << "run " << run.id << " outlived SIGKILL: " << code;
        commit_outcome(run, may_commit, code);
        return check("the end of run " + std::to_string(run.id));
    }
    if (while_committing && may_commit && fs::is_directory(target()) &&
        read_tree(target()) == run_output(run.id))
        expected_ = run_output(run.id);  // killed after its commit's rename
    const std::string own = "out.partial-" + std::to_string(run.pid);
    for (const auto& entry : fs::directory_iterator(dir_)) {
        const std::string name = entry.path().filename().string();
        if (decoys_.count(name) == 0 && (name == own || name.rfind(own + "-", 0) == 0))
            leftovers_.insert(name);
    }
    check("the kill of run " + std::to_string(run.id));
}

// SIGTERM while staged, as glint's handler takes it: the run stops before its commit and
// removes what it staged (exit 130).
void Interleaving::terminate_run(std::size_t index) {
    const PendingRun run = pending_[index];
    pending_.erase(pending_.begin() + static_cast<std::ptrdiff_t>(index));
    log_ += "SIGTERM run " + std::to_string(run.id) + "\n";
    ::kill(run.pid, SIGTERM);
    EXPECT_EQ(::write(run.go_fd, "g", 1), 1);
    ::close(run.go_fd);
    const int code = wait_exit(run.pid);
    EXPECT_EQ(code, kExitCancelled) << "run " << run.id << " after SIGTERM";
    check("the SIGTERM of run " + std::to_string(run.id));
}

void Interleaving::user_makes_target() {
    if (expected_) return user_writes_into_target();
    const std::string name = "mine-" + std::to_string(next_user_file_) + ".txt";
    const std::string text = "user file " + std::to_string(next_user_file_++);
    log_ += "user makes out/ with " + name + "\n";
    fs::create_directory(target());
    write_text(target() / name, text);
    expected_ = Files{{name, text}};
    check("the user making the target");
}

void Interleaving::user_writes_into_target() {
    if (!expected_) return user_makes_target();
    const std::string name = "mine-" + std::to_string(next_user_file_) + ".txt";
    const std::string text = "user file " + std::to_string(next_user_file_++);
    log_ += "user writes out/" + name + "\n";
    write_text(target() / name, text);
    (*expected_)[name] = text;
    check("the user writing into the target");
}

// A folder named as a staging wrapper, without glint's marker: often with the pid the next
// run is likely to get, so that its wrapper name is taken.
void Interleaving::user_makes_decoy() {
    const long number = pick(2) == 0 ? last_pid_ + 1 + pick(3) : 100000 + pick(900000);
    const std::string name = "out.partial-" + std::to_string(number);
    if (fs::exists(dir_ / name)) return;
    log_ += "user makes " + name + "/\n";
    fs::create_directory(dir_ / name);
    write_text(dir_ / name / "keep.txt", "user decoy");
    decoys_.insert(name);
    check("the user making a decoy");
}

void Interleaving::user_removes_something() {
    if (!decoys_.empty() && (pick(2) == 0 || !expected_)) {
        auto it = decoys_.begin();
        std::advance(it, pick(static_cast<int>(decoys_.size())));
        log_ += "user removes " + *it + "/\n";
        fs::remove_all(dir_ / *it);
        decoys_.erase(it);
    } else if (expected_) {
        log_ += "user removes out/\n";
        fs::remove_all(target());
        expected_.reset();
    }
    check("the user removing something");
}

bool Interleaving::belongs_to_pending_run(const std::string& name) const {
    for (const auto& run : pending_) {
        const std::string own = "out.partial-" + std::to_string(run.pid);
        if (name == own || name.rfind(own + "-", 0) == 0) return true;
    }
    return false;
}

void Interleaving::check(const std::string& after) {
    for (const auto& entry : fs::directory_iterator(dir_)) {
        const std::string name = entry.path().filename().string();
        if (name == "out" || leftovers_.count(name) != 0 || belongs_to_pending_run(name)) continue;
        if (decoys_.count(name) != 0) {
            EXPECT_EQ(describe(read_tree(entry.path())),
                      describe(Files{{"keep.txt", "user decoy"}}))
                << "after " << after << ": the user's " << name << " changed";
            continue;
        }
        ADD_FAILURE() << "after " << after << ": " << name << " is left beside the target";
    }
    for (const auto& name : decoys_)
        EXPECT_TRUE(fs::exists(dir_ / name))
            << "after " << after << ": the user's " << name << " is gone";
    std::optional<Files> actual;
    if (fs::exists(target())) actual = read_tree(target());
    EXPECT_EQ(describe(actual), describe(expected_)) << "after " << after << ": the target";
}

TEST(OutputFolderProperty, RandomRunsSignalsAndUserActionsLoseNothing) {
    const fs::path root = fs::path(GLINT_TEST_OUTPUT_DIR) / "output_folder_property";
    for (unsigned seed = 1; seed <= kInterleavings; ++seed) {
        const fs::path dir = root / std::to_string(seed);
        {
            Interleaving interleaving(seed, dir);
            interleaving.run(kSteps);
            if (::testing::Test::HasFailure()) {
                ADD_FAILURE() << "seed " << seed << ", steps:\n" << interleaving.log();
                return;
            }
        }
        fs::remove_all(dir);
    }
}

}  // namespace
}  // namespace glint
