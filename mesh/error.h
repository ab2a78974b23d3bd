// glint's error vocabulary (STYLE.md §5).
//
// The world is wrong -> throw one of these; our code is wrong -> GLINT_ASSERT.
// Messages answer what, where, found, expected in one line a user can act on:
//   mesh "jaw.stl": triangle 1042 uses vertex 9001, mesh has 9000 vertices
#pragma once

#include <stdexcept>
#include <string>

namespace glint {

/// Base of every error glint reports to a user.
class Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// Bad input: a malformed or inconsistent file, an invalid option or scenario. Exit code 2.
class InputError : public Error {
  public:
    using Error::Error;
};

/// An invalid option: an InputError that also names the option by its key as scenario files
/// write it ("sweep.size", "registration.loss"), so a scenario loader can point at the line
/// that set it. Message: "<key> = <value>: <rule>".
class OptionError : public InputError {
  public:
    OptionError(std::string key, const std::string& value, const std::string& rule)
        : InputError(key + " = " + value + ": " + rule), key_(std::move(key)) {}
    OptionError(std::string key, double value, const std::string& rule);
    /// The same error under a section prefix: "size" → "sweep.size".
    [[nodiscard]] OptionError prefixed(const std::string& section) const;
    /// The message with the option named as a front end spells it ("--threshold-deg",
    /// "threshold_deg"): "<name> = <value>: <rule>"; the key stays.
    [[nodiscard]] std::string named(const std::string& name) const;
    [[nodiscard]] const std::string& key() const noexcept { return key_; }

  private:
    struct Whole {};  // the message is already complete
    OptionError(Whole, std::string key, const std::string& message)
        : InputError(message), key_(std::move(key)) {}
    std::string key_;
};

/// A read or write failed (missing file, unwritable folder, short write). Exit code 3.
class IoError : public Error {
  public:
    using Error::Error;
};

/// No usable compute/graphics device, or a device call failed. Exit code 3.
class DeviceError : public Error {
  public:
    using Error::Error;
};

/// An input file as messages name it: quoted_mesh("jaw.stl") → mesh "jaw.stl".
inline std::string quoted_mesh(const std::string& source) { return "mesh \"" + source + "\""; }
/// quoted_volume("CThead.nrrd") → volume "CThead.nrrd".
inline std::string quoted_volume(const std::string& source) { return "volume \"" + source + "\""; }

namespace detail {
[[noreturn]] void assert_failed(const char* cond, const std::string& msg, const char* file,
                                int line);
}  // namespace detail

}  // namespace glint

/// Cheap invariant check that stays on in release; throws std::logic_error with file:line.
#define GLINT_ASSERT(cond, msg)                                                        \
    do {                                                                               \
        if (!(cond)) ::glint::detail::assert_failed(#cond, (msg), __FILE__, __LINE__); \
    } while (false)
