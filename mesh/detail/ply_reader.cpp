#include "mesh/detail/ply_reader.h"

#include "mesh/detail/ply_format.h"
#include "mesh/detail/scan.h"
#include "mesh/error.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string_view>
#include <vector>

namespace glint::detail {

namespace {

using namespace ply;

// What the reader builds while it walks the body.
struct Builder {
    Mesh mesh;
    std::size_t vertex_count = 0;
    bool has_normals = false;
    bool has_colors = false;
    bool has_labels = false;
    std::size_t split_polygons = 0;
    std::size_t short_faces = 0;  ///< faces with fewer than 3 corners, skipped

    void store(std::size_t v, const Property& p, double value) {
        switch (p.target) {
            case Target::X: mesh.positions[v].x() = static_cast<float>(value); break;
            case Target::Y: mesh.positions[v].y() = static_cast<float>(value); break;
            case Target::Z: mesh.positions[v].z() = static_cast<float>(value); break;
            case Target::Nx: mesh.normals[v].x() = static_cast<float>(value); break;
            case Target::Ny: mesh.normals[v].y() = static_cast<float>(value); break;
            case Target::Nz: mesh.normals[v].z() = static_cast<float>(value); break;
            case Target::Red: mesh.colors[v][0] = color_byte(p.type, value); break;
            case Target::Green: mesh.colors[v][1] = color_byte(p.type, value); break;
            case Target::Blue: mesh.colors[v][2] = color_byte(p.type, value); break;
            case Target::Label: mesh.labels[v] = clamp_to<std::int32_t>(value); break;
            case Target::Scalar:
                mesh.scalars[p.scalar_index].values[v] = static_cast<float>(value);
                break;
            case Target::Ignore:
            case Target::FaceIndices: break;
        }
    }

    static std::uint8_t color_byte(Type t, double value) {
        // note: float colours are in [0, 1] by convention, integer ones in [0, 255].
        const double scaled = is_integer(t) ? value : value * 255.0;
        return static_cast<std::uint8_t>(std::clamp(std::lround(scaled), 0L, 255L));
    }
};

class PlyParser {
  public:
    PlyParser(std::span<const char> data, const std::string& source, LoadReport& report,
              std::uint64_t max_triangles)
        : data_(data), source_(source), report_(report), max_triangles_(max_triangles) {}

    Mesh parse() {
        parse_header();
        setup_targets();
        for (std::size_t e = 0; e < elements_.size(); ++e) {
            const Element& el = elements_[e];
            check_element_fits(el);
            const bool is_vertex = static_cast<std::ptrdiff_t>(e) == vertex_element_;
            const bool is_face = static_cast<std::ptrdiff_t>(e) == face_element_;
            switch (encoding_) {
                case Encoding::Ascii: read_ascii(el, is_vertex, is_face); break;
                case Encoding::BinaryLe: read_binary<false>(el, is_vertex, is_face); break;
                case Encoding::BinaryBe: read_binary<true>(el, is_vertex, is_face); break;
            }
        }
        finish();
        return std::move(b_.mesh);
    }

  private:
    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(quoted_mesh(source_) + ": " + what);
    }
    [[noreturn]] void fail_line(std::size_t line, const std::string& what) const {
        throw InputError(quoted_mesh(source_) + ": line " + std::to_string(line) + ": " + what);
    }

    // The fewest bytes one item of `el` can take: its fixed-size properties plus each list's
    // count in binary; in ASCII a value and a separator ("0 ") per property.
    [[nodiscard]] std::uint64_t min_item_bytes(const Element& el) const {
        if (encoding_ == Encoding::Ascii) return 2 * el.properties.size();
        std::uint64_t bytes = 0;
        for (const auto& p : el.properties)
            bytes += p.is_list ? size_of(p.count_type) : size_of(p.type);
        return bytes;
    }

