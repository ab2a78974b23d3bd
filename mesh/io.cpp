#include "mesh/io.h"

#include "mesh/atomic_file.h"
#include "mesh/cancel.h"
#include "mesh/checksum.h"
#include "mesh/detail/assimp_reader.h"
#include "mesh/detail/guarded_mapping.h"
#include "mesh/detail/ply_reader.h"
#include "mesh/detail/scene_check.h"
#include "mesh/detail/stl_reader.h"
#include "mesh/detail/vtk_reader.h"
#include "mesh/error.h"
#include "mesh/input_path.h"
#include "mesh/normals.h"
#include "mesh/units.h"
#include "mesh/validate.h"
#include "mesh/weld.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <span>
#include <string_view>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace glint {

namespace fs = std::filesystem;

namespace {

std::atomic<std::uint64_t> g_default_max_triangles{kDefaultMaxTriangles};

std::string lower_extension(const fs::path& path) {
    std::string ext = path.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

// A mesh file's bytes, read into memory. Only regular files are read, opened without blocking
// (a FIFO or a device never hangs the run; issue 23 item 11).
// note: read(2), not mmap, up to detail::map_above_bytes(): a mapped file that shrinks while it is parsed
// (another program rewriting it, a network filesystem) ends the process with SIGBUS (issue 23
// item 8); a read that comes up short, or a size that changed meanwhile, is an error naming
// the file. The copy costs the file's size once, freed (release()) before the mesh is built
// up. A larger file (no mesh within the triangle budget needs one: 50 M triangles are ~1.5 GB
// of binary PLY; only padding, comments or junk elements make it so big) is mapped, so that
// its pages are read only as far as the parser gets before it refuses the file; the mapping is
// guarded (detail/guarded_mapping.h): pages lost to a shrinking file read as zeros and
// shrank() says so, and load() then reports the change instead of what the parser made of it.
class FileBytes {
  public:
    FileBytes(const fs::path& path, const std::string& source) {
        if (!reachable_input(path, quoted_mesh(source)))
            throw InputError(quoted_mesh(source) + ": file not found");
        std::error_code ec;
        if (fs::is_directory(path, ec))
            throw InputError(quoted_mesh(source) + ": is a folder, expected a mesh file");
        const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
        if (fd < 0) throw IoError(quoted_mesh(source) + ": cannot open: " + std::strerror(errno));
        try {
            read_all(fd, source);
        } catch (...) {
            ::close(fd);
            throw;
        }
        ::close(fd);
    }
    FileBytes(const FileBytes&) = delete;
    FileBytes& operator=(const FileBytes&) = delete;

    ~FileBytes() { release(); }

    void release() {
        mapped_.reset();
        data_.reset();
        size_ = 0;
    }
    [[nodiscard]] std::span<const char> bytes() const {
        return mapped_ ? mapped_->bytes() : std::span<const char>(data_.get(), size_);
    }
    /// True when the mapped file was cut short while it was read (its lost bytes read as 0).
    [[nodiscard]] bool shrank() const { return mapped_ && mapped_->shrank(); }

  private:
    static std::size_t regular_size(int fd, const std::string& source) {
        struct stat st {};
        if (::fstat(fd, &st) != 0)
            throw IoError(quoted_mesh(source) + ": cannot read its size: " + std::strerror(errno));
        if (!S_ISREG(st.st_mode))
            throw InputError(quoted_mesh(source) + ": is " +
                             (S_ISFIFO(st.st_mode)   ? "a FIFO"
                              : S_ISCHR(st.st_mode)  ? "a character device"
                              : S_ISBLK(st.st_mode)  ? "a block device"
                              : S_ISSOCK(st.st_mode) ? "a socket"
                                                     : "not a regular file") +
                             ", expected a regular mesh file");
        return static_cast<std::size_t>(st.st_size);
    }

    void read_all(int fd, const std::string& source) {
        size_ = regular_size(fd, source);
        if (size_ == 0)
            throw InputError(quoted_mesh(source) + ": file is empty (0 bytes), expected a mesh");
        if (size_ > detail::map_above_bytes()) {
            try {
                mapped_ = std::make_unique<detail::GuardedMapping>(fd, size_);
            } catch (const IoError& e) {
                throw IoError(quoted_mesh(source) + ": " + e.what());
            }
            return;
        }
        data_ = std::make_unique_for_overwrite<char[]>(size_);
        std::size_t done = 0;
        while (done < size_) {
            throw_if_cancelled();
            const std::size_t chunk = std::min<std::size_t>(size_ - done, std::size_t{1} << 26);
            const ssize_t n = ::read(fd, data_.get() + done, chunk);
            if (n < 0 && errno == EINTR) continue;
            if (n < 0)
                throw IoError(quoted_mesh(source) + ": cannot read: " + std::strerror(errno));
            if (n == 0) break;
            done += static_cast<std::size_t>(n);
        }
        const std::size_t now = regular_size(fd, source);
        if (done != size_ || now != size_)
            throw InputError(quoted_mesh(source) + ": changed while it was read (" +
                             std::to_string(size_) + " bytes when opened, " + std::to_string(done) +
                             " read, " + std::to_string(now) +
                             " now); expected a file no other program is writing");
    }

    std::unique_ptr<char[]> data_;
    std::unique_ptr<detail::GuardedMapping> mapped_;
    std::size_t size_ = 0;
};

bool starts_with(std::span<const char> data, std::string_view prefix) {
    return data.size() >= prefix.size() && std::equal(prefix.begin(), prefix.end(), data.begin());
}

// Text formats (OBJ, OFF, ASCII PLY/STL) never contain NUL or most control bytes. Returns the
// offset of the first byte that cannot be text, or npos.
std::size_t first_binary_byte(std::span<const char> data) {
    const std::size_t n = std::min<std::size_t>(data.size(), 4096);
    for (std::size_t i = 0; i < n; ++i) {
        const auto c = static_cast<unsigned char>(data[i]);
        if (c == 0 || (c < 32 && c != '\n' && c != '\r' && c != '\t' && c != '\f' && c != '\v'))
            return i;
    }
    return std::string_view::npos;
}

enum class Format { Ply, Stl, Vtk, AssimpText, AssimpBinary, Unknown };

// Content decides where it can; the extension only for formats without a signature.
Format detect(std::span<const char> data, const std::string& ext) {
    if (starts_with(data, "ply\n") || starts_with(data, "ply\r\n")) return Format::Ply;
    if (starts_with(data, "# vtk DataFile")) return Format::Vtk;
    if (starts_with(data, "glTF")) return Format::AssimpBinary;  // GLB
    if (ext == ".stl") return Format::Stl;
    // note: a text extension wins over an STL-sized body, so binary bytes in an .obj are
    // reported as such instead of being read as whatever they happen to fit.
    if (ext == ".obj" || ext == ".off" || ext == ".gltf") return Format::AssimpText;
    if (detail::is_binary_stl(data)) return Format::Stl;
    if (ext == ".ply" || ext == ".vtk") return ext == ".ply" ? Format::Ply : Format::Vtk;
    if (starts_with(data, "OFF") || starts_with(data, "solid")) return Format::AssimpText;
    if (ext == ".glb") return Format::AssimpBinary;
    // note: assimp would try any other extension (3ds, dae, fbx, …) with readers nobody has
    // fuzzed here; glint reads the formats it documents and tests, nothing else.
    return Format::Unknown;
}

// assimp gives an OBJ one vertex per face corner; the file's own count is its "v" lines.
// Welding merges the corners back: that is not a repair of the file, so finish() keeps it
// apart from welded_vertices.
void count_obj_vertices(std::span<const char> data, LoadReport& report) {
    std::size_t v_lines = 0;
    bool line_start = true;
    for (std::size_t i = 0; i + 1 < data.size(); ++i) {
        if (line_start && data[i] == 'v' && (data[i + 1] == ' ' || data[i + 1] == '\t')) ++v_lines;
        line_start = data[i] == '\n';
    }
    if (report.file_vertices > v_lines) {
        report.importer_corner_vertices = report.file_vertices;
        report.file_vertices = v_lines;
    }
}

void finish(LoadedMesh& loaded, const LoadOptions& options, const std::string& source) {
    Mesh& mesh = loaded.mesh;
    LoadReport& report = loaded.report;
    // Non-finite coordinates are reported with the file's own vertex id, before any repair
    // renumbers vertices.
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        const Vec3f& p = mesh.positions[v];
        if (!p.allFinite()) {
            const int k = !std::isfinite(p.x()) ? 0 : !std::isfinite(p.y()) ? 1 : 2;
            throw InputError(quoted_mesh(source) + ": vertex " + std::to_string(v) + " of " +
                             std::to_string(mesh.positions.size()) + ": coordinate " + "xyz"[k] +
                             " is " + (std::isnan(p[k]) ? "NaN" : "infinite") +
                             ", expected a finite number");
        }
    }
    const auto n = mesh.positions.size();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
        for (auto i : mesh.triangles[t])
            if (i >= n)
                throw InputError(quoted_mesh(source) + ": triangle " + std::to_string(t) +
                                 " uses vertex " + std::to_string(i) + ", the file has " +
                                 std::to_string(n) + " vertices");
    if (!mesh.normals.empty() && mesh.normals.size() != n) mesh.normals.clear();

    const bool points_only = mesh.triangles.empty();
    if (points_only && !options.allow_points_only)
        throw InputError(quoted_mesh(source) + ": has " + std::to_string(n) +
                         " vertices but no triangles, expected a triangle mesh");
    RepairCounts counts;
    if (!points_only) {
        if (options.weld) weld_vertices(mesh, counts);
        if (options.drop_degenerate) drop_degenerate_triangles(mesh, counts);
        if (options.drop_unused) drop_unused_vertices(mesh, counts);
    }
    report.welded_vertices = counts.welded_vertices;
    if (report.importer_corner_vertices > 0) {
        // The corners assimp made beyond the file's vertices were merged first; what welding
        // merged beyond that were duplicate vertices of the file itself.
        const std::size_t split = report.importer_corner_vertices - report.file_vertices;
        report.welded_vertices -= std::min(report.welded_vertices, split);
    }
    report.degenerate_triangles = counts.degenerate_triangles;
    report.duplicate_triangles = counts.duplicate_triangles;
    report.unused_vertices = counts.unused_vertices;
    if (!points_only && mesh.triangles.empty())
        throw InputError(quoted_mesh(source) + ": all " +
                         std::to_string(counts.degenerate_triangles + counts.duplicate_triangles) +
                         " triangles are degenerate (zero area) or duplicates, expected a "
                         "triangle mesh with area");
    if (!points_only) {
        check_mesh(mesh, source);
    } else if (mesh.positions.empty()) {
        throw InputError(quoted_mesh(source) + ": has no vertices, expected a mesh or point cloud");
    }
    if (options.compute_normals && !points_only) compute_vertex_normals(mesh);
}

// note: assimp 5.2 loops forever on a PLY without "end_header", crashes in Triangulate on a
// PLY whose header overstates its counts, and silently accepts truncated bodies. Before a PLY
// or STL goes to assimp, our own reader checks it and throws the precise error.
void validate_with_own_reader(Mesh (*reader)(std::span<const char>, const std::string&, LoadReport&,
                                             const LoadOptions&),
                              std::span<const char> bytes, const std::string& source,
                              const LoadOptions& options) {
    LoadReport scratch;
    (void)reader(bytes, source, scratch, options);
}

// The mesh in `data`, the bytes of the file at `path`, before finish().
LoadedMesh parse(std::span<const char> data, const fs::path& path, const LoadOptions& options,
                 bool allow_fast) {
    const std::string source = path.string();
    LoadedMesh loaded;
    loaded.report.path = path;
    const std::string ext = lower_extension(path);
    const Format format = detect(data, ext);
    const std::span<const char> bytes = data;
    switch (format) {
        case Format::Ply:
            if (!starts_with(data, "ply"))
                throw InputError(quoted_mesh(source) +
                                 ": does not start with \"ply\", not a PLY file");
            if (allow_fast) {
                loaded.report.reader = MeshReader::FastPly;
                loaded.mesh = detail::read_ply(bytes, source, loaded.report, options);
            } else {
                validate_with_own_reader(detail::read_ply, bytes, source, options);
                loaded.mesh = detail::read_assimp(path, source, loaded.report, options);
            }
            break;
        case Format::Stl:
            if (allow_fast) {
                loaded.report.reader = MeshReader::FastStl;
                loaded.mesh = detail::read_stl(bytes, source, loaded.report, options);
            } else {
                validate_with_own_reader(detail::read_stl, bytes, source, options);
                loaded.mesh = detail::read_assimp(path, source, loaded.report, options);
            }
            break;
        case Format::Vtk:
            // note: assimp has no VTK reader, so load_mesh_assimp uses ours too.
            loaded.report.reader = MeshReader::Vtk;
            loaded.mesh = detail::read_vtk(bytes, source, loaded.report, options);
            break;
        case Format::AssimpText: {
            const std::size_t bad = first_binary_byte(data);
            if (bad != std::string_view::npos) {
                char hex[8];
                std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned char>(data[bad]));
                throw InputError(quoted_mesh(source) + ": byte " + std::to_string(bad) + " is " +
                                 hex + ", binary content in a ." + ext.substr(1) +
                                 " file, which is a text format");
            }
            detail::check_before_assimp(data, ext, source, options.max_triangles);
            loaded.mesh = detail::read_assimp(path, source, loaded.report, options);
            break;
        }
        case Format::AssimpBinary:
            detail::check_before_assimp(data, ext, source, options.max_triangles);
            loaded.mesh = detail::read_assimp(path, source, loaded.report, options);
            break;
        case Format::Unknown:
            throw InputError(
                quoted_mesh(source) + ": unknown mesh format (" +
                (ext.empty() ? std::string("no extension") : "extension " + ext) +
                " and no known signature); expected PLY, STL, OBJ, OFF, glTF/GLB or VTK");
    }
    if (format == Format::AssimpText && ext == ".obj") count_obj_vertices(data, loaded.report);
    // note: 64 KiB holds any header glint has met; a unit comment further in is not looked for.
    if (loaded.mesh.unit.empty())
        loaded.mesh.unit =
            unit_from_header(data.first(std::min<std::size_t>(data.size(), 65536)), ext);
    return loaded;
}

