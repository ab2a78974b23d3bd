// Volume reading and writing through ITK (GDCM for DICOM). Every ITK exception becomes a
// one-line InputError / IoError naming the file. No Eigen here (see itk_io.h).
#include "volume/detail/itk_io.h"

#include "mesh/error.h"
#include "volume/detail/dicom_check.h"

#include <gdcmTrace.h>
#include <itkGDCMImageIO.h>
#include <itkGDCMSeriesFileNames.h>
#include <itkImage.h>
#include <itkImageFileReader.h>
#include <itkImageFileWriter.h>
#include <itkImageSeriesReader.h>
#include <itkMetaImageIO.h>
#include <itkNiftiImageIO.h>
#include <itkNrrdImageIO.h>
#include <nifti1_io.h>
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
#include <regex>
#include <sstream>

namespace glint::detail {

namespace fs = std::filesystem;

namespace {

using FloatImage = itk::Image<float, 3>;

bool ends_with(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() &&
           std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(), [](char a, char b) {
               return std::tolower(static_cast<unsigned char>(a)) ==
                      std::tolower(static_cast<unsigned char>(b));
           });
}

std::string quoted(const fs::path& p) { return "volume \"" + p.string() + "\""; }

// ITK's messages span several lines and start with the source location: keep one line.
std::string one_line(const itk::ExceptionObject& e) {
    std::string text = e.GetDescription();
    std::replace(text.begin(), text.end(), '\n', ' ');
    std::replace(text.begin(), text.end(), '\r', ' ');
    text.erase(
        std::unique(text.begin(), text.end(), [](char a, char b) { return a == ' ' && b == ' '; }),
        text.end());
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

// The ImageIO for a file name, chosen by extension (no factory search: the formats glint
// reads are exactly these).
itk::ImageIOBase::Pointer image_io_for(const fs::path& path) {
    const std::string format = volume_format(path);
    if (format == "metaimage") return itk::MetaImageIO::New().GetPointer();
    if (format == "nifti") return itk::NiftiImageIO::New().GetPointer();
    if (format == "nrrd") return itk::NrrdImageIO::New().GetPointer();
    if (format == "dicom") return itk::GDCMImageIO::New().GetPointer();
    throw InputError(
        quoted(path) +
        ": unknown volume format, expected .mhd .mha .nii .nii.gz .nrrd .nhdr .dcm or a "
        "DICOM folder");
}

std::string size_text(const itk::ImageIOBase& io) {
    std::ostringstream s;
    for (unsigned d = 0; d < io.GetNumberOfDimensions(); ++d)
        s << (d ? " x " : "") << io.GetDimensions(d);
    return s.str();
}

// A direction matrix (m[row][column], columns the axes) must be finite with columns of
// non-zero length that span 3D. (Plain arrays: this file sees ITK's bundled Eigen, not ours.)
// note: 1e-6 on the determinant of the column-normalised matrix: axes closer than ~0.06° to
// lying in one plane are not a scanner's grid.
using Matrix3 = std::array<std::array<double, 3>, 3>;

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
        text << quoted(path) << ": direction matrix [";
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

// note: 1e6 mm for a voxel axis (a kilometre) and 1e9 mm for a position bound what any scan
// holds; far beyond them ITK's matrix code overflows.
constexpr double kMaxAxisMm = 1e6;
constexpr double kMaxPositionMm = 1e9;

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
        throw InputError(quoted(path) + ": NIfTI dim[0] = " + std::to_string(n->dim0) +
                         ", dim[1] = " + std::to_string(n->dim1) +
                         ", expected 1 to 7 dimensions of at least one voxel");
    if (std::find(kDatatypes.begin(), kDatatypes.end(), n->datatype) == kDatatypes.end())
        throw InputError(quoted(path) + ": NIfTI datatype " + std::to_string(n->datatype) +
                         ", expected one of NIfTI's codes");
    auto refuse = [&](const std::string& field, double value, const std::string& expected) {
        std::ostringstream text;
        text << quoted(path) << ": NIfTI " << field << " = " << value << ", expected " << expected;
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
            quoted(path) + ": ElementDataFile = \"" + printable(value.substr(0, 60)) +
            "\", expected LOCAL, LIST, a file name or a slice pattern 'name%d first last step' "
            "(first <= last, step > 0)");
}

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
        throw InputError(quoted(path) + ": MetaImage header line " + std::to_string(n + 1) + " " +
                         found + ", expected text lines 'Key = Value' up to ElementDataFile");
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
            throw InputError(quoted(path) + ": NDims = \"" + printable(value.substr(0, 40)) +
                             "\", expected an integer from 1 to 4");
    }
    throw InputError(
        quoted(path) + ": no ElementDataFile within the first " + std::to_string(kMaxLines) +
        " lines of the MetaImage header, expected 'ElementDataFile = LOCAL' or a file name");
}