    // A count the rest of the file cannot hold is refused before any allocation or loop
    // (an item without properties counts one byte: 2^63 empty items are refused, not looped).
    // note: the last ASCII value of the file may lack its separator, hence one byte of slack.
    void check_element_fits(const Element& el) const {
        const std::uint64_t left = data_.size() - std::min(body_, data_.size());
        check_count_fits(el.count, min_item_bytes(el),
                         left + (encoding_ == Encoding::Ascii ? 1 : 0), source_,
                         "PLY element \"" + el.name + "\"");
    }

    // ---- header -------------------------------------------------------------------------

    /// One "property" line of the current (last) element: a scalar, which takes the next
    /// bytes of a fixed-size item, or a list.
    Property parse_property(std::string_view line, const std::vector<std::string_view>& words,
                            std::size_t line_no) {
        Property p;
        if (words.size() == 5 && words[1] == "list") {
            p.is_list = true;
            const auto ct = parse_type(words[2]);
            const auto it = parse_type(words[3]);
            if (!ct || !it) fail_line(line_no, "unknown type in \"" + std::string(line) + "\"");
            if (!is_integer(*ct))
                fail_line(line_no, "list count type must be an integer type, found \"" +
                                       std::string(words[2]) + "\"");
            p.count_type = *ct;
            p.type = *it;
            p.name = std::string(words[4]);
            elements_.back().is_fixed_size = false;
        } else if (words.size() == 3) {
            const auto t = parse_type(words[1]);
            if (!t) fail_line(line_no, "unknown property type \"" + std::string(words[1]) + "\"");
            p.type = *t;
            p.name = std::string(words[2]);
            p.offset = elements_.back().stride;
            elements_.back().stride += size_of(*t);
        } else {
            fail_line(line_no,
                      "expected \"property TYPE NAME\" or \"property list "
                      "COUNT_TYPE INDEX_TYPE NAME\", found \"" +
                          std::string(line) + "\"");
        }
        return p;
    }

    void parse_header() {
        std::size_t pos = 0;
        std::size_t line_no = 0;
        bool has_format = false;
        auto next_header_line = [&](std::string_view& line) {
            if (!next_line(data_, pos, line)) return false;
            ++line_no;
            return true;
        };
        std::string_view line;
        if (!next_header_line(line) || line != "ply")
            fail("does not start with \"ply\", not a PLY file");
        while (true) {
            if (!next_header_line(line)) fail("PLY header has no end_header line");
            const auto words = split_words(line);
            if (words.empty()) continue;
            const std::string_view key = words[0];
            if (key == "end_header") break;
            if (key == "comment" || key == "obj_info") continue;
            if (key == "format") {
                if (words.size() < 2) fail_line(line_no, "format line without an encoding");
                if (words[1] == "ascii") encoding_ = Encoding::Ascii;
                else if (words[1] == "binary_little_endian") encoding_ = Encoding::BinaryLe;
                else if (words[1] == "binary_big_endian") encoding_ = Encoding::BinaryBe;
                else
                    fail_line(line_no, "unknown PLY format \"" + std::string(words[1]) +
                                           "\", expected ascii, binary_little_endian or "
                                           "binary_big_endian");
                has_format = true;
            } else if (key == "element") {
                if (words.size() != 3) fail_line(line_no, "expected \"element NAME COUNT\"");
                Element el;
                el.name = std::string(words[1]);
                const auto r =
                    std::from_chars(words[2].data(), words[2].data() + words[2].size(), el.count);
                if (r.ec != std::errc() || r.ptr != words[2].data() + words[2].size())
                    fail_line(line_no, "element \"" + el.name + "\" has count \"" +
                                           std::string(words[2]) +
                                           "\", expected a non-negative integer");
                elements_.push_back(std::move(el));
            } else if (key == "property") {
                if (elements_.empty()) fail_line(line_no, "property before any element");
                Property p = parse_property(line, words, line_no);
                for (const Property& q : elements_.back().properties)
                    if (q.name == p.name)
                        fail_line(line_no, "property \"" + p.name +
                                               "\" declared twice in element \"" +
                                               elements_.back().name + "\"");
                elements_.back().properties.push_back(std::move(p));
            } else {
                fail_line(line_no, "unknown PLY header keyword \"" + std::string(key) + "\"");
            }
        }
        if (!has_format) fail("PLY header has no format line");
        body_ = pos;
        line_ = line_no + 1;
        report_.format = encoding_ == Encoding::Ascii      ? "ply-ascii"
                         : encoding_ == Encoding::BinaryLe ? "ply-binary-le"
                                                           : "ply-binary-be";
    }

