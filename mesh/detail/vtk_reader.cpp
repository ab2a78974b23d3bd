#include "mesh/detail/vtk_reader.h"

#include "mesh/detail/scan.h"
#include "mesh/detail/vtk_values.h"
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

std::vector<std::string_view> split(std::string_view line) { return split_words(line); }

class VtkParser {
  public:
    VtkParser(std::span<const char> data, const std::string& source, LoadReport& report,
              std::uint64_t max_triangles)
        : data_(data), source_(source), report_(report), max_triangles_(max_triangles) {}

    Mesh parse() {
        parse_preamble();
        std::string_view line;
        while (next_line(line)) {
            words_ = split(line);
            if (words_.empty()) continue;
            const std::string_view key = words_[0];
            if (iequals(key, "FIELD")) read_field();
            else if (iequals(key, "POINTS")) read_points();
            else if (iequals(key, "POLYGONS")) read_cells(CellKind::Polygons);
            else if (iequals(key, "TRIANGLE_STRIPS")) read_cells(CellKind::Strips);
            else if (iequals(key, "VERTICES")) read_cells(CellKind::Vertices);
            else if (iequals(key, "LINES")) read_cells(CellKind::Lines);
            else if (iequals(key, "POINT_DATA")) begin_data(Section::Point);
            else if (iequals(key, "CELL_DATA")) begin_data(Section::Cell);
            else if (iequals(key, "METADATA")) skip_metadata();
            else if (is_attribute(key)) read_attribute();
            else fail("unknown VTK keyword \"" + printable(key) + "\"");
        }
        if (!has_points_) fail("VTK POLYDATA has no POINTS section");
        report_.file_vertices = mesh_.positions.size();
        report_.file_triangles = mesh_.triangles.size();
        for (const auto& [what, count] : skipped_cells_)
            report_.warnings.push_back("VTK " + what + " (" + std::to_string(count) +
                                       " cells) skipped");
        if (strips_ > 0)
            report_.warnings.push_back(std::to_string(strips_) +
                                       " triangle strips converted into " +
                                       std::to_string(strip_triangles_) + " triangles");
        return std::move(mesh_);
    }

  private:
    enum class Section { None, Point, Cell };
    enum class CellKind { Polygons, Strips, Vertices, Lines };

    // ---- messages -------------------------------------------------------------------------

