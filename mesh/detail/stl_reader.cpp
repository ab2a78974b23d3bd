#include "mesh/detail/stl_reader.h"

#include "mesh/detail/scan.h"
#include "mesh/error.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <vector>

namespace glint::detail {

namespace {

constexpr std::size_t kHeaderBytes = 84;  ///< 80-byte comment + uint32 facet count
constexpr std::size_t kFacetBytes = 50;   ///< normal + 3 corners (12 floats) + uint16 attribute

std::string_view trim_left(std::string_view s) {
    while (!s.empty() &&
           (s.front() == ' ' || s.front() == '\t' || s.front() == '\r' || s.front() == '\n'))
        s.remove_prefix(1);
    return s;
}

bool starts_with_solid(std::span<const char> data) {
    const std::string_view s =
        trim_left(std::string_view(data.data(), std::min<std::size_t>(data.size(), 512)));
    return s.size() >= 5 && s.substr(0, 5) == "solid";
}

// After the "solid" line, an ASCII STL continues with "facet" or "endsolid".
bool looks_ascii(std::span<const char> data) {
    const std::string_view head(data.data(), std::min<std::size_t>(data.size(), 1024));
    if (head.find('\0') != std::string_view::npos) return false;
    const auto nl = head.find('\n');
    if (nl == std::string_view::npos) return false;
    const std::string_view rest = trim_left(head.substr(nl + 1));
    return rest.starts_with("facet") || rest.starts_with("endsolid") || rest.starts_with("FACET") ||
           rest.starts_with("ENDSOLID");
}

std::uint32_t facet_count(std::span<const char> data) {
    std::uint32_t n = 0;
    std::memcpy(&n, data.data() + 80, 4);  // note: little endian on every platform glint runs on
    return n;
}

Mesh read_binary(std::span<const char> data, const std::string& source, LoadReport& report,
                 std::uint64_t max_triangles) {
    if (data.size() < kHeaderBytes)
        throw InputError(quoted_mesh(source) + ": binary STL needs at least " +
                         std::to_string(kHeaderBytes) +
                         " bytes (header and facet count), the file has " +
                         std::to_string(data.size()) + " bytes");
    const std::uint64_t n = facet_count(data);
    const std::uint64_t expected = kHeaderBytes + kFacetBytes * n;
    if (expected != data.size())
        throw InputError(quoted_mesh(source) + ": binary STL declares " + std::to_string(n) +
                         " facets (" + std::to_string(expected) + " bytes) but the file has " +
                         std::to_string(data.size()) + " bytes");
    check_triangle_budget(n, max_triangles, source, "binary STL declares");
    report.format = "stl-binary";
    Mesh mesh;
    mesh.positions.resize(3 * n);
    mesh.triangles.resize(n);
    const char* p = data.data() + kHeaderBytes;
    for (std::size_t f = 0; f < n; ++f, p += kFacetBytes) {
        poll_cancel(f);
        float c[9];
        std::memcpy(c, p + 12, sizeof c);  // skip the stored facet normal
        for (std::size_t k = 0; k < 3; ++k) {
            const Vec3f v(c[3 * k], c[3 * k + 1], c[3 * k + 2]);
            if (!v.allFinite())
                throw InputError(quoted_mesh(source) + ": facet " + std::to_string(f) + " of " +
                                 std::to_string(n) + ", corner " + std::to_string(k) +
                                 ": coordinate is not finite (" + std::to_string(v.x()) + ", " +
                                 std::to_string(v.y()) + ", " + std::to_string(v.z()) + ")");
            mesh.positions[3 * f + k] = v;
        }
        const auto base = static_cast<std::uint32_t>(3 * f);
        mesh.triangles[f] = {base, base + 1, base + 2};
    }
    report.file_vertices = mesh.positions.size();
    report.file_triangles = mesh.triangles.size();
    return mesh;
}

class AsciiStl {
  public:
    AsciiStl(std::span<const char> data, const std::string& source, LoadReport& report,
             std::uint64_t max_triangles)
        : data_(data), source_(source), report_(report), max_triangles_(max_triangles) {}