    /// Which of the vertex element's properties fill positions, normals, colours, labels and
    /// scalars; incomplete normals or colours are ignored with a warning.
    void target_vertex_properties(Element& v, std::size_t n) {
        int xyz = 0, normal = 0, rgb = 0;
        for (auto& p : v.properties) {
            if (p.is_list) {
                report_.warnings.push_back("vertex list property \"" + p.name + "\" ignored");
                continue;
            }
            const std::string& s = p.name;
            if (s == "x") p.target = Target::X, ++xyz;
            else if (s == "y") p.target = Target::Y, ++xyz;
            else if (s == "z") p.target = Target::Z, ++xyz;
            else if (s == "nx") p.target = Target::Nx, ++normal;
            else if (s == "ny") p.target = Target::Ny, ++normal;
            else if (s == "nz") p.target = Target::Nz, ++normal;
            else if (s == "red" || s == "diffuse_red") p.target = Target::Red, ++rgb;
            else if (s == "green" || s == "diffuse_green") p.target = Target::Green, ++rgb;
            else if (s == "blue" || s == "diffuse_blue") p.target = Target::Blue, ++rgb;
            else if (s == "alpha" || s == "diffuse_alpha") {
                report_.warnings.push_back("vertex property \"" + s + "\" (colour alpha) ignored");
            } else if (s == "label" && is_integer(p.type)) {
                p.target = Target::Label;
                b_.has_labels = true;
            } else {
                p.target = Target::Scalar;
                p.scalar_index = b_.mesh.scalars.size();
                b_.mesh.scalars.push_back({scalar_name(v, s), std::vector<float>(n, 0.0f)});
            }
        }
        if (xyz != 3) fail("PLY element \"vertex\" lacks one of the properties x, y, z");
        b_.mesh.positions.assign(n, Vec3f::Zero());
        if (normal == 3) {
            b_.has_normals = true;
            b_.mesh.normals.assign(n, Vec3f::Zero());
        } else if (normal != 0) {
            for (auto& p : v.properties)
                if (p.target == Target::Nx || p.target == Target::Ny || p.target == Target::Nz)
                    p.target = Target::Ignore;
            report_.warnings.push_back("incomplete vertex normal (not all of nx, ny, nz) ignored");
        }
        if (rgb == 3) {
            b_.has_colors = true;
            b_.mesh.colors.assign(n, Rgb8{0, 0, 0});
        } else if (rgb != 0) {
            for (auto& p : v.properties)
                if (p.target == Target::Red || p.target == Target::Green ||
                    p.target == Target::Blue)
                    p.target = Target::Ignore;
            report_.warnings.push_back(
                "incomplete vertex colour (not all of red, green, blue) ignored");
        }
        if (b_.has_labels) b_.mesh.labels.assign(n, 0);
    }

    /// The face element's index list (vertex_indices or vertex_index), which must be integer.
    void target_face_indices() {
        if (face_element_ < 0) return;
        Element& f = elements_[static_cast<std::size_t>(face_element_)];
        bool found = false;
        for (auto& p : f.properties) {
            if (!found && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) {
                if (!is_integer(p.type))
                    fail("PLY face list \"" + p.name + "\" has a non-integer index type");
                p.target = Target::FaceIndices;
                found = true;
            }
        }
        if (!found) fail("PLY element \"face\" has no \"vertex_indices\" list property");
        const std::size_t faces = static_cast<std::size_t>(
            std::min<std::uint64_t>(f.count, (data_.size() - body_) / 2 + 1));
        b_.mesh.triangles.reserve(faces);
    }

