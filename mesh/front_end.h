// How the user names an option in the front end running this process.
//
// Some library messages tell the user what to give next ("exists; give --force to replace
// it"). The command line spells an option --force, Python force=True: the message must speak
// the words of the front end the user typed into. Each front end says once, at start-up,
// which it is (the Python module on import); the library spells options through these
// functions instead of writing a flag into its text. The names are the option registry's
// (analysis/option_registry.h): the Python keyword, whose flag is --name with '_' as '-'.
//
// note: one front end per process (the CLI and the Python module never share one), so a
// process-wide setting is enough.
#pragma once

#include <string>
#include <string_view>

namespace glint {

enum class FrontEnd { CommandLine, Python };

/// Says which front end runs this process (default: the command line).
void set_front_end(FrontEnd front_end) noexcept;
[[nodiscard]] FrontEnd front_end() noexcept;

/// A flag turned on or off: "--force" / "force=True"; off: "--no-views" / "views=False".
[[nodiscard]] std::string spell_flag(std::string_view name, bool on = true);

/// An option given a value: "--iso VALUE" / "iso=VALUE" for a placeholder (capitals), "--unit
/// mm" / "unit='mm'" for a word.
[[nodiscard]] std::string spell_option(std::string_view name, std::string_view value);

/// The option alone, as its front end lists it: "--allow-scale-mismatch" /
/// "allow_scale_mismatch".
[[nodiscard]] std::string spell_name(std::string_view name);

}  // namespace glint
