// Reading scenario TOML tables: typed values, every key accounted for, errors that name the
// file, the line and the key (scenario/scenario.cpp, scenario/detail/scenario_options.cpp). Internal.
#pragma once

#include "mesh/error.h"

#include <toml++/toml.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace glint::detail {

// Reads typed values from one TOML table and rejects keys nobody asked about.
class TableReader {
  public:
    TableReader(const toml::table& table, std::string file, std::string section)
        : table_(table), file_(std::move(file)), section_(std::move(section)) {}

    [[noreturn]] void fail(const toml::node* node, const std::string& key,
                           const std::string& what) const {
        std::ostringstream s;
        s << "scenario \"" << file_ << "\"";
        if (node) s << " line " << node->source().begin.line;
        s << ": " << qualified(key) << ": " << what;
        throw InputError(s.str());
    }

    /// A message that already names the key (an OptionError's), with the file and line.
    [[noreturn]] void fail_whole(const toml::node* node, const std::string& message) const {
        std::ostringstream s;
        s << "scenario \"" << file_ << "\"";
        if (node) s << " line " << node->source().begin.line;
        s << ": " << message;
        throw InputError(s.str());
    }

    [[nodiscard]] std::string qualified(const std::string& key) const {
        return section_.empty() ? key : section_ + "." + key;
    }

    [[nodiscard]] const toml::node* get(const std::string& key) {
        seen_.insert(key);
        return table_.get(key);
    }

    [[nodiscard]] bool has(const std::string& key) const { return table_.contains(key); }

    template <class T>
    std::optional<T> optional(const std::string& key, const char* expected) {
        const toml::node* node = get(key);
        if (!node) return std::nullopt;
        if constexpr (std::is_same_v<T, double>) {
            if (auto v = node->value<double>()) {  // integers convert too
                // Issue 23 item 15: TOML's nan and inf were taken (noise = nan passed).
                if (!std::isfinite(*v))
                    fail(node, key,
                         std::string("expected ") + expected + ", found " + std::to_string(*v));
                return *v;
            }
        } else if constexpr (std::is_same_v<T, std::int64_t>) {
            if (node->is_integer()) return node->value<std::int64_t>();
        } else if constexpr (std::is_same_v<T, bool>) {
            if (node->is_boolean()) return node->value<bool>();
        } else if constexpr (std::is_same_v<T, std::string>) {
            if (node->is_string()) return node->value<std::string>();
        }
        fail(node, key, std::string("expected ") + expected + ", found " + type_name(*node));
    }

    std::optional<std::vector<double>> numbers(const std::string& key, std::size_t min_count,
                                               std::size_t max_count) {
        const toml::node* node = get(key);
        if (!node) return std::nullopt;
        std::vector<double> out;
        if (auto v = node->value<double>()) {
            out.push_back(*v);
        } else if (const auto* arr = node->as_array()) {
            for (const auto& e : *arr) {
                auto v2 = e.value<double>();
                if (!v2)
                    fail(node, key,
                         "expected an array of numbers, found an element of type " + type_name(e));
                if (!std::isfinite(*v2))
                    fail(node, key, "expected finite numbers, found " + std::to_string(*v2));
                out.push_back(*v2);
            }
        } else {
            fail(node, key, "expected a number or an array of numbers, found " + type_name(*node));
        }
        if (out.size() < min_count || out.size() > max_count) {
            std::ostringstream s;
            s << "expected " << min_count;
            if (max_count != min_count) s << " to " << max_count;
            s << " numbers, found " << out.size();
            fail(node, key, s.str());
        }
        return out;
    }

    /// An integer in [lo, hi] (issue 23 item 15: resolution = 4294967301 became 5 through a
    /// cast to int; seeds wrapped at 2^32).
    std::optional<std::int64_t> integer(const std::string& key, std::int64_t lo, std::int64_t hi) {
        auto v = optional<std::int64_t>(key, "an integer");
        if (v && (*v < lo || *v > hi))
            fail(get(key), key,
                 "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                     "], found " + std::to_string(*v));
        return v;
    }

    std::optional<double> positive(const std::string& key) {
        auto v = optional<double>(key, "a number");
        if (v && !(*v > 0)) fail(get(key), key, "must be > 0, found " + std::to_string(*v));
        return v;
    }

    /// Every key of the table must have been asked for.
    void finish() const {
        for (const auto& [k, node] : table_) {
            const std::string key(k.str());
            if (!seen_.count(key))
                fail(&node, key,
                     "unknown key (check its spelling; docs/inputs.md lists every key)");
        }
    }

    static std::string type_name(const toml::node& n) {
        switch (n.type()) {
            case toml::node_type::string: return "a string";
            case toml::node_type::integer: return "an integer";
            case toml::node_type::floating_point: return "a number";
            case toml::node_type::boolean: return "a boolean";
            case toml::node_type::array: return "an array";
            case toml::node_type::table: return "a table";
            default: return "a date/time";
        }
    }

    [[nodiscard]] const std::string& file() const { return file_; }

  private:
    const toml::table& table_;
    std::string file_;
    std::string section_;
    std::set<std::string> seen_;
};

}  // namespace glint::detail