// Rejects what is not one scalar 3D volume, before any voxel is read.
void check_header(const itk::ImageIOBase& io, const fs::path& path) {
    const unsigned dims = io.GetNumberOfDimensions();
    if (dims == 2)
        throw InputError(quoted(path) + ": a 2D image (" + size_text(io) +
                         "), expected a 3D volume");
    if (dims == 4 && io.GetDimensions(3) != 1)
        throw InputError(quoted(path) + ": a 4D image (" + size_text(io) +
                         "), expected a 3D volume");
    if (dims < 2 || dims > 4)
        throw InputError(quoted(path) + ": a " + std::to_string(dims) +
                         "D image, expected a 3D volume");
    if (io.GetNumberOfComponents() != 1)
        throw InputError(quoted(path) + ": " + std::to_string(io.GetNumberOfComponents()) +
                         " components per voxel, expected a scalar volume");
    for (unsigned d = 0; d < 3; ++d)
        if (io.GetDimensions(d) < 2)
            throw InputError(quoted(path) + ": size " + size_text(io) +
                             ", expected at least 2 voxels along every axis");
    // The geometry ITK would hand to the image: a non-finite or singular one makes its matrix
    // code abort the process (vnl), so it is refused here, before the voxels are read.
    Matrix3 direction{};
    for (unsigned d = 0; d < 3; ++d) {
        const double spacing = io.GetSpacing(d), origin = io.GetOrigin(d);
        if (!plausible(spacing, kMaxAxisMm) || spacing == 0.0 ||
            !plausible(origin, kMaxPositionMm)) {
            std::ostringstream text;
            text << quoted(path) << ": spacing " << spacing << " and origin " << origin
                 << " along axis " << d
                 << ", expected a spacing other than 0 up to 1e6 mm and an origin within 1e9 mm";
            throw InputError(text.str());
        }
        const auto column = io.GetDirection(d);
        for (unsigned r = 0; r < 3; ++r) {
            direction[r][d] = r < column.size() ? column[r] : 0.0;
            if (!plausible(direction[r][d], kMaxAxisMm))
                direction[r][d] = std::numeric_limits<double>::quiet_NaN();
        }
    }
    check_direction(direction, path);
}

