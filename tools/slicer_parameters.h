// The one table the Slicer module's XML description and its command-line parser are made
// from (tools/slicer_module.h).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace glint::cli {

/// One Execution Model parameter. A flagged parameter is passed as --longflag VALUE (a
/// boolean as --longflag alone, when true); an index parameter positionally; an output
/// parameter with neither is a return parameter (written to --returnparameterfile).
struct SlicerParameter {
    std::string
        tag;  ///< integer, double, boolean, string, string-enumeration, double-vector, geometry, table, image, file, region, pointfile
    std::string name;      ///< unique; also the key in the return parameter file
    std::string longflag;  ///< without dashes; empty for index and return parameters
    int index = -1;        ///< position among the index parameters; -1: not one
    std::string channel;  ///< "input" or "output" (files and return values); empty for plain values
    std::string label;
    std::string description;
    std::string default_value;  ///< empty: none
    std::string type;  ///< the type attribute (geometry "model", image "vector"); empty: none
    std::string
        file_extensions;  ///< the fileExtensions attribute; the first is what Slicer writes/reads
    std::string coordinate_system;  ///< point, pointfile, region: "lps" (tools/slicer_markups.h)
    std::string
        multiple;  ///< the multiple attribute ("false": Slicer passes one point); empty: none
    std::vector<std::string> elements;                 ///< enumerations
    std::optional<std::array<double, 3>> constraints;  ///< minimum, maximum, step
};

struct SlicerGroup {
    std::string label;
    std::string description;
    bool advanced = false;
    std::vector<SlicerParameter> parameters;
};

/// The sweep as a Slicer module; defaults are the library's (AnalysisOptions{}).
[[nodiscard]] const std::vector<SlicerGroup>& slicer_groups();

/// The Execution Model XML description of slicer_groups().
[[nodiscard]] std::string slicer_xml();

}  // namespace glint::cli
