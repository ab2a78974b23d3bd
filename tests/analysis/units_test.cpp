// The analysis unit and the size check (analysis/units.h): a stated unit wins, files in two
// stated units are converted, sizes 1000× apart are refused before any work.
#include "analysis/units.h"

#include "mesh/error.h"

#include <gtest/gtest.h>

#include <string>

namespace glint {
namespace {

Mesh triangle(float size, std::string unit) {
    Mesh m;
    m.positions = {{0, 0, 0}, {size, 0, 0}, {0, size, 0}};
    m.triangles = {{0, 1, 2}};
    m.unit = std::move(unit);
    return m;
}

TEST(ResolveUnits, TakesTheUnitAFileStates) {
    const UnitResolution r = resolve_units(triangle(10, "mm"), triangle(10, ""), {});
    EXPECT_EQ(r.unit, "mm");
    EXPECT_DOUBLE_EQ(r.examined_scale, 1.0);
    EXPECT_TRUE(r.warnings.empty());
}

TEST(ResolveUnits, ConvertsAnExaminedInAnotherStatedUnit) {
    const UnitResolution r = resolve_units(triangle(10, "mm"), triangle(0.01f, "m"), {});
    EXPECT_EQ(r.unit, "mm");
    EXPECT_DOUBLE_EQ(r.examined_scale, 1000.0);
    EXPECT_NEAR(r.examined_size, r.reference_size, 1e-4);
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("scaled by 1000"), std::string::npos) << r.warnings[0];
}

TEST(ResolveUnits, AStatedUnitWinsAndSaysWhatItOverrode) {
    const UnitResolution r =
        resolve_units(triangle(10, "m"), triangle(10, ""), {.unit = "millimetres"});
    EXPECT_EQ(r.unit, "mm");
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("states unit m"), std::string::npos) << r.warnings[0];
}

TEST(ResolveUnits, RefusesSizes1000TimesApartNamingBoth) {
    try {
        (void)resolve_units(triangle(10, ""), triangle(0.01f, ""), {});
        FAIL() << "a 1000x size difference was accepted";
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("reference 14.14 units, examined 0.01414 units"), std::string::npos) << m;
        EXPECT_NE(m.find("1000× smaller"), std::string::npos) << m;
        EXPECT_NE(m.find("--allow-scale-mismatch"), std::string::npos) << m;
    }
}

TEST(ResolveUnits, AllowsAMismatchWhenToldAndWarns) {
    const UnitResolution r =
        resolve_units(triangle(10, ""), triangle(0.01f, ""), {.allow_scale_mismatch = true});
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("allowed"), std::string::npos);
    // Issue 53: allowed, the examined proceeds at the conversion the ratio states.
    EXPECT_EQ(r.examined_scale, 1000.0);
    EXPECT_NEAR(r.examined_size, r.reference_size, 1e-6 * r.reference_size);
    EXPECT_NE(r.warnings[0].find("nearest the conversion m → mm"), std::string::npos)
        << r.warnings[0];
    EXPECT_EQ(starting_scale(r), 1.0);
    // A ratio near no conversion is left to --fit-scale, which starts from it.
    const UnitResolution odd =
        resolve_units(triangle(10, ""), triangle(0.3f, ""), {.allow_scale_mismatch = true});
    EXPECT_EQ(odd.examined_scale, 1.0);
    EXPECT_NE(odd.warnings[0].find("near no unit conversion"), std::string::npos)
        << odd.warnings[0];
    EXPECT_NEAR(starting_scale(odd), 10.0 / 0.3, 1e-3);
}

// Issue 53: a reference cropped around a condyle is 6× smaller than the whole examined jaw, a
// ratio near no unit conversion: a part against a whole, run with a note. 10× (cm → mm) and
// beyond 20× are still refused.
TEST(ResolveUnits, TakesAPartAgainstAWholeAtARatioNearNoConversion) {
    const UnitResolution part = resolve_units(triangle(10, ""), triangle(60, ""), {});
    EXPECT_EQ(part.examined_scale, 1.0);
    ASSERT_EQ(part.warnings.size(), 1u);
    EXPECT_NE(part.warnings[0].find("examined mesh is 6× the size of the reference"),
              std::string::npos)
        << part.warnings[0];
    EXPECT_NE(part.warnings[0].find("a part against a whole"), std::string::npos);
    EXPECT_THROW((void)resolve_units(triangle(10, ""), triangle(100, ""), {}), InputError);
    EXPECT_THROW((void)resolve_units(triangle(10, ""), triangle(300, ""), {}), InputError);
}

// Coordinates scaled by 1e20 spent minutes in closest-point queries under
// --allow-scale-mismatch (issue 23, item 14); their float diagonal overflowed to inf.
TEST(ResolveUnits, RefusesHugeCoordinatesEvenWhenAMismatchIsAllowed) {
    try {
        (void)resolve_units(triangle(10, ""), triangle(1e20f, ""), {.allow_scale_mismatch = true});
        FAIL() << "a 1e19x size difference was accepted";
    } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("examined 1.414e+20 units"), std::string::npos) << m;
        EXPECT_NE(m.find("allows up to 10^6×"), std::string::npos) << m;
    }
}

TEST(ResolveUnits, AcceptsAPartialScanWithinTheRatio) {
    // A condyle against its mandible is ~4× smaller: not a unit mistake.
    EXPECT_NO_THROW((void)resolve_units(triangle(40, "mm"), triangle(10, "mm"), {}));
}

TEST(ResolveUnits, RefusesAnUnknownUnitName) {
    EXPECT_THROW((void)resolve_units(triangle(1, ""), triangle(1, ""), {.unit = "furlong"}),
                 OptionError);
}

}  // namespace
}  // namespace glint
