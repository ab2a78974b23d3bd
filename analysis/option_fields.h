// Declaring the fields of an option table (analysis/option_registry.h) in one line each: the
// accessor is a generic lambda returning the field, `[](auto& o) -> auto& { return o.size; }`,
// so one accessor serves reading (const) and writing. Used by the analysis table
// (analysis/option_registry.cpp) and report/'s export table (report/export_options.cpp).
#pragma once

#include "analysis/option_registry.h"

#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace glint {

template <class Options>
struct OptionFields {
    using Field = OptionField<Options>;

    template <class Member>
    static Field number(OptionInfo info, Member member) {
        info.kind = OptionKind::Number;
        return {std::move(info),
                [member](const Options& o) -> OptionValue { return as_double(member(o)); },
                [member](Options& o, const OptionValue& v) {
                    using Target = std::remove_cvref_t<decltype(member(o))>;
                    member(o) = static_cast<Target>(std::get<double>(v));
                }};
    }

    template <class Member>
    static Field integer(OptionInfo info, Member member) {
        info.kind = OptionKind::Integer;
        return {std::move(info),
                [member](const Options& o) -> OptionValue {
                    return static_cast<std::int64_t>(member(o));
                },
                [member](Options& o, const OptionValue& v) {
                    using T = std::remove_reference_t<decltype(member(o))>;  // int, size_t, …
                    member(o) = static_cast<T>(std::get<std::int64_t>(v));
                }};
    }

    template <class Member>
    static Field flag(OptionInfo info, Member member) {
        info.kind = OptionKind::Flag;
        return {std::move(info), [member](const Options& o) -> OptionValue { return member(o); },
                [member](Options& o, const OptionValue& v) { member(o) = std::get<bool>(v); }};
    }

    template <class Member>
    static Field optional_number(OptionInfo info, Member member) {
        info.kind = OptionKind::OptionalNumber;
        info.may_be_unset = true;
        return {std::move(info),
                [member](const Options& o) -> OptionValue {
                    const std::optional<double>& v = member(o);
                    return v ? OptionValue(*v) : OptionValue();
                },
                [member](Options& o, const OptionValue& v) {
                    if (std::holds_alternative<double>(v)) member(o) = std::get<double>(v);
                    else member(o).reset();
                }};
    }

    template <class Member>
    static Field numbers(OptionInfo info, Member member) {
        info.kind = OptionKind::Numbers;
        return {std::move(info), [member](const Options& o) -> OptionValue { return member(o); },
                [member](Options& o, const OptionValue& v) {
                    member(o) = std::get<std::vector<double>>(v);
                }};
    }

    /// A text-valued option whose field is set by a parser (choices, regions, plans, paths);
    /// with `unset`, the option may be left unset.
    static Field text(OptionInfo info, OptionKind kind,
                      std::function<OptionValue(const Options&)> get,
                      std::function<void(Options&, const std::string&)> parse,
                      std::function<void(Options&)> unset = {}) {
        info.kind = kind;
        if (unset) info.may_be_unset = true;
        return {
            std::move(info), std::move(get),
            [parse = std::move(parse), unset = std::move(unset)](Options& o, const OptionValue& v) {
                if (std::holds_alternative<std::string>(v)) parse(o, std::get<std::string>(v));
                else if (unset) unset(o);
            }};
    }

    /// A float field as the double it was given as (0.37f reads 0.37, not 0.3700000048): the
    /// shortest decimal that round-trips the float.
    static double as_double(float f) {
        char text[32];
        const auto end = std::to_chars(text, text + sizeof text - 1, f).ptr;
        *end = '\0';
        return std::strtod(text, nullptr);
    }
    static double as_double(double d) { return d; }

    /// "" as unset.
    static OptionValue text_or_unset(const std::string& s) {
        return s.empty() ? OptionValue() : OptionValue(s);
    }
};

}  // namespace glint
