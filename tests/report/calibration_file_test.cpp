#include "report/calibration_file.h"

#include "mesh/error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace glint {
namespace {

// Regression (issue 16): values of the wrong type threw nlohmann's type_error (exit 4).
TEST(ReadCalibration, TurnsWrongTypesIntoInputErrors) {
    for (
        const std::string text :
        {R"({"glint_calibration": 1, "found": "yes", "footprint": 1, "threshold_deg": 4})",
         R"({"glint_calibration": 1, "found": true, "footprint": 1, "threshold_deg": "4"})",
         R"({"glint_calibration": 1, "found": true, "footprint": 1})",
         R"({"glint_calibration": 1, "found": true, "footprint": 1, "threshold_deg": 4, "referential": 3})"}) {
        const auto path =
            std::filesystem::path(GLINT_TEST_OUTPUT_DIR) / "calibration_wrong_type.json";
        std::ofstream(path) << text;
        EXPECT_THROW((void)read_calibration(path), InputError) << text;
    }
}

}  // namespace
}  // namespace glint