InputError changed_while_read(const std::string& source) {
    return InputError(quoted_mesh(source) +
                      ": was cut short while it was read (a mapped file lost its end); expected a "
                      "file no other program is writing");
}

LoadedMesh load(const fs::path& path, const LoadOptions& options, bool allow_fast) {
    const std::string source = path.string();
    FileBytes file(path, source);
    protect_input(path);
    LoadedMesh loaded;
    try {
        loaded = parse(file.bytes(), path, options, allow_fast);
    } catch (const Error&) {
        if (file.shrank()) throw changed_while_read(source);  // the parser met the zeros
        throw;
    }
    if (file.shrank()) throw changed_while_read(source);
    loaded.report.sha256 = sha256_hex(file.bytes());
    if (file.shrank()) throw changed_while_read(source);
    file.release();
    finish(loaded, options, source);
    return loaded;
}

}  // namespace

std::uint64_t default_max_triangles() noexcept { return g_default_max_triangles.load(); }

void set_default_max_triangles(std::uint64_t max_triangles) noexcept {
    g_default_max_triangles.store(max_triangles);
}

LoadedMesh load_mesh(const fs::path& path, const LoadOptions& options) {
    return load(path, options, options.allow_fast_path);
}

LoadedMesh load_mesh_assimp(const fs::path& path, const LoadOptions& options) {
    return load(path, options, false);
}

}  // namespace glint
