// A mapped mesh file that shrinks while it is read (issue 23, item 8): zeros and a flag, never
// SIGBUS; faults elsewhere keep their old fate; no handler left behind.
#include "mesh/detail/guarded_mapping.h"
#include "mesh/error.h"
#include "mesh/io.h"
#include "tests/mesh/test_files.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <unistd.h>
#include <string>

namespace glint {
namespace {

namespace fs = std::filesystem;
using detail::GuardedMapping;

constexpr std::size_t kBytes = 64 * 1024;

fs::path file_of_x(const std::string& name) {
    return test::write_bytes(test::output_dir("guarded_mapping"), name, std::string(kBytes, 'x'));
}

class Fd {
  public:
    explicit Fd(const fs::path& p) : fd_(::open(p.c_str(), O_RDONLY | O_CLOEXEC)) {}
    ~Fd() { ::close(fd_); }
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    [[nodiscard]] int get() const { return fd_; }

  private:
    int fd_;
};

TEST(GuardedMapping, ReadsTheFileAsItIs) {
    const fs::path path = file_of_x("whole.bin");
    const Fd fd(path);
    const GuardedMapping map(fd.get(), kBytes);
    ASSERT_EQ(map.bytes().size(), kBytes);
    EXPECT_EQ(std::string(map.bytes().begin(), map.bytes().end()), std::string(kBytes, 'x'));
    EXPECT_FALSE(map.shrank());
}

TEST(GuardedMapping, AFileCutShortReadsAsZerosInsteadOfEndingTheProcess) {
    const fs::path path = file_of_x("cut.bin");
    const Fd fd(path);
    const GuardedMapping map(fd.get(), kBytes);
    fs::resize_file(path, 100);  // another program rewrites the file
    const volatile char* bytes = map.bytes().data();
    EXPECT_EQ(bytes[50], 'x');
    EXPECT_FALSE(map.shrank()) << "the first page still lies inside the file";
    EXPECT_EQ(bytes[kBytes - 1], 0);  // beyond the end: SIGBUS without the guard
    EXPECT_TRUE(map.shrank());
    EXPECT_EQ(bytes[kBytes / 2], 0);
}

TEST(GuardedMapping, LeavesNoHandlerBehind) {
    struct sigaction before {
    }, after{};
    ::sigaction(SIGBUS, nullptr, &before);
    {
        const fs::path path = file_of_x("handler.bin");
        const Fd fd(path);
        const GuardedMapping map(fd.get(), kBytes);
    }
    ::sigaction(SIGBUS, nullptr, &after);
    EXPECT_EQ(before.sa_handler, after.sa_handler);
    EXPECT_EQ(before.sa_flags & SA_SIGINFO, after.sa_flags & SA_SIGINFO);
}

// A fault in a mapping nobody guards is not swallowed: the process still ends with SIGBUS.
TEST(GuardedMappingDeathTest, AFaultOutsideEveryGuardedRangeStillEndsTheProcess) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const fs::path guarded = file_of_x("guarded.bin");
    const fs::path plain = file_of_x("plain.bin");
    EXPECT_EXIT(
        {
            const Fd gfd(guarded);
            const GuardedMapping map(gfd.get(), kBytes);
            const Fd pfd(plain);
            void* raw = ::mmap(nullptr, kBytes, PROT_READ, MAP_PRIVATE, pfd.get(), 0);
            ::ftruncate(::open(plain.c_str(), O_WRONLY), 10);
            const volatile char c = static_cast<const char*>(raw)[kBytes - 1];
            (void)c;
            ::_exit(0);
        },
        testing::KilledBySignal(SIGBUS), "");
}

// The mapped path of load_mesh (files over 2 GiB) on a small file: the same mesh as read.
TEST(GuardedMapping, LoadMeshReadsAMappedFileLikeARead) {
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const fs::path path = test::write_bytes(test::output_dir("guarded_mapping"), "tri.ply", ply);
    const LoadedMesh read = load_mesh(path);
    detail::set_map_above_bytes_for_testing(0);
    const LoadedMesh mapped = load_mesh(path);
    detail::set_map_above_bytes_for_testing(std::size_t{2} << 30);
    EXPECT_EQ(mapped.mesh.positions, read.mesh.positions);
    EXPECT_EQ(mapped.mesh.triangles, read.mesh.triangles);
}

}  // namespace
}  // namespace glint