// A file pattern "CThead.%d 1 113 1" (printf pattern, first, last, step): one file per slice,
// each exactly one slice of bytes (MetaIO would read a missing slice as nothing and go on).
void require_slice_files(const itk::ImageIOBase& io, const fs::path& header,
                         const std::string& pattern) {
    std::istringstream in(pattern);
    std::string format;
    long first = 0, last = 0, step = 1;
    in >> format >> first >> last >> step;
    if (!in || step <= 0 || last < first)
        return;  // not a pattern MetaIO reads either: let it say so
    // note: the pattern comes from the file: only one integer conversion (%d, %03d, …) may
    // reach snprintf, anything else (%s, %n, two conversions) is refused as bad input.
    if (!std::regex_match(format, std::regex("[^%]*%0?[0-9]{0,3}d[^%]*")))
        throw InputError(quoted(header) + ": file pattern \"" + format +
                         "\", expected a name with one %d");
    if (io.GetDimensions(2) == 0) return;
    const auto slice_bytes =
        static_cast<std::uintmax_t>(io.GetImageSizeInBytes()) / io.GetDimensions(2);
    if (first < 0 || last > 1'000'000)
        throw InputError(quoted(header) + ": file pattern \"" + pattern + "\" numbers slices " +
                         std::to_string(first) + " to " + std::to_string(last) +
                         ", expected 0 to 1000000");
    for (long n = first; n <= last; n += step) {
        char name[1024];
        std::snprintf(name, sizeof name, format.c_str(), static_cast<int>(n));
        const fs::path slice = header.parent_path() / name;
        std::error_code ec;
        if (!fs::exists(slice, ec))
            throw InputError(quoted(header) + ": slice file \"" + slice.string() +
                             "\" is missing (pattern \"" + pattern + "\")");
        const auto found = fs::file_size(slice, ec);
        if (!ec && found != slice_bytes)
            throw InputError(quoted(header) + ": slice file \"" + slice.string() + "\" holds " +
                             std::to_string(found) + " bytes, one slice needs " +
                             std::to_string(slice_bytes));
    }
}

// A detached, uncompressed MetaImage data file must hold what the header promises (the
// reader would otherwise fail with a message that names neither file nor sizes).
void require_data_size(const itk::ImageIOBase& io, const fs::path& header) {
    auto* meta = dynamic_cast<itk::MetaImageIO*>(const_cast<itk::ImageIOBase*>(&io));
    if (!meta) return;
    MetaImage* m = meta->GetMetaImagePointer();
    const std::string data_name = m->ElementDataFileName();
    // note: LOCAL data and a LIST are left to MetaIO.
    if (m->CompressedData() || data_name == "LOCAL" || data_name == "LIST") return;
    if (data_name.find(' ') != std::string::npos) {
        require_slice_files(io, header, data_name);
        return;
    }
    const fs::path data = header.parent_path() / data_name;
    std::error_code ec;
    if (!fs::exists(data, ec))
        throw InputError(quoted(header) + ": data file \"" + data.string() + "\" is missing");
    const auto found = fs::file_size(data, ec);
    const auto expected = static_cast<std::uintmax_t>(io.GetImageSizeInBytes());
    if (!ec && found != expected)
        throw InputError(quoted(header) + ": data file \"" + data.string() + "\" holds " +
                         std::to_string(found) + " bytes, the header (" + size_text(io) + " " +
                         itk::ImageIOBase::GetComponentTypeAsString(io.GetComponentType()) +
                         ") needs " + std::to_string(expected));
}

RawVolume from_itk(const FloatImage& image, std::string format, std::string stored) {
    RawVolume v;
    const auto size = image.GetLargestPossibleRegion().GetSize();
    for (unsigned d = 0; d < 3; ++d) {
        v.size[d] = size[d];
        v.spacing[d] = image.GetSpacing()[d];
        v.origin[d] = image.GetOrigin()[d];
        for (unsigned c = 0; c < 3; ++c) v.direction[3 * d + c] = image.GetDirection()[d][c];
    }
    const float* data = image.GetBufferPointer();
    v.voxels.assign(data, data + size[0] * size[1] * size[2]);
    v.format = std::move(format);
    v.stored_type = std::move(stored);
    return v;
}

// zlib's deflate cannot compress better than about 1032:1, so compressed voxels need at least
// 1/1032 of their size in the file (bzip2 is bounded similarly, far above this).
constexpr double kMaxCompressionRatio = 1032.0;

// NRRD header fields glint needs for the size check: "encoding:" and "data file:".
std::string nrrd_field(const fs::path& path, const std::string& key) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    for (int n = 0; n < 256 && std::getline(in, line) && !line.empty() && line != "\r"; ++n)
        if (line.rfind(key, 0) == 0) {
            std::string v = line.substr(key.size());
            v.erase(0, v.find_first_not_of(" \t"));
            while (!v.empty() && (v.back() == '\r' || v.back() == ' ')) v.pop_back();
            return v;
        }
    return "";
}

