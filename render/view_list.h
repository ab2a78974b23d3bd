// Lists of views given as text: the `--views "az=0,el=0;az=90,el=30"` items of `glint render`
// and its views files (one item a line, '#' comments). Here rather than in the command so
// that fuzz/fuzz_views.cpp reaches the same parser (issue 23: views files are hostile input).
#pragma once

#include "render/view.h"

#include <cstddef>
#include <string>
#include <vector>

namespace glint {

/// At most this many views in one list (10 000 views already take hours).
inline constexpr std::size_t kMaxListedViews = 10000;
/// A views file is at most 1 MiB (~30 000 lines): /dev/zero or a FIFO used to grow memory
/// without end.
inline constexpr std::size_t kMaxViewsFileBytes = std::size_t{1} << 20;

/// "az=30,el=20[,fp=0.1|dist=5]" → `base` with those fields. `where` names the item in
/// messages ("views.txt:3"). \throw InputError naming `where`, the item and what was expected.
[[nodiscard]] ViewSpec parse_view_item(const std::string& item, const ViewSpec& base,
                                       const std::string& where);

/// The items of `text` separated by `separator` (';' for --views, '\n' for a file; with '\n'
/// a '#' starts a comment and blank lines are skipped), each over `base` and validated.
/// `source` names the list in messages ("--views", "views file \"v.txt\""); a file's items are
/// named by line. \throw InputError for a bad item or more than kMaxListedViews.
[[nodiscard]] std::vector<ViewSpec> parse_view_list(const std::string& text, char separator,
                                                    const ViewSpec& base,
                                                    const std::string& source);

/// A views file's text: a regular file, opened without blocking, of at most
/// kMaxViewsFileBytes. \throw IoError unreadable; InputError not a regular file, too big.
[[nodiscard]] std::string read_views_file(const std::string& path);

}  // namespace glint
