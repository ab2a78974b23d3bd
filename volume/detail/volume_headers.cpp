// Volume header checks made before ITK reads a file (see volume_headers.h).
#include "volume/detail/volume_headers.h"

#include "mesh/error.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>
#include <string>

namespace glint::detail {

namespace fs = std::filesystem;

namespace {}  // namespace

// A direction matrix (m[row][column], columns the axes) must be finite with columns of
// non-zero length that span 3D. (Plain arrays: this file sees ITK's bundled Eigen, not ours.)
// note: 1e-6 on the determinant of the column-normalised matrix: axes closer than ~0.06° to
// lying in one plane are not a scanner's grid.
void check_direction(const Matrix3& m, const fs::path& path) {
    Matrix3 u = m;
    bool ok = true;
    for (std::size_t c = 0; c < 3 && ok; ++c) {
        double n = 0.0;
        for (std::size_t r = 0; r < 3; ++r) n += m[r][c] * m[r][c];
        n = std::sqrt(n);
        ok = std::isfinite(n) && n > 0.0;
        for (std::size_t r = 0; r < 3 && ok; ++r) u[r][c] = m[r][c] / n;
    }
    const double det = ok ? u[0][0] * (u[1][1] * u[2][2] - u[1][2] * u[2][1]) -
                                u[0][1] * (u[1][0] * u[2][2] - u[1][2] * u[2][0]) +
                                u[0][2] * (u[1][0] * u[2][1] - u[1][1] * u[2][0])
                          : 0.0;
    if (!(std::abs(det) > 1e-6)) {
        std::ostringstream text;
        text << quoted_volume(path.string()) << ": direction matrix [";
        for (std::size_t r = 0; r < 3; ++r)
            text << (r ? "; " : "") << m[r][0] << " " << m[r][1] << " " << m[r][2];
        text << "], expected finite axes that span 3D";
        throw InputError(text.str());
    }
}

// A number a scanner's geometry can hold: finite, at most `limit` in magnitude, and either
// zero or a normal float. note: subnormal entries (|x| < 1.2e-38) send ITK's float SVD of a
// NIfTI orientation into an endless loop (a fuzz_nii finding); 1e-30 keeps well clear of them
// while a rounded rotation's "zeros" (~1e-8) stay.
bool plausible(double x, double limit) {
    return std::isfinite(x) && std::abs(x) <= limit && (x == 0.0 || std::abs(x) >= 1e-30);
}

namespace {

// The fields of a NIfTI-1 (348-byte) or NIfTI-2 (540-byte) header glint checks, either byte
// order; nullopt when the file cannot be opened or is shorter than a header (ITK then says so).
struct NiftiHeader {
    std::int64_t dim0 = 0, dim1 = 0;
    std::int32_t datatype = 0, qform_code = 0, sform_code = 0;
    std::array<double, 3> pixdim{};
    std::array<double, 6> quatern{};  // b, c, d, qoffset x, y, z
    std::array<double, 12> srow{};    // srow_x, srow_y, srow_z
};

std::optional<NiftiHeader> read_nifti_header(const fs::path& path) {
    gzFile file = gzopen(path.c_str(), "rb");  // zlib reads .nii and .nii.gz alike
    if (file == nullptr) return std::nullopt;
    std::array<unsigned char, 540> h{};
    const int got = gzread(file, h.data(), static_cast<unsigned>(h.size()));
    gzclose(file);
    if (got < 348) return std::nullopt;
    bool swap = false;
    auto integer = [&](std::size_t at, std::size_t bytes) {
        std::uint64_t v = 0;
        for (std::size_t k = 0; k < bytes; ++k)
            v |= static_cast<std::uint64_t>(h[at + (swap ? bytes - 1 - k : k)]) << (8 * k);
        if (bytes == 8) return static_cast<std::int64_t>(v);
        const std::uint64_t sign = std::uint64_t{1} << (8 * bytes - 1);
        return v & sign ? static_cast<std::int64_t>(v) - static_cast<std::int64_t>(sign << 1)
                        : static_cast<std::int64_t>(v);
    };
    // note: as niftilib does: 540 in either byte order is NIfTI-2; anything else is read as
    // NIfTI-1 (niftilib goes on past a wrong sizeof_hdr), its byte order told by dim[0].
    bool v2 = integer(0, 4) == 540;
    if (!v2) {
        swap = true;
        v2 = integer(0, 4) == 540 && got >= 540;
        if (!v2) {
            swap = false;
            const auto dim0 = integer(40, 2);
            swap = dim0 < 1 || dim0 > 7;
        }
    }
    auto real = [&](std::size_t at) {
        const std::int64_t bits = integer(at, v2 ? 8 : 4);
        if (v2) return std::bit_cast<double>(bits);
        return static_cast<double>(std::bit_cast<float>(static_cast<std::int32_t>(bits)));
    };
    const std::size_t step = v2 ? 8 : 4;
    NiftiHeader n;
    n.dim0 = v2 ? integer(16, 8) : integer(40, 2);
    n.dim1 = v2 ? integer(24, 8) : integer(42, 2);
    n.datatype = static_cast<std::int32_t>(integer(v2 ? 12 : 70, 2));
    n.qform_code = static_cast<std::int32_t>(v2 ? integer(344, 4) : integer(252, 2));
    n.sform_code = static_cast<std::int32_t>(v2 ? integer(348, 4) : integer(254, 2));
    for (std::size_t k = 0; k < 3; ++k) n.pixdim[k] = real((v2 ? 104 : 76) + (k + 1) * step);
    for (std::size_t k = 0; k < 6; ++k) n.quatern[k] = real((v2 ? 352 : 256) + k * step);
    for (std::size_t k = 0; k < 12; ++k) n.srow[k] = real((v2 ? 400 : 280) + k * step);
    return n;
}

}  // namespace

// What ITK would otherwise trip over in a NIfTI header, before it reads it: niftilib prints its
// own "** ERROR" lines for a bad dim[0], dim[1] or datatype, and ITK's matrix code aborts the
// process on a non-finite or singular orientation (a fuzz_nii finding: an sform with NaN) or
// loops forever on one with subnormal entries.
void check_nifti_header(const fs::path& path) {
    const std::optional<NiftiHeader> n = read_nifti_header(path);
    if (!n) return;
    static constexpr std::array<std::int32_t, 16> kDatatypes{
        2, 4, 8, 16, 32, 64, 128, 256, 512, 768, 1024, 1280, 1536, 1792, 2048, 2304};
    if (n->dim0 < 1 || n->dim0 > 7 || n->dim1 < 1)
        throw InputError(quoted_volume(path.string()) + ": NIfTI dim[0] = " +
                         std::to_string(n->dim0) + ", dim[1] = " + std::to_string(n->dim1) +
                         ", expected 1 to 7 dimensions of at least one voxel");
    if (std::find(kDatatypes.begin(), kDatatypes.end(), n->datatype) == kDatatypes.end())
        throw InputError(quoted_volume(path.string()) + ": NIfTI datatype " +
                         std::to_string(n->datatype) + ", expected one of NIfTI's codes");
    auto refuse = [&](const std::string& field, double value, const std::string& expected) {
        std::ostringstream text;
        text << quoted_volume(path.string()) << ": NIfTI " << field << " = " << value
             << ", expected " << expected;
        throw InputError(text.str());
    };
    for (std::size_t k = 0; k < 3; ++k)
        if (!plausible(n->pixdim[k], kMaxAxisMm) || (n->qform_code > 0 && n->pixdim[k] == 0.0))
            refuse("pixdim[" + std::to_string(k + 1) + "]", n->pixdim[k],
                   "a spacing other than 0, at most 1e6 mm");
    for (std::size_t k = 0; k < 6 && n->qform_code > 0; ++k)
        if (!(k < 3 ? std::isfinite(n->quatern[k]) && std::abs(n->quatern[k]) <= 1.0 + 1e-5
                    : plausible(n->quatern[k], kMaxPositionMm)))
            refuse("qform parameter " + std::to_string(k), n->quatern[k],
                   k < 3 ? "a quaternion component in [-1, 1]" : "a position within 1e9 mm");
    if (n->sform_code <= 0) return;
    Matrix3 m{};
    for (std::size_t r = 0; r < 3; ++r) {
        for (std::size_t c = 0; c < 4; ++c) {
            const double x = n->srow[4 * r + c];
            if (!plausible(x, c < 3 ? kMaxAxisMm : kMaxPositionMm))
                refuse(std::string("srow_") + "xyz"[r] + "[" + std::to_string(c) + "]", x,
                       "a finite, normal number of plausible size");
            if (c < 3) m[r][c] = x;
        }
    }
    check_direction(m, path);
}

namespace {

// Bytes of a hostile header shown in a message: anything but printable ASCII becomes '?'.
std::string printable(std::string text) {
    for (char& c : text)
        if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
    return text;
}

// ElementDataFile is LOCAL, LIST, one file name, or a slice pattern "name%d first last step";
// MetaIO divides by the step of anything with a space in it (a fuzz_mha SIGFPE on
// "LOCObjectType = Image%"), so a pattern must parse with first <= last and a step above 0.
void check_data_file_value(const fs::path& path, const std::string& value) {
    if (value.find_first_of(" \t") == std::string::npos) return;
    std::istringstream in(value);
    std::string format, rest;
    long first = 0, last = 0, step = 0;
    in >> format >> first >> last >> step;
    const bool parsed = !in.fail() && !(in >> rest);
    if (!parsed || step <= 0 || last < first)
        throw InputError(
            quoted_volume(path.string()) + ": ElementDataFile = \"" +
            printable(value.substr(0, 60)) +
            "\", expected LOCAL, LIST, a file name or a slice pattern 'name%d first last step' "
            "(first <= last, step > 0)");
}

}  // namespace

// MetaIO trusts its header: it reads every array field with NDims entries, and on a value it
// cannot parse ("NDims = = -3") goes on reading a failed stream through billions of entries;
// a NUL inside a key made it loop, a key of a few hundred bytes overran a fixed buffer (libc
// aborted the process), and so did a value of a few hundred bytes (MetaIO keeps its string
// fields in 255-byte arrays): fuzz_mha findings. So the header is read here first, up to
// ElementDataFile: text lines 'Key = Value' (a key of letters, digits and '_' up to 64
// characters, a line up to 254 bytes, no control byte), NDims one integer from 1 to 4.
void check_metaimage_header(const fs::path& path) {
    constexpr std::size_t kMaxKey = 64, kMaxLine = 254;
    constexpr int kMaxLines = 1024;
    std::ifstream in(path, std::ios::binary);
    std::string line;
    auto refuse = [&](int n, const std::string& found) {
        throw InputError(quoted_volume(path.string()) + ": MetaImage header line " +
                         std::to_string(n + 1) + " " + found +
                         ", expected text lines 'Key = Value' up to ElementDataFile");
    };
    auto trim = [](std::string t) {
        t.erase(0, t.find_first_not_of(" \t\r"));
        t.erase(t.find_last_not_of(" \t\r") + 1);
        return t;
    };
    for (int n = 0; n < kMaxLines && std::getline(in, line); ++n) {
        if (line.size() > kMaxLine)
            refuse(n, "is " + std::to_string(line.size()) + " bytes long (MetaIO's fields hold " +
                          std::to_string(kMaxLine) + ")");
        for (const char c : line) {
            const auto u = static_cast<unsigned char>(c);
            if (u < 0x20 && c != '\t' && c != '\r') {
                std::ostringstream found;
                found << "holds the control byte 0x" << std::hex << static_cast<int>(u);
                refuse(n, found.str());
            }
        }
        if (trim(line).empty()) continue;
        const auto eq = line.find('=');
        if (eq == std::string::npos)
            refuse(n, "has no '=' (\"" + printable(trim(line).substr(0, 40)) + "\")");
        const std::string key = trim(line.substr(0, eq)), value = trim(line.substr(eq + 1));
        const bool identifier =
            !key.empty() && key.size() <= kMaxKey &&
            std::all_of(key.begin(), key.end(), [](char c) {
                return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
            });
        if (!identifier)
            refuse(n, "has the key \"" + printable(key.substr(0, 40)) +
                          (key.size() > 40 ? "...\"" : "\""));
        if (key == "ElementDataFile") {
            check_data_file_value(path, value);
            return;
        }
        if (key != "NDims") continue;
        int dims = 0;
        const auto r = std::from_chars(value.data(), value.data() + value.size(), dims);
        if (r.ec != std::errc() || r.ptr != value.data() + value.size() || dims < 1 || dims > 4)
            throw InputError(quoted_volume(path.string()) + ": NDims = \"" +
                             printable(value.substr(0, 40)) +
                             "\", expected an integer from 1 to 4");
    }
    throw InputError(
        quoted_volume(path.string()) + ": no ElementDataFile within the first " +
        std::to_string(kMaxLines) +
        " lines of the MetaImage header, expected 'ElementDataFile = LOCAL' or a file name");
}

}  // namespace glint::detail
