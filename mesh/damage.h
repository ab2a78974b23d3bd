// Synthetic damage with exact ground truth, on any mesh (phantoms and real meshes alike).
//
// Each damage displaces vertices along their normals and records, per vertex:
//   labels[v]            = id of the damage that moved v most (1-based), 0 = untouched
//   scalar "gt_displacement" = signed displacement along the normal (negative = loss/dent)
//   scalar "gt_label"        = labels as float (so PLY viewers show it as a scalar field)
// A vertex counts as damaged when |displacement| > kDamageLabelThreshold × depth of its damage.
#pragma once

#include "mesh/geometry.h"
#include "mesh/mesh.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace glint {

enum class DamageKind {
    Dent,     ///< smooth inward radial bump (negative depth = loss)
    Bump,     ///< smooth outward radial bump
    Pit,      ///< steep narrow hole: flat-bottomed with a short smooth wall
    Groove,   ///< scratch along a polyline path, smooth cross-section
    Flatten,  ///< planar cut: vertices beyond a plane are pushed onto it, blended at the rim
    Erosion,  ///< rough loss: dent modulated by seeded value noise
    Noise,    ///< global Gaussian noise along normals (not counted as damage in labels)
};

/// One damage. Positions are in mesh coordinates.
struct DamageSpec {
    DamageKind kind = DamageKind::Dent;
    Vec3d center{0, 0, 0};    ///< projected onto the surface (closest point) when applied
    double radius = 1.0;      ///< footprint radius on the surface (mesh units)
    double depth = 0.1;       ///< magnitude of displacement (mesh units, > 0)
    std::vector<Vec3d> path;  ///< Groove: polyline (center unused); ≥ 2 points
    /// Flatten: outward normal of the cutting plane, which passes `depth` below the surface
    /// point nearest `center`; unset: the surface's normal there (a flattening of the surface
    /// as it faces, whatever its orientation in space).
    std::optional<Vec3d> plane_normal;
    double sigma = 0.01;     ///< Noise: standard deviation (mesh units)
    std::uint32_t seed = 1;  ///< Erosion / Noise
};

/// Fraction of a damage's depth above which a vertex is labelled damaged.
/// note: 10 %, the ground-truth rule of the real-data pairs (scenario/pair_truth): a vertex
/// is damaged where the surface moved by more than a tenth of the damage's depth. The decision
/// measures a region's extent the same way (decision/decision.h, fused rule step 4); the flank
/// beyond it still tilts the normals by a few degrees, but moves the surface by less than a
/// tenth of the depth.
inline constexpr double kDamageLabelThreshold = 0.1;

/// Applies damages in order to a mesh (normals must be present; recomputed afterwards).
/// Adds/updates labels and the scalars "gt_displacement" and "gt_label".
/// \throw InputError radius/depth/sigma not > 0, groove path < 2 points, a center farther than
///        `radius` from the surface ("damage outside the surface").
void apply_damage(Mesh& mesh, const std::vector<DamageSpec>& damages);

/// Parses a damage spec into a DamageSpec. Syntax:
///   KIND[:KEY=VALUE[;KEY=VALUE]…]
///   KIND  dent | bump | pit | groove (alias scratch) | flatten (alias flattening) | erosion | noise
///   center=x,y,z        damage centre, mesh units (projected onto the surface)
///   radius=R            footprint radius (> 0)
///   depth=D             displacement magnitude (> 0); flatten: plane depth below the surface
///   path=x,y,z/x,y,z/…  groove polyline, ≥ 2 points
///   normal=x,y,z        flatten: outward normal of the cutting plane
///   sigma=S             noise: standard deviation along normals (> 0)
///   seed=N              erosion / noise: random seed
/// Omitted keys keep DamageSpec's defaults; empty items (";;") are skipped.
/// Example: "dent:center=0,0,10;radius=2;depth=0.3", "groove:path=-3,0,10/3,0,10;radius=0.5;depth=0.2".
/// \throw InputError naming the spec, the key and what was expected.
[[nodiscard]] DamageSpec parse_damage_spec(const std::string& text);

/// A rigid pose given as "rx,ry,rz,tx,ty,tz" (rotation vector in degrees about x,y,z applied in
/// that order, then translation) or "axis=x,y,z;angle=deg;t=x,y,z". \throw InputError.
[[nodiscard]] Rigid parse_pose_spec(const std::string& text);

[[nodiscard]] std::string to_string(DamageKind kind);

}  // namespace glint