    Mesh parse() {
        report_.format = "stl-ascii";
        enum class State { Outside, InSolid, InFacet, InLoop, LoopDone };
        State state = State::Outside;
        std::vector<Vec3f> corners;
        std::size_t facet = 0;
        std::size_t facet_line = 0;
        std::string_view line;
        while (next_line(data_, pos_, line)) {
            poll_cancel(++line_no_);
            const auto w = split_words(line);
            if (w.empty()) continue;
            const std::string_view key = w[0];
            if (iequals(key, "solid") && state == State::Outside) {
                state = State::InSolid;
            } else if (iequals(key, "facet") && state == State::InSolid) {
                state = State::InFacet;
                corners.clear();
                facet_line = line_no_;
            } else if (iequals(key, "outer") && state == State::InFacet) {
                if (w.size() < 2 || !iequals(w[1], "loop")) fail(line, "\"outer loop\"");
                state = State::InLoop;
            } else if (iequals(key, "vertex") && state == State::InLoop) {
                if (w.size() != 4) fail(line, "\"vertex X Y Z\"");
                Vec3f v;
                for (int k = 0; k < 3; ++k) {
                    const std::string_view t = w[static_cast<std::size_t>(k) + 1];
                    float x = 0.0f;
                    const auto r = std::from_chars(t.data(), t.data() + t.size(), x);
                    if (r.ec == std::errc::result_out_of_range)
                        x = t.front() == '-' ? -HUGE_VALF : HUGE_VALF;
                    else if (r.ec != std::errc() || r.ptr != t.data() + t.size())
                        fail(line, "\"vertex X Y Z\" with numbers");
                    v[k] = x;
                }
                if (!v.allFinite())
                    throw InputError(quoted_mesh(source_) + ": line " + std::to_string(line_no_) +
                                     ": facet " + std::to_string(facet) + ", corner " +
                                     std::to_string(corners.size()) +
                                     ": coordinate is not finite: \"" + std::string(line) + "\"");
                corners.push_back(v);
            } else if (iequals(key, "endloop") && state == State::InLoop) {
                state = State::LoopDone;
            } else if (iequals(key, "endfacet") && state == State::LoopDone) {
                add_facet(corners, facet, facet_line);
                ++facet;
                state = State::InSolid;
            } else if (iequals(key, "endsolid") && state == State::InSolid) {
                state = State::Outside;
            } else {
                static constexpr const char* kExpected[] = {
                    "\"solid\"", "\"facet\" or \"endsolid\"", "\"outer loop\"",
                    "\"vertex\" or \"endloop\"", "\"endfacet\""};
                fail(line, kExpected[static_cast<int>(state)]);
            }
        }
        if (state == State::InFacet || state == State::InLoop || state == State::LoopDone)
            throw InputError(quoted_mesh(source_) + ": ASCII STL ends inside facet " +
                             std::to_string(facet) + " (begun at line " +
                             std::to_string(facet_line) + "): the file is truncated");
        if (state == State::InSolid)
            report_.warnings.push_back("ASCII STL has no final \"endsolid\" line");
        report_.file_vertices = mesh_.positions.size();
        report_.file_triangles = mesh_.triangles.size();
        return std::move(mesh_);
    }

  private:
    [[noreturn]] void fail(std::string_view line, const std::string& expected) const {
        const std::string text = printable(line, 80);
        throw InputError(quoted_mesh(source_) + ": line " + std::to_string(line_no_) +
                         ": expected " + expected + ", found \"" + text + "\"");
    }

    void add_facet(const std::vector<Vec3f>& corners, std::size_t facet, std::size_t facet_line) {
        if (corners.size() < 3)
            throw InputError(quoted_mesh(source_) + ": facet " + std::to_string(facet) + " (line " +
                             std::to_string(facet_line) + ") has " +
                             std::to_string(corners.size()) + " vertices, expected 3");
        if (corners.size() > 3) ++report_.split_polygons;
        check_triangle_budget(mesh_.triangles.size() + corners.size() - 2, max_triangles_, source_,
                              "ASCII STL facet " + std::to_string(facet) + " brings the mesh to");
        const auto base = static_cast<std::uint32_t>(mesh_.positions.size());
        mesh_.positions.insert(mesh_.positions.end(), corners.begin(), corners.end());
        for (std::uint32_t k = 2; k < corners.size(); ++k)
            mesh_.triangles.push_back({base, base + k - 1, base + k});
    }

    std::span<const char> data_;
    const std::string& source_;
    LoadReport& report_;
    std::uint64_t max_triangles_;
    std::size_t pos_ = 0;
    std::size_t line_no_ = 0;
    Mesh mesh_;
};

}  // namespace

bool is_binary_stl(std::span<const char> data) {
    if (data.size() < kHeaderBytes) return false;
    const std::uint64_t n = facet_count(data);
    if (kHeaderBytes + kFacetBytes * n != data.size()) return false;
    return !(starts_with_solid(data) && looks_ascii(data));
}

Mesh read_stl(std::span<const char> data, const std::string& source, LoadReport& report,
              const LoadOptions& options) {
    const std::uint64_t max_triangles = options.max_triangles;
    if (is_binary_stl(data)) return read_binary(data, source, report, max_triangles);
    const std::string_view head(data.data(), std::min<std::size_t>(data.size(), 1024));
    if (starts_with_solid(data) && head.find('\0') == std::string_view::npos)
        return AsciiStl(data, source, report, max_triangles).parse();
    return read_binary(data, source, report, max_triangles);  // throws with the size mismatch
}

}  // namespace glint::detail
