// The option registry: every option of an analysis declared once — its name, type, default,
// unit, range, help text and group — and bound to its field of AnalysisOptions. Every front end
// is generated from it:
//
//   command line   --<name with dashes>   (tools/option_flags.h; a flag that defaults to true
//                                         also takes --no-<name>)
//   scenario TOML  [<section>] <key>      (scenario/detail/scenario_options.cpp)
//   Python         <name>=                (python/keywords.cpp; help() lists type, default, unit)
//   JSON           "<section>": {"<key>"} (report/options_json.cpp: report.json's "analysis",
//                                         --print-options), the same layout as the TOML
//   3D Slicer      <slicer name>          (tools/slicer_module.cpp)
//
// The same machinery binds report/'s ExportOptions (report/export_options.h), so one template
// serves both tables. How the examined mesh is brought into the reference's frame (the fit mode
// and the fit file) is not an option of this table: each front end says it in its own way
// (--register / --fit FILE, [registration] mode, register= / fit=, the Slicer "Register" box).
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace glint {

struct AnalysisOptions;

/// What an option holds and how its text is read.
enum class OptionKind {
    Flag,            ///< true / false
    Integer,         ///< a whole number within the range
    Number,          ///< a finite number within the range
    OptionalNumber,  ///< a number, or unset (the run measures it); 0 means unset in Slicer
    Numbers,         ///< comma-separated finite numbers within the range
    Choice,          ///< one of `choices`
    Text,            ///< free text (a plan, a device name); the field's parser checks it
    Region,          ///< sphere:x,y,z,r | box:x0,y0,z0,x1,y1,z1 | mask:FILE[:SCALAR]
    Path,            ///< a file
};

/// Which part of a run an option belongs to (for help, docs and which functions take it).
enum OptionGroup : unsigned {
    kUnitGroup = 1u << 0,
    kFitGroup = 1u << 1,
    kSweepGroup = 1u << 2,
    kDecisionGroup = 1u << 3,
    kExportGroup = 1u << 4,
};

/// An option's value: unset (an optional number or path not given), a flag, an integer, a
/// number, text (choices, text, regions, paths) or numbers.
using OptionValue =
    std::variant<std::monostate, bool, std::int64_t, double, std::string, std::vector<double>>;

/// What every front end needs to know of an option, apart from its field.
struct OptionInfo {
    std::string_view name;     ///< Python keyword; the flag is --name with '_' as '-'
    std::string_view section;  ///< TOML section / JSON object ("" = the scenario's top level)
    std::string_view key;      ///< TOML key / JSON member within the section
    std::string_view slicer;   ///< the Slicer module's parameter name and flag
    OptionKind kind = OptionKind::Text;
    OptionGroup group = kSweepGroup;
    std::string_view unit;  ///< "deg", "px", "mesh units", … ("" = none)
    double min = -std::numeric_limits<double>::infinity();  ///< numbers: inclusive bounds
    double max = std::numeric_limits<double>::infinity();
    bool min_exclusive = false;  ///< numbers: the lower bound itself is refused
    bool max_exclusive = false;  ///< numbers: the upper bound itself is refused
    /// The option may be unset (monostate): an optional number, a path, a region, a unit or a
    /// device not given.
    bool may_be_unset = false;
    std::string_view label;            ///< a few words (the Slicer panel)
    std::string_view help;             ///< one line
    std::vector<std::string> choices;  ///< Choice: the accepted spellings

    /// "--azimuth-step".
    [[nodiscard]] std::string flag() const;
    /// "sweep.azimuth_step" (a top-level key alone): what OptionError names.
    [[nodiscard]] std::string path() const;
};

/// One option of the table of `Options`: its description and its field.
template <class Options>
struct OptionField {
    OptionInfo info;
    std::function<OptionValue(const Options&)> get;
    /// Sets the field from a value of the option's kind (checked by check_value first).
    /// \throw InputError the field's own parser refused it (a plan, a region).
    std::function<void(Options&, const OptionValue&)> set;
};

/// The analysis options, in the order help and docs list them.
[[nodiscard]] const std::vector<OptionField<AnalysisOptions>>& analysis_option_table();

/// Reads a value of the option's kind from text (the command line, the Slicer module):
/// "true"/"false", integers, numbers, "1,2,3", choices; "" for an optional number or a path
/// is unset. \throw InputError naming the option, the text and what was expected.
[[nodiscard]] OptionValue parse_option_text(const OptionInfo& info, std::string_view text);

/// The value as the command line would spell it ("" when unset).
[[nodiscard]] std::string option_text(const OptionInfo& info, const OptionValue& value);

/// Checks a value against the option's kind, range and choices (an integer given for a number
/// is converted). \throw InputError naming the option: "<flag> = <value>: <rule>".
[[nodiscard]] OptionValue check_value(const OptionInfo& info, OptionValue value);

/// "a number in (0, 360] deg", "one of cauchy, huber, tukey, none", …: for errors and help.
[[nodiscard]] std::string describe_expected(const OptionInfo& info);

/// Sets one option: check_value, then the field. \throw InputError.
template <class Options>
void set_option(Options& options, const OptionField<Options>& field, OptionValue value) {
    field.set(options, check_value(field.info, std::move(value)));
}

/// The field of `name` (Python keyword spelling), or nullptr.
template <class Options>
[[nodiscard]] const OptionField<Options>* find_option(
    const std::vector<OptionField<Options>>& table, std::string_view name) {
    for (const auto& f : table)
        if (f.info.name == name) return &f;
    return nullptr;
}

}  // namespace glint