    void setup_targets() {
        for (std::size_t e = 0; e < elements_.size(); ++e) {
            if (elements_[e].name == "vertex" && vertex_element_ < 0)
                vertex_element_ = static_cast<std::ptrdiff_t>(e);
            if (elements_[e].name == "face" && face_element_ < 0)
                face_element_ = static_cast<std::ptrdiff_t>(e);
        }
        if (vertex_element_ < 0) fail("PLY header declares no \"vertex\" element");
        Element& v = elements_[static_cast<std::size_t>(vertex_element_)];
        const std::size_t n = static_cast<std::size_t>(v.count);
        // note: a lying header must not make us allocate gigabytes: every vertex needs at
        // least one byte per property in any encoding.
        const std::size_t left = data_.size() - body_;
        if (encoding_ != Encoding::Ascii && v.is_fixed_size && v.stride > 0 && n > left / v.stride)
            fail_truncated(v, left / v.stride);
        check_element_fits(v);
        b_.vertex_count = n;
        target_vertex_properties(v, n);

        target_face_indices();
        for (const auto& el : elements_) {
            if (&el == &v || static_cast<std::ptrdiff_t>(&el - elements_.data()) == face_element_)
                continue;
            report_.warnings.push_back("PLY element \"" + el.name + "\" (" +
                                       std::to_string(el.count) + " items) skipped");
        }
    }

    // ---- faces ---------------------------------------------------------------------------

    // Adds one polygon given by `n` corner indices read through `index(k)`; fan-split.
    template <class IndexAt>
    void add_face(std::uint64_t face_id, std::int64_t n, IndexAt index) {
        if (n < 3) {
            ++b_.short_faces;
            return;
        }
        if (n > 3) ++b_.split_polygons;
        if (b_.mesh.triangles.size() + static_cast<std::uint64_t>(n - 2) > max_triangles_)
            check_triangle_budget(b_.mesh.triangles.size() + static_cast<std::uint64_t>(n - 2),
                                  max_triangles_, source_,
                                  "PLY face " + std::to_string(face_id) + " brings the mesh to");
        const auto nv = static_cast<std::int64_t>(b_.vertex_count);
        auto checked = [&](std::int64_t k) {
            const std::int64_t i = index(k);
            if (i < 0 || i >= nv)
                fail("PLY face " + std::to_string(face_id) + ": corner " + std::to_string(k) +
                     " uses vertex " + std::to_string(i) + ", the file has " + std::to_string(nv) +
                     " vertices");
            return static_cast<std::uint32_t>(i);
        };
        const std::uint32_t first = checked(0);
        std::uint32_t prev = checked(1);
        for (std::int64_t k = 2; k < n; ++k) {
            const std::uint32_t cur = checked(k);
            b_.mesh.triangles.push_back({first, prev, cur});
            prev = cur;
        }
    }

    // ---- binary --------------------------------------------------------------------------

    [[noreturn]] void fail_truncated(const Element& el, std::uint64_t index) const {
        fail("PLY element \"" + el.name + "\" " + std::to_string(index) + " of " +
             std::to_string(el.count) + " is truncated: the file ends before the header's count");
    }