    std::string where(std::size_t at) const {
        if (!binary_) {
            const auto line =
                1 +
                std::count(data_.begin(),
                           data_.begin() + static_cast<std::ptrdiff_t>(std::min(at, data_.size())),
                           '\n');
            return "line " + std::to_string(line);
        }
        return "byte " + std::to_string(at);
    }
    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(quoted_mesh(source_) + ": " + where(line_start_) + ": " + what);
    }
    // ---- low-level reading ----------------------------------------------------------------

    // Reads the next line (without its '\n'); false at end of file.
    bool next_line(std::string_view& line) {
        if (pos_ >= data_.size()) return false;
        line_start_ = pos_;
        poll_cancel(++lines_read_);
        return detail::next_line(data_, pos_, line);
    }

    // Next non-blank line's words without consuming it (empty at end of file).
    std::vector<std::string_view> peek_words() {
        const std::size_t save_pos = pos_, save_start = line_start_;
        std::string_view line;
        std::vector<std::string_view> w;
        while (w.empty() && next_line(line)) w = split(line);
        pos_ = save_pos;
        line_start_ = save_start;
        return w;
    }

    std::string_view token() {
        const char* d = data_.data();
        while (pos_ < data_.size() &&
               (d[pos_] == ' ' || d[pos_] == '\t' || d[pos_] == '\r' || d[pos_] == '\n'))
            ++pos_;
        const std::size_t start = pos_;
        while (pos_ < data_.size() && d[pos_] != ' ' && d[pos_] != '\t' && d[pos_] != '\r' &&
               d[pos_] != '\n')
            ++pos_;
        return {d + start, pos_ - start};
    }

    // The line's first word, or "" for a line of none (messages name it).
    [[nodiscard]] std::string_view first_word() const {
        return words_.empty() ? std::string_view() : words_[0];
    }

    std::uint64_t count_word(std::size_t i, const char* what) const {
        if (i >= words_.size())
            fail(std::string("expected ") + what + " after \"" + std::string(first_word()) + "\"");
        std::uint64_t n = 0;
        const auto w = words_[i];
        const auto r = std::from_chars(w.data(), w.data() + w.size(), n);
        if (r.ec != std::errc() || r.ptr != w.data() + w.size())
            fail(std::string(what) + " of \"" + std::string(first_word()) + "\" is \"" +
                 printable(w) + "\", expected a non-negative integer");
        return n;
    }

    VtkType type_word(std::size_t i) const {
        if (i >= words_.size())
            fail("expected a data type after \"" + std::string(first_word()) + "\"");
        const auto t = parse_vtk_type(words_[i]);
        if (!t) fail("unknown VTK data type \"" + printable(words_[i]) + "\"");
        return *t;
    }

    // Reads `count` values of `type`, calling sink(i, value). `what` names the section.
    template <class Sink>
    void read_values(std::uint64_t count, VtkType type, const std::string& what, Sink sink) {
        if (type == VtkType::String) {
            if (!binary_) {  // ASCII: one string per line
                std::string_view line;
                for (std::uint64_t i = 0; i < count; ++i)
                    if (!next_line(line)) truncated(what, i, count);  // polls cancellation
                return;
            }
            // BINARY: each string is prefixed by its length, whose first two bits say how
            // many bytes the length takes: 11 -> 6 bits in 1 byte, 10 -> 14 bits in 2,
            // 01 -> 30 bits in 4, 00 -> 62 bits in 8 (vtkDataWriter's string encoding).
            for (std::uint64_t i = 0; i < count; ++i) {
                poll_cancel(i);
                if (pos_ >= data_.size()) truncated(what, i, count);
                const auto tag = static_cast<unsigned char>(data_[pos_]) >> 6;
                const std::size_t bytes = tag == 3 ? 1 : tag == 2 ? 2 : tag == 1 ? 4 : 8;
                if (data_.size() - pos_ < bytes) truncated(what, i, count);
                std::uint64_t length = 0;
                for (std::size_t b = 0; b < bytes; ++b)
                    length = (length << 8) | static_cast<unsigned char>(data_[pos_ + b]);
                length &= (std::uint64_t{1} << (8 * bytes - 2)) - 1;
                pos_ += bytes;
                if (length > data_.size() - pos_) truncated(what, i, count);
                pos_ += static_cast<std::size_t>(length);
            }
            return;
        }
        if (!binary_) {
            for (std::uint64_t i = 0; i < count; ++i) {
                poll_cancel(i);
                const std::string_view t = token();
                if (t.empty()) truncated(what, i, count);
                double v = 0.0;
                const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
                if (r.ec == std::errc::result_out_of_range)
                    v = t.front() == '-' ? -HUGE_VAL : HUGE_VAL;
                else if (r.ec != std::errc() || r.ptr != t.data() + t.size()) {
                    line_start_ = static_cast<std::size_t>(t.data() - data_.data());
                    fail(what + ": value " + std::to_string(i) + " of " + std::to_string(count) +
                         " is \"" + printable(t) + "\", expected a number");
                }
                sink(static_cast<std::size_t>(i), v);
            }
            return;
        }
        if (type == VtkType::Bit) {
            const std::uint64_t bytes = (count + 7) / 8;
            if (bytes > data_.size() - pos_) truncated(what, (data_.size() - pos_) * 8, count);
            for (std::uint64_t i = 0; i < count; ++i) {
                poll_cancel(i);
                sink(static_cast<std::size_t>(i),
                     (static_cast<unsigned char>(data_[pos_ + i / 8]) >> (7 - i % 8)) & 1u);
            }
            pos_ += bytes;
            return;
        }
        const std::size_t s = size_of(type);
        if (count > (data_.size() - pos_) / s) truncated(what, (data_.size() - pos_) / s, count);
        const char* p = data_.data() + pos_;
        for (std::uint64_t i = 0; i < count; ++i, p += s) {
            poll_cancel(i);
            sink(static_cast<std::size_t>(i), load_value(p, type));
        }
        pos_ += static_cast<std::size_t>(count) * s;
    }

    void skip_values(std::uint64_t count, VtkType type, const std::string& what) {
        read_values(count, type, what, [](std::size_t, double) {});
    }

    [[noreturn]] void truncated(const std::string& what, std::uint64_t got, std::uint64_t count) {
        throw InputError(quoted_mesh(source_) + ": " + where(line_start_) + ": " + what +
                         " ends after " + std::to_string(got) + " of " + std::to_string(count) +
                         " values: the file is truncated");
    }

    // ---- sections -------------------------------------------------------------------------

    void parse_preamble() {
        std::string_view line;
        if (!next_line(line) || !line.starts_with("# vtk DataFile"))
            fail("does not start with \"# vtk DataFile Version\", not a VTK legacy file");
        if (!next_line(line)) fail("VTK header ends after the version line");  // title
        if (!next_line(line)) fail("VTK header has no ASCII/BINARY line");
        const auto enc = split(line);
        if (enc.size() == 1 && iequals(enc[0], "ASCII")) binary_ = false;
        else if (enc.size() == 1 && iequals(enc[0], "BINARY")) binary_ = true;
        else fail("expected ASCII or BINARY, found \"" + printable(line) + "\"");
        report_.format = binary_ ? "vtk-binary" : "vtk-ascii";
        std::vector<std::string_view> w;
        while (w.empty()) {
            if (!next_line(line)) fail("VTK header has no DATASET line");
            w = split(line);
        }
        if (w.size() != 2 || !iequals(w[0], "DATASET"))
            fail("expected \"DATASET POLYDATA\", found \"" + printable(line) + "\"");
        if (!iequals(w[1], "POLYDATA"))
            fail("dataset is " + printable(w[1]) + ", glint reads only POLYDATA (surface meshes)");
    }

    // A lying count must not make us allocate gigabytes before the data runs out: every value
    // takes at least its binary size, or two characters ("0 ") in ASCII.
    void guard_count(std::uint64_t count, VtkType t, const std::string& what) {
        const std::size_t left = data_.size() - pos_;
        const std::size_t min_bytes = binary_ ? std::max<std::size_t>(size_of(t), 1) : 2;
        if (count <= left / min_bytes + 1) return;
        if (binary_) truncated(what, left / min_bytes, count);
        throw InputError(quoted_mesh(source_) + ": " + where(line_start_) + ": " + what +
                         " declares " + std::to_string(count) + " values but only " +
                         std::to_string(left) + " bytes follow: the file is truncated");
    }

    void read_points() {
        if (has_points_) fail("second POINTS section");
        const std::uint64_t n = count_word(1, "point count");
        const VtkType t = type_word(2);
        if (t == VtkType::String || t == VtkType::Bit) fail("POINTS must be numeric");
        guard_count(saturating_mul(3, n), t, "POINTS");
        mesh_.positions.resize(static_cast<std::size_t>(n));
        float* out = mesh_.positions.empty() ? nullptr : mesh_.positions[0].data();
        // note: Vec3f is three packed floats (Eigen fixed-size, no padding) so index 3v+k works.
        static_assert(sizeof(Vec3f) == 3 * sizeof(float));
        read_values(saturating_mul(3, n), t, "POINTS",
                    [&](std::size_t i, double v) { out[i] = static_cast<float>(v); });
        has_points_ = true;
        point_count_ = static_cast<std::size_t>(n);
    }

    std::vector<std::int64_t> read_ints(std::uint64_t count, VtkType t, const std::string& what) {
        if (!is_integer(t)) fail(what + " must have an integer type");
        guard_count(count, t, what);
        std::vector<std::int64_t> out(static_cast<std::size_t>(count));
        read_values(count, t, what,
                    [&](std::size_t i, double v) { out[i] = clamp_to<std::int64_t>(v); });
        return out;
    }

    /// Reads a cell section's arrays as (offsets, connectivity), from either layout; false when
    /// the section holds no cell.
    bool read_cell_arrays(const std::string& what, std::vector<std::int64_t>& offsets,
                          std::vector<std::int64_t>& conn) {
        const std::uint64_t n = count_word(1, "cell count");
        const std::uint64_t size = count_word(2, "connectivity size");
        // Cells as (offsets, connectivity): the classic layout stores [k, i0..ik-1] per cell;
        // VTK 5.1 writes OFFSETS (n+1 entries) and CONNECTIVITY arrays.
        const auto next = peek_words();
        if (!next.empty() && iequals(next[0], "OFFSETS")) {
            // note: peek_words() looked past blank lines; so does the read (a fuzz_vtk finding:
            // a blank line before OFFSETS left no words, and the message read the first of
            // none).
            std::string_view line;
            words_.clear();
            while (words_.empty() && next_line(line)) words_ = split(line);
            offsets = read_ints(n, type_word(1), what + " OFFSETS");
            std::vector<std::string_view> w;
            while (w.empty()) {
                if (!next_line(line)) fail(what + " has OFFSETS but no CONNECTIVITY");
                w = split(line);
            }
            words_ = w;
            if (!iequals(words_[0], "CONNECTIVITY"))
                fail("expected CONNECTIVITY after " + what + " OFFSETS, found \"" +
                     printable(line) + "\"");
            conn = read_ints(size, type_word(1), what + " CONNECTIVITY");
            if (!offsets.empty() && offsets.back() != static_cast<std::int64_t>(conn.size()))
                fail(what + " OFFSETS end at " + std::to_string(offsets.back()) +
                     " but CONNECTIVITY has " + std::to_string(conn.size()) + " entries");
            if (offsets.empty()) return false;
        } else {
            const auto flat = read_ints(size, VtkType::Int32, what);
            if (n > flat.size())
                fail(what + " declares " + std::to_string(n) + " cells in only " +
                     std::to_string(size) + " numbers");
            offsets.reserve(static_cast<std::size_t>(n) + 1);
            conn.reserve(flat.size());
            offsets.push_back(0);
            std::size_t i = 0;
            for (std::uint64_t c = 0; c < n; ++c) {
                poll_cancel(c);
                if (i >= flat.size())
                    fail(what + " declares " + std::to_string(n) + " cells in " +
                         std::to_string(size) + " numbers, but the numbers end at cell " +
                         std::to_string(c));
                const std::int64_t k = flat[i++];
                if (k < 0 || static_cast<std::uint64_t>(k) > flat.size() - i)
                    fail(what + " cell " + std::to_string(c) + " has " + std::to_string(k) +
                         " points, more than the " + std::to_string(flat.size() - i) +
                         " numbers left");
                conn.insert(
                    conn.end(), flat.begin() + static_cast<std::ptrdiff_t>(i),
                    flat.begin() + static_cast<std::ptrdiff_t>(i + static_cast<std::size_t>(k)));
                i += static_cast<std::size_t>(k);
                offsets.push_back(static_cast<std::int64_t>(conn.size()));
            }
            if (i != flat.size())
                fail(what + " declares size " + std::to_string(size) + " but its " +
                     std::to_string(n) + " cells use " + std::to_string(i) + " numbers");
        }
        return true;
    }

    /// Adds the triangles of polygon or strip cells; counts the cells of fewer than 3 points.
    void add_cells(CellKind kind, const std::string& what, const std::vector<std::int64_t>& offsets,
                   const std::vector<std::int64_t>& conn) {
        const std::size_t cells = offsets.size() - 1;
        auto index = [&](std::size_t c, std::int64_t i) {
            if (i < 0 || (has_points_ && static_cast<std::uint64_t>(i) >= point_count_))
                fail(what + " cell " + std::to_string(c) + " uses point " + std::to_string(i) +
                     ", the file has " + std::to_string(point_count_) + " points");
            return static_cast<std::uint32_t>(i);
        };
        for (std::size_t c = 0; c < cells; ++c) {
            poll_cancel(c);
            const auto b = static_cast<std::size_t>(offsets[c]);
            const auto e = static_cast<std::size_t>(offsets[c + 1]);
            if (e < b || e > conn.size())
                fail(what + " OFFSETS are not increasing at cell " + std::to_string(c));
            const std::size_t k = e - b;
            if (k >= 3 && mesh_.triangles.size() + k - 2 > max_triangles_)
                check_triangle_budget(mesh_.triangles.size() + k - 2, max_triangles_, source_,
                                      what + " cell " + std::to_string(c) + " brings the mesh to");
            if (k < 3) {
                ++short_cells_;
                continue;
            }
            if (kind == CellKind::Polygons) {
                if (k > 3) ++report_.split_polygons;
                const auto first = index(c, conn[b]);
                auto prev = index(c, conn[b + 1]);
                for (std::size_t j = 2; j < k; ++j) {
                    const auto cur = index(c, conn[b + j]);
                    mesh_.triangles.push_back({first, prev, cur});
                    prev = cur;
                }
            } else {
                // Strip v0 v1 v2 v3 …: triangle j is (v_j, v_j+1, v_j+2), every odd one flipped
                // so all keep the strip's orientation.
                ++strips_;
                for (std::size_t j = 0; j + 2 < k; ++j) {
                    const auto a = index(c, conn[b + j]);
                    const auto bb = index(c, conn[b + j + 1]);
                    const auto cc = index(c, conn[b + j + 2]);
                    if (j % 2 == 0) mesh_.triangles.push_back({a, bb, cc});
                    else mesh_.triangles.push_back({bb, a, cc});
                    ++strip_triangles_;
                }
            }
        }
    }

    void read_cells(CellKind kind) {
        const std::string what(words_[0]);
        std::vector<std::int64_t> offsets;
        std::vector<std::int64_t> conn;
        if (!read_cell_arrays(what, offsets, conn)) return;
        const std::size_t cells = offsets.size() - 1;
        cell_count_ += cells;
        if (kind == CellKind::Vertices || kind == CellKind::Lines) {
            skipped_cells_.emplace_back(what, cells);
            return;
        }
        add_cells(kind, what, offsets, conn);
        if (short_cells_ > 0 && kind == CellKind::Polygons) {
            report_.warnings.push_back(std::to_string(short_cells_) + " " + what +
                                       " cells with fewer than 3 points skipped");
            short_cells_ = 0;
        }
    }

    void begin_data(Section s) {
        section_ = s;
        section_count_ = static_cast<std::size_t>(count_word(1, "count"));
        if (s == Section::Point && has_points_ && section_count_ != point_count_)
            fail("POINT_DATA has " + std::to_string(section_count_) + " values, the file has " +
                 std::to_string(point_count_) + " points");
    }

    static bool is_attribute(std::string_view key) {
        for (const char* k : {"SCALARS", "COLOR_SCALARS", "LOOKUP_TABLE", "VECTORS", "NORMALS",
                              "TEXTURE_COORDINATES", "TENSORS", "GLOBAL_IDS", "PEDIGREE_IDS"})
            if (iequals(key, k)) return true;
        return false;
    }

    std::string attribute_name() const {
        std::string name = words_.size() > 1 ? std::string(words_[1]) : std::string();
        // note: VTK legacy writers encode spaces in names as %20.
        for (std::size_t i = 0; (i = name.find("%20", i)) != std::string::npos;)
            name.replace(i, 3, " ");
        return name;
    }

    void read_attribute() {
        const std::string key(words_[0]);
        std::string upper = key;
        for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        if (upper == "LOOKUP_TABLE") {
            // A standalone colour table: size RGBA entries (floats in ASCII, bytes in BINARY).
            const std::uint64_t size = count_word(2, "table size");
            skip_values(saturating_mul(4, size), binary_ ? VtkType::UInt8 : VtkType::Float32,
                        "LOOKUP_TABLE");
            return;
        }
        if (section_ == Section::None) fail(key + " outside POINT_DATA / CELL_DATA");
        const std::size_t n = section_count_;
        const bool keep = section_ == Section::Point;
        const std::string name = attribute_name();
        const std::string what = key + " \"" + name + "\"";
        if (upper == "SCALARS") {
            const VtkType t = type_word(2);
            const std::uint64_t comps = words_.size() > 3 ? count_word(3, "component count") : 1;
            const auto next = peek_words();
            if (!next.empty() && iequals(next[0], "LOOKUP_TABLE")) {
                std::string_view line;
                next_line(line);
            }
            read_array(name, t, comps, n, keep, what);
        } else if (upper == "COLOR_SCALARS") {
            const std::uint64_t comps = count_word(2, "component count");
            const VtkType t = binary_ ? VtkType::UInt8 : VtkType::Float32;
            if (keep && comps >= 3) {
                guard_count(saturating_mul(comps, n), t, what);
                mesh_.colors.assign(n, Rgb8{0, 0, 0});
                read_values(saturating_mul(comps, n), t, what, [&](std::size_t i, double v) {
                    const std::size_t c = i % comps;
                    if (c >= 3) return;
                    const double scaled = binary_ ? v : v * 255.0;  // ASCII colours are in [0, 1]
                    mesh_.colors[i / comps][c] =
                        static_cast<std::uint8_t>(std::clamp(std::lround(scaled), 0L, 255L));
                });
            } else {
                skip_values(saturating_mul(comps, n), t, what);
            }
        } else if (upper == "NORMALS") {
            const VtkType t = type_word(2);
            if (keep) {
                guard_count(saturating_mul(3, n), t, what);
                mesh_.normals.assign(n, Vec3f::Zero());
                float* out = n ? mesh_.normals[0].data() : nullptr;
                read_values(saturating_mul(3, n), t, what,
                            [&](std::size_t i, double v) { out[i] = static_cast<float>(v); });
            } else {
                skip_values(saturating_mul(3, n), t, what);
            }
        } else if (upper == "VECTORS") {
            skip_values(saturating_mul(3, n), type_word(2), what);
            if (keep) report_.warnings.push_back("VTK point " + what + " skipped");
        } else if (upper == "TEXTURE_COORDINATES") {
            const std::uint64_t dim = count_word(2, "dimension");
            skip_values(saturating_mul(dim, n), type_word(3), what);
        } else if (upper == "TENSORS") {
            skip_values(saturating_mul(9, n), type_word(2), what);
        } else {  // GLOBAL_IDS, PEDIGREE_IDS
            skip_values(n, type_word(2), what);
        }
    }

    // One data array of `tuples` × `comps` values: a point scalar when kept and 1-component.
    void read_array(const std::string& name, VtkType t, std::uint64_t comps, std::uint64_t tuples,
                    bool keep, const std::string& what) {
        const bool as_field = keep && comps == 1 && tuples == point_count_ && t != VtkType::String;
        if (!as_field) {
            if (keep && t != VtkType::String)
                report_.warnings.push_back(
                    "VTK point array \"" + name + "\" with " + std::to_string(comps) +
                    " components skipped (only 1-component arrays are kept)");
            skip_values(saturating_mul(comps, tuples), t, what);
            return;
        }
        if (name == "label" && is_integer(t)) {
            mesh_.labels.assign(static_cast<std::size_t>(tuples), 0);
            read_values(tuples, t, what, [&](std::size_t i, double v) {
                mesh_.labels[i] = clamp_to<std::int32_t>(v);
            });
            return;
        }
        std::vector<float> values(static_cast<std::size_t>(tuples));
        read_values(tuples, t, what,
                    [&](std::size_t i, double v) { values[i] = static_cast<float>(v); });
        if (auto* existing = mesh_.find_scalar(name)) existing->values = std::move(values);
        else mesh_.scalars.push_back({name, std::move(values)});
    }

    void read_field() {
        const std::string field_name = words_.size() > 1 ? std::string(words_[1]) : "";
        const std::uint64_t arrays = count_word(2, "array count");
        for (std::uint64_t a = 0; a < arrays; ++a) {
            std::string_view line;
            std::vector<std::string_view> w;
            while (w.empty()) {
                if (!next_line(line))
                    fail("FIELD \"" + field_name + "\" declares " + std::to_string(arrays) +
                         " arrays, the file ends after " + std::to_string(a));
                w = split(line);
            }
            words_ = w;
            if (iequals(words_[0], "NULL_ARRAY")) continue;
            if (words_.size() != 4)
                fail("FIELD \"" + field_name + "\" array " + std::to_string(a) +
                     ": expected \"NAME COMPONENTS TUPLES TYPE\", found \"" + printable(line) +
                     "\"");
            std::string name(words_[0]);
            for (std::size_t i = 0; (i = name.find("%20", i)) != std::string::npos;)
                name.replace(i, 3, " ");
            const std::uint64_t comps = count_word(1, "component count");
            const std::uint64_t tuples = count_word(2, "tuple count");
            const VtkType t = type_word(3);
            read_array(name, t, comps, tuples, section_ == Section::Point,
                       "FIELD \"" + field_name + "\" array \"" + name + "\"");
            const auto next = peek_words();
            if (!next.empty() && iequals(next[0], "METADATA")) {
                next_line(line);
                skip_metadata();
            }
        }
    }

    // METADATA blocks (VTK ≥ 8) end at the next blank line.
    void skip_metadata() {
        std::string_view line;
        while (next_line(line))
            if (split(line).empty()) return;
    }

    std::span<const char> data_;
    const std::string& source_;
    LoadReport& report_;
    std::uint64_t max_triangles_;
    Mesh mesh_;
    bool binary_ = false;
    std::size_t pos_ = 0;
    std::size_t line_start_ = 0;    ///< start of the current header line (for messages)
    std::uint64_t lines_read_ = 0;  ///< for polling cancellation
    std::vector<std::string_view> words_;
    bool has_points_ = false;
    std::size_t point_count_ = 0;
    std::size_t cell_count_ = 0;
    Section section_ = Section::None;
    std::size_t section_count_ = 0;
    std::size_t short_cells_ = 0;
    std::size_t strips_ = 0;
    std::size_t strip_triangles_ = 0;
    std::vector<std::pair<std::string, std::size_t>> skipped_cells_;
};

}  // namespace

Mesh read_vtk(std::span<const char> data, const std::string& source, LoadReport& report,
              const LoadOptions& options) {
    return VtkParser(data, source, report, options.max_triangles).parse();
}

}  // namespace glint::detail
