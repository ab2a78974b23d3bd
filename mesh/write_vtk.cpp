// VTK writers (mesh/write.h): legacy ASCII for every viewer, XML PolyData for exact values.
//
// note: the legacy layout is shaped by two readers. CloudCompare 2.11's (qCC_io VTKFilter)
// refuses BINARY files, and every NORMALS / COLOR_SCALARS / SCALARS block consumes the size
// set by the POINT_DATA line before it: without a POINT_DATA line of its own, each array
// after the first is refused as "malformed". VTK's (ParaView, 3D Slicer) refuses a second
// POINT_DATA line inside point data ("Unsupported point attribute type") but follows a switch
// to CELL_DATA and back. So arrays after the first are introduced by "CELL_DATA 0" (an empty
// cell section: VTK reads nothing, CloudCompare skips 0 lines) and "POINT_DATA n"; both
// programs were checked to read every array (tests/tools/viewers_test.sh). VTK's legacy
// ASCII reader parses numbers with operator>>, which fails on "nan": NaN becomes a finite
// number there (WriteOptions::vtk_legacy_nan).
#include "mesh/write.h"

#include "mesh/atomic_file.h"
#include "mesh/detail/write_common.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <string>
#include <vector>

namespace glint {

namespace fs = std::filesystem;
using detail::check_sizes;
using detail::safe_name;
using detail::StreamBuffer;

namespace {

// Shortest text that reads back as the same float (std::to_chars round-trips).
template <class Out>
void append_number(Out& out, float v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, static_cast<std::size_t>(r.ptr - buf));
}

template <class Out>
void append_number(Out& out, std::int64_t v) {
    char buf[24];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, static_cast<std::size_t>(r.ptr - buf));
}

// Items 0…count−1 as text (format(i, text) appends item i's), formatted in blocks on every
// worker and written in order; at most kBlocks blocks are held at once.
template <class Format>
void format_in_parallel(StreamBuffer& out, std::size_t count, const Format& format) {
    constexpr std::size_t kBlock = std::size_t{1} << 16, kBlocks = 16;
    std::vector<std::string> texts(kBlocks);
    for (std::size_t first = 0; first < count; first += kBlock * kBlocks) {
        const std::size_t blocks = std::min(kBlocks, (count - first + kBlock - 1) / kBlock);
        tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
            std::string& text = texts[b];
            text.clear();
            const std::size_t begin = first + b * kBlock, end = std::min(count, begin + kBlock);
            for (std::size_t i = begin; i < end; ++i) format(i, text);
        });
        for (std::size_t b = 0; b < blocks; ++b) out += texts[b];
    }
}

// Values, `per_line` to a line.
void append_floats(StreamBuffer& out, const float* values, std::size_t count, std::size_t per_line,
                   float nan_as) {
    format_in_parallel(out, count, [&](std::size_t i, std::string& text) {
        append_number(text, std::isnan(values[i]) ? nan_as : values[i]);
        text.push_back((i + 1) % per_line == 0 || i + 1 == count ? '\n' : ' ');
    });
}

}  // namespace