    /// The items of a fixed-size binary vertex element (their bytes already known to be there).
    template <bool Swap>
    void read_fixed_vertices(const Element& el) {
        const char* base = data_.data() + body_;
        // note: float positions (the usual case) are copied straight into the Vec3f
        // array; every other property goes through the typed store.
        std::vector<const Property*> rest;
        std::size_t float_xyz[3] = {0, 0, 0};
        int float_xyz_found = 0;
        for (const auto& p : el.properties) {
            if (p.target == Target::Ignore) continue;
            const int axis = p.target == Target::X   ? 0
                             : p.target == Target::Y ? 1
                             : p.target == Target::Z ? 2
                                                     : -1;
            if (axis >= 0 && p.type == Type::Float32) {
                float_xyz[axis] = p.offset;
                ++float_xyz_found;
            } else {
                rest.push_back(&p);
            }
        }
        if (float_xyz_found != 3) {
            rest.clear();
            for (const auto& p : el.properties)
                if (p.target != Target::Ignore) rest.push_back(&p);
        }
        Vec3f* out = b_.mesh.positions.data();
        for (std::size_t v = 0; v < el.count; ++v, base += el.stride) {
            poll_cancel(v);
            if (float_xyz_found == 3)
                out[v] = Vec3f(load<float, Swap>(base + float_xyz[0]),
                               load<float, Swap>(base + float_xyz[1]),
                               load<float, Swap>(base + float_xyz[2]));
            for (const Property* p : rest)
                b_.store(v, *p, load_value<Swap>(base + p->offset, p->type));
        }
    }

    template <bool Swap>
    void read_binary(const Element& el, bool is_vertex, bool is_face) {
        const char* const begin = data_.data();
        const std::size_t size = data_.size();
        if (el.is_fixed_size) {
            const std::size_t available = size - body_;
            if (el.stride > 0 && el.count > available / el.stride)
                fail_truncated(el, available / el.stride);
            if (is_vertex) read_fixed_vertices<Swap>(el);
            body_ += static_cast<std::size_t>(el.count) * el.stride;
            return;
        }
        std::size_t pos = body_;
        for (std::uint64_t item = 0; item < el.count; ++item) {
            poll_cancel(item);
            for (const auto& p : el.properties) {
                if (!p.is_list) {
                    const std::size_t s = size_of(p.type);
                    if (size - pos < s) fail_truncated(el, item);
                    if (is_vertex && p.target != Target::Ignore)
                        b_.store(static_cast<std::size_t>(item), p,
                                 load_value<Swap>(begin + pos, p.type));
                    pos += s;
                    continue;
                }
                const std::size_t cs = size_of(p.count_type);
                if (size - pos < cs) fail_truncated(el, item);
                const std::int64_t n = load_int<Swap>(begin + pos, p.count_type);
                pos += cs;
                const std::size_t is = size_of(p.type);
                if (n < 0 || static_cast<std::uint64_t>(n) > (size - pos) / is)
                    fail_truncated(el, item);
                if (is_face && p.target == Target::FaceIndices) {
                    const char* at = begin + pos;
                    const Type t = p.type;
                    if (n == 3 && t == Type::Int32) {
                        // note: the common case (triangles, int indices) without the fan loop.
                        const std::int64_t a = load<std::int32_t, Swap>(at);
                        const std::int64_t b = load<std::int32_t, Swap>(at + 4);
                        const std::int64_t c = load<std::int32_t, Swap>(at + 8);
                        const auto nv = static_cast<std::int64_t>(b_.vertex_count);
                        if (a >= 0 && a < nv && b >= 0 && b < nv && c >= 0 && c < nv &&
                            b_.mesh.triangles.size() < max_triangles_) {
                            b_.mesh.triangles.push_back({static_cast<std::uint32_t>(a),
                                                         static_cast<std::uint32_t>(b),
                                                         static_cast<std::uint32_t>(c)});
                        } else {
                            add_face(item, n, [&](std::int64_t k) {
                                return load_int<Swap>(at + static_cast<std::size_t>(k) * is, t);
                            });
                        }
                    } else {
                        add_face(item, n, [&](std::int64_t k) {
                            return load_int<Swap>(at + static_cast<std::size_t>(k) * is, t);
                        });
                    }
                }
                pos += static_cast<std::size_t>(n) * is;
            }
        }
        body_ = pos;
    }

    // ---- ASCII ---------------------------------------------------------------------------

