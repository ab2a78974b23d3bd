// The DICOM reader's child process (volume/detail/isolated_read.h): whatever the reader does,
// crash, abort, throw or hang until cancelled, the caller gets one error and goes on.
#include "volume/detail/isolated_read.h"
#include "mesh/cancel.h"
#include "mesh/error.h"
#include "mesh/plugin_library.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <unistd.h>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <new>
#include <string>
#include <thread>

namespace glint {
namespace {

namespace fs = std::filesystem;
using detail::RawVolume;

const fs::path kInput = "series";

std::string message_of(const std::function<RawVolume()>& read) {
    try {
        (void)detail::read_in_child(kInput, read);
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no InputError";
    return "";
}

TEST(ReadInChild, GivesBackTheVolumeTheChildRead) {
    RawVolume v;
    v.size = {3, 2, 2};
    v.spacing = {0.5, 0.75, 2.0};
    v.origin = {-1.0, 2.0, 3.5};
    v.direction = {0, 1, 0, 1, 0, 0, 0, 0, -1};
    v.format = "dicom";
    v.stored_type = "short";
    for (int i = 0; i < 12; ++i) v.voxels.push_back(static_cast<float>(i) * 1.5f - 4.0f);
    const RawVolume back = detail::read_in_child(kInput, [&] { return v; });
    EXPECT_EQ(back.size, v.size);
    EXPECT_EQ(back.spacing, v.spacing);
    EXPECT_EQ(back.origin, v.origin);
    EXPECT_EQ(back.direction, v.direction);
    EXPECT_EQ(back.format, "dicom");
    EXPECT_EQ(back.stored_type, "short");
    EXPECT_EQ(back.voxels, v.voxels);
}

// A plugin loading on another thread (the image plugin, preloaded by every run) must have
// ended before the child is made: a child forked while another thread is inside dlopen
// inherits the loader's lock held and may hang in its first dlopen or thrown exception.
TEST(ReadInChild, WaitsForPluginsLoadingInTheBackgroundBeforeItForks) {
    static std::atomic<bool> loaded{false};
    detail::load_in_background([] {
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        loaded.store(true);
    });
    const RawVolume back = detail::read_in_child(kInput, [] {
        RawVolume v;
        v.size = {1, 1, 1};
        v.spacing = {1, 1, 1};
        v.direction = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        v.format = loaded.load() ? "forked after the load" : "forked during the load";
        v.stored_type = "float";
        v.voxels = {0.0f};
        return v;
    });
    EXPECT_EQ(back.format, "forked after the load");
}

TEST(ReadInChild, ASegmentationFaultIsOneLineNamingTheInputAndTheSignal) {
    const std::string m = message_of([]() -> RawVolume {
        ::raise(SIGSEGV);
        return {};
    });
    EXPECT_NE(m.find("\"series\""), std::string::npos) << m;
    EXPECT_NE(m.find("crashed on it (SIGSEGV"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

TEST(ReadInChild, AnAssertionsAbortIsOneLine) {
    const std::string m = message_of([]() -> RawVolume { std::abort(); });
    EXPECT_NE(m.find("SIGABRT"), std::string::npos) << m;
}

TEST(ReadInChild, AChildThatExitsWithoutAResultIsAnInputError) {
    const std::string m = message_of([]() -> RawVolume { ::_exit(7); });
    EXPECT_NE(m.find("exit code 7"), std::string::npos) << m;
}

TEST(ReadInChild, ErrorsComeBackAsTheirOwnKindAndMessage) {
    EXPECT_EQ(message_of([]() -> RawVolume { throw InputError("DICOM folder \"s\": no series"); }),
              "DICOM folder \"s\": no series");
    try {
        (void)detail::read_in_child(kInput, []() -> RawVolume { throw IoError("disk gone"); });
        ADD_FAILURE() << "no IoError";
    } catch (const IoError& e) {
        EXPECT_STREQ(e.what(), "disk gone");
    }
    EXPECT_THROW((void)detail::read_in_child(kInput, []() -> RawVolume { throw std::bad_alloc(); }),
                 std::bad_alloc);
}

TEST(ReadInChild, TheChildsChatterNeverReachesTheTerminal) {
    testing::internal::CaptureStderr();
    testing::internal::CaptureStdout();
    (void)detail::read_in_child(kInput, [] {
        std::fprintf(stderr, "GDCM chatter\n");
        std::printf("more chatter\n");
        std::fflush(nullptr);
        return RawVolume{};
    });
    EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(ReadInChild, ItsTemporaryFilesAreRemovedEvenWhenItCrashes) {
    const fs::path parent_temp = fs::temp_directory_path();
    fs::path seen;
    (void)message_of([&]() -> RawVolume {
        // The child writes its TMPDIR into a file of the parent's temp folder, then crashes.
        const fs::path own = fs::temp_directory_path();
        std::FILE* f = std::fopen((own / "left-behind").c_str(), "w");
        if (f != nullptr) std::fclose(f);
        std::FILE* note = std::fopen(
            (parent_temp / ("glint-child-temp-" + std::to_string(::getppid()))).c_str(), "w");
        if (note != nullptr) {
            std::fputs(own.c_str(), note);
            std::fclose(note);
        }
        ::raise(SIGSEGV);
        return {};
    });
    const fs::path note = parent_temp / ("glint-child-temp-" + std::to_string(::getpid()));
    std::FILE* f = std::fopen(note.c_str(), "r");
    ASSERT_NE(f, nullptr);
    char buffer[4096] = {};
    const std::size_t n = std::fread(buffer, 1, sizeof buffer - 1, f);
    std::fclose(f);
    fs::remove(note);
    seen = std::string(buffer, n);
    EXPECT_NE(seen, parent_temp) << "the child had no temporary folder of its own";
    EXPECT_FALSE(fs::exists(seen)) << seen;
}

TEST(ReadInChild, CancellingKillsAReaderThatDoesNotReturn) {
    reset_cancel();
    std::thread stopper([] {
        std::this_thread::sleep_for(std::chrono::milliseconds(200));
        request_cancel(SIGINT);
    });
    const auto start = std::chrono::steady_clock::now();
    EXPECT_THROW((void)detail::read_in_child(kInput,
                                             []() -> RawVolume {
                                                 ::sleep(60);
                                                 return {};
                                             }),
                 Cancelled);
    stopper.join();
    reset_cancel();
    // Not a timing claim: a reader that was not killed would hold the test for a minute.
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
}

}  // namespace
}  // namespace glint
