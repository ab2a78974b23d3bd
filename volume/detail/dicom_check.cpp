#include "volume/detail/dicom_check.h"

#include "mesh/error.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <array>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

namespace glint::detail {

namespace fs = std::filesystem;

namespace {

class Fd {
  public:
    explicit Fd(const fs::path& p) : fd_(::open(p.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)) {}
    ~Fd() {
        if (fd_ >= 0) ::close(fd_);
    }
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    [[nodiscard]] int get() const { return fd_; }

  private:
    int fd_;
};

bool read_at(int fd, std::uint64_t offset, void* into, std::size_t n) {
    return ::pread(fd, into, n, static_cast<off_t>(offset)) == static_cast<ssize_t>(n);
}

std::uint16_t u16(const unsigned char* p) { return static_cast<std::uint16_t>(p[0] | p[1] << 8); }
std::uint32_t u32(const unsigned char* p) {
    return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
           static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

// VRs with a 2-byte reserved field and a 4-byte length in explicit VR encoding.
bool long_vr(std::string_view vr) {
    for (std::string_view v :
         {"OB", "OD", "OF", "OL", "OV", "OW", "SQ", "SV", "UC", "UN", "UR", "UT", "UV"})
        if (vr == v) return true;
    return false;
}

// The value representations DICOM defines (PS3.5 6.2). note: GDCM reads an unknown one as a
// long-form VR, so the two bytes after it and the next element's tag become a 4-byte length:
// "DW" for "DS" made GDCM allocate 2.2 GB and take 12 s for three 614-byte files (fuzz_dicom).
bool known_vr(std::string_view vr) {
    for (std::string_view v :
         {"AE", "AS", "AT", "CS", "DA", "DS", "DT", "FD", "FL", "IS", "LO", "LT",
          "OB", "OD", "OF", "OL", "OV", "OW", "PN", "SH", "SL", "SQ", "SS", "ST",
          "SV", "TM", "UC", "UI", "UL", "UN", "UR", "US", "UT", "UV"})
        if (vr == v) return true;
    return false;
}

// The VRs the standard gives the elements GDCM reads through gdcm::Attribute while it makes an
// image: any other VR there fails its assertion "GetVR().Compatible(de.GetVR())" (SIGABRT;
// fuzz_dicom: Columns (0028,0011) given as "SS"). Elements not listed are not checked.
struct ExpectedVr {
    std::uint16_t group, element;
    std::string_view vrs;  ///< allowed VRs, space-separated
};
constexpr ExpectedVr kImageElements[] = {
    {0x0002, 0x0010, "UI"},    {0x0008, 0x0016, "UI"},    {0x0008, 0x0018, "UI"},
    {0x0008, 0x0060, "CS"},    {0x0018, 0x0050, "DS"},    {0x0018, 0x0088, "DS"},
    {0x0020, 0x000D, "UI"},    {0x0020, 0x000E, "UI"},    {0x0020, 0x0013, "IS"},
    {0x0020, 0x0032, "DS"},    {0x0020, 0x0037, "DS"},    {0x0028, 0x0002, "US"},
    {0x0028, 0x0004, "CS"},    {0x0028, 0x0006, "US"},    {0x0028, 0x0008, "IS"},
    {0x0028, 0x0010, "US"},    {0x0028, 0x0011, "US"},    {0x0028, 0x0030, "DS"},
    {0x0028, 0x0034, "IS"},    {0x0028, 0x0100, "US"},    {0x0028, 0x0101, "US"},
    {0x0028, 0x0102, "US"},    {0x0028, 0x0103, "US"},    {0x0028, 0x0106, "US SS"},
    {0x0028, 0x0107, "US SS"}, {0x0028, 0x0120, "US SS"}, {0x0028, 0x1050, "DS"},
    {0x0028, 0x1051, "DS"},    {0x0028, 0x1052, "DS"},    {0x0028, 0x1053, "DS"},
    {0x0028, 0x1054, "LO"},    {0x0028, 0x1101, "US SS"}, {0x0028, 0x1102, "US SS"},
    {0x0028, 0x1103, "US SS"}, {0x0028, 0x2110, "CS"},    {0x0028, 0x2112, "DS"},
    {0x0054, 0x0081, "US"},    {0x7FE0, 0x0010, "OB OW"},
};

// The problem with element (group, element) given as `vr`, or "".
std::string unexpected_vr(std::uint16_t group, std::uint16_t element, std::string_view vr) {
    for (const ExpectedVr& e : kImageElements) {
        if (e.group != group || e.element != element) continue;
        for (std::size_t at = 0; at + 2 <= e.vrs.size(); at += 3)
            if (e.vrs.substr(at, 2) == vr) return "";
        char tag[16];
        std::snprintf(tag, sizeof tag, "(%04X,%04X)", group, element);
        return std::string("element ") + tag + " has value representation \"" + std::string(vr) +
               "\", expected " + std::string(e.vrs);
    }
    return "";
}

// Values GDCM asserts on (SIGABRT) rather than refusing: Samples per Pixel "spp <= 4"
// (fuzz_dicom), and the pixel layout it derives buffers from. US elements only.
struct UsRange {
    std::uint16_t element;  ///< in group 0028
    std::uint16_t min, max;
    const char* name;
};
constexpr UsRange kPixelValues[] = {
    {0x0002, 1, 4, "Samples per Pixel"}, {0x0006, 0, 1, "Planar Configuration"},
    {0x0010, 1, 65535, "Rows"},          {0x0011, 1, 65535, "Columns"},
    {0x0100, 1, 64, "Bits Allocated"},   {0x0101, 1, 64, "Bits Stored"},
    {0x0102, 0, 63, "High Bit"},         {0x0103, 0, 1, "Pixel Representation"},
};

std::string unexpected_value(std::uint16_t group, std::uint16_t element, std::uint16_t value) {
    if (group != 0x0028) return "";
    // note: GDCM's GetScalarType asserts "type <= INT64" on any other width (fuzz_dicom).
    if (element == 0x0100 && value != 8 && value != 16 && value != 32 && value != 64)
        return "Bits Allocated is " + std::to_string(value) + ", expected 8, 16, 32 or 64";
    for (const UsRange& r : kPixelValues)
        if (r.element == element && (value < r.min || value > r.max))
            return std::string(r.name) + " is " + std::to_string(value) + ", expected " +
                   std::to_string(r.min) + " to " + std::to_string(r.max);
    return "";
}

struct Walk {
    std::uint64_t offset = 0;
    std::string transfer_syntax;
    std::string problem;
    std::optional<std::uint32_t> meta_length;  ///< (0002,0000), the group's stated length
    std::uint64_t meta_start = 0;              ///< where the elements it counts begin
    bool big_endian = false;                   ///< explicit VR big endian data set
};

// One element at w.offset; false at the end of what can be walked. `explicit_vr`: the VR is in
// the stream. `meta_only`: stop at the first element outside group 0002.
bool step(int fd, std::uint64_t size, bool explicit_vr, bool meta_only, Walk& w) {
    const auto r16 = [&](const unsigned char* p) {
        return w.big_endian ? static_cast<std::uint16_t>(p[1] | p[0] << 8) : u16(p);
    };
    const auto r32 = [&](const unsigned char* p) {
        return w.big_endian
                   ? static_cast<std::uint32_t>(p[3]) | static_cast<std::uint32_t>(p[2]) << 8 |
                         static_cast<std::uint32_t>(p[1]) << 16 |
                         static_cast<std::uint32_t>(p[0]) << 24
                   : u32(p);
    };
    if (w.offset == size) return false;
    unsigned char h[12];
    if (size - w.offset < 8 || !read_at(fd, w.offset, h, 8)) {
        w.problem = "an element header at byte " + std::to_string(w.offset) + " is cut off";
        return false;
    }
    const std::uint16_t group = r16(h);
    if (meta_only && group != 0x0002) return false;
    std::uint64_t header = 8, length = 0;
    const std::string_view vr(reinterpret_cast<const char*>(h + 4), 2);
    if (explicit_vr && !(vr[0] >= 'A' && vr[0] <= 'Z' && vr[1] >= 'A' && vr[1] <= 'Z')) {
        w.problem = "byte " + std::to_string(w.offset + 4) + ": no value representation";
        return false;
    }
    if (explicit_vr && !known_vr(vr)) {
        w.problem = "byte " + std::to_string(w.offset + 4) + ": value representation \"" +
                    std::string(vr) + "\" is none DICOM defines";
        return false;
    }
    if (explicit_vr) {
        if (std::string problem = unexpected_vr(group, r16(h + 2), vr); !problem.empty()) {
            w.problem = "byte " + std::to_string(w.offset) + ": " + problem;
            return false;
        }
    }
    if (explicit_vr && long_vr(vr)) {
        if (size - w.offset < 12 || !read_at(fd, w.offset + 8, h + 8, 4)) {
            w.problem = "an element header at byte " + std::to_string(w.offset) + " is cut off";
            return false;
        }
        header = 12;
        length = r32(h + 8);
    } else {
        length = explicit_vr ? r16(h + 6) : r32(h + 4);
    }
    if (length == 0xFFFFFFFFu) return false;  // undefined length: GDCM parses the rest
    if (length > size - w.offset - header) {
        w.problem = "element (" + std::to_string(group) + "," + std::to_string(r16(h + 2)) +
                    ") at byte " + std::to_string(w.offset) + " holds " + std::to_string(length) +
                    " bytes, the file has " + std::to_string(size - w.offset - header) + " left";
        return false;
    }
    if (explicit_vr && vr == "US" && length == 2) {
        unsigned char v[2];
        if (read_at(fd, w.offset + header, v, 2))
            if (std::string problem = unexpected_value(group, r16(h + 2), r16(v));
                !problem.empty()) {
                w.problem = "byte " + std::to_string(w.offset) + ": " + problem;
                return false;
            }
    }
    if (group == 0x0002 && r16(h + 2) == 0x0000 && length == 4) {
        unsigned char v[4];
        if (read_at(fd, w.offset + header, v, 4)) {
            w.meta_length = r32(v);
            w.meta_start = w.offset + header + length;
        }
    }
    if (group == 0x0002 && r16(h + 2) == 0x0010 && length < 128) {
        std::string uid(length, '\0');
        if (read_at(fd, w.offset + header, uid.data(), length))
            w.transfer_syntax = uid.substr(0, uid.find_last_not_of(std::string("\0 ", 2)) + 1);
    }
    w.offset += header + length;
    return true;
}

}  // namespace

std::string dicom_file_problem(const fs::path& path) {
    const Fd fd(path);
    if (fd.get() < 0) return std::string("cannot open: ") + std::strerror(errno);
    struct stat st {};
    if (::fstat(fd.get(), &st) != 0 || !S_ISREG(st.st_mode))
        return "not a regular file, expected a DICOM file";
    const auto size = static_cast<std::uint64_t>(st.st_size);
    std::array<char, 4> magic{};
    if (size < 132 || !read_at(fd.get(), 128, magic.data(), 4))
        return std::to_string(size) + " bytes, expected at least 132 (preamble and \"DICM\")";
    if (std::string_view(magic.data(), 4) != "DICM")
        return "no \"DICM\" after the 128-byte preamble, expected a DICOM Part 10 file";
    Walk w{.offset = 132};
    while (step(fd.get(), size, true, true, w)) {
    }
    if (!w.problem.empty()) return "file meta group: " + w.problem;
    if (w.offset == 132) return "no file meta group (0002) after \"DICM\"";
    // note: GDCM reads the meta group by its stated length and asserts ("Should not happen",
    // SIGABRT) when the file ends inside it: fuzz_dicom's first finding.
    // note: both are Type 1 in PS3.10; GDCM asserted on a meta group without them that the file
    // ended after (fuzz_dicom).
    if (!w.meta_length) return "file meta group: no group length (0002,0000)";
    if (*w.meta_length != w.offset - w.meta_start)
        return "file meta group: its length (0002,0000) says " + std::to_string(*w.meta_length) +
               " bytes, its elements take " + std::to_string(w.offset - w.meta_start);
    if (w.transfer_syntax.empty()) return "file meta group: no transfer syntax (0002,0010)";
    if (w.offset == size) return "no data set after the file meta group";
    const std::string& ts = w.transfer_syntax;
    if (ts == "1.2.840.10008.1.2.1.99") return {};  // deflated: not walked
    // note: big endian was not walked either; GDCM read a 395-byte one into 4.3 GB (fuzz_dicom).
    w.big_endian = ts == "1.2.840.10008.1.2.2";
    const bool explicit_vr = ts != "1.2.840.10008.1.2";
    for (int n = 0; n < 100000 && step(fd.get(), size, explicit_vr, false, w); ++n) {
    }
    return w.problem.empty() ? std::string() : "data set: " + w.problem;
}

DicomFolderScan scan_dicom_folder(const fs::path& folder) {
    DicomFolderScan scan;
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        std::error_code e2;
        if (it->is_directory(e2)) continue;  // GDCM reads one level, as glint does
        std::string problem = dicom_file_problem(it->path());
        if (problem.empty()) {
            scan.accepted.push_back(it->path());
            continue;
        }
        if (scan.rejected++ == 0)
            scan.first_rejection = "\"" + it->path().filename().string() + "\": " + problem;
    }
    return scan;
}

CheckedDicomFolder::CheckedDicomFolder(const fs::path& folder) : path_(folder) {
    const DicomFolderScan scan = scan_dicom_folder(folder);
    const std::string quoted = "\"" + folder.string() + "\"";
    if (scan.accepted.empty())
        throw InputError(quoted + ": a folder with no DICOM series in it" +
                         (scan.rejected == 0 ? std::string()
                                             : " (" + std::to_string(scan.rejected) +
                                                   " file(s) are not DICOM files; first " +
                                                   scan.first_rejection + ")"));
    if (scan.rejected == 0) return;
    static std::atomic<unsigned> counter{0};
    std::error_code ec;
    path_ = fs::temp_directory_path(ec) /
            ("glint-dicom-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    temporary_ = true;
    fs::remove_all(path_, ec);
    fs::create_directory(path_, ec);
    for (const fs::path& f : scan.accepted)
        if (!ec) fs::create_symlink(fs::absolute(f), path_ / f.filename(), ec);
    if (ec)
        throw IoError(quoted + ": cannot link its DICOM files into \"" + path_.string() +
                      "\": " + ec.message());
}

CheckedDicomFolder::~CheckedDicomFolder() {
    std::error_code ec;
    if (temporary_) fs::remove_all(path_, ec);
}

}  // namespace glint::detail
