// Length units (mesh/units.h): names, sizes, and the unit a file's header states.
#include "mesh/units.h"

#include "mesh/io.h"

#include "tests/mesh/test_files.h"

#include <gtest/gtest.h>

#include <string>

namespace glint {
namespace {

std::span<const char> text(const std::string& s) { return {s.data(), s.size()}; }

TEST(Units, SpellingsBecomeOneCanonicalName) {
    EXPECT_EQ(canonical_unit("mm"), "mm");
    EXPECT_EQ(canonical_unit("Millimetres"), "mm");
    EXPECT_EQ(canonical_unit("METER"), "m");
    EXPECT_EQ(canonical_unit("\xC2\xB5m"), "um");  // µm
    EXPECT_EQ(canonical_unit("microns"), "um");
    EXPECT_EQ(canonical_unit("inch"), "in");
    EXPECT_EQ(canonical_unit("furlong"), "");
    EXPECT_EQ(canonical_unit(""), "");
    EXPECT_DOUBLE_EQ(*metres_per_unit("mm"), 1e-3);
    EXPECT_FALSE(metres_per_unit("").has_value());
}

TEST(Units, ReadFromTheCommentsFormatsCarry) {
    EXPECT_EQ(
        unit_from_header(
            text("ply\nformat ascii 1.0\ncomment unit mm\nelement vertex 0\nend_header\n"), ".ply"),
        "mm");
    EXPECT_EQ(unit_from_header(text("ply\ncomment units: um\nend_header\n"), ".ply"), "um");
    EXPECT_EQ(
        unit_from_header(text("# vtk DataFile Version 3.0\nglint mesh unit m\nASCII\n"), ".vtk"),
        "m");
    EXPECT_EQ(unit_from_header(text("# Exported\n# Units = millimeters\nv 0 0 0\n"), ".obj"), "mm");
    EXPECT_EQ(unit_from_header(text("# coordinates in unit in cm\nv 0 0 0\n"), ".obj"),
              "cm");  // "in" then a unit
    EXPECT_EQ(
        unit_from_header(
            text("UNITS=mm binary STL header, padded to 80 bytes.............................."),
            ".stl"),
        "mm");
    EXPECT_EQ(unit_from_header(text("{}"), ".gltf"), "m");  // glTF 2.0: metres
    // 3D Slicer's models are in millimetres; its header names only the patient space (issue 51).
    EXPECT_EQ(
        unit_from_header(text("# vtk DataFile Version 4.2\n3D Slicer output. SPACE=LPS\nBINARY\n"),
                         ".vtk"),
        "mm");
    EXPECT_EQ(unit_from_header(text("solid ascii\n"), ".stl"), "");
    EXPECT_EQ(unit_from_header(text("# SPACE=RAS\nv 0 0 0\n"), ".obj"), "mm");
}

TEST(Units, NotGuessedFromDataOrOtherWords) {
    // Only comment lines count; "community" and "unity" are not "unit".
    EXPECT_EQ(
        unit_from_header(text("# Blender3D v249 OBJ File: community unity\nv 0 0 0\n"), ".obj"),
        "");
    EXPECT_EQ(
        unit_from_header(text("ply\nelement unit_mm 0\nend_header\ncomment unit mm\n"), ".ply"),
        "");
    EXPECT_EQ(unit_from_header(text("solid part\nfacet normal 0 0 1\n"), ".stl"), "");
}

TEST(Units, NumbersForPeopleCarryTheirUnit) {
    EXPECT_EQ(with_unit(0.4, "mm"), "0.4 mm");
    EXPECT_EQ(with_unit(12.5, "mm", 2), "12.5 mm²");
    EXPECT_EQ(with_unit(3, "", 3), "3 units³");
    EXPECT_EQ(unit_suffix("mm", 2), "_mm2");
    EXPECT_EQ(unit_suffix(""), "_units");
}

TEST(Units, LoadingRecordsTheUnitAFileStates) {
    const auto dir = test::output_dir("units_test");
    const auto path =
        test::write_bytes(dir, "stated.obj", "# units: mm\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(load_mesh(path).mesh.unit, "mm");
    const auto none = test::write_bytes(dir, "none.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(load_mesh(none).mesh.unit, "");
}

}  // namespace
}  // namespace glint
