#include "mesh/detail/scene_check.h"

#include "mesh/detail/scan.h"
#include "mesh/error.h"
#include "mesh/json_text.h"
#include "mesh/output_guard.h"

#include <nlohmann/json.hpp>

#include <sys/stat.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace glint::detail {

namespace {

using nlohmann::json;

std::uint64_t add_sat(std::uint64_t a, std::uint64_t b) {
    return a > UINT64_MAX - b ? UINT64_MAX : a + b;
}

// Deepest object/array nesting, outside strings; stops counting past the limit.
void check_json_depth(std::span<const char> text, const std::string& source) {
    int depth = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (in_string) {
            if (c == '\\') ++i;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '{' || c == '[') {
            if (++depth > kMaxJsonDepth)
                throw InputError(quoted_mesh(source) +
                                 ": glTF JSON nests objects/arrays deeper than " +
                                 std::to_string(kMaxJsonDepth) + " levels (at byte " +
                                 std::to_string(i) + "), more than the limit");
        } else if (c == '}' || c == ']') {
            --depth;
        }
    }
}

// A glTF id: an array index (2.0) or an object key (1.0) turned into an index.
struct Ids {
    std::unordered_map<std::string, std::size_t> by_key;
    std::size_t size = 0;

    explicit Ids(const json& collection) {
        if (collection.is_array()) size = collection.size();
        if (!collection.is_object()) return;
        for (const auto& [key, value] : collection.items()) by_key.emplace(key, size++);
    }
    // Index of `ref` (a number or a key), or npos when it names nothing.
    [[nodiscard]] std::size_t index(const json& ref) const {
        if (ref.is_number_unsigned() && ref.get<std::uint64_t>() < size)
            return static_cast<std::size_t>(ref.get<std::uint64_t>());
        if (ref.is_string()) {
            const auto it = by_key.find(ref.get<std::string>());
            if (it != by_key.end()) return it->second;
        }
        return std::string::npos;
    }
};

// Elements of a glTF collection in index order (array items or object values).
std::vector<const json*> elements(const json& collection) {
    std::vector<const json*> out;
    if (collection.is_array() || collection.is_object())
        for (const auto& item : collection) out.push_back(&item);
    return out;
}

const json& member(const json& object, const char* key) {
    static const json kNull;
    if (!object.is_object()) return kNull;
    const auto it = object.find(key);
    return it == object.end() ? kNull : *it;
}

// Triangles one instance of each mesh draws, from its primitives' accessor counts. A primitive
// must draw points or triangles from a POSITION accessor that exists: assimp 5.2 reads line
// loops and strips past their index buffer (a fuzz_gltf SEGV) and sizes a primitive without
// positions from a count of −1 (a fuzz_glb 68 GB allocation); neither is a surface.
std::vector<std::uint64_t> mesh_triangles(const json& doc, const std::string& source) {
    const json& accessors = member(doc, "accessors");
    const Ids accessor_ids(accessors);
    const auto accessor_list = elements(accessors);
    auto count_of = [&](const json& ref) -> std::uint64_t {
        const std::size_t a = accessor_ids.index(ref);
        if (a == std::string::npos) return 0;
        const json& count = member(*accessor_list[a], "count");
        return count.is_number_unsigned() ? count.get<std::uint64_t>() : 0;
    };
    std::vector<std::uint64_t> out;
    const auto meshes = elements(member(doc, "meshes"));
    for (std::size_t m = 0; m < meshes.size(); ++m) {
        std::uint64_t triangles = 0;
        const auto prims = elements(member(*meshes[m], "primitives"));
        for (std::size_t p = 0; p < prims.size(); ++p) {
            const json* prim = prims[p];
            const std::string where = quoted_mesh(source) + ": glTF mesh " + std::to_string(m) +
                                      " primitive " + std::to_string(p);
            const json& mode_json = member(*prim, "mode");
            if (!mode_json.is_null() && !mode_json.is_number_unsigned())
                throw InputError(
                    where + ": mode is not a number, expected 0 (points) or 4, 5, 6 (triangles)");
            const std::uint64_t mode =
                mode_json.is_number_unsigned() ? mode_json.get<std::uint64_t>() : 4;
            if (mode != 0 && (mode < 4 || mode > 6))
                throw InputError(
                    where + ": mode " + std::to_string(mode) + (mode <= 3 ? " (lines)" : "") +
                    ", expected 0 (points) or 4, 5, 6 (triangles): glint reads surfaces");
            if (accessor_ids.index(member(member(*prim, "attributes"), "POSITION")) ==
                std::string::npos)
                throw InputError(where + ": no POSITION accessor, expected vertex positions");
            const json& indices = member(*prim, "indices");
            const std::uint64_t n = indices.is_null()
                                        ? count_of(member(member(*prim, "attributes"), "POSITION"))
                                        : count_of(indices);
            // note: assimp sizes a strip or fan of n < 3 vertices as n − 2 faces (a fuzz_glb
            // allocation of 2^64 bytes from an index accessor of count 0).
            const std::uint64_t needed = mode == 0 ? 1 : 3;
            if (n < needed)
                throw InputError(where + ": draws " + std::to_string(n) + " vertices (" +
                                 (indices.is_null() ? "POSITION" : "indices") +
                                 " accessor count), expected at least " + std::to_string(needed));
            if (mode == 4) triangles = add_sat(triangles, n / 3);
            else if ((mode == 5 || mode == 6) && n > 2) triangles = add_sat(triangles, n - 2);
        }
        out.push_back(triangles);
    }
    return out;
}

