// Iso-surface extraction from a volume, in physical coordinates (mm).
//
// Pipeline (VTK, behind this header):
//   crop to the ROI's voxels ─▶ flying edges (vtkFlyingEdges3D: marching cubes with linear
//   interpolation along voxel edges, sub-voxel accurate) in index space ─▶ index → physical
//   (origin, direction, spacing) ─▶ triangles outside the ROI dropped
//   (vtkExtractPolyDataGeometry) ─▶ one component kept, the largest or the one nearest a seed
//   point (vtkPolyDataConnectivityFilter) ─▶ windowed-sinc smoothing (vtkWindowedSincPolyData-
//   Filter, a low-pass filter that does not shrink the surface, Taubin 1995) ─▶ decimation to a
//   target edge length with a stated tolerance (meshoptimizer's quadric simplification).
// Triangles are wound so that normals point from the inside (values above iso, bone) out.
#pragma once

#include "mesh/io.h"
#include "mesh/mesh.h"
#include "mesh/roi.h"
#include "volume/volume.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace glint {

struct SurfaceOptions {
    std::optional<double>
        iso;                 ///< iso value in voxel units (CT: HU or the scanner's units); required
    std::optional<Roi> roi;  ///< sphere or box in physical coordinates (mm): only what lies inside
    bool largest = false;    ///< keep only the largest connected component
    std::optional<Vec3d> seed;  ///< keep only the component nearest this physical point (mm)
    int smooth_iterations = 0;  ///< windowed-sinc iterations (0: no smoothing; 10–20 is light)
    double passband = 0.1;      ///< windowed-sinc pass band (0, 2): lower smooths more
    double edge_mm = 0.0;       ///< target mean edge length (mm) after decimation; 0: no decimation
    /// Largest distance (mm) decimation may move the surface; 0: a quarter of the smallest spacing.
    double tolerance_mm = 0.0;
    /// Most triangles the contour may have, checked before flying edges runs (a lower bound
    /// counted from the voxel edges that cross the iso value) and after it; 0: the process'
    /// budget at the time of extraction (default_max_triangles(), the CLI's --max-triangles).
    std::uint64_t max_triangles = 0;

    /// \throw OptionError naming the key (iso, surface_roi, seed, smooth, passband, edge, tolerance).
    void validate() const;
    /// Whether any option beyond `iso` was given (a mesh file takes none of them).
    [[nodiscard]] bool any() const;
};

/// What extraction did: enough to repeat it and to judge it.
struct SurfaceReport {
    std::array<std::size_t, 3> voxels{0, 0, 0};   ///< size of the volume
    std::array<std::size_t, 3> cropped{0, 0, 0};  ///< size of the part contoured (the ROI's voxels)
    Vec3d spacing{1, 1, 1};
    double iso = 0.0;
    std::array<float, 2> range{0.0f, 0.0f};  ///< data range of the volume
    std::size_t components_found = 0;        ///< connected components before selection
    std::size_t components_kept = 0;
    std::size_t contour_triangles = 0;  ///< straight from flying edges (after the ROI)
    std::size_t triangles = 0;          ///< in the result
    std::size_t vertices = 0;
    double decimation_error_mm = 0.0;  ///< meshoptimizer's error estimate (0: none)
    double seconds = 0.0;
    double noise_sigma = 0.0;        ///< the volume's noise σ, estimated (volume/contrast.h)
    std::vector<std::string> notes;  ///< what was done, in words
};

struct ExtractedSurface {
    Mesh mesh;  ///< positions in mm, unit "mm", vertex normals computed
    SurfaceReport report;
};

/// Extracts the iso-surface of a volume. \throw OptionError invalid options; InputError an
/// iso value outside the data range (the message gives the range), a ROI that holds no voxel,
/// an empty result (says which step emptied it); all naming the volume's path.
[[nodiscard]] ExtractedSurface extract_surface(const Volume& volume, const SurfaceOptions& options);

/// A one-line summary of a surface extracted from a volume ("256 x 256 x 113 voxels of …, iso
/// 1250 (data 0 … 3272): 569526 triangles, 1 of 356 component(s), 1.40 s").
[[nodiscard]] std::string describe(const SurfaceReport& report);

}  // namespace glint
