// Scenario files → AnalysisOptions: the same options, the same defaults as the command line.
#include "scenario/detail/scenario_options.h"

#include "analysis/option_registry.h"
#include "mesh/error.h"
#include "mesh/roi.h"

#include <algorithm>

namespace glint::detail {

namespace {

namespace fs = std::filesystem;

fs::path local_path(const fs::path& dir, const std::string& text) {
    const fs::path p(text);
    return p.is_absolute() ? p : dir / p;
}

// One TOML value as the option's kind: booleans, integers, numbers, strings, arrays of numbers
// (a single number for a list too). A wrong type names what was expected.
[[noreturn]] void wrong_type(const TableReader& r, const toml::node& node, const OptionInfo& info) {
    r.fail(&node, std::string(info.key),
           "expected " + describe_expected(info) + ", found " + TableReader::type_name(node));
}

OptionValue toml_value(const TableReader& r, const toml::node& node, const OptionInfo& info) {
    switch (info.kind) {
        case OptionKind::Flag:
            if (!node.is_boolean()) wrong_type(r, node, info);
            return *node.value<bool>();
        case OptionKind::Integer:
            if (node.is_integer()) return *node.value<std::int64_t>();
            if (node.is_floating_point()) return *node.value<double>();  // 2.0: checked whole
            wrong_type(r, node, info);
        case OptionKind::Number:
        case OptionKind::OptionalNumber:
            if (auto v = node.value<double>()) return *v;
            wrong_type(r, node, info);
        case OptionKind::Numbers: {
            if (auto v = node.value<double>()) return std::vector<double>{*v};
            const auto* arr = node.as_array();
            if (arr == nullptr) wrong_type(r, node, info);
            std::vector<double> out;
            for (const auto& e : *arr) {
                const auto v = e.value<double>();
                if (!v) wrong_type(r, node, info);
                out.push_back(*v);
            }
            return out;
        }
        case OptionKind::Choice:
        case OptionKind::Text:
        case OptionKind::Region:
        case OptionKind::Path:
            if (!node.is_string()) wrong_type(r, node, info);
            return *node.value<std::string>();
    }
    wrong_type(r, node, info);
}

// Relative paths in a scenario (files and mask regions) are the scenario folder's.
OptionValue resolved(const OptionInfo& info, OptionValue value, const fs::path& dir) {
    auto* text = std::get_if<std::string>(&value);
    if (text == nullptr || text->empty()) return value;
    if (info.kind == OptionKind::Path) return local_path(dir, *text).string();
    if (info.kind == OptionKind::Region && text->rfind("mask:", 0) == 0) {
        Roi roi = parse_roi(*text);
        roi.mask_file = local_path(dir, roi.mask_file.string());
        return to_string(roi);
    }
    return value;
}

// Every option of `table` whose section is `section` ("" = the top level), read when present.
template <class Options>
void read_options(TableReader& r, const std::string& section, const fs::path& dir, Options& options,
                  const std::vector<OptionField<Options>>& table) {
    for (const auto& field : table) {
        if (field.info.section != section) continue;
        const std::string key(field.info.key);
        const toml::node* node = r.get(key);
        if (node == nullptr) continue;
        try {
            set_option(options, field, resolved(field.info, toml_value(r, *node, field.info), dir));
        } catch (const OptionError& e) {
            r.fail_whole(node, e.named(field.info.path()));
        } catch (const InputError& e) {
            r.fail(node, key, e.what());
        }
    }
}

// The fit mode and the fit file: how the examined mesh is placed (not registry options).
void read_fit_mode(TableReader& r, const fs::path& dir, FitOptions& f) {
    if (const toml::node* node = r.get("mode")) {
        if (!node->is_string())
            r.fail(node, "mode",
                   "expected a string (register, truth, identity, file), found " +
                       TableReader::type_name(*node));
        try {
            f.mode = parse_fit_mode(*node->value<std::string>());
        } catch (const InputError& e) {
            r.fail(node, "mode", e.what());
        }
    }
    if (auto v = r.optional<std::string>("fit", "a string (a fit.json path)"))
        f.fit_file = local_path(dir, *v);
}

// The section `key` of `top`, when present, read by `read` (unknown keys then fail).
template <class Read>
void read_section(TableReader& top, const std::string& key, Read read) {
    const toml::node* node = top.get(key);
    if (!node) return;
    const auto* t = node->as_table();
    if (!t)
        top.fail(node, key,
                 "expected a section [" + key + "], found " + TableReader::type_name(*node));
    TableReader r(*t, top.file(), key);
    read(r);
    r.finish();
}

}  // namespace

void read_analysis_sections(TableReader& top, const fs::path& dir, AnalysisOptions& options) {
    // Scenarios register unless told otherwise (the command line's default is to take the
    // meshes as aligned: a scenario with a pose always needs a fit).
    options.fit.mode = FitMode::Register;
    // The unit both meshes are in (analysis/units.h; phantoms are in mm) and the other
    // top-level options.
    read_options(top, "", dir, options, analysis_option_table());
    const auto section = [&](const std::string& key, auto read) { read_section(top, key, read); };
    section("registration", [&](TableReader& r) {
        read_fit_mode(r, dir, options.fit);
        read_options(r, "registration", dir, options, analysis_option_table());
    });
    for (const char* name : {"sweep", "threshold", "decision"})
        section(name, [&](TableReader& r) {
            read_options(r, name, dir, options, analysis_option_table());
        });
}

void read_export_section(TableReader& top, const fs::path& dir, ExportOptions& exports) {
    read_section(top, "exports", [&](TableReader& r) {
        read_options(r, "exports", dir, exports, export_option_table());
    });
}

void validate_analysis_sections(const toml::table& root, const std::string& file,
                                const AnalysisOptions& options) {
    try {
        options.validate();
    } catch (const OptionError& e) {
        std::ostringstream s;
        s << "scenario \"" << file << "\"";
        if (const auto node = root.at_path(e.key()))
            s << " line " << node.node()->source().begin.line;
        s << ": " << e.what();
        throw InputError(s.str());
    }
}

}  // namespace glint::detail