struct Node {
    std::vector<std::size_t> children;
    std::uint64_t own_triangles = 0;
    // Filled by the walk: levels below and including this node, node instances and
    // triangles of the expanded subtree.
    int height = 0;
    std::uint64_t instances = 0;
    std::uint64_t triangles = 0;
    int state = 0;  // 0 unvisited, 1 on the walk's stack, 2 done
    bool has_parent = false;
};

std::vector<Node> read_nodes(const json& doc, const std::string& source) {
    const json& nodes_json = member(doc, "nodes");
    const Ids node_ids(nodes_json);
    const Ids mesh_ids(member(doc, "meshes"));
    const std::vector<std::uint64_t> tris = mesh_triangles(doc, source);
    std::vector<Node> nodes(node_ids.size);
    std::size_t k = 0;
    for (const json* n : elements(nodes_json)) {
        Node& node = nodes[k++];
        for (const json* c : elements(member(*n, "children"))) {
            const std::size_t child = node_ids.index(*c);
            if (child != std::string::npos) node.children.push_back(child);
        }
        auto add_mesh = [&](const json& ref) {
            const std::size_t m = mesh_ids.index(ref);
            if (m != std::string::npos) node.own_triangles = add_sat(node.own_triangles, tris[m]);
        };
        add_mesh(member(*n, "mesh"));                                       // glTF 2.0
        for (const json* m : elements(member(*n, "meshes"))) add_mesh(*m);  // glTF 1.0
    }
    for (const Node& node : nodes)
        for (std::size_t c : node.children) nodes[c].has_parent = true;
    return nodes;
}

// Post-order walk from `root` with an explicit stack: heights, instance and triangle counts
// (saturating), memoised so a shared subtree is walked once.
void walk(std::vector<Node>& nodes, std::size_t root, const std::string& source) {
    std::vector<std::pair<std::size_t, std::size_t>> stack;  // node, next child
    if (nodes[root].state == 2) return;
    stack.emplace_back(root, 0);
    nodes[root].state = 1;
    while (!stack.empty()) {
        auto& [id, next] = stack.back();
        Node& node = nodes[id];
        if (next < node.children.size()) {
            const std::size_t c = node.children[next++];
            if (nodes[c].state == 1)
                throw InputError(
                    quoted_mesh(source) + ": glTF node " + std::to_string(c) +
                    " is its own ancestor (the node graph has a cycle), expected a tree");
            if (nodes[c].state == 0) {
                nodes[c].state = 1;
                stack.emplace_back(c, 0);
            }
            continue;
        }
        node.height = 1;
        node.instances = 1;
        node.triangles = node.own_triangles;
        for (std::size_t c : node.children) {
            node.height = std::max(node.height, nodes[c].height + 1);
            node.instances = add_sat(node.instances, nodes[c].instances);
            node.triangles = add_sat(node.triangles, nodes[c].triangles);
        }
        node.state = 2;
        stack.pop_back();
    }
}

