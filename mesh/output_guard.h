// One output discipline for every command that writes: an output never is, contains or lies
// inside an input of the same process.
//
// Readers register what they read (protect_input); every atomic write and every output folder
// checks its target against those inputs, and the front ends check their outputs against the
// inputs they were given before any work (guard_outputs), so a run is refused before it
// loads, not after it has computed.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <span>
#include <vector>

namespace glint {

/// Registers a path (file or folder) as an input of this process: every output check refuses
/// it, a folder holding it and a path inside it.
void protect_input(const std::filesystem::path& path);

/// The files an input consists of: the path itself and, for a header naming separate data
/// (.mhd ElementDataFile, .nhdr "data file"), every file it names: one file, a LIST (the
/// header's following lines) or a slice pattern "FORMAT MIN MAX STEP" (issue 52).
[[nodiscard]] std::vector<std::filesystem::path> input_files(const std::filesystem::path& path);

/// The files an output consists of: the path itself and, for .mhd / .nhdr, the data files ITK
/// writes beside the header.
[[nodiscard]] std::vector<std::filesystem::path> output_files(const std::filesystem::path& path);

/// \throw InputError (exit 2), one line: `output "X" is|contains|lies inside the input "Y";
/// expected an output apart from every input` when `output` is, holds or lies inside a
/// protected input or one of `inputs`. Empty paths are skipped.
void refuse_output_over_inputs(const std::filesystem::path& output,
                               std::span<const std::filesystem::path> inputs = {});

/// Whether the folder an output goes into must exist, or may be made by the command (glint run
/// makes its -o folder).
enum class OutputParent { MustExist, MayBeCreated };

/// \throw InputError (exit 2), one line naming the output, the folder, what was found and what
/// was expected, when the folder `output` goes into is missing (unless `parent` allows it to be
/// made and the nearest folder that exists is writable), is no folder, or is not writable.
/// An empty path is skipped.
void check_output_folder(const std::filesystem::path& output,
                         OutputParent parent = OutputParent::MustExist);

/// The front ends' check before any work: registers every input (with its input_files),
/// refuses every output (with its output_files) that is, contains or lies inside one, and
/// checks each output's folder (check_output_folder), so a run that could not write its
/// results stops before it loads.
void guard_outputs(std::initializer_list<std::filesystem::path> outputs,
                   std::initializer_list<std::filesystem::path> inputs,
                   OutputParent parent = OutputParent::MustExist);

}  // namespace glint
