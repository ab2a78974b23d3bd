#include "analysis/option_registry.h"

#include "analysis/analysis.h"
#include "mesh/error.h"
#include "mesh/units.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <utility>

namespace glint {

namespace {

std::string number_text(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.10g", v);
    return b;
}

std::string range_text(const OptionInfo& i) {
    const bool low = std::isfinite(i.min), high = std::isfinite(i.max);
    if (!low && !high) return "";
    if (low && !high) return std::string(i.min_exclusive ? "> " : "≥ ") + number_text(i.min);
    if (!low) return std::string(i.max_exclusive ? "< " : "≤ ") + number_text(i.max);
    return std::string(i.min_exclusive ? "(" : "[") + number_text(i.min) + ", " +
           number_text(i.max) + (i.max_exclusive ? ")" : "]");
}

bool in_range(const OptionInfo& i, double v) {
    if (!std::isfinite(v)) return false;
    if (i.min_exclusive ? !(v > i.min) : !(v >= i.min)) return false;
    if (i.max_exclusive ? !(v < i.max) : !(v <= i.max)) return false;
    return true;
}

[[noreturn]] void refuse(const OptionInfo& info, const std::string& found) {
    throw OptionError(info.path(), found, "expected " + describe_expected(info));
}

}  // namespace

std::string OptionInfo::flag() const {
    std::string f = "--" + std::string(name);
    for (char& c : f)
        if (c == '_') c = '-';
    return f;
}

std::string OptionInfo::path() const {
    return section.empty() ? std::string(key) : std::string(section) + "." + std::string(key);
}

std::string describe_expected(const OptionInfo& i) {
    const std::string range = range_text(i);
    const std::string unit = i.unit.empty() ? "" : " (" + std::string(i.unit) + ")";
    const std::string in =
        range.empty() ? "" : (range[0] == '(' || range[0] == '[' ? " in " : " ") + range;
    switch (i.kind) {
        case OptionKind::Flag: return "true or false";
        case OptionKind::Integer: return "an integer" + in + unit;
        case OptionKind::Number: return "a number" + in + unit;
        case OptionKind::OptionalNumber: return "a number" + in + unit + ", or unset";
        case OptionKind::Numbers: return "comma-separated numbers, each" + in + unit;
        case OptionKind::Choice: {
            std::string list;
            for (const auto& c : i.choices) list += (list.empty() ? "" : ", ") + c;
            return "one of " + list;
        }
        case OptionKind::Text: return "text";
        case OptionKind::Region:
            return "a region: sphere:x,y,z,r, box:x0,y0,z0,x1,y1,z1 or mask:FILE[:SCALAR]";
        case OptionKind::Path: return "a file path";
    }
    return "?";
}

OptionValue check_value(const OptionInfo& info, OptionValue value) {
    if (std::holds_alternative<std::monostate>(value)) {
        if (!info.may_be_unset) refuse(info, "(unset)");
        return value;
    }
    switch (info.kind) {
        case OptionKind::Flag:
            if (!std::holds_alternative<bool>(value)) refuse(info, option_text(info, value));
            return value;
        case OptionKind::Integer: {
            if (const double* d = std::get_if<double>(&value)) {
                // note: a whole number given as a float (TOML 2.0, Python 2.0) is that integer;
                // 2.5 is refused, never truncated.
                if (!(std::isfinite(*d) && *d == std::floor(*d) && std::fabs(*d) < 9.0e15))
                    refuse(info, number_text(*d));
                value = static_cast<std::int64_t>(*d);
            }
            const std::int64_t* n = std::get_if<std::int64_t>(&value);
            if (n == nullptr) refuse(info, option_text(info, value));
            if (!in_range(info, static_cast<double>(*n))) refuse(info, std::to_string(*n));
            return value;
        }
        case OptionKind::Number:
        case OptionKind::OptionalNumber: {
            if (const std::int64_t* n = std::get_if<std::int64_t>(&value))
                value = static_cast<double>(*n);
            const double* d = std::get_if<double>(&value);
            if (d == nullptr) refuse(info, option_text(info, value));
            if (!in_range(info, *d)) refuse(info, number_text(*d));
            return value;
        }
        case OptionKind::Numbers: {
            const auto* list = std::get_if<std::vector<double>>(&value);
            if (list == nullptr) refuse(info, option_text(info, value));
            for (double v : *list)
                if (!in_range(info, v)) refuse(info, number_text(v));
            return value;
        }
        case OptionKind::Choice: {
            const std::string* s = std::get_if<std::string>(&value);
            if (s == nullptr) refuse(info, option_text(info, value));
            for (const auto& c : info.choices)
                if (c == *s) return value;
            if (info.name == "unit" && !canonical_unit(*s).empty())
                return OptionValue(canonical_unit(*s));  // "millimetre" is mm
            refuse(info, "\"" + *s + "\"");
        }
        case OptionKind::Text:
        case OptionKind::Region:
        case OptionKind::Path: {
            const std::string* s = std::get_if<std::string>(&value);
            if (s == nullptr) refuse(info, option_text(info, value));
            if (s->empty() && info.may_be_unset) return OptionValue();
            if (s->empty()) refuse(info, "\"\"");
            return value;
        }
    }
    return value;
}

OptionValue parse_option_text(const OptionInfo& info, std::string_view text_in) {
    const std::string text(text_in);
    auto parse_double = [&](const std::string& t) -> double {
        char* end = nullptr;
        const double v = std::strtod(t.c_str(), &end);
        if (t.empty() || end == nullptr || *end != '\0' ||
            std::isspace(static_cast<unsigned char>(t[0])))
            refuse(info, "\"" + text + "\"");
        return v;
    };
    switch (info.kind) {
        case OptionKind::Flag:
            if (text == "true" || text == "1" || text == "yes" || text == "on") return true;
            if (text == "false" || text == "0" || text == "no" || text == "off") return false;
            refuse(info, "\"" + text + "\"");
        case OptionKind::Integer: {
            const double v = parse_double(text);
            return check_value(info, v);
        }
        case OptionKind::Number: return check_value(info, parse_double(text));
        case OptionKind::OptionalNumber:
            if (text.empty()) return OptionValue();
            return check_value(info, parse_double(text));
        case OptionKind::Numbers: {
            std::vector<double> out;
            if (text.empty()) return check_value(info, out);
            for (std::size_t start = 0;;) {
                const std::size_t comma = text.find(',', start);
                out.push_back(parse_double(text.substr(
                    start, comma == std::string::npos ? std::string::npos : comma - start)));
                if (comma == std::string::npos) break;
                start = comma + 1;
            }
            return check_value(info, out);
        }
        case OptionKind::Choice:
            if (text.empty() && info.may_be_unset) return OptionValue();
            return check_value(info, text);
        case OptionKind::Text:
        case OptionKind::Region:
        case OptionKind::Path: return check_value(info, text);
    }
    return OptionValue();
}

std::string option_text(const OptionInfo&, const OptionValue& value) {
    struct Visit {
        std::string operator()(std::monostate) const { return ""; }
        std::string operator()(bool b) const { return b ? "true" : "false"; }
        std::string operator()(std::int64_t n) const { return std::to_string(n); }
        std::string operator()(double d) const { return number_text(d); }
        std::string operator()(const std::string& s) const { return s; }
        std::string operator()(const std::vector<double>& v) const {
            std::string out;
            for (double d : v) out += (out.empty() ? "" : ",") + number_text(d);
            return out;
        }
    };
    return std::visit(Visit{}, value);
}

}  // namespace glint