std::vector<std::size_t> scene_roots(const json& doc, const std::vector<Node>& nodes) {
    const Ids node_ids(member(doc, "nodes"));
    std::vector<std::size_t> roots;
    for (const json* scene : elements(member(doc, "scenes")))
        for (const json* r : elements(member(*scene, "nodes"))) {
            const std::size_t id = node_ids.index(*r);
            if (id != std::string::npos) roots.push_back(id);
        }
    if (roots.empty())
        for (std::size_t i = 0; i < nodes.size(); ++i)
            if (!nodes[i].has_parent) roots.push_back(i);
    return roots;
}

// A glTF uri's %XX escapes decoded (RFC 3986); a malformed escape is kept as written.
std::string percent_decoded(const std::string& uri) {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        unsigned value = 0;
        if (uri[i] == '%' && i + 2 < uri.size() &&
            std::from_chars(uri.data() + i + 1, uri.data() + i + 3, value, 16).ptr ==
                uri.data() + i + 3) {
            out += static_cast<char>(value);
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

// The files a glTF's buffers name (issue 52). assimp opens each buffer uri relative to the
// glTF: one naming "/etc/passwd" was read as a buffer, one naming a FIFO blocked `glint info`,
// and one in the output folder was deleted by `-o … --force`. A buffer is read only from the
// glTF's folder or a folder below it, only when it is a regular file, and it becomes an input
// of the run (mesh/output_guard.h). `data:` URIs are embedded and read by assimp alone.
void check_buffer_uris(const json& doc, const std::string& source) {
    namespace fs = std::filesystem;
    const fs::path folder = fs::path(source).parent_path();
    const auto buffers = elements(member(doc, "buffers"));
    for (std::size_t b = 0; b < buffers.size(); ++b) {
        const json& uri = member(*buffers[b], "uri");
        if (!uri.is_string()) continue;
        const std::string text = uri.get<std::string>();
        if (text.rfind("data:", 0) == 0) continue;
        const std::string where = quoted_mesh(source) + ": glTF buffer " + std::to_string(b) +
                                  " uri \"" + printable(text) + "\"";
        const std::string name = percent_decoded(text);
        const fs::path relative = fs::path(name).lexically_normal();
        const bool outside = name.empty() || name.find('\0') != std::string::npos ||
                             relative.is_absolute() || relative.has_root_name() ||
                             name.find(':') != std::string::npos ||
                             (!relative.empty() && *relative.begin() == "..");
        if (outside)
            throw InputError(where +
                             " names a file outside the glTF's folder; expected a buffer file "
                             "beside the glTF or in a folder below it");
        const fs::path file = folder / relative;
        struct stat st {};
        if (::stat(file.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
            throw InputError(where + ": \"" + file.string() + "\" is " +
                             (S_ISFIFO(st.st_mode)  ? "a FIFO"
                              : S_ISDIR(st.st_mode) ? "a folder"
                                                    : "not a regular file") +
                             ", expected a buffer file");
        protect_input(file);
    }
}

}  // namespace

void check_gltf_json(std::span<const char> text, const std::string& source,
                     std::uint64_t max_triangles) {
    check_json_depth(text, source);
    json doc;
    try {
        doc = json::parse(text.begin(), text.end());
    } catch (const json::exception& e) {
        throw InputError(quoted_mesh(source) + ": glTF JSON does not parse: " + e.what());
    }
    if (!doc.is_object()) throw InputError(quoted_mesh(source) + ": glTF JSON is not an object");
    // note: assimp's glTF importers claim a file only when asset.version starts with 1 or 2;
    // any other file it hands to every importer it has, by content (a fuzz_glb finding: an
    // 18-byte non-glTF file overran a buffer in one of them), so such a file stops here.
    const json* asset = doc.contains("asset") ? &doc["asset"] : nullptr;
    const json* version =
        asset && asset->is_object() && asset->contains("version") ? &(*asset)["version"] : nullptr;
    if (!version || !version->is_string() || version->get<std::string>().empty() ||
        (version->get<std::string>()[0] != '1' && version->get<std::string>()[0] != '2'))
        throw InputError(quoted_mesh(source) + ": glTF JSON has " +
                         (version ? "asset.version " + printable(json_text(*version).substr(0, 40))
                                  : std::string("no asset.version")) +
                         ", expected \"1.0\" or \"2.0\"");
    check_buffer_uris(doc, source);
    std::vector<Node> nodes = read_nodes(doc, source);
    std::uint64_t instances = 0, triangles = 0;
    for (std::size_t root : scene_roots(doc, nodes)) {
        throw_if_cancelled();
        walk(nodes, root, source);
        const Node& r = nodes[root];
        if (r.height > kMaxGltfNodeDepth)
            throw InputError(quoted_mesh(source) + ": glTF nodes nest " + std::to_string(r.height) +
                             " levels deep below root node " + std::to_string(root) +
                             ", more than the limit " + std::to_string(kMaxGltfNodeDepth));
        instances = add_sat(instances, r.instances);
        triangles = add_sat(triangles, r.triangles);
    }
    if (instances > kMaxGltfInstances)
        throw InputError(
            quoted_mesh(source) + ": glTF node graph expands to " +
            (instances == UINT64_MAX ? std::string("over 2^64") : std::to_string(instances)) +
            " node instances (a node shared by several parents is copied for each), "
            "more than the limit " +
            std::to_string(kMaxGltfInstances));
    check_triangle_budget(triangles, max_triangles, source, "glTF scene instances add up to");
}

namespace {

std::uint32_t le32(std::span<const char> data, std::size_t at) {
    return load_bytes<std::uint32_t, false>(data.data() + at);
}

// The JSON of a GLB: version 2 has a 12-byte header then chunks (length, type "JSON", data),
// version 1 a 20-byte header with the content length at 12; both put the JSON at byte 20.
void check_glb(std::span<const char> data, const std::string& source, std::uint64_t max_triangles) {
    if (data.size() < 20)
        throw InputError(quoted_mesh(source) + ": GLB is " + std::to_string(data.size()) +
                         " bytes, shorter than its 20-byte header");
    const std::uint32_t version = le32(data, 4);
    if (version != 1 && version != 2)
        throw InputError(quoted_mesh(source) + ": GLB version " + std::to_string(version) +
                         ", expected 1 or 2");
    const std::size_t start = 20;
    const std::uint64_t length = le32(data, 12);  // both versions: JSON length at 12, data at 20
    if (version == 2 && le32(data, 16) != 0x4E4F534Au)
        throw InputError(quoted_mesh(source) + ": GLB's first chunk is not JSON");
    if (length > data.size() - start)
        throw InputError(quoted_mesh(source) + ": GLB JSON chunk declares " +
                         std::to_string(length) + " bytes, only " +
                         std::to_string(data.size() - start) + " follow");
    check_gltf_json(data.subspan(start, static_cast<std::size_t>(length)), source, max_triangles);
}

// assimp's own reading of an OFF header (its OFFLoader), byte for byte: the data ends in a NUL
// (assimp appends one; an embedded NUL ends a line), tokens are separated by spaces, tabs and
// line ends, lines starting with '#' are skipped only between tokens, the keyword's optional
// letters ST, C, N, 4, n are taken one by one before "OFF", "n" adds a dimension number before
// the counts, and a number is the run of digits at the cursor read into 32 bits (it wraps and
// stops at the first non-digit; no digit reads 0).
class OffHeaderCursor {
  public:
    explicit OffHeaderCursor(std::span<const char> data) : data_(data) {}
    char at(std::size_t k = 0) const { return pos_ + k < data_.size() ? data_[pos_ + k] : '\0'; }
    std::size_t pos() const { return pos_; }
    std::size_t end() const { return data_.size() + 1; }  // counting assimp's NUL
    void advance(std::size_t n) { pos_ += n; }
    void next_token() {
        skip_blanks();
        while (pos_ < end() && (at() == '#' || at() == '\n' || at() == '\r')) {
            while (at() != '\r' && at() != '\n' && at() != '\0') ++pos_;
            while (at() == '\r' || at() == '\n') ++pos_;
            skip_blanks();
        }
    }
    std::uint32_t number() {
        std::uint32_t value = 0;
        while (at() >= '0' && at() <= '9')
            value = value * 10u + static_cast<std::uint32_t>(at() - '0'), ++pos_;
        return value;
    }

  private:
    void skip_blanks() {
        while (at() == ' ' || at() == '\t' || at() == '\r' || at() == '\n') ++pos_;
    }
    std::span<const char> data_;
    std::size_t pos_ = 0;
};

struct OffCounts {
    std::uint64_t vertices = 0, faces = 0;
    std::size_t header_end = 0;
};

// The vertex and face counts as assimp reads them; nullopt where assimp refuses the header itself.
std::optional<OffCounts> assimp_off_counts(std::span<const char> data) {
    OffHeaderCursor c(data);
    c.next_token();
    const auto take = [&](std::string_view letters) {
        // assimp tests "car < end - letters" before comparing, so a prefix touching the end is not taken
        if (c.pos() + letters.size() >= c.end()) return false;
        for (std::size_t k = 0; k < letters.size(); ++k)
            if (c.at(k) != letters[k]) return false;
        c.advance(letters.size());
        return true;
    };
    take("ST");
    take("C");
    take("N");
    take("4");
    const bool dimension = take("n");
    if (take("OFF")) {
        c.next_token();
    } else {
        c.next_token();
        if (c.pos() + 1 >= c.end() || c.at() < '0' || c.at() > '9') return std::nullopt;
    }
    if (dimension) {
        if (c.number() > 3) return std::nullopt;
        c.next_token();
    }
    c.next_token();
    OffCounts counts;
    counts.vertices = c.number();
    c.next_token();
    counts.faces = c.number();
    c.next_token();
    (void)c.number();  // edges
    counts.header_end = std::min(c.pos(), data.size());
    return counts;
}

// The line number (1-based) of byte offset `pos`.
std::size_t line_of(std::span<const char> data, std::size_t pos) {
    return 1 + static_cast<std::size_t>(
                   std::count(data.begin(), data.begin() + std::min(pos, data.size()), '\n'));
}

// Every OFF face's corner indices name a vertex of the file. assimp clamps an index past the
// last vertex to the last one and reads −1 as 0: a different surface, without a word.
// `pos` is the first byte after the counts; the plain reading of the layout (vertex lines, then
// face lines "n i1 … in [colour]"; blank and # lines skipped).
void check_off_faces(std::span<const char> data, std::size_t pos, std::uint64_t vertices,
                     std::uint64_t faces, const std::string& source) {
    std::string_view line;
    std::uint64_t seen = 0;
    while (seen < vertices + faces && next_line(data, pos, line)) {
        const auto words = split_words(line);
        if (words.empty() || words[0].starts_with('#')) continue;
        if (seen++ < vertices) continue;
        std::uint64_t n = 0;
        const auto nr = std::from_chars(words[0].data(), words[0].data() + words[0].size(), n);
        if (nr.ec != std::errc() || nr.ptr != words[0].data() + words[0].size() || n < 3 ||
            n + 1 > words.size())
            throw InputError(quoted_mesh(source) + ": line " +
                             std::to_string(line_of(data, pos - 1)) + ": OFF face " +
                             std::to_string(seen - vertices - 1) + " starts \"" + printable(line) +
                             "\", expected a corner count of at least 3 and " +
                             "that many vertex indices");
        for (std::size_t k = 1; k <= n && k < words.size(); ++k) {
            const auto w = words[k];
            std::uint64_t index = 0;
            const auto r = std::from_chars(w.data(), w.data() + w.size(), index);
            if (r.ec != std::errc() || r.ptr != w.data() + w.size() || index >= vertices)
                throw InputError(quoted_mesh(source) + ": line " +
                                 std::to_string(line_of(data, pos - 1)) + ": OFF face " +
                                 std::to_string(seen - vertices - 1) + " uses vertex \"" +
                                 printable(w) + "\", expected an index from 0 to " +
                                 std::to_string(vertices == 0 ? 0 : vertices - 1));
        }
    }
}

// OFF header: an optional "[ST][C][N][4][n]OFF" keyword, then vertex, face and edge counts. Two
// readings are checked: the plain one (words of the first lines, a count glued to "OFF" split
// off), which names what a person reads, and assimp's own (assimp_off_counts), which is what
// assimp allocates for: it reads "nOFF 3 1 N" as dimension 3, 1 vertex and N faces.
// note: both found by fuzz/fuzz_off: a count glued to "OFF" made assimp run for minutes, and a
// face count after "nOFF" made it allocate 39 GB.
void check_off(std::span<const char> data, const std::string& source) {
    std::size_t pos = 0;
    std::string_view line;
    std::vector<std::string_view> words;
    int count_lines = 0;  // lines the counts came from
    bool first = true;
    while (words.size() < 3 && next_line(data, pos, line)) {
        if (line.starts_with('#') || split_words(line).empty()) continue;
        // note: without the OFF keyword the first line must be the three counts: a first line
        // of 8 numbers made assimp read a face without indices (an invalid read under ASan,
        // fuzz/fuzz_off).
        if (first && line.find("OFF") == std::string_view::npos && split_words(line).size() != 3)
            throw InputError(quoted_mesh(source) + ": line " +
                             std::to_string(line_of(data, pos - 1)) +
                             ": an OFF file without the OFF keyword starts with " +
                             std::to_string(split_words(line).size()) +
                             " words, expected the three counts (vertices faces edges)");
        first = false;
        const std::size_t before = words.size();
        for (auto w : split_words(line)) {
            if (words.empty() && w.find("OFF") != std::string_view::npos) {
                w.remove_prefix(w.find("OFF") + 3);
                if (w.empty()) continue;
            }
            words.push_back(w);
        }
        count_lines += words.size() > before;
    }
    if (words.size() >= 2) {
        std::uint64_t counts[2] = {0, 0};
        for (std::size_t k = 0; k < 2; ++k) {
            const auto w = words[k];
            const auto r = std::from_chars(w.data(), w.data() + w.size(), counts[k]);
            if (r.ec != std::errc() || r.ptr != w.data() + w.size())
                throw InputError(quoted_mesh(source) + ": OFF " + (k == 0 ? "vertex" : "face") +
                                 " count is \"" + printable(w) +
                                 "\", expected a non-negative integer");
        }
        const std::uint64_t left = data.size() - std::min(pos, data.size()) + 1;
        check_count_fits(counts[0], 6, left, source, "OFF vertex list");  // "0 0 0\n"
        check_count_fits(counts[1], 2, left, source, "OFF face list");    // "0\n"
        // note: the faces are checked where the layout is plain: three counts on one line.
        if (words.size() == 3 && count_lines == 1)
            check_off_faces(data, pos, counts[0], counts[1], source);
    }
    if (const auto assimp = assimp_off_counts(data)) {
        const std::uint64_t left = data.size() - assimp->header_end + 1;
        check_count_fits(assimp->vertices, 6, left, source,
                         "OFF vertex list (as assimp reads the header)");
        check_count_fits(assimp->faces, 2, left, source,
                         "OFF face list (as assimp reads the header)");
    }
}

// note: assimp triangulates a polygon by ear clipping, quadratic in its corners: 15 faces of
// 30 000 corners took 107 s. Scanned and CAD meshes hold faces of 3–8 corners; a cap face of a
// cylinder a few hundred.
inline constexpr std::uint64_t kMaxObjFaceCorners = 1024;

// A "v x y z" line's coordinates: a NaN or infinite one is named by line, vertex and axis
// (issue 23 item 18: after assimp it was "vertex 14 of 15: coordinate x" for the z of the
// fifth). Words that are no number are left to assimp.
void check_obj_vertex(std::string_view line, std::uint64_t line_no, std::uint64_t vertex,
                      const std::string& source) {
    const auto words = split_words(line);
    for (std::size_t k = 1; k < std::min<std::size_t>(words.size(), 4); ++k) {
        double x = 0.0;
        const auto w = words[k];
        const auto r = std::from_chars(w.data(), w.data() + w.size(), x);
        if (r.ec == std::errc() && !std::isfinite(x))
            throw InputError(quoted_mesh(source) + ": line " + std::to_string(line_no) +
                             ": vertex " + std::to_string(vertex) + " coordinate " + "xyz"[k - 1] +
                             " is \"" + printable(w) + "\", expected a finite number");
    }
}

// The largest positive vertex index of the faces, and its line (checked once every vertex is
// counted: an index may name a vertex given later in the file).
struct ObjIndex {
    std::uint64_t value = 0, line = 0;
};

// A face's corners "v", "v/vt", "v//vn", "v/vt/vn": v an integer, not 0, a negative one
// counting back from the vertices given so far (issue 23 item 18: assimp said only "OBJ:
// Invalid face index.", with no line).
void check_obj_face(const std::vector<std::string_view>& words, std::uint64_t line_no,
                    std::uint64_t vertices, const std::string& source, ObjIndex& last) {
    for (std::size_t k = 1; k < words.size(); ++k) {
        const std::string_view w = words[k].substr(0, words[k].find('/'));
        long long index = 0;
        const auto r = std::from_chars(w.data(), w.data() + w.size(), index);
        const bool number = r.ec == std::errc() && r.ptr == w.data() + w.size();
        if (!number || index == 0 || (index < 0 && static_cast<std::uint64_t>(-index) > vertices))
            throw InputError(quoted_mesh(source) + ": line " + std::to_string(line_no) +
                             ": face corner " + std::to_string(k) + " is \"" + printable(words[k]) +
                             "\", expected a vertex index from 1 to the vertex count, or from -1 "
                             "back to -" +
                             std::to_string(vertices) + " (the vertices so far)");
        if (index > 0 && static_cast<std::uint64_t>(index) > last.value)
            last = {static_cast<std::uint64_t>(index), line_no};
    }
}

// An OBJ face line of n corners gives n − 2 triangles; no face may have more than
// kMaxObjFaceCorners corners. Vertex coordinates are finite.
void check_obj(std::span<const char> data, const std::string& source, std::uint64_t max_triangles) {
    std::uint64_t triangles = 0, lines = 0, vertices = 0;
    ObjIndex last_index;
    std::size_t pos = 0;
    std::string_view line;
    while (next_line(data, pos, line)) {
        poll_cancel(++lines);
        while (!line.empty() && (line.front() == ' ' || line.front() == '\t'))
            line.remove_prefix(1);
        if (line.size() >= 2 && line[0] == 'v' && (line[1] == ' ' || line[1] == '\t'))
            check_obj_vertex(line, lines, ++vertices, source);
        if (line.size() < 2 || line[0] != 'f' || (line[1] != ' ' && line[1] != '\t')) continue;
        const auto corner_words = split_words(line);
        const std::uint64_t corners = corner_words.size() - 1;
        check_obj_face(corner_words, lines, vertices, source, last_index);
        if (corners > kMaxObjFaceCorners)
            throw InputError(quoted_mesh(source) + ": line " + std::to_string(lines) +
                             ": a face of " + std::to_string(corners) +
                             " corners, expected at most " + std::to_string(kMaxObjFaceCorners) +
                             " (split the polygon; triangulating it would take minutes)");
        triangles += std::max<std::uint64_t>(1, corners >= 2 ? corners - 2 : 1);
    }
    if (last_index.value > vertices)
        throw InputError(quoted_mesh(source) + ": line " + std::to_string(last_index.line) +
                         ": a face uses vertex " + std::to_string(last_index.value) +
                         ", the file has " + std::to_string(vertices) +
                         " vertices; expected an index from 1 to " + std::to_string(vertices));
    check_triangle_budget(triangles, max_triangles, source, "OBJ's faces give at least");
}

}  // namespace

void check_before_assimp(std::span<const char> data, const std::string& ext,
                         const std::string& source, std::uint64_t max_triangles) {
    const bool glb_magic = data.size() >= 4 && std::memcmp(data.data(), "glTF", 4) == 0;
    if (glb_magic) check_glb(data, source, max_triangles);
    else if (ext == ".glb")
        throw InputError(
            quoted_mesh(source) + ": a .glb file that does not start with \"glTF\" (found \"" +
            printable(std::string_view(data.data(), std::min<std::size_t>(data.size(), 4))) +
            "\"), expected a binary glTF");
    else if (ext == ".gltf") check_gltf_json(data, source, max_triangles);
    else if (ext == ".off") check_off(data, source);
    else if (ext == ".obj") check_obj(data, source, max_triangles);
}

}  // namespace glint::detail
