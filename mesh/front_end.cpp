#include "mesh/front_end.h"

#include <algorithm>
#include <atomic>
#include <cctype>

namespace glint {

namespace {

std::atomic<FrontEnd> g_front_end{FrontEnd::CommandLine};

bool is_placeholder(std::string_view value) {
    return !value.empty() && std::all_of(value.begin(), value.end(), [](char c) {
        return std::isupper(static_cast<unsigned char>(c)) || c == '_';
    });
}

}  // namespace

void set_front_end(FrontEnd front_end) noexcept { g_front_end.store(front_end); }

FrontEnd front_end() noexcept { return g_front_end.load(); }

std::string spell_name(std::string_view name) {
    std::string out(name);
    if (front_end() == FrontEnd::Python) return out;
    std::replace(out.begin(), out.end(), '_', '-');
    return "--" + out;
}

std::string spell_flag(std::string_view name, bool on) {
    if (front_end() == FrontEnd::Python) return std::string(name) + (on ? "=True" : "=False");
    if (on) return spell_name(name);
    return "--no-" + spell_name(name).substr(2);
}

std::string spell_option(std::string_view name, std::string_view value) {
    if (front_end() == FrontEnd::Python)
        return std::string(name) + "=" +
               (is_placeholder(value) ? std::string(value) : "'" + std::string(value) + "'");
    return spell_name(name) + " " + std::string(value);
}

}  // namespace glint
