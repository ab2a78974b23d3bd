// The mirror (mid-sagittal) symmetry plane of one surface (issue 27: left–right asymmetry from
// one scan).
//
//   hypotheses: the three principal axes through the area centroid, each a candidate normal
//       │
//   reflect the surface about the candidate (winding flipped, so normals stay outward)
//       │
//   robust ICP (registration/icp.h) of the reflection onto the surface: T
//       │
//   A = T · S is an improper motion (a reflection when the surface is symmetric): the plane's
//   normal is the eigenvector of A's linear part with eigenvalue −1, its point the midpoint of
//   the centroid and its image; refined by reflecting about that plane and fitting again
//
// The ICP's robust loss keeps a one-sided change (and its mirror image) from pulling the plane;
// an ROI restricts the fit to a stable region. A surface that no plane maps onto itself (the
// bunny) gets a verdict, not a forced plane.
#pragma once

#include "mesh/mesh.h"
#include "mesh/roi.h"
#include "registration/icp.h"

#include <optional>
#include <string>
#include <vector>

namespace glint {

/// The plane {x : normal·x = offset}; normal unit.
struct SymmetryPlane {
    Vec3d normal{1, 0, 0};
    double offset = 0.0;

    /// The point of the plane nearest the origin.
    [[nodiscard]] Vec3d point() const { return offset * normal; }
    /// Signed distance of `p` from the plane (positive on the normal's side).
    [[nodiscard]] double distance(const Vec3d& p) const { return normal.dot(p) - offset; }
    /// The reflection about the plane (an improper motion: determinant −1).
    [[nodiscard]] Eigen::Affine3d reflection() const;
};

/// A plane through `point` with normal `normal` (normalised). \throw InputError a zero normal.
[[nodiscard]] SymmetryPlane plane_through(const Vec3d& point, const Vec3d& normal);

/// The plane given by hand (--plane). Syntax:
///   x=C | y=C | z=C                      the plane of that axis at C (mesh units)
///   point=x,y,z;normal=x,y,z             a point and a normal
///   landmarks=x,y,z/x,y,z/x,y,z          three points on the plane (e.g. nasion, basion, a
///                                        midline landmark)
/// \throw InputError naming the text, what was found and what was expected.
[[nodiscard]] SymmetryPlane parse_plane_spec(const std::string& text);

/// The plane as parse_plane_spec reads it back ("point=…;normal=…").
[[nodiscard]] std::string to_string(const SymmetryPlane& plane);

/// The plane whose reflection is nearest to the improper motion `mirror` (linear part with
/// determinant −1): normal = eigenvector of the symmetric part of the linear part with the
/// eigenvalue nearest −1, through the midpoint of `at` and mirror(at).
[[nodiscard]] SymmetryPlane plane_from_mirror(const Eigen::Affine3d& mirror, const Vec3d& at);

/// The mesh reflected about the plane: positions and normals reflected, every triangle's
/// winding flipped (so the normals stay outward); vertex i of the result is the image of vertex
/// i, and every per-vertex array follows. The field of view and the voxel axes of a surface from
/// a volume are reflected too.
[[nodiscard]] Mesh reflect_mesh(const Mesh& mesh, const SymmetryPlane& plane);

struct SymmetryPlaneOptions {
    /// The ICP of the reflection onto the surface (robust loss, samples, iterations, fit ROI,
    /// seed); its coarse alignment and initial pose are not used (the hypotheses are the start).
    RegistrationOptions registration;
    /// Fit the reflection of the plane found again this many times (each starts from the
    /// reflection about the previous plane, so the last ICP is close to the identity).
    int refinements = 2;
    /// A surface is plausibly symmetric when the fit's residual (RMS of inliers) is at most
    /// `max_relative_residual` of its bounding diagonal and at least `min_overlap` of it finds
    /// its mirror image (registration/icp.h overlap: within 1 % of the size, normals agreeing).
    /// note: measured with the defaults: the jaw (jaw_smooth.obj) re-tessellated and moved by
    /// 10–30° fits at 5e-5 of its size with overlap 100 %; the real CBCT skull
    /// (skull.vtk: open field-of-view borders, 291 components, real anatomy) at 3.7e-3 with 72 %;
    /// the Stanford bunny's best plane at 4.1e-3 with 58 %. The inliers' RMS cannot tell the skull
    /// from the bunny (inliers lie within 1 % of the size by definition); the overlap does, with a
    /// thin margin: 0.65 lies between 0.58 and 0.72. A surface between is better given a plane by
    /// hand (--plane) or a fit region (--fit-roi).
    double max_relative_residual = 5e-3;
    double min_overlap = 0.65;
    /// ... or, when the overlap falls short, at least `min_mirror_share` of it has its mirror
    /// image within the same distance of the surface on either face (mirror_share below).
    /// note: a CT bone surface has thin walls (skull base, maxilla, orbits, vertebrae) whose two
    /// faces lie closer than 1 % of the head: a mirrored sample lands nearer the other face of
    /// the wall, whose normal points the other way, and the overlap does not count it.
    /// Measured (either face; share of it on the other face; overlap): CThead lower head
    /// (--iso 1200, box z 130–226) 90 %, 30 %, 60.5 %; the real CBCT skull 98 %, 25 %, 72 %;
    /// the Stanford bunny 68.5 %, 6 %, 58 %; the chiral test shape 52.5 %, 5 %, 31.5 %; the
    /// jaw 100 %, 0 %, 100 %. 0.8 lies between the bunny and the CT surfaces.
    double min_mirror_share = 0.8;

    /// \throw InputError naming the field, its value and the rule.
    void validate() const;
};

/// One candidate plane, after its fit.
struct SymmetryHypothesis {
    std::string name;  ///< "principal axis 1 (largest spread)", …
    SymmetryPlane plane;
    double rms = 0.0;  ///< the fit's residual (mesh units)
    double overlap = 0.0;
    bool converged = false;
};

struct SymmetryPlaneResult {
    SymmetryPlane plane;
    std::string source;  ///< which hypothesis was kept, or "given"
    double rms = 0.0;    ///< residual of the last fit of the reflection (mesh units)
    double inlier_fraction = 0.0;
    double overlap = 0.0;
    /// Share of the surface (area-uniform samples, inside the fit ROI) whose mirror image lies
    /// within the overlap distance of the surface, on either face, and the share of those
    /// whose nearest surface faces the other way (a thin wall's other face).
    double mirror_share = 0.0;
    double mirror_share_opposite = 0.0;
    double size = 0.0;  ///< bounding diagonal of the surface (mesh units)
    bool converged = false;
    /// The surface is plausibly mirror-symmetric about `plane` (see SymmetryPlaneOptions).
    bool plausible = false;
    /// One sentence: why the plane is or is not plausible, with the numbers.
    std::string verdict;
    std::vector<SymmetryHypothesis> hypotheses;
};

/// Estimates the plane (see the file comment). The mesh needs vertex normals (loaded ones do).
/// \throw InputError invalid options, an empty mesh, an ROI with no surface inside.
[[nodiscard]] SymmetryPlaneResult estimate_symmetry_plane(const Mesh& mesh,
                                                          const SymmetryPlaneOptions& options = {});

/// How symmetric the surface is about a given plane: one robust fit of its reflection,
/// reported the same way (source "given"); the plane itself is kept as given. The residual is
/// the fit's, which may move the reflection: the plane that fit implies is the one hypothesis,
/// to compare with the given one.
[[nodiscard]] SymmetryPlaneResult check_symmetry_plane(const Mesh& mesh, const SymmetryPlane& plane,
                                                       const SymmetryPlaneOptions& options = {});

}  // namespace glint
