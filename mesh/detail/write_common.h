// Helpers the mesh writers (mesh/write.cpp, mesh/write_vtk.cpp) share.
#pragma once

#include "mesh/mesh.h"

#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>
#include <string_view>

namespace glint::detail {

/// Property / array names are single words in PLY and VTK: anything else becomes '_'.
[[nodiscard]] std::string safe_name(const std::string& name);

/// \throw InputError when a per-vertex array's size differs from the vertex count or a
/// triangle uses a vertex that does not exist (names the file being written).
void check_sizes(const Mesh& mesh, const std::filesystem::path& path);

/// Text or bytes formatted into a buffer that goes to `stream` whenever it passes 1 MiB, so a
/// writer holds 1 MiB of its file in memory, not the whole of it (hundreds of MB for an atlas
/// of 2M triangles). flush() at the end.
class StreamBuffer {
  public:
    explicit StreamBuffer(std::ostream& stream) : stream_(stream) { text_.reserve(kChunk + 4096); }
    StreamBuffer& operator+=(std::string_view s) {
        text_ += s;
        spill();
        return *this;
    }
    void push_back(char c) {
        text_.push_back(c);
        spill();
    }
    void append(const char* data, std::size_t size) {
        text_.append(data, size);
        spill();
    }
    void flush() {
        stream_.write(text_.data(), static_cast<std::streamsize>(text_.size()));
        text_.clear();
    }

  private:
    static constexpr std::size_t kChunk = std::size_t{1} << 20;
    void spill() {
        if (text_.size() >= kChunk) flush();
    }
    std::ostream& stream_;
    std::string text_;
};

}  // namespace glint::detail