std::string count_text(long double n) {
    std::ostringstream text;
    text << std::setprecision(n < 1e19L ? 0 : 3) << (n < 1e19L ? std::fixed : std::scientific) << n;
    return text.str();
}

// The voxels a header declares must fit the budget and the bytes that hold them (the file, or
// its detached data file), before ITK allocates the image: a header may declare a volume of
// terabytes in a file of a few hundred bytes.
void require_data_fits(const itk::ImageIOBase& io, const fs::path& path, const std::string& format,
                       std::size_t max_voxels) {
    long double voxels = 1.0L;
    for (unsigned d = 0; d < io.GetNumberOfDimensions(); ++d)
        voxels *= static_cast<long double>(io.GetDimensions(d));
    voxels *= static_cast<long double>(io.GetNumberOfComponents());
    if (voxels > static_cast<long double>(max_voxels))
        throw InputError(quoted(path) + ": size " + size_text(io) + " is " + count_text(voxels) +
                         " voxels, more than the limit " + std::to_string(max_voxels));
    fs::path holder = path;
    bool compressed = false;
    if (format == "nifti") {
        compressed = path.extension() == ".gz";
    } else if (format == "nrrd") {
        const std::string encoding = nrrd_field(path, "encoding:");
        compressed = encoding != "raw" && encoding != "";
        const std::string data = nrrd_field(path, "data file:");
        if (!data.empty() && data.find(' ') == std::string::npos && data != "LIST")
            holder = path.parent_path() / data;
        else if (!data.empty()) return;  // a list or pattern of files: ITK reads it slice by slice
    } else if (auto* meta = dynamic_cast<itk::MetaImageIO*>(const_cast<itk::ImageIOBase*>(&io))) {
        MetaImage* m = meta->GetMetaImagePointer();
        compressed = m->CompressedData();
        const std::string data = m->ElementDataFileName();
        if (data == "LIST" || data.find(' ') != std::string::npos)
            return;  // slice files, checked apart
        if (data != "LOCAL") holder = path.parent_path() / data;
    }
    std::error_code ec;
    const auto available = fs::file_size(holder, ec);
    if (ec) return;  // ITK says the data file is missing
    const long double needed = voxels * static_cast<long double>(io.GetComponentSize());
    const long double room =
        static_cast<long double>(available) * (compressed ? kMaxCompressionRatio : 1.0);
    if (needed > room)
        throw InputError(quoted(path) + ": size " + size_text(io) + " needs " + count_text(needed) +
                         " bytes of voxels, " +
                         (compressed ? "more than a compressed " : "more than the ") +
                         std::to_string(available) + "-byte file \"" + holder.filename().string() +
                         "\" can hold");
}

RawVolume read_file(const fs::path& path, std::size_t max_voxels) {
    itk::ImageIOBase::Pointer io = image_io_for(path);
    const std::string format = volume_format(path);
    io->SetFileName(path.string());
    if (!io->CanReadFile(path.string().c_str()))
        throw InputError(quoted(path) + ": not a readable " + format + " file");
    if (format == "nifti") check_nifti_header(path);
    if (format == "metaimage") check_metaimage_header(path);
    io->ReadImageInformation();
    check_header(*io, path);
    require_data_fits(*io, path, format, max_voxels);
    require_data_size(*io, path);
    const std::string stored = itk::ImageIOBase::GetComponentTypeAsString(io->GetComponentType());
    auto reader = itk::ImageFileReader<FloatImage>::New();
    reader->SetImageIO(io);
    reader->SetFileName(path.string());
    reader->Update();
    return from_itk(*reader->GetOutput(), format, stored);
}

