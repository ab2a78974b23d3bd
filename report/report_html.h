// report.html: one self-contained page per run, opened from disk without a server and
// without network access.
//
//   banner        the verdict in one sentence ("2 regions: 1 dent, 1 bump") and every warning
//                 of report.json by severity (report/html/evidence.js);
//   atlas in 3D   three.js (Debian's libjs-three, r111) and its OrbitControls, inlined: rotate,
//                 zoom, click a vertex to read every field there (a ring marks it, of a fixed
//                 size on screen); the field and its colour range are selectable among the
//                 atlas scalars (signed distance, normal deviation per zoom, regions, seen /
//                 observations); each region outlined on the surface and labelled with its id
//                 (report/html/overlays.js);
//   live          the method itself on the reader's GPU (WebGL2, report/html/live.js): both
//                 surfaces, the examined one fitted, rendered as normal-colour frames into
//                 float targets at any view and zoom, s×s sub-samples averaged per pixel,
//                 and their difference (angle, the paper's RGB difference, signed depth);
//   regions       the table of report.json, units in its headings, each region's evidence
//                 sentence and best view by name; a click on a row flies the camera to the
//                 region and shows its best view (the per-view picture, report/pictures.h);
//   evidence      atlas.png; thresholds and floors with their rules, coverage, the fit (mode,
//                 rotation °, translation and its length, RMS in the unit, iterations), units,
//                 inputs; the mosaics.
//
// The style is report/html/glint.css, which the cohort summary's cohort.html inlines too, and
// report.css for what only this page has.
//
// The page's template, script and the libraries are embedded in the binary at build time
// (cmake/GlintEmbed.cmake; sources in report/html/). The meshes go in as base64
// little-endian typed arrays (float32 positions, int16 normals scaled by 32767, uint32
// indices, float32 per-vertex fields), pictures as base64 PNG data URIs: only the regions'
// best views, the mosaics and atlas.png (a fixed-size picture), so the size stays bounded (about 0.9 MB of libraries + 56 bytes
// per reference vertex + 16 per reference triangle for one zoom, + 24 per examined vertex and
// 16 per examined triangle for the live view, plus the pictures). A surface of more than
// kReportPageTriangles is shown decimated (mesh/decimate.h): the triangles touching a region
// (on the examined surface: near one) stay as they are, the rest is collapsed to the budget;
// the decimated vertices are vertices of the input, so their normals are the ones the sweep
// rendered; the page names vertices by their ids in the atlas files. With `#selftest`
// appended to its URL the page checks itself and writes a JSON verdict into the element
// #selftest-verdict (tests/tools/report_html_check.py).
#pragma once

#include "analysis/analysis.h"
#include "mesh/mesh.h"
#include "report/pictures.h"

#include <memory>
#include <string>

namespace glint {

/// Triangles the page shows at most (about: the triangles touching a region are all kept).
/// note: 250 000 triangles make a page of ~10 MB that browsers open in a second; a
/// 2M-triangle atlas shown whole made 81 MB.
inline constexpr std::size_t kReportPageTriangles = 250000;

/// The examined surface as the page's live view shows it: the fitted mesh (reference
/// coordinates) with the vertex normals the sweep rendered; above the budget decimated, the
/// triangles near a region of any zoom kept as they are.
struct LiveSurface {
    Mesh mesh;                  ///< positions, triangles, normals only
    std::size_t triangles = 0;  ///< of the mesh it was made from
    double error = 0.0;         ///< the simplifier's error estimate, mesh units (0: whole)
    [[nodiscard]] bool is_decimated() const { return mesh.triangle_count() != triangles; }
};

/// The live view's examined surface from the fitted mesh analyse() hands its observer
/// (AnalysisObserver::fitted); without normals, with those the renderer makes. A triangle is
/// kept whole when one of its vertices lies within two cells of 1 % of the size from a region
/// vertex of the reference.
/// \pre result decided (its decisions set) on `reference`.
[[nodiscard]] LiveSurface live_examined(const Mesh& fitted, const Mesh& reference,
                                        const AnalysisResult& result,
                                        std::size_t max_triangles = kReportPageTriangles);

/// What the page shows of the analysis itself: the mesh (decimated when large), its fields and
/// the colour maps, and the live view's examined surface when given. The slow part of the page for a large mesh (the decimation: 0.9 s at 2M
/// triangles), independent of the pictures, so it is made while they render (report/report.cpp).
struct ReportPageData {
    struct Parts;
    std::shared_ptr<Parts> parts;
};

/// `examined` null: the page's live view says that the run kept no examined surface.
/// \pre result from analyse() on `reference`.
[[nodiscard]] ReportPageData report_page_data(const Mesh& reference, const AnalysisResult& result,
                                              const LiveSurface* examined,
                                              std::size_t max_triangles = kReportPageTriangles);

/// The page from its data (consumed: its mesh arrays move into the page, not copied),
/// report.json's text (embedded whole) and the pictures.
[[nodiscard]] std::string report_html(ReportPageData data, const std::string& report_json,
                                      const PictureOutput& pictures);

/// The page for a finished analysis, in one call (report_page_data, then report_html).
/// \pre result from analyse() on `reference`.
[[nodiscard]] std::string report_html(const Mesh& reference, const AnalysisResult& result,
                                      const LiveSurface* examined, const std::string& report_json,
                                      const PictureOutput& pictures,
                                      std::size_t max_triangles = kReportPageTriangles);

/// Replaces every @NAME@ (capitals, digits, _) of `page_template` by values[NAME], in one pass:
/// inserted text is never scanned again. \throw std::logic_error for a name without a value.
[[nodiscard]] std::string fill_template(
    std::string_view page_template, const std::vector<std::pair<std::string, std::string>>& values);

/// `text` with &, <, > and " as character references: safe inside HTML and XML elements and
/// double-quoted attributes (report.html, the Slicer module's XML).
[[nodiscard]] std::string escape_markup(const std::string& text);

}  // namespace glint
