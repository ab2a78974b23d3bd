// Volume reading and writing through ITK (GDCM for DICOM). Every ITK exception becomes a
// one-line InputError / IoError naming the file. No Eigen here (see itk_io.h).
#include "volume/plugin/itk_side.h"

#include "mesh/error.h"
#include "volume/detail/dicom_check.h"
#include "volume/detail/volume_headers.h"
#include "volume/plugin/metaimage_data.h"

#include <gdcmTrace.h>
#include <itkGDCMImageIO.h>
#include <itkGDCMSeriesFileNames.h>
#include <itkImage.h>
#include <itkImageFileReader.h>
#include <itkImageFileWriter.h>
#include <itkImageSeriesReader.h>
#include <itkMetaDataObject.h>
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
#include <iostream>
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
        quoted_volume(path.string()) +
        ": unknown volume format, expected .mhd .mha .nii .nii.gz .nrrd .nhdr .dcm or a "
        "DICOM folder");
}

std::string size_text(const itk::ImageIOBase& io) {
    std::ostringstream s;
    for (unsigned d = 0; d < io.GetNumberOfDimensions(); ++d)
        s << (d ? " x " : "") << io.GetDimensions(d);
    return s.str();
}

// Rejects what is not one scalar 3D volume, before any voxel is read.
void check_header(const itk::ImageIOBase& io, const fs::path& path) {
    const unsigned dims = io.GetNumberOfDimensions();
    if (dims == 2)
        throw InputError(quoted_volume(path.string()) + ": a 2D image (" + size_text(io) +
                         "), expected a 3D volume");
    if (dims == 4 && io.GetDimensions(3) != 1)
        throw InputError(quoted_volume(path.string()) + ": a 4D image (" + size_text(io) +
                         "), expected a 3D volume");
    if (dims < 2 || dims > 4)
        throw InputError(quoted_volume(path.string()) + ": a " + std::to_string(dims) +
                         "D image, expected a 3D volume");
    if (io.GetNumberOfComponents() != 1)
        throw InputError(quoted_volume(path.string()) + ": " +
                         std::to_string(io.GetNumberOfComponents()) +
                         " components per voxel, expected a scalar volume");
    for (unsigned d = 0; d < 3; ++d)
        if (io.GetDimensions(d) < 2)
            throw InputError(quoted_volume(path.string()) + ": size " + size_text(io) +
                             ", expected at least 2 voxels along every axis");
    // The geometry ITK would hand to the image: a non-finite or singular one makes its matrix
    // code abort the process (vnl), so it is refused here, before the voxels are read.
    Matrix3 direction{};
    for (unsigned d = 0; d < 3; ++d) {
        const double spacing = io.GetSpacing(d), origin = io.GetOrigin(d);
        if (!plausible(spacing, kMaxAxisMm) || spacing == 0.0 ||
            !plausible(origin, kMaxPositionMm)) {
            std::ostringstream text;
            text << quoted_volume(path.string()) << ": spacing " << spacing << " and origin "
                 << origin << " along axis " << d
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
        throw InputError(quoted_volume(header.string()) + ": file pattern \"" + format +
                         "\", expected a name with one %d");
    if (io.GetDimensions(2) == 0) return;
    const auto slice_bytes =
        static_cast<std::uintmax_t>(io.GetImageSizeInBytes()) / io.GetDimensions(2);
    if (first < 0 || last > 1'000'000)
        throw InputError(quoted_volume(header.string()) + ": file pattern \"" + pattern +
                         "\" numbers slices " + std::to_string(first) + " to " +
                         std::to_string(last) + ", expected 0 to 1000000");
    for (long n = first; n <= last; n += step) {
        char name[1024];
        std::snprintf(name, sizeof name, format.c_str(), static_cast<int>(n));
        const fs::path slice = header.parent_path() / name;
        std::error_code ec;
        if (!fs::exists(slice, ec))
            throw InputError(quoted_volume(header.string()) + ": slice file \"" + slice.string() +
                             "\" is missing (pattern \"" + pattern + "\")");
        const auto found = fs::file_size(slice, ec);
        if (!ec && found != slice_bytes)
            throw InputError(quoted_volume(header.string()) + ": slice file \"" + slice.string() +
                             "\" holds " + std::to_string(found) + " bytes, one slice needs " +
                             std::to_string(slice_bytes));
    }
}

// A MetaImage's voxels must be what the header promises: a detached data file that names
// neither file nor sizes when it fails, LOCAL or compressed data that MetaIO reads short with
// chatter on stderr and no error (metaimage_data.h).
void require_data_size(const itk::ImageIOBase& io, const fs::path& header) {
    auto* meta = dynamic_cast<itk::MetaImageIO*>(const_cast<itk::ImageIOBase*>(&io));
    if (!meta) return;
    MetaImage* m = meta->GetMetaImagePointer();
    const std::string data_name = m->ElementDataFileName();
    StoredVoxels stored;
    stored.compressed = m->CompressedData();
    const MetaImageLayout layout = metaimage_layout(header);
    stored.compressed_bytes = layout.compressed_bytes;
    stored.expected = static_cast<std::uint64_t>(io.GetImageSizeInBytes());
    // note: a LIST is left to MetaIO.
    if (data_name == "LIST") return;
    if (data_name == "LOCAL") {
        if (!layout.data_offset)
            throw InputError(quoted_volume(header.string()) +
                             ": no voxels follow its header (ElementDataFile = LOCAL ends the "
                             "file), expected " +
                             std::to_string(stored.expected) + " bytes of them");
        stored.offset = *layout.data_offset;
        // note: MetaIO reads LOCAL compressed voxels only as far as CompressedDataSize says;
        // without it the volume came back as uninitialised memory.
        if (stored.compressed && !stored.compressed_bytes)
            throw InputError(quoted_volume(header.string()) +
                             ": CompressedData = True without CompressedDataSize, expected the "
                             "count of compressed bytes that follow the header");
        if (const std::string problem = metaimage_voxel_problem(header, stored); !problem.empty())
            throw InputError(quoted_volume(header.string()) + ": " + problem);
        return;
    }
    if (data_name.find(' ') != std::string::npos) {
        if (!stored.compressed) require_slice_files(io, header, data_name);
        return;
    }
    const fs::path data = header.parent_path() / data_name;
    std::error_code ec;
    if (!fs::exists(data, ec))
        throw InputError(quoted_volume(header.string()) + ": data file \"" + data.string() +
                         "\" is missing");
    if (stored.compressed) {
        if (const std::string problem = metaimage_voxel_problem(data, stored); !problem.empty())
            throw InputError(quoted_volume(header.string()) + ": data file \"" + data.string() +
                             "\": " + problem);
        return;
    }
    const auto found = fs::file_size(data, ec);
    const auto expected = static_cast<std::uintmax_t>(io.GetImageSizeInBytes());
    if (!ec && found != expected)
        throw InputError(quoted_volume(header.string()) + ": data file \"" + data.string() +
                         "\" holds " + std::to_string(found) + " bytes, the header (" +
                         size_text(io) + " " +
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
        throw InputError(quoted_volume(path.string()) + ": size " + size_text(io) + " is " +
                         count_text(voxels) + " voxels, more than the limit " +
                         std::to_string(max_voxels));
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
        throw InputError(quoted_volume(path.string()) + ": size " + size_text(io) + " needs " +
                         count_text(needed) + " bytes of voxels, " +
                         (compressed ? "more than a compressed " : "more than the ") +
                         std::to_string(available) + "-byte file \"" + holder.filename().string() +
                         "\" can hold");
}

RawVolume read_file(const fs::path& path, std::size_t max_voxels) {
    itk::ImageIOBase::Pointer io = image_io_for(path);
    const std::string format = volume_format(path);
    io->SetFileName(path.string());
    if (!io->CanReadFile(path.string().c_str()))
        throw InputError(quoted_volume(path.string()) + ": not a readable " + format + " file");
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

// A series read as one grid takes the spacing (last − first) / (n − 1): with a slice missing
// or refused as truncated, a 2 mm series was read at 2.111 mm without a word (issue 52). The
// slices' own positions (0020,0032) along the slice normal must be evenly spaced.
void refuse_gaps(const fs::path& folder, const std::vector<std::string>& files,
                 itk::ImageSeriesReader<FloatImage>& reader) {
    const auto* dictionaries = reader.GetMetaDataDictionaryArray();
    if (dictionaries == nullptr || dictionaries->size() != files.size()) return;
    const auto& direction = reader.GetOutput()->GetDirection();
    std::vector<double> along;
    for (const auto* dictionary : *dictionaries) {
        std::string text;
        if (dictionary == nullptr ||
            !itk::ExposeMetaData<std::string>(*dictionary, "0020|0032", text))
            return;  // no positions: nothing to check them by
        std::replace(text.begin(), text.end(), '\\', ' ');
        std::istringstream in(text);
        double p[3] = {};
        if (!(in >> p[0] >> p[1] >> p[2])) return;
        along.push_back(p[0] * direction[0][2] + p[1] * direction[1][2] + p[2] * direction[2][2]);
    }
    std::vector<double> gaps;
    for (std::size_t i = 1; i < along.size(); ++i)
        gaps.push_back(std::fabs(along[i] - along[i - 1]));
    std::vector<double> sorted = gaps;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2),
                     sorted.end());
    const double typical = sorted[sorted.size() / 2];
    for (std::size_t i = 0; i < gaps.size(); ++i)
        // note: 1.5 × the typical step: one slice missing doubles a step, while scanners
        // write positions rounded to 0.01 mm or finer.
        if (typical > 0 && gaps[i] > 1.5 * typical) {
            std::ostringstream text;
            text << quoted_volume(folder.string()) << ": the DICOM series has a gap: slices "
                 << i + 1 << " and " << i + 2 << " of " << files.size() << " (\""
                 << fs::path(files[i + 1]).filename().string() << "\") lie " << gaps[i]
                 << " mm apart, the others " << typical
                 << " mm; expected evenly spaced slices (a slice is missing or was refused)";
            throw InputError(text.str());
        }
}

RawVolume read_dicom_folder(const fs::path& folder, std::size_t max_voxels) {
    const CheckedDicomFolder checked(folder);  // GDCM asserts on some malformed files
    auto names = itk::GDCMSeriesFileNames::New();
    names->SetUseSeriesDetails(true);
    names->SetDirectory(checked.path().string());
    const auto& uids = names->GetSeriesUIDs();
    if (uids.empty())
        throw InputError(quoted_volume(folder.string()) + ": a folder with no DICOM series in it");
    // note: the series with the most slices; a folder often also holds a scout or a dose report.
    std::vector<std::string> files;
    for (const auto& uid : uids) {
        auto f = names->GetFileNames(uid);
        if (f.size() > files.size()) files = f;
    }
    if (files.size() < 2)
        throw InputError(quoted_volume(folder.string()) + ": the DICOM series has " +
                         std::to_string(files.size()) +
                         " slice, expected a 3D volume (2 or more slices)");
    auto io = itk::GDCMImageIO::New();
    io->SetFileName(files.front());
    io->ReadImageInformation();
    const long double voxels =
        static_cast<long double>(io->GetDimensions(0)) * io->GetDimensions(1) * files.size();
    if (voxels > static_cast<long double>(max_voxels))
        throw InputError(quoted_volume(folder.string()) + ": " + std::to_string(files.size()) +
                         " slices of " + std::to_string(io->GetDimensions(0)) + " x " +
                         std::to_string(io->GetDimensions(1)) + " voxels, more than the limit " +
                         std::to_string(max_voxels));
    auto reader = itk::ImageSeriesReader<FloatImage>::New();
    reader->SetImageIO(io);
    reader->SetFileNames(files);
    reader->Update();
    refuse_gaps(folder, files, *reader);
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

namespace itk_side {

// MetaIO writes why it fails to std::cerr ("DimSize defined prior to defining NDims", then
// three lines of "Read: Cannot parse file") and ITK's exception then says only "File cannot be
// read … Reason: Invalid argument". While a volume is read, std::cerr goes into a buffer: library
// code never prints, and the first line becomes the reason of the error.
// note: std::cerr is process-wide; glint prints nothing through it while a volume is read (the
// progress display writes with stdio).
class CerrCapture {
  public:
    CerrCapture() : previous_(std::cerr.rdbuf(captured_.rdbuf())) {}
    ~CerrCapture() { std::cerr.rdbuf(previous_); }
    CerrCapture(const CerrCapture&) = delete;
    CerrCapture& operator=(const CerrCapture&) = delete;
    /// The first non-empty line written, trimmed; "" when none.
    [[nodiscard]] std::string first_line() const {
        std::istringstream lines(captured_.str());
        for (std::string line; std::getline(lines, line);) {
            line.erase(0, line.find_first_not_of(" \t\r"));
            line.erase(line.find_last_not_of(" \t\r.") + 1);
            // hostile header bytes are not echoed to a terminal
            for (char& c : line)
                if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
            if (!line.empty()) return line;
        }
        return "";
    }

  private:
    std::ostringstream captured_;
    std::streambuf* previous_;
};

RawVolume read(const fs::path& path, std::size_t max_voxels) {
    itk::Object::GlobalWarningDisplayOff();  // library code never prints
    gdcm::Trace::WarningOff();
    nifti_set_debug_level(0);  // niftilib writes "** ERROR: …" to stderr; ITK's exception says it
    const CerrCapture chatter;
    try {
        std::error_code ec;
        if (fs::is_directory(path, ec)) return read_dicom_folder(path, max_voxels);
        if (volume_format(path) == "dicom")
            if (const std::string problem = dicom_file_problem(path); !problem.empty())
                throw InputError(quoted_volume(path.string()) + ": " + problem);
        return read_file(path, max_voxels);
    } catch (const itk::ExceptionObject& e) {
        const std::string reason = chatter.first_line();
        if (!reason.empty() && volume_format(path) == "metaimage")
            throw InputError(quoted_volume(path.string()) + ": MetaImage header: " + reason +
                             "; expected a header MetaIO can read");
        throw InputError(quoted_volume(path.string()) + ": " + one_line(e));
    }
}

void write(const RawVolume& volume, const fs::path& path) {
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
        throw IoError(quoted_volume(path.string()) + ": cannot write: " + one_line(e));
    }
}

}  // namespace itk_side
}  // namespace glint::detail
