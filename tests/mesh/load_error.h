// Shared by the tests of rejected input: load a file expecting one exception class.
#pragma once

#include "mesh/error.h"
#include "mesh/io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <typeinfo>

namespace glint::test {

/// Loads `path` expecting exactly exception class E; returns its message (a test failure,
/// and the message, when something else or nothing was thrown).
template <class E>
std::string load_error(const std::filesystem::path& path, const LoadOptions& options = {}) {
    try {
        (void)load_mesh(path, options);
    } catch (const Error& e) {
        EXPECT_EQ(typeid(e), typeid(E)) << "threw " << typeid(e).name() << ": " << e.what();
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "threw a non-glint exception " << typeid(e).name() << ": " << e.what();
        return e.what();
    }
    ADD_FAILURE() << "loading " << path << " did not throw";
    return {};
}

}  // namespace glint::test

#define EXPECT_CONTAINS(text, part) \
    EXPECT_NE(std::string(text).find(part), std::string::npos) << "message: " << (text)
