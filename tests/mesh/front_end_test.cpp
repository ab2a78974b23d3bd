// Options spelled in the words of the front end that runs.
#include "mesh/front_end.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

// Restores the command line (every other test expects it) however the test ends.
struct PythonFrontEnd {
    PythonFrontEnd() { set_front_end(FrontEnd::Python); }
    ~PythonFrontEnd() { set_front_end(FrontEnd::CommandLine); }
};

TEST(FrontEnd, TheCommandLineIsTheDefaultAndSpellsFlags) {
    EXPECT_EQ(front_end(), FrontEnd::CommandLine);
    EXPECT_EQ(spell_flag("force"), "--force");
    EXPECT_EQ(spell_flag("views", false), "--no-views");
    EXPECT_EQ(spell_flag("allow_scale_mismatch"), "--allow-scale-mismatch");
    EXPECT_EQ(spell_option("iso", "VALUE"), "--iso VALUE");
    EXPECT_EQ(spell_option("unit", "mm"), "--unit mm");
    EXPECT_EQ(spell_name("azimuth_step"), "--azimuth-step");
}

TEST(FrontEnd, PythonSpellsKeywords) {
    const PythonFrontEnd python;
    EXPECT_EQ(spell_flag("force"), "force=True");
    EXPECT_EQ(spell_flag("views", false), "views=False");
    EXPECT_EQ(spell_flag("allow_scale_mismatch"), "allow_scale_mismatch=True");
    EXPECT_EQ(spell_option("iso", "VALUE"), "iso=VALUE");
    EXPECT_EQ(spell_option("unit", "mm"), "unit='mm'");
    EXPECT_EQ(spell_name("azimuth_step"), "azimuth_step");
}

}  // namespace
}  // namespace glint