    // Next whitespace-separated token of the body; empty at end of file. Counts lines.
    std::string_view token() {
        const char* d = data_.data();
        const std::size_t size = data_.size();
        while (body_ < size) {
            const char c = d[body_];
            if (c == '\n') ++line_;
            else if (c != ' ' && c != '\t' && c != '\r') break;
            ++body_;
        }
        const std::size_t start = body_;
        while (body_ < size) {
            const char c = d[body_];
            if (c == ' ' || c == '\t' || c == '\r' || c == '\n') break;
            ++body_;
        }
        return {d + start, body_ - start};
    }

    double ascii_number(const Element& el, std::uint64_t item, const std::string& what) {
        const std::string_view t = token();
        if (t.empty())
            fail("PLY element \"" + el.name + "\" " + std::to_string(item) + " of " +
                 std::to_string(el.count) + " is truncated: the file ends at line " +
                 std::to_string(line_) + " before the header's count");
        double value = 0.0;
        const auto r = std::from_chars(t.data(), t.data() + t.size(), value);
        if (r.ec == std::errc::result_out_of_range) {
            value = (t.front() == '-') ? -HUGE_VAL : HUGE_VAL;
        } else if (r.ec != std::errc() || r.ptr != t.data() + t.size()) {
            fail_line(line_, "PLY element \"" + el.name + "\" " + std::to_string(item) + ": " +
                                 what + " is \"" + std::string(t) + "\", expected a number");
        }
        return value;
    }

    void read_ascii(const Element& el, bool is_vertex, bool is_face) {
        std::vector<std::int64_t> corners;
        for (std::uint64_t item = 0; item < el.count; ++item) {
            poll_cancel(item);
            for (const auto& p : el.properties) {
                if (!p.is_list) {
                    const double v = ascii_number(el, item, "property \"" + p.name + "\"");
                    if (is_vertex && p.target != Target::Ignore)
                        b_.store(static_cast<std::size_t>(item), p, v);
                    continue;
                }
                const double count = ascii_number(el, item, "list count of \"" + p.name + "\"");
                if (!(count >= 0) || count != std::floor(count) || count > 1e6)
                    fail_line(line_, "PLY element \"" + el.name + "\" " + std::to_string(item) +
                                         ": list \"" + p.name + "\" has count " +
                                         std::to_string(count) +
                                         ", expected a small non-negative integer");
                const auto n = static_cast<std::int64_t>(count);
                const bool keep = is_face && p.target == Target::FaceIndices;
                if (keep) corners.clear();
                for (std::int64_t k = 0; k < n; ++k) {
                    const double idx = ascii_number(el, item, "entry of \"" + p.name + "\"");
                    if (keep) {
                        if (idx != std::floor(idx))
                            fail_line(line_, "PLY face " + std::to_string(item) + ": index " +
                                                 std::to_string(idx) + " is not an integer");
                        corners.push_back(clamp_to<std::int64_t>(idx));
                    }
                }
                if (keep)
                    add_face(item, n,
                             [&](std::int64_t k) { return corners[static_cast<std::size_t>(k)]; });
            }
        }
    }

    void finish() {
        report_.file_vertices = b_.vertex_count;
        report_.file_triangles = b_.mesh.triangles.size();
        report_.split_polygons += b_.split_polygons;
        if (b_.short_faces > 0)
            report_.warnings.push_back(std::to_string(b_.short_faces) +
                                       " faces with fewer than 3 corners skipped");
        if (face_element_ < 0) report_.warnings.push_back("PLY file has no \"face\" element");
    }

    std::span<const char> data_;
    const std::string& source_;
    LoadReport& report_;
    std::uint64_t max_triangles_;
    Encoding encoding_ = Encoding::Ascii;
    std::vector<Element> elements_;
    std::ptrdiff_t vertex_element_ = -1;
    std::ptrdiff_t face_element_ = -1;
    std::size_t body_ = 0;  ///< read position in data_
    std::size_t line_ = 0;  ///< current line (ASCII body)
    Builder b_;
};

}  // namespace

Mesh read_ply(std::span<const char> data, const std::string& source, LoadReport& report,
              const LoadOptions& options) {
    return PlyParser(data, source, report, options.max_triangles).parse();
}

}  // namespace glint::detail