void write_vtk(const Mesh& mesh, const fs::path& path, const WriteOptions& options) {
    check_sizes(mesh, path);
    const std::size_t n = mesh.positions.size();
    const bool normals = options.write_normals && mesh.has_normals();
    const bool colors = options.write_colors && mesh.colors.size() == n && n > 0;
    const bool labels = options.write_labels && mesh.labels.size() == n && n > 0;
    const bool scalars = options.write_scalars && !mesh.scalars.empty();
    const float nan_as = options.vtk_legacy_nan;
    write_atomically(path, [&](std::ostream& stream) {
        StreamBuffer out(stream);
        // The first array opens point data; every later one re-opens it (see the note above).
        std::string point_data = "POINT_DATA " + std::to_string(n) + "\n";
        auto open_array = [&] {
            out += point_data;
            point_data = "CELL_DATA 0\nPOINT_DATA " + std::to_string(n) + "\n";
        };
        out += "# vtk DataFile Version 3.0\nglint mesh" +
               (mesh.unit.empty() ? std::string() : " unit " + mesh.unit) +
               "\nASCII\nDATASET POLYDATA\nPOINTS " + std::to_string(n) + " float\n";
        append_floats(out, mesh.positions.empty() ? nullptr : mesh.positions[0].data(), 3 * n, 3,
                      nan_as);
        out += "POLYGONS " + std::to_string(mesh.triangles.size()) + " " +
               std::to_string(4 * mesh.triangles.size()) + "\n";
        format_in_parallel(out, mesh.triangles.size(), [&](std::size_t t, std::string& text) {
            text += "3";
            for (auto i : mesh.triangles[t]) {
                text.push_back(' ');
                append_number(text, static_cast<std::int64_t>(i));
            }
            text.push_back('\n');
        });
        // The scalars first: VTK makes the first SCALARS block the active scalars.
        if (scalars)
            for (const auto& f : mesh.scalars) {
                open_array();
                out += "SCALARS " + safe_name(f.name) + " float 1\nLOOKUP_TABLE default\n";
                append_floats(out, f.values.data(), n, 9, nan_as);
            }
        if (normals) {
            open_array();
            out += "NORMALS Normals float\n";
            append_floats(out, mesh.normals[0].data(), 3 * n, 3, 0.0f);
        }
        if (colors) {
            open_array();
            out += "COLOR_SCALARS rgb 3\n";  // ASCII colour scalars are floats in [0, 1]
            std::vector<float> c(3 * n);
            for (std::size_t v = 0; v < n; ++v)
                for (int k = 0; k < 3; ++k)
                    c[3 * v + static_cast<std::size_t>(k)] =
                        mesh.colors[v][static_cast<std::size_t>(k)] / 255.0f;
            append_floats(out, c.data(), c.size(), 3, 0.0f);
        }
        if (labels) {
            open_array();
            out += "SCALARS label int 1\nLOOKUP_TABLE default\n";
            format_in_parallel(out, n, [&](std::size_t v, std::string& text) {
                append_number(text, static_cast<std::int64_t>(mesh.labels[v]));
                text.push_back((v + 1) % 9 == 0 || v + 1 == n ? '\n' : ' ');
            });
        }
        out.flush();
    });
}

namespace {

// RFC 4648 base64 (VTK XML "binary" arrays) of bytes that arrive in pieces: whole 3-byte
// groups are encoded as they come, what is left waits for the next piece; finish() pads. The
// text is the one the whole sequence encoded at once gives.
class Base64Writer {
  public:
    explicit Base64Writer(StreamBuffer& out) : out_(out) {}
    void add(const void* data, std::size_t size) {
        const auto* bytes = static_cast<const std::uint8_t*>(data);
        for (std::size_t i = 0; i < size; ++i) {
            group_[held_++] = bytes[i];
            if (held_ == 3) {
                const char quad[4] = {kAlphabet[group_[0] >> 2],
                                      kAlphabet[((group_[0] & 3) << 4) | (group_[1] >> 4)],
                                      kAlphabet[((group_[1] & 15) << 2) | (group_[2] >> 6)],
                                      kAlphabet[group_[2] & 63]};
                out_.append(quad, 4);
                held_ = 0;
            }
        }
    }
    void finish() {
        if (held_ == 1) {
            const char quad[4] = {kAlphabet[group_[0] >> 2], kAlphabet[(group_[0] & 3) << 4], '=',
                                  '='};
            out_.append(quad, 4);
        } else if (held_ == 2) {
            const char quad[4] = {kAlphabet[group_[0] >> 2],
                                  kAlphabet[((group_[0] & 3) << 4) | (group_[1] >> 4)],
                                  kAlphabet[(group_[1] & 15) << 2], '='};
            out_.append(quad, 4);
        }
        held_ = 0;
    }

