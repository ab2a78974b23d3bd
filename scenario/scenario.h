// Scenarios: a TOML file that says which surfaces, which damage, which misalignment, which
// sweep and what outcome is expected, so that a run can be repeated, shared and scored.
// The format is documented in docs/inputs.md ("Scenario files"); every key is checked: an unknown
// key or a wrong type is an InputError naming the file, the key, its line and what was
// expected.
#pragma once

#include "analysis/analysis.h"
#include "mesh/damage.h"
#include "mesh/geometry.h"
#include "mesh/mesh.h"
#include "mesh/phantom.h"
#include "report/export_options.h"
#include "scenario/asymmetry_scenario.h"
#include "volume/edit.h"
#include "volume/surface.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace glint {

/// A partial scan or a field of view: a surface keeps the side of a plane that `normal` points
/// to (scenario/detail/partial_scan.h), given in the reference's frame.
struct ScanCut {
    Vec3d point{0, 0, 0};
    Vec3d normal{1, 0, 0};
};

/// How one scan of a volume pair is acquired from the noiseless volume
/// (scenario/detail/ct_acquisition.h).
struct Acquisition {
    std::optional<Vec3d> voxel_size;  ///< mm; unset: the volume's own grid
    double noise = 0.0;               ///< σ of Gaussian noise per voxel (the volume's values)
    std::uint32_t noise_seed = 1;
    double noise_correlation = 0.0;  ///< mm (volume/acquisition.h); 0: white
    double psf_fwhm = 0.0;           ///< mm, the scanner's blur; 0: none
    [[nodiscard]] bool any() const { return voxel_size.has_value() || noise > 0 || psf_fwhm > 0; }
};

/// Where a surface comes from: a phantom or a mesh file.
struct SurfaceSource {
    std::optional<PhantomOptions> phantom;
    std::filesystem::path mesh;    ///< resolved path (relative to the scenario or the data root)
    std::string mesh_as_written;   ///< as written in the file
    bool needs_data_root = false;  ///< path was resolved against the data root
    /// For a volume file (keys iso, surface_roi, largest, surface_seed, smooth, passband, edge,
    /// tolerance): how its surface is extracted. An examined volume without iso takes the
    /// reference's options.
    SurfaceOptions surface;
    /// keep_side = [x, y, z, nx, ny, nz]: only that side is kept (a partial scan, a field of
    /// view); an examined cut needs an examined surface derived from the reference.
    std::optional<ScanCut> cut;
    /// [reference] crop_ball = [x, y, z, r]: the reference keeps only its part inside the ball
    /// (a reference cropped around one condyle) after the examined surface was derived from the
    /// whole; the examined covers more than the reference (issue 53).
    std::optional<Eigen::Vector4d> crop_ball;
    Acquisition acquisition;  ///< a volume pair's scan: its noise and voxel size
    /// [reference] scan_as_ct = true: the mesh or phantom is a solid that both scans image as CT
    /// (scenario/ct_of_mesh.h), each with its acquisition; ct_values = [outside, inside].
    bool scan_as_ct = false;
    float ct_background = 1040.0f;
    float ct_object = 1800.0f;
};

struct ScenarioExpect {
    std::optional<std::size_t> regions;  ///< exact region count (zoom 0)
    std::optional<std::size_t> min_regions;
    std::optional<std::size_t> max_regions;
    std::optional<double> min_iou;
    std::optional<double> min_f1;
    std::optional<double> min_precision;
    std::optional<double> min_recall;
    std::optional<double> max_rotation_error_deg;
    std::optional<double> max_translation_error;
    std::optional<double> max_scale_error;  ///< |fitted − true| examined scale
    /// Some warning of the run contains this text (a fit that should say what it saw).
    std::optional<std::string> warning;
    std::optional<double> max_centroid_error;
    std::optional<double> min_coverage;
    /// "dent", "bump" or "missing surface" for the largest region
    std::optional<std::string> kind;
    /// The kind of every region (zoom 0): worn-away surface is a loss everywhere.
    std::optional<std::string> every_kind;
    /// The first listed region's kind (zoom 0): "surface gone" (a loss in a hole, listed
    /// first), "dent", "bump" or "missing surface"; its area between these bounds (mesh
    /// units²) and at least this volume lost (mesh units³).
    std::optional<std::string> first_kind;
    std::optional<double> min_first_area;
    std::optional<double> max_first_area;
    std::optional<double> min_first_volume_lost;
    /// Every region (zoom 0) whose significance was stated (Region::p_value, read at a scale)
    /// stands out at least this strongly: its family-wise p at most this.
    std::optional<double> max_p_value;
    /// At least this share of the reference's area compared (decision/comparison.h).
    std::optional<double> min_compared;
    /// At most this share compared: a partial scan must say that it covers only a part.
    std::optional<double> max_compared;
    /// Every region (zoom 0) must be explained by a real change of shape: somewhere in it the
    /// reference lies at least this far (mesh units) from the examined surface. For pairs that
    /// differ where a decimation or a re-meshing really moved the surface.
    std::optional<double> min_region_shape_change;
    /// Real-data pairs: regions that hold no damaged vertex (truth needed).
    std::optional<std::size_t> max_false_regions;
    bool all_damages_detected = false;  ///< every damage touched by a region
    /// Pairs without labels (two scans of one surface): region vertices whose true distance to
    /// the examined surface is below region_min_true_distance count as false.
    std::optional<std::size_t> max_close_region_vertices;
    double region_min_true_distance = 0.1;
    AsymmetryExpect asymmetry;  ///< asymmetry = true: findings, plane, no_plane
};

