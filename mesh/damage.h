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
#include <string>
#include <vector>

namespace glint {

enum class DamageKind {
    Dent,       ///< smooth inward radial bump (negative depth = loss)
    Bump,       ///< smooth outward radial bump
    Pit,        ///< steep narrow hole: flat-bottomed with a short smooth wall
    Groove,     ///< scratch along a polyline path, smooth cross-section
    Flatten,    ///< planar cut: vertices beyond a plane are pushed onto it, blended at the rim
    Erosion,    ///< rough loss: dent modulated by seeded value noise
    Noise,      ///< global Gaussian noise along normals (not counted as damage in labels)
};

/// One damage. Positions are in mesh coordinates.
struct DamageSpec {
    DamageKind kind = DamageKind::Dent;
    Vec3d center{0, 0, 0};     ///< snapped to the nearest surface vertex when applied
    double radius = 1.0;       ///< footprint radius on the surface (mesh units)
    double depth = 0.1;        ///< magnitude of displacement (mesh units, > 0)
    std::vector<Vec3d> path;   ///< Groove: polyline (center unused); ≥ 2 points
    Vec3d plane_normal{0, 0, 1};  ///< Flatten: outward normal of the cutting plane; the plane
                                  ///< passes at `depth` below the surface point nearest center
    double sigma = 0.01;       ///< Noise: standard deviation (mesh units)
    std::uint32_t seed = 1;    ///< Erosion / Noise
};

/// Fraction of a damage's depth above which a vertex is labelled damaged.
inline constexpr double kDamageLabelThreshold = 0.1;

/// Applies damages in order to a mesh (normals must be present; recomputed afterwards).
/// Adds/updates labels and the scalars "gt_displacement" and "gt_label".
/// \throw InputError radius/depth/sigma not > 0, groove path < 2 points, a center farther than
///        `radius` from the surface ("damage outside the surface").
void apply_damage(Mesh& mesh, const std::vector<DamageSpec>& damages);

/// Parses "dent:center=x,y,z;radius=R;depth=D" style specs (see README) into a DamageSpec.
/// Keys: center, radius, depth, path (x,y,z/x,y,z/…), normal, sigma, seed.
/// \throw InputError naming the spec, the key and what was expected.
[[nodiscard]] DamageSpec parse_damage_spec(const std::string& text);

/// A rigid pose given as "rx,ry,rz,tx,ty,tz" (rotation vector in degrees about x,y,z applied in
/// that order, then translation) or "axis=x,y,z;angle=deg;t=x,y,z". \throw InputError.
[[nodiscard]] Rigid parse_pose_spec(const std::string& text);

[[nodiscard]] std::string to_string(DamageKind kind);

}  // namespace glint
