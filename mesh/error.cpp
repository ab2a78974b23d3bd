#include "mesh/error.h"

#include <sstream>
#include <string>

namespace glint {

namespace {
std::string number_text(double value) {
    std::ostringstream s;
    s.precision(10);
    s << value;
    return s.str();
}
}  // namespace

OptionError::OptionError(std::string key, double value, const std::string& rule)
    : OptionError(std::move(key), number_text(value), rule) {}

OptionError OptionError::prefixed(const std::string& section) const {
    const std::string full = section + "." + key_;
    const std::string message = what();
    // The message starts with the key: put the prefix there too.
    return OptionError(Whole{}, full,
                       message.rfind(key_, 0) == 0 ? section + "." + message : message);
}

std::string OptionError::named(const std::string& name) const {
    const std::string message = what();
    return message.rfind(key_, 0) == 0 ? name + message.substr(key_.size()) : message;
}

}  // namespace glint

namespace glint::detail {

void assert_failed(const char* cond, const std::string& msg, const char* file, int line) {
    throw std::logic_error(std::string("internal error at ") + file + ":" + std::to_string(line) +
                           ": " + cond + " failed: " + msg);
}

}  // namespace glint::detail