struct Scenario {
    std::filesystem::path file;
    std::string name;
    std::string description;
    std::vector<std::string> tags;  ///< "ci", "full", "data", …
    SurfaceSource reference;
    /// Examined: a file, or derived from the reference (re-tessellated phantom and/or damage,
    /// noise, pose). A derived examined mesh has exact ground truth on the reference.
    SurfaceSource examined;  ///< mesh or phantom; empty = the reference
    bool examined_derived = true;
    std::vector<DamageSpec> damages;
    double noise_sigma = 0.0;
    std::uint32_t noise_seed = 1;
    Rigid pose = Rigid::Identity();  ///< examined = pose · (damaged surface)
    /// Re-tessellation of a reference mesh file (mesh/remesh.h): target edge = remesh × the
    /// reference's median edge; vertices lie on the reference surface.
    std::optional<double> remesh;
    int remesh_iterations = 3;
    bool shuffle = false;  ///< shuffle vertex and triangle order
    /// reverse_winding = true: every examined triangle wound the other way (inside out, as
    /// some STL exporters write it), applied before the pose
    bool reverse_winding = false;
    /// scale = k: the examined surface k times its size (about the origin, after the pose), as
    /// a scanner calibrated k apart would see it (issue 53)
    double examined_scale = 1.0;
    /// as_mesh_files = true (a volume pair): both extracted surfaces are handed on as mesh files
    /// exported from a segmentation would be (STL, PLY: vertices and triangles only), without
    /// the grid, field of view and contrast flags a volume's surface carries (issue 50)
    bool as_mesh_files = false;
    std::uint32_t shuffle_seed = 1;
    /// The plain distance threshold glint's decision is compared with (mesh units); default
    /// 10 % of the smallest damage depth.
    std::optional<double> baseline_distance;
    /// A volume reference: the examined scan is the reference volume resampled under `pose`
    /// about `pivot` ([examined] pivot = [x, y, z]) with erosions ([examined] erode =
    /// [x, y, z, r], erode_to = value), its surface cut with the reference's options.
    /// Without pivot or erode, a volume reference's examined surface is derived from the
    /// reference mesh like any other (pose, [[damage]], noise), no resampling.
    Vec3d pivot{0, 0, 0};
    std::vector<Erosion> erosions;
    bool resample_volume = false;  ///< pivot or erode given
    /// Per-vertex ground-truth mask on the *reference* from a file (tooth-wear .npy masks).
    std::filesystem::path truth_mask;
    /// A range scan's ground-truth pose from a Stanford .conf file ([examined]
    /// truth_pose_conf, truth_pose_entry; scenario/pose_conf.h): sets pose.
    std::filesystem::path truth_pose_conf;
    bool truth_pose_conf_needs_data_root = false;
    std::string truth_pose_entry;
    /// The analysis: [registration] (fit mode register by default; "truth" uses the known
    /// pose), [sweep], [threshold] and [decision], with the command line's defaults.
    AnalysisOptions analysis;
    /// [exports]: what a run writes (pictures, views, atlas files, which way is up); the run's
    /// --views and --no-pictures add to it. Its output folder is the run's.
    ExportOptions exports;
    /// asymmetry = true: the examined surface (derived from the reference) is compared with its
    /// own mirror image instead (scenario/asymmetry_scenario.h).
    AsymmetrySpec asymmetry;
    ScenarioExpect expect;
};

/// Parses and checks a scenario file. `data_root` resolves mesh paths that are not found
/// relative to the scenario file. \throw InputError (file, key, line, expected), IoError.
[[nodiscard]] Scenario load_scenario(const std::filesystem::path& file,
                                     const std::filesystem::path& data_root);

/// The meshes of a scenario, built and ready to compare.
struct ScenarioMeshes {
    Mesh reference;
    Mesh examined;  ///< in its own (posed) coordinates
    Rigid true_reference_from_examined = Rigid::Identity();
    /// reference = true_reference_from_examined × (true_examined_scale × examined)
    double true_examined_scale = 1.0;
    bool has_truth_pose = false;
    std::vector<std::uint8_t> truth;  ///< per reference vertex: 1 = damaged (empty if none)
    std::vector<std::int32_t>
        truth_damage;  ///< per reference vertex: 1-based damage id (derived pairs)
    /// Per reference vertex: distance to the examined surface placed back with the true pose,
    /// before noise (derived pairs; mesh-file pairs whose frames agree). Empty when unknown.
    std::vector<float> true_distance;
    std::vector<std::string> notes;
};

/// Builds the reference and examined meshes and the ground truth.
/// \throw InputError a damage outside the surface, a missing mesh, a bad mask.
[[nodiscard]] ScenarioMeshes build_scenario_meshes(const Scenario& scenario);

/// Reads a NumPy .npy boolean/uint8 vector (v1.0/2.0, '|b1' or '|u1', C order).
/// \throw InputError naming the file and what is wrong.
[[nodiscard]] std::vector<std::uint8_t> read_npy_mask(const std::filesystem::path& path);

}  // namespace glint
