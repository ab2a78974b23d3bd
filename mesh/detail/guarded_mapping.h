// A read-only mapping of a file that survives the file shrinking under it (issue 23, item 8).
//
// Mesh files up to 2 GiB are read into memory (mesh/io.cpp); a larger one is mapped so that
// its pages are read only as far as the parser gets. Reading a mapped page beyond the end of a
// file that another program cut short raises SIGBUS, which would end the process. While a
// GuardedMapping lives, a SIGBUS handler replaces the missing pages of its range by zero pages
// and marks the mapping as shrunk: the parser reads zeros (and usually refuses them), and the
// caller reports "changed while it was read" instead of a parse error. Faults outside every
// guarded range go to the handler that was there before (the default one ends the process as
// it always did). The handler is installed by the first live mapping and the previous one put
// back by the last, so the library leaves no handler behind.
#pragma once

#include <cstddef>
#include <span>

namespace glint::detail {

/// Mesh files larger than this are mapped rather than read: 2 GiB.
[[nodiscard]] std::size_t map_above_bytes() noexcept;
/// Lowers (or restores) that size so that tests exercise the mapped path on small files.
void set_map_above_bytes_for_testing(std::size_t bytes) noexcept;

class GuardedMapping {
  public:
    /// Maps `size` bytes of the open file `fd` (read-only, private).
    /// \throw IoError with strerror's words (the caller names the file).
    GuardedMapping(int fd, std::size_t size);
    ~GuardedMapping();
    GuardedMapping(const GuardedMapping&) = delete;
    GuardedMapping& operator=(const GuardedMapping&) = delete;

    [[nodiscard]] std::span<const char> bytes() const;
    /// True once a read beyond the file's end was caught (those bytes read as zeros).
    [[nodiscard]] bool shrank() const noexcept;

  private:
    void* data_ = nullptr;
    std::size_t size_ = 0;
    int slot_ = -1;
};

}  // namespace glint::detail