  private:
    static constexpr char kAlphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    StreamBuffer& out_;
    std::uint8_t group_[3] = {0, 0, 0};
    int held_ = 0;
};

void open_data_array(StreamBuffer& out, const char* type, const std::string& name, int components) {
    out += std::string("        <DataArray type=\"") + type + "\"" +
           (name.empty() ? "" : " Name=\"" + name + "\"") + " NumberOfComponents=\"" +
           std::to_string(components) + "\" format=\"binary\">";
}

// One inline binary DataArray: base64 of a UInt32 byte count followed by the raw values
// (little endian: the machines glint runs on, checked below).
template <class T>
void append_array(StreamBuffer& out, const char* type, const std::string& name, int components,
                  const T* values, std::size_t count) {
    static_assert(std::endian::native == std::endian::little,
                  "VTP arrays are written as LittleEndian");
    const auto bytes = static_cast<std::uint32_t>(count * sizeof(T));
    open_data_array(out, type, name, components);
    Base64Writer b64(out);
    b64.add(&bytes, sizeof bytes);
    if (count > 0) b64.add(values, bytes);
    b64.finish();
    out += "</DataArray>\n";
}

}  // namespace

void write_vtp(const Mesh& mesh, const fs::path& path, const WriteOptions& options) {
    check_sizes(mesh, path);
    const std::size_t n = mesh.positions.size();
    const std::size_t t = mesh.triangles.size();
    const bool normals = options.write_normals && mesh.has_normals();
    const bool colors = options.write_colors && mesh.colors.size() == n && n > 0;
    const bool labels = options.write_labels && mesh.labels.size() == n && n > 0;
    const bool scalars = options.write_scalars && !mesh.scalars.empty();

    write_atomically(path, [&](std::ostream& stream) {
        StreamBuffer out(stream);
        out += "<?xml version=\"1.0\"?>\n";
        if (!mesh.unit.empty()) out += "<!-- unit " + mesh.unit + " -->\n";
        out +=
            "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt32\">\n"
            "  <PolyData>\n    <Piece NumberOfPoints=\"" +
            std::to_string(n) +
            "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"" +
            std::to_string(t) + "\">\n";
        out += "      <PointData";
        if (scalars) out += " Scalars=\"" + safe_name(mesh.scalars.front().name) + "\"";
        if (normals) out += " Normals=\"Normals\"";
        out += ">\n";
        if (scalars)
            for (const auto& f : mesh.scalars)
                append_array(out, "Float32", safe_name(f.name), 1, f.values.data(), n);
        if (normals) append_array(out, "Float32", "Normals", 3, mesh.normals[0].data(), 3 * n);
        if (colors) append_array(out, "UInt8", "rgb", 3, mesh.colors[0].data(), 3 * n);
        if (labels) append_array(out, "Int32", "label", 1, mesh.labels.data(), n);
        out += "      </PointData>\n      <Points>\n";
        append_array(out, "Float32", "Points", 3, n > 0 ? mesh.positions[0].data() : nullptr,
                     3 * n);
        out += "      </Points>\n      <Polys>\n";
        // Connectivity and offsets as Int32, made and encoded a block of triangles at a time.
        constexpr std::size_t kBlock = 16384;
        std::vector<std::int32_t> block;
        block.reserve(3 * kBlock);
        open_data_array(out, "Int32", "connectivity", 1);
        Base64Writer connectivity(out);
        const auto connectivity_bytes = static_cast<std::uint32_t>(3 * t * sizeof(std::int32_t));
        connectivity.add(&connectivity_bytes, sizeof connectivity_bytes);
        for (std::size_t first = 0; first < t; first += kBlock) {
            block.clear();
            for (std::size_t i = first; i < std::min(t, first + kBlock); ++i)
                for (std::size_t k = 0; k < 3; ++k)
                    block.push_back(static_cast<std::int32_t>(mesh.triangles[i][k]));
            connectivity.add(block.data(), block.size() * sizeof(std::int32_t));
        }
        connectivity.finish();
        out += "</DataArray>\n";
        open_data_array(out, "Int32", "offsets", 1);
        Base64Writer offsets(out);
        const auto offsets_bytes = static_cast<std::uint32_t>(t * sizeof(std::int32_t));
        offsets.add(&offsets_bytes, sizeof offsets_bytes);
        for (std::size_t first = 0; first < t; first += kBlock) {
            block.clear();
            for (std::size_t i = first; i < std::min(t, first + kBlock); ++i)
                block.push_back(static_cast<std::int32_t>(3 * (i + 1)));
            offsets.add(block.data(), block.size() * sizeof(std::int32_t));
        }
        offsets.finish();
        out += "</DataArray>\n";
        out += "      </Polys>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
        out.flush();
    });
}

}  // namespace glint