RawVolume read_dicom_folder(const fs::path& folder, std::size_t max_voxels) {
    const CheckedDicomFolder checked(folder);  // GDCM asserts on some malformed files
    auto names = itk::GDCMSeriesFileNames::New();
    names->SetUseSeriesDetails(true);
    names->SetDirectory(checked.path().string());
    const auto& uids = names->GetSeriesUIDs();
    if (uids.empty()) throw InputError(quoted(folder) + ": a folder with no DICOM series in it");
    // note: the series with the most slices; a folder often also holds a scout or a dose report.
    std::vector<std::string> files;
    for (const auto& uid : uids) {
        auto f = names->GetFileNames(uid);
        if (f.size() > files.size()) files = f;
    }
    if (files.size() < 2)
        throw InputError(quoted(folder) + ": the DICOM series has " + std::to_string(files.size()) +
                         " slice, expected a 3D volume (2 or more slices)");
    auto io = itk::GDCMImageIO::New();
    io->SetFileName(files.front());
    io->ReadImageInformation();
    const long double voxels =
        static_cast<long double>(io->GetDimensions(0)) * io->GetDimensions(1) * files.size();
    if (voxels > static_cast<long double>(max_voxels))
        throw InputError(quoted(folder) + ": " + std::to_string(files.size()) + " slices of " +
                         std::to_string(io->GetDimensions(0)) + " x " +
                         std::to_string(io->GetDimensions(1)) + " voxels, more than the limit " +
                         std::to_string(max_voxels));
    auto reader = itk::ImageSeriesReader<FloatImage>::New();
    reader->SetImageIO(io);
    reader->SetFileNames(files);
    reader->Update();
    return from_itk(*reader->GetOutput(), "dicom",
                    itk::ImageIOBase::GetComponentTypeAsString(io->GetComponentType()));
}

FloatImage::Pointer to_itk(const RawVolume& v) {
    auto image = FloatImage::New();
    FloatImage::SizeType size;
    FloatImage::SpacingType spacing;
    FloatImage::PointType origin;
    FloatImage::DirectionType direction;
    for (unsigned d = 0; d < 3; ++d) {
        size[d] = v.size[d];
        spacing[d] = v.spacing[d];
        origin[d] = v.origin[d];
        for (unsigned c = 0; c < 3; ++c) direction[d][c] = v.direction[3 * d + c];
    }
    image->SetRegions(FloatImage::RegionType(size));
    image->SetSpacing(spacing);
    image->SetOrigin(origin);
    image->SetDirection(direction);
    image->Allocate();
    std::copy(v.voxels.begin(), v.voxels.end(), image->GetBufferPointer());
    return image;
}

}  // namespace

std::string volume_format(const fs::path& path) {
    const std::string name = path.filename().string();
    if (ends_with(name, ".mha") || ends_with(name, ".mhd")) return "metaimage";
    if (ends_with(name, ".nii") || ends_with(name, ".nii.gz")) return "nifti";
    if (ends_with(name, ".nrrd") || ends_with(name, ".nhdr")) return "nrrd";
    if (ends_with(name, ".dcm")) return "dicom";
    return "";
}

RawVolume itk_read(const fs::path& path, std::size_t max_voxels) {
    itk::Object::GlobalWarningDisplayOff();  // library code never prints
    gdcm::Trace::WarningOff();
    nifti_set_debug_level(0);  // niftilib writes "** ERROR: …" to stderr; ITK's exception says it
    try {
        std::error_code ec;
        if (fs::is_directory(path, ec)) return read_dicom_folder(path, max_voxels);
        if (volume_format(path) == "dicom")
            if (const std::string problem = dicom_file_problem(path); !problem.empty())
                throw InputError(quoted(path) + ": " + problem);
        return read_file(path, max_voxels);
    } catch (const itk::ExceptionObject& e) {
        throw InputError(quoted(path) + ": " + one_line(e));
    }
}

void itk_write(const RawVolume& volume, const fs::path& path) {
    itk::Object::GlobalWarningDisplayOff();
    try {
        auto writer = itk::ImageFileWriter<FloatImage>::New();
        writer->SetImageIO(image_io_for(path));
        writer->SetFileName(path.string());
        writer->SetInput(to_itk(volume));
        writer->SetUseCompression(ends_with(path.string(), ".gz") ||
                                  ends_with(path.string(), ".nhdr"));
        writer->Update();
    } catch (const itk::ExceptionObject& e) {
        throw IoError(quoted(path) + ": cannot write: " + one_line(e));
    }
}

}  // namespace glint::detail
