// The Slicer module's parameter table, its XML description, and how a Slicer call is told
// apart from glint's own commands (tools/slicer_module.h).
#include "tools/slicer_module.h"

#include "mesh/units.h"
#include "mesh/version.h"
#include "registration/icp.h"
#include "render/context.h"
#include "scanner/analysis.h"
#include "scanner/metric.h"
#include "scanner/report_html.h"
#include "tools/slicer_parameters.h"

#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>

namespace glint::cli {

namespace {

std::string number(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.10g", v);
    return b;
}

std::string joined(const std::vector<double>& values) {
    std::string out;
    for (double v : values) out += (out.empty() ? "" : ",") + number(v);
    return out;
}

std::vector<std::string> split(const std::string& text, const std::string& separator) {
    std::vector<std::string> out;
    std::size_t start = 0;
    for (std::size_t at; (at = text.find(separator, start)) != std::string::npos;
         start = at + separator.size())
        out.push_back(text.substr(start, at - start));
    out.push_back(text.substr(start));
    return out;
}

SlicerGroup surfaces_group() {
    return {
        "Surfaces",
        "The surface before (reference) and the surface examined; the atlas is the reference coloured by damage.",
        false,
        {{.tag = "geometry",
          .name = "reference",
          .index = 0,
          .channel = "input",
          .label = "Reference model",
          .description = "The surface before (the reference): the atlas is drawn on it.",
          .type = "model",
          .file_extensions = ".vtk,.ply,.stl,.obj"},
         {.tag = "geometry",
          .name = "examined",
          .index = 1,
          .channel = "input",
          .label = "Examined model",
          .description = "The surface examined, fitted onto the reference.",
          .type = "model",
          .file_extensions = ".vtk,.ply,.stl,.obj"},
         {.tag = "geometry",
          .name = "atlas",
          .index = 2,
          .channel = "output",
          .label = "Damage atlas",
          .description =
              "The reference with the atlas scalars (angle_mean_z0: per-vertex normal deviation in "
              "degrees, distance: signed distance to the examined surface, negative = loss, region_z0: "
              "region id, seen_z0, count_z0, …).",
          .type = "model",
          .file_extensions = ".vtp"},
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
          .description = "Every view's heat map, azimuth across, elevation down (mosaic_z0.png).",
          .type = "vector",
          .file_extensions = ".png"}}};
}

SlicerGroup fit_group(const AnalysisOptions& d) {
    return {
        "Fit",
        "How the examined surface is brought into the reference's frame.",
        false,
        {{.tag = "boolean",
          .name = "register",
          .longflag = "register",
          .label = "Register",
          .description =
              "Fit the examined surface onto the reference (robust ICP); off: they are already aligned.",
          .default_value = "true"},
         {.tag = "string-enumeration",
          .name = "loss",
          .longflag = "loss",
          .label = "Robust loss",
          .description = "Registration loss (damage must not pull the fit).",
          .default_value = to_string(d.fit.registration.loss),
          .elements = {"cauchy", "huber", "tukey", "none"}},
         {.tag = "string",
          .name = "fitRoi",
          .longflag = "fitRoi",
          .label = "Fit region",
          .description =
              "Fit only on this stable region: sphere:x,y,z,r or box:x0,y0,z0,x1,y1,z1 (empty: all)."}}};
}

SlicerGroup sweep_group(const AnalysisOptions& d) {
    std::vector<std::string> metric_names, backends{"auto", "embree", "vulkan"};
    for (const auto& m : metrics()) metric_names.emplace_back(m.name);
    const SweepPlanOptions& p = d.sweep.plan;
    return {
        "Sweep",
        "The virtual rotary scanner: views, image size, metric.",
        false,
        {{.tag = "integer",
          .name = "size",
          .longflag = "size",
          .label = "Image size",
          .description = "Pixels across a frame of the whole surface.",
          .default_value = std::to_string(p.size),
          .constraints = std::array<double, 3>{32, 4096, 32}},
         {.tag = "double",
          .name = "azimuthStep",
          .longflag = "azimuthStep",
          .label = "Azimuth step (deg)",
          .description = "Angle between two views around the surface.",
          .default_value = number(p.azimuth_step_deg),
          .constraints = std::array<double, 3>{1, 360, 1}},
         {.tag = "double-vector",
          .name = "elevations",
          .longflag = "elevations",
          .label = "Elevations (deg)",
          .description = "Elevation rings, comma-separated, each in [-90, 90].",
          .default_value = joined(p.elevations_deg)},
         {.tag = "integer",
          .name = "supersample",
          .longflag = "supersample",
          .label = "Supersampling",
          .description = "s x s sub-samples per pixel (footprint averaging).",
          .default_value = std::to_string(d.sweep.render.supersample),
          .constraints = std::array<double, 3>{1, 8, 1}},
         {.tag = "string",
          .name = "roi",
          .longflag = "roi",
          .label = "Analysed region",
          .description =
              "Analyse only part of the surface: sphere:x,y,z,r or box:x0,y0,z0,x1,y1,z1 (empty: all)."},
         {.tag = "string-enumeration",
          .name = "metric",
          .longflag = "metric",
          .label = "Metric",
          .description =
              "angle: degrees between normals; rgb: the paper's 8-bit colour difference.",
          .default_value = to_string(d.sweep.metric),
          .elements = metric_names},
         {.tag = "string-enumeration",
          .name = "backend",
          .longflag = "backend",
          .label = "Renderer",
          .description = "auto: Vulkan on a GPU, else Embree on the CPU.",
          .default_value = to_string(d.sweep.render.backend),
          .elements = backends}}};
}

SlicerGroup decision_group(const AnalysisOptions& d) {
    std::vector<std::string> units{"auto"};
    for (const auto& u : split(known_units(), ", ")) units.push_back(u);
    return {
        "Decision",
        "What counts as damage; 0 for a threshold means the floor measured from the run itself.",
        true,
        {{.tag = "string-enumeration",
          .name = "rule",
          .longflag = "rule",
          .label = "Rule",
          .description = "fused: normal and shape evidence; normal: the paper's angle-only rule.",
          .default_value = to_string(d.decision.rule),
          .elements = {"fused", "normal"}},
         {.tag = "double",
          .name = "thresholdDeg",
          .longflag = "thresholdDeg",
          .label = "Normal threshold",
          .description = "In the metric's unit; 0: the run's noise floor.",
          .default_value = "0",
          .constraints = std::array<double, 3>{0, 90, 0.5}},
         {.tag = "double",
          .name = "shapeThreshold",
          .longflag = "shapeThreshold",
          .label = "Shape threshold",
          .description = "In mesh units; 0: the run's floor.",
          .default_value = "0",
          .constraints = std::array<double, 3>{0, 1000, 0.01}},
         {.tag = "integer",
          .name = "minRegionVertices",
          .longflag = "minRegionVertices",
          .label = "Smallest region (vertices)",
          .description = "Smaller groups are dropped.",
          .default_value = std::to_string(d.decision.min_region_vertices),
          .constraints = std::array<double, 3>{1, 10000, 1}},
         {.tag = "string-enumeration",
          .name = "unit",
          .longflag = "unit",
          .label = "Length unit",
          .description =
              "The unit both models are in (Slicer's models are in mm); auto: what the files state.",
          .default_value = "mm",
          .elements = units}}};
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
        const AnalysisOptions defaults;
        return std::vector<SlicerGroup>{surfaces_group(), fit_group(defaults),
                                        sweep_group(defaults), decision_group(defaults),
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
         "surface).</description>\n"
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
