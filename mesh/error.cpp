#include "mesh/error.h"

#include <string>

namespace glint::detail {

void assert_failed(const char* cond, const std::string& msg, const char* file, int line) {
    throw std::logic_error(std::string("internal error at ") + file + ":" + std::to_string(line) +
                           ": " + cond + " failed: " + msg);
}

}  // namespace glint::detail
