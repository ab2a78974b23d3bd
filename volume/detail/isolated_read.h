// DICOM read in a child process (issue 23, item 6). GDCM, the library ITK reads DICOM through,
// asserts (SIGABRT) or crashes (SIGSEGV) on some malformed files that the structural pre-check
// of dicom_check.h cannot foresee: fuzzing found one after the other. A crash there would end
// glint, or the Python interpreter that loaded the module, and lose the user's session. So the
// read runs in a forked child: the volume comes back through an anonymous memory file, and a
// child that dies becomes one InputError line naming the input and the signal.
#pragma once

#include "volume/detail/itk_io.h"

#include <filesystem>
#include <functional>

namespace glint::detail {

/// Runs `read` in a child process and returns its volume. The child's standard output and error
/// go to /dev/null (GDCM and ITK chatter), its temporary files into a folder of the parent's
/// that is removed afterwards, and a cancellation request (Ctrl-C) kills it and throws
/// Cancelled. Errors thrown by `read` come back as the same kind (InputError, IoError) with
/// the same message.
/// \throw InputError when the child dies by a signal or exits without a result ("…: the DICOM
/// reader (GDCM) crashed on it: SIGSEGV …"); IoError when no child can be started.
[[nodiscard]] RawVolume read_in_child(const std::filesystem::path& input,
                                      const std::function<RawVolume()>& read);

}  // namespace glint::detail
