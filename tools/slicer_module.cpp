// The Slicer module's parameter table, its XML description, and how a Slicer call is told
// apart from glint's own commands (tools/slicer_module.h).
#include "tools/slicer_module.h"

#include "analysis/analysis.h"
#include "analysis/option_registry.h"
#include "mesh/version.h"
#include "registration/icp.h"
#include "render/context.h"
#include "report/report_html.h"
#include "scanner/metric.h"
#include "tools/slicer_parameters.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <utility>

namespace glint::cli {

namespace {

std::string number(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.10g", v);
    return b;
}

// Slicer writes a model node with the first of these and a volume node as .nrrd (its first).
constexpr const char* kModelFiles = ".vtk,.ply,.stl,.obj";
constexpr const char* kVolumeFiles = ".nrrd,.nii,.nii.gz,.mha";

SlicerParameter input_node(const char* tag, const char* name, const char* label,
                           std::string description) {
    const bool model = std::string(tag) == "geometry";
    return {.tag = tag,
            .name = name,
            .longflag = name,
            .channel = "input",
            .label = label,
            .description = std::move(description),
            .type = model ? "model" : "scalar",
            .file_extensions = model ? kModelFiles : kVolumeFiles};
}

// Each surface is a model or a volume (its iso-surface): flagged, not index, parameters, since
// Slicer refuses to run a module whose index node is not selected.
SlicerGroup inputs_group() {
    constexpr const char* kEither = " Give the model or the volume, not both.";
    return {"Inputs",
            "The surface before (reference) and the surface examined, each a model or a scalar "
            "volume (CT, CBCT) whose iso-surface is used; the atlas is the reference coloured by "
            "damage.",
            false,
            {input_node("geometry", "referenceModel", "Reference model",
                        std::string("The surface before (the reference): the atlas is drawn on "
                                    "it.") +
                            kEither),
             input_node("image", "referenceVolume", "Reference volume",
                        std::string("The reference as a scalar volume: its surface at the iso "
                                    "value.") +
                            kEither),
             input_node("geometry", "examinedModel", "Examined model",
                        std::string("The surface examined, fitted onto the reference.") + kEither),
             input_node("image", "examinedVolume", "Examined volume",
                        std::string("The examined surface as a scalar volume.") + kEither),
             {.tag = "double",
              .name = "iso",
              .longflag = "iso",
              .label = "Iso value (volumes)",
              .description = "The value of the surface in a volume, in its units (CT bone: about "
                             "300 HU; CBCT grey values vary: read one off the volume in Slicer's "
                             "Data Probe). Ignored for models.",
              .default_value = "300"},
             {.tag = "boolean",
              .name = "largest",
              .longflag = "largest",
              .label = "Largest surface only (volumes)",
              .description = "Keep only the largest connected part of a volume's surface (drops "
                             "noise islands and loose fragments).",
              .default_value = "false"},
             {.tag = "point",
              .name = "seed",
              .longflag = "seed",
              .channel = "input",
              .label = "Surface seed (volumes)",
              .description = "Keep only the part of a volume's surface nearest this point (the "
                             "first point of a point list), e.g. the mandible rather than the "
                             "skull. Not with Largest surface only; ignored for models.",
              .coordinate_system = "lps",
              .multiple = "false"}}};
}

SlicerGroup outputs_group() {
    return {
        "Outputs",
        "What the run returns to Slicer.",
        false,
        {{.tag = "geometry",
          .name = "atlas",
          .index = 0,
          .channel = "output",
          .label = "Damage atlas",
          .description =
              "The reference with the atlas fields, shown first shape_change_mm (signed distance "
              "to the examined surface in the run's unit, negative = loss; in a hole of the "
              "examined surface the depth gone), then "
              "shape_tolerance_mm, per zoom seen_z0 (1 seen, 0 unseen), angle_mean_deg_z0 and "
              "angle_max_deg_z0 (normal deviation, 0 where unseen), missing_fraction_z0, "
              "pixels_z0, region_id_z0 (docs/outputs.md: the atlas fields). In the reference's space "
              "(LPS, as Slicer writes models and volumes).",
          .type = "model",
          .file_extensions = ".vtp"},
         {.tag = "image",
          .name = "atlasPicture",
          .longflag = "atlasPicture",
          .channel = "output",
          .label = "Atlas picture",
          .description = "atlas.png: the surface from six sides and close-ups of every region, "
                         "numbered, with a legend and scale bar (loads as a colour volume).",
          .type = "vector",
          .file_extensions = ".png"},
         {.tag = "file",
          .name = "report",
          .longflag = "report",
          .channel = "output",
          .label = "Report page",
          .description = "report.html: one self-contained page with the fit, the floors, every "
                         "region and the pictures; open it in a web browser.",
          .file_extensions = ".html"},
         {.tag = "table",
          .name = "regions",
          .longflag = "regions",
          .channel = "output",
          .label = "Regions table",
          .description =
              "One row per region (regions.csv): kind, area, depths, volume, centroid, best view.",
          .file_extensions = ".csv"},
         {.tag = "image",
          .name = "mosaic",
          .longflag = "mosaic",
          .channel = "output",
          .label = "View mosaic",
          .description =
              "How much each view measured beyond its floor (azimuth × elevation) and the views "
              "that saw the regions (mosaic_z0.png).",
          .type = "vector",
          .file_extensions = ".png"}}};
}

// Slicer's step for a slider over [min, max]: a power of ten about a hundredth of the range.
double slider_step(const OptionInfo& info) {
    if (info.kind == OptionKind::Integer) return 1;
    const double span = info.max - info.min;
    return std::pow(10.0, std::floor(std::log10(span / 100.0)));
}

// One registry option as a Slicer parameter. A flag that is on by default becomes its negation
// (noCoarse): Slicer passes a boolean only when it is true, so an on-by-default flag could not
// be turned off otherwise. An optional number is 0 when unset (Slicer always passes a value).
SlicerParameter registry_parameter(const OptionInfo& info, const OptionValue& current) {
    SlicerParameter p{.name = std::string(info.slicer),
                      .longflag = std::string(info.slicer),
                      .label = std::string(info.label),
                      .description = std::string(info.help) + "."};
    if (!info.unit.empty()) p.label += " (" + std::string(info.unit) + ")";
    const std::string shown = option_text(info, current);
    const bool bounded = std::isfinite(info.min) && std::isfinite(info.max);
    switch (info.kind) {
        case OptionKind::Flag:
            p.tag = "boolean";
            if (shown == "true") {
                p.name = p.longflag =
                    "no" +
                    std::string(1, static_cast<char>(
                                       std::toupper(static_cast<unsigned char>(info.slicer[0])))) +
                    std::string(info.slicer.substr(1));
                p.label = "No " + std::string(info.label) + " (on by default)";
            }
            p.default_value = "false";
            break;
        case OptionKind::Integer:
            p.tag = "integer";
            p.default_value = shown;
            if (bounded) p.constraints = std::array<double, 3>{info.min, info.max, 1};
            break;
        case OptionKind::Number:
            p.tag = "double";
            p.default_value = shown;
            if (bounded)
                p.constraints = std::array<double, 3>{info.min, info.max, slider_step(info)};
            break;
        case OptionKind::OptionalNumber:
            p.tag = "double";
            p.default_value = shown.empty() ? "0" : shown;
            p.description += " 0: measured from the run.";
            break;
        case OptionKind::Numbers:
            p.tag = "double-vector";
            p.default_value = shown;
            break;
        case OptionKind::Choice:
            p.tag = "string-enumeration";
            p.elements = info.choices;
            if (info.may_be_unset) p.elements.insert(p.elements.begin(), "auto");
            p.default_value = shown.empty() ? "auto" : shown;
            break;
        case OptionKind::Path:
            p.tag = "file";
            p.channel = "input";
            p.file_extensions = ".json";
            break;
        case OptionKind::Region:
            // note: an ROI markup; Slicer passes "cx,cy,cz,rx,ry,rz" (tools/slicer_markups.h).
            p.tag = "region";
            p.channel = "input";
            p.coordinate_system = "lps";
            p.description = std::string(info.help.substr(0, info.help.find(": sphere:"))) +
                            ": an ROI (axis-aligned: its box is the region). glint's command "
                            "line also takes sphere:, box: and mask: text.";
            break;
        case OptionKind::Text:
            p.tag = "string";
            p.default_value = shown;
            break;
    }
    return p;
}

SlicerGroup registry_group(std::string label, std::string description, bool advanced,
                           unsigned groups, std::vector<SlicerParameter> first = {}) {
    const AnalysisOptions defaults;
    SlicerGroup g{std::move(label), std::move(description), advanced, std::move(first)};
    for (const auto& f : analysis_option_table())
        if ((f.info.group & groups) != 0)
            g.parameters.push_back(registry_parameter(f.info, f.get(defaults)));
    return g;
}

// Landmarks as two point lists, paired in order (the n-th reference point with the n-th
// examined one): Slicer writes each markups node to a file in LPS.
SlicerParameter landmarks_parameter(const std::string& side) {
    return {.tag = "pointfile",
            .name = side + "Landmarks",
            .longflag = side + "Landmarks",
            .channel = "input",
            .label = (side == "reference" ? "Reference" : "Examined") + std::string(" landmarks"),
            .description = "Registration: start from landmarks, a point list on the " + side +
                           " surface paired in order with the " +
                           (side == "reference" ? "examined" : "reference") +
                           " list (at least 3 pairs; give both lists).",
            .file_extensions = ".mrk.json,.fcsv",
            .coordinate_system = "lps"};
}

SlicerGroup fit_group() {
    return registry_group(
        "Fit", "How the examined surface is brought into the reference's frame.", false, kFitGroup,
        {{.tag = "boolean",
          .name = "register",
          .longflag = "register",
          .label = "Register",
          .description =
              "Fit the examined surface onto the reference (robust ICP); off: they are already aligned.",
          .default_value = "true"},
         landmarks_parameter("reference"),
         landmarks_parameter("examined")});
}

SlicerGroup results_group() {
    auto value = [](const char* tag, const char* name, const char* label, const char* description) {
        return SlicerParameter{.tag = tag,
                               .name = name,
                               .channel = "output",
                               .label = label,
                               .description = description};
    };
    return {"Results",
            "What the run found (zoom 0), filled in when it completes.",
            false,
            {value("integer", "regionCount", "Regions", "Number of damaged regions."),
             value("double", "largestRegionArea", "Largest area",
                   "Area of the largest region (mesh units squared)."),
             value("double", "peakDepth", "Peak depth",
                   "Signed depth of largest magnitude (negative = loss)."),
             value("double", "volumeLost", "Volume lost",
                   "Sum over dents (mesh units cubed, positive)."),
             value("double", "volumeGained", "Volume gained", "Sum over bumps (mesh units cubed)."),
             value("double", "coverage", "Coverage (%)",
                   "Share of the reference surface the sweep saw."),
             value("double", "fitRotationDeg", "Fit rotation (deg)",
                   "Rotation that brought the examined surface in."),
             value("double", "fitRms", "Fit RMS",
                   "Point-to-plane RMS of the fit's inliers (0 without registration)."),
             value("string", "lengthUnit", "Unit", "Unit of every length (empty when unknown).")}};
}

void write_parameter(std::ostringstream& x, const SlicerParameter& p) {
    x << "    <" << p.tag;
    if (!p.type.empty()) x << " type=\"" << p.type << '"';
    if (!p.multiple.empty()) x << " multiple=\"" << p.multiple << '"';
    if (!p.coordinate_system.empty()) x << " coordinateSystem=\"" << p.coordinate_system << '"';
    if (!p.file_extensions.empty()) x << " fileExtensions=\"" << p.file_extensions << '"';
    x << ">\n      <name>" << p.name << "</name>\n";
    if (!p.longflag.empty()) x << "      <longflag>" << p.longflag << "</longflag>\n";
    x << "      <label>" << escape_markup(p.label) << "</label>\n";
    x << "      <description>" << escape_markup(p.description) << "</description>\n";
    if (!p.channel.empty()) x << "      <channel>" << p.channel << "</channel>\n";
    if (p.index >= 0) x << "      <index>" << p.index << "</index>\n";
    if (!p.default_value.empty())
        x << "      <default>" << escape_markup(p.default_value) << "</default>\n";
    for (const auto& e : p.elements) x << "      <element>" << escape_markup(e) << "</element>\n";
    if (p.constraints)
        x << "      <constraints>\n        <minimum>" << number((*p.constraints)[0])
          << "</minimum>\n        <maximum>" << number((*p.constraints)[1])
          << "</maximum>\n        <step>" << number((*p.constraints)[2])
          << "</step>\n      </constraints>\n";
    x << "    </" << p.tag << ">\n";
}

}  // namespace

const std::vector<SlicerGroup>& slicer_groups() {
    static const std::vector<SlicerGroup> groups = [] {
        return std::vector<SlicerGroup>{
            inputs_group(),
            outputs_group(),
            fit_group(),
            registry_group("Sweep", "The virtual rotary scanner: views, image size, metric.", false,
                           kSweepGroup),
            registry_group("Decision",
                           "What counts as damage; 0 for a threshold means the floor measured "
                           "from the run itself. Length unit: auto is what the files state (Slicer "
                           "writes its models in mm).",
                           true, kDecisionGroup | kUnitGroup),
            results_group()};
    }();
    return groups;
}

std::string slicer_xml() {
    std::ostringstream x;
    x << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<executable>\n"
      << "  <category>Surface Models</category>\n"
      << "  <title>glint damage atlas</title>\n"
      << "  <description>Finds damage on a surface by light-reflection analysis: fits the examined model onto the "
         "reference, sweeps a virtual camera around both, compares normal-colour frames view by view and folds the "
         "differences onto the reference as a per-vertex damage atlas with regions (dents, bumps, missing "
         "surface). Each surface is a model or a scalar volume (its iso-surface); returns the atlas model, "
         "atlas.png, report.html and the regions table.</description>\n"
      << "  <version>" << kVersion << "</version>\n"
      << "  <license>see the glint repository</license>\n"
      << "  <contributor>glint developers</contributor>\n"
      << "  <acknowledgements>Method: light-reflection analysis for surface damage "
         "identification.</acknowledgements>\n";
    for (const SlicerGroup& g : slicer_groups()) {
        x << "  <parameters" << (g.advanced ? " advanced=\"true\"" : "") << ">\n"
          << "    <label>" << escape_markup(g.label) << "</label>\n    <description>"
          << escape_markup(g.description) << "</description>\n";
        for (const SlicerParameter& p : g.parameters) write_parameter(x, p);
        x << "  </parameters>\n";
    }
    x << "</executable>\n";
    return x.str();
}

bool is_slicer_call(int argc, char** argv) {
    if (argc < 2) return false;
    const std::string first = argv[1];
    if (first == "--xml" || first == "--returnparameterfile" ||
        first == "--processinformationaddress" || first == "--echo")
        return true;
    if (!first.starts_with("--")) return false;
    for (const SlicerGroup& g : slicer_groups())
        for (const SlicerParameter& p : g.parameters)
            if (!p.longflag.empty() && first == "--" + p.longflag) return true;
    return false;
}

}  // namespace glint::cli
