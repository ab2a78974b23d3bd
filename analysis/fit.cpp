#include "analysis/fit.h"

#include "analysis/landmarks.h"
#include "analysis/units.h"
#include "mesh/components.h"
#include "mesh/error.h"
#include "mesh/front_end.h"
#include "mesh/json_text.h"
#include "registration/closest_point.h"
#include "registration/fit_io.h"
#include "registration/landmarks.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace glint {

namespace {

// The starting pose from landmark pairs (points kept, picked pixels resolved).
Rigid landmark_start(const Mesh& reference, const Mesh& examined, const std::filesystem::path& file,
                     const std::shared_ptr<const SurfaceIndex>& reference_index) {
    const std::vector<LandmarkPair> pairs = read_landmarks(file.string());
    const std::string source = "landmarks \"" + file.string() + "\"";
    // Indexes only when some side is a picked pixel (building one costs a BVH).
    const bool has_pixels = std::any_of(pairs.begin(), pairs.end(), [](const LandmarkPair& p) {
        return !p.examined.point || !p.reference.point;
    });
    ResolvedLandmarks points;
    if (has_pixels) {
        const ClosestPointIndex ref = reference_index
                                          ? ClosestPointIndex(reference, reference_index)
                                          : ClosestPointIndex(reference);
        points = resolve_landmarks(pairs, ref, ClosestPointIndex(examined), source);
    } else {
        for (const auto& p : pairs) {
            points.examined.push_back(*p.examined.point);
            points.reference.push_back(*p.reference.point);
        }
    }
    try {
        return fit_landmarks(points.examined, points.reference);
    } catch (const InputError& e) {
        throw InputError(source + ": " + e.what());
    }
}

// A motion read from a file must bring the examined surface onto the reference: one that
// leaves it far away (a translation of 1e9 mm, a file of other units or the inverse direction)
// ran a registration for over 200 s, or a sweep that compared nothing for 30 s and then
// misled (issue 52). Refused before any work when the moved examined surface's centre lies
// more than ten sizes (the larger bounding diagonal) from the reference's.
FittedMotion checked_motion(const Mesh& reference, const Mesh& examined, const FittedMotion& motion,
                            const std::string& what, const std::string& file) {
    const Rigid& reference_from_examined = motion.reference_from_examined;
    const Bounds r = bounds(reference), e = bounds(examined);
    const Vec3d moved =
        reference_from_examined * (motion.examined_scale * e.center().cast<double>());
    const double apart = (moved - r.center().cast<double>()).norm();
    const double size = std::max<double>(r.diagonal(), e.diagonal());
    if (!reference_from_examined.matrix().allFinite() || !(apart <= 10.0 * size))
        throw InputError(what + " \"" + file + "\": moves the examined surface's centre " +
                         std::to_string(apart) +
                         " mesh units from the reference's, more than ten " + "times their size (" +
                         std::to_string(size) +
                         "); expected a motion that brings it onto the reference (check the "
                         "file's units and that it maps examined to reference)");
    return motion;
}

// A rigid fit between two scanners of different calibration leaves the signed distance growing
// with the distance from the centre: said, with the scale it measures, and the remedy.
void warn_of_scale_trend(const RegistrationResult& r, const RegistrationOptions& o,
                         std::vector<std::string>& warnings) {
    if (o.fit_scale || !r.converged) return;
    const double trend = r.scale_trend, se = r.scale_trend_uncertainty;
    if (!(std::abs(trend) >= kScaleTrendWarning && std::abs(trend) >= kScaleTrendSignificance * se))
        return;
    char line[400];
    std::snprintf(line, sizeof line,
                  "the rigid fit leaves a scale-like pattern: the signed distance grows with the "
                  "distance from the centre as if the examined surface were %.2f %% %s (scale "
                  "%.4f ± %.2g); scanners calibrated apart? give %s to fit the scale",
                  100.0 * std::abs(trend), trend < 0 ? "too large" : "too small", 1.0 + trend, se,
                  spell_flag("fit_scale").c_str());
    warnings.emplace_back(line);
}

FitOutcome register_examined(const Mesh& reference, const Mesh& examined, const FitOptions& options,
                             const std::shared_ptr<const SurfaceIndex>& reference_index) {
    RegistrationOptions o = options.registration;
    RegistrationSources sources;
    if (o.roi && o.roi->needs_mask()) read_roi_mask(*o.roi, reference.vertex_count());
    if (!options.init_file.empty()) {
        const FittedMotion m =
            checked_motion(reference, examined, read_fit(options.init_file.string()),
                           "initial pose", options.init_file.string());
        o.initial = m.reference_from_examined;
        o.initial_scale *= m.examined_scale;
        sources.init_file = options.init_file.string();
    }
    if (!options.landmarks_file.empty()) {
        o.initial = landmark_start(reference, examined, options.landmarks_file, reference_index);
        sources.landmarks_file = options.landmarks_file.string();
    }
    FitOutcome out;
    out.mode = FitMode::Register;
    const RegistrationResult r = register_meshes(reference, examined, o, reference_index);
    out.reference_from_examined = r.reference_from_examined;
    out.examined_scale = r.examined_scale;
    out.converged = r.converged;
    out.json = to_json(r, o, sources);
    out.registration = r;
    if (!r.converged)
        out.warnings.push_back("registration did not converge: " + r.termination_detail);
    warn_of_scale_trend(r, o, out.warnings);
    return out;
}

}  // namespace

FitMode parse_fit_mode(const std::string& text) {
    if (text == "identity") return FitMode::Identity;
    if (text == "file") return FitMode::File;
    if (text == "register") return FitMode::Register;
    if (text == "truth") return FitMode::Truth;
    throw InputError("fit mode \"" + text + "\": expected register, identity, truth or file");
}

std::string to_string(FitMode mode) {
    switch (mode) {
        case FitMode::Identity: return "identity";
        case FitMode::File: return "file";
        case FitMode::Register: return "register";
        case FitMode::Truth: return "truth";
    }
    return "?";
}

void FitOptions::validate() const {
    try {
        registration.validate();
    } catch (const OptionError& e) {
        throw e.prefixed("registration");
    }
    if (mode == FitMode::File && fit_file.empty())
        throw OptionError("registration.mode", "file",
                          "needs a fit file (" + spell_option("fit", "FILE") + ")");
    if (mode != FitMode::File && !fit_file.empty())
        throw OptionError("registration.fit", "\"" + fit_file.string() + "\"",
                          "a fit file is given but the fit mode is " + to_string(mode));
    // note: both would set the starting pose; composing them (landmarks picked on an
    // already-moved mesh?) has no single obvious meaning, so the user must choose.
    if (!landmarks_file.empty() && !init_file.empty())
        throw OptionError("registration.landmarks", "\"" + landmarks_file.string() + "\"",
                          "landmarks and an initial pose \"" + init_file.string() +
                              "\" both set the starting pose: give one of them");
    if ((!landmarks_file.empty() || !init_file.empty()) && mode != FitMode::Register)
        throw OptionError("registration.mode", to_string(mode),
                          "landmarks and an initial pose start a registration (mode register, " +
                              spell_flag("register") + ")");
}

FitOutcome fit_examined(const Mesh& reference, const Mesh& examined, const FitOptions& options,
                        const std::shared_ptr<const SurfaceIndex>& reference_index) {
    options.validate();
    FitOutcome out;
    out.mode = options.mode;
    switch (options.mode) {
        case FitMode::Identity:
            out.json =
                R"({"mode": "identity", "note": "the meshes were taken as already aligned"})";
            out.warnings.push_back("no fit requested (" + spell_option("fit", "FILE") + " or " +
                                   spell_flag("register") +
                                   "): the meshes are taken as already aligned");
            return out;
        case FitMode::Truth: {
            out.reference_from_examined = options.truth;
            out.examined_scale = options.truth_scale;
            RegistrationResult r;
            r.reference_from_examined = options.truth;
            r.examined_scale = options.truth_scale;
            r.examined_from_reference = options.truth.inverse();
            r.converged = true;
            r.termination = "known transform (scenario ground truth)";
            out.json = to_json(r, options.registration);
            out.registration = r;
            return out;
        }
        case FitMode::File: {
            const FittedMotion m =
                checked_motion(reference, examined, read_fit(options.fit_file.string()), "fit",
                               options.fit_file.string());
            out.reference_from_examined = m.reference_from_examined;
            out.examined_scale = m.examined_scale;
            out.json = R"({"mode": "file", "path": ")" + options.fit_file.string() +
                       "\", \"examined_scale\": " + json_text(m.examined_scale) + "}";
            return out;
        }
        case FitMode::Register:
            return register_examined(reference, examined, options, reference_index);
    }
    return out;
}

void apply_fit(Mesh& examined, const FitOutcome& fit) {
    scale_examined(examined, fit.examined_scale);
    transform_mesh(examined, fit.reference_from_examined);
}

namespace {

// Per vertex of a mesh: the longest edge at it (h) and its sharpness θ, the largest angle
// between its vertex normal and the normals of the triangles around it (radians).
struct LocalShape {
    std::vector<float> edge;
    std::vector<float> sharpness;
};

LocalShape local_shape(const Mesh& m) {
    LocalShape out{std::vector<float>(m.vertex_count(), 0.0f),
                   std::vector<float>(m.vertex_count(), 0.0f)};
    // note: the largest angle is the arc cosine of the smallest cosine (acos decreases): one
    // acos per vertex instead of one per corner, the same value.
    std::vector<float> min_cos(m.vertex_count(), 1.0f);
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
        const auto& tri = m.triangles[t];
        const Vec3f n = face_normal(m, t);
        for (std::size_t k = 0; k < 3; ++k) {
            const auto a = tri[k], b = tri[(k + 1) % 3];
            const float h = (m.positions[a] - m.positions[b]).norm();
            out.edge[a] = std::max(out.edge[a], h);
            out.edge[b] = std::max(out.edge[b], h);
            if (n.squaredNorm() == 0.0f) continue;  // a degenerate triangle has no direction
            min_cos[a] = std::min(min_cos[a], std::clamp(m.normals[a].dot(n), -1.0f, 1.0f));
        }
    }
    for (std::size_t v = 0; v < m.vertex_count(); ++v) out.sharpness[v] = std::acos(min_cos[v]);
    return out;
}

// How far the examined surface bulges out of its flat triangle at the closest point, along the
// triangle's outward normal: Phong tessellation (each corner's tangent plane, blended by the
// barycentric weights, shape factor 3/4) stands in for the smooth surface the triangle is a
// chord of. The examined vertices lie on the surface, its flat interiors do not: on a convex
// part a reference vertex lies outside the chord by about its sagitta.
double curved_offset(const Mesh& exa, const Triangle& t, const ClosestPoint& c) {
    constexpr double kShape = 0.75;
    const Vec3d& p = c.point;
    Vec3d blended{0, 0, 0};
    for (std::size_t k = 0; k < 3; ++k) {
        const Vec3d corner = exa.positions[t[k]].cast<double>();
        const Vec3d n = exa.normals[t[k]].cast<double>();
        blended += c.barycentric[static_cast<Eigen::Index>(k)] * (p - (p - corner).dot(n) * n);
    }
    const Vec3d a = exa.positions[t[0]].cast<double>(), b = exa.positions[t[1]].cast<double>(),
                d = exa.positions[t[2]].cast<double>();
    const Vec3d face = (b - a).cross(d - a);
    if (face.squaredNorm() == 0.0) return 0.0;
    return kShape * (blended - p).dot(face.normalized());
}

}  // namespace

ShapeEvidence measure_shape(const Mesh& reference, const Mesh& fitted_examined,
                            const std::shared_ptr<const SurfaceIndex>& examined_index) {
    GLINT_ASSERT(reference.has_normals(), "shape evidence needs the reference's vertex normals");
    const ClosestPointIndex index = examined_index
                                        ? ClosestPointIndex(fitted_examined, examined_index)
                                        : ClosestPointIndex::borrowing(fitted_examined);
    const Mesh& exa = index.mesh();  // with normals (the index computes them when absent)
    const std::size_t n = reference.vertex_count();
    const auto border = border_vertices(exa);
    const LocalShape ref_shape = local_shape(reference);
    const LocalShape exa_shape = local_shape(exa);
    ShapeEvidence e;
    e.distance.resize(n);
    e.tolerance.resize(n);
    e.at_border.assign(n, 0);
    e.facing_away.assign(n, 0);
    // note: each vertex's closest point is used where it is found, not gathered first: a
    // ClosestPoint is 112 bytes, 112 MB at 1M vertices on top of the index at this stage's
    // peak (issue 13: peak memory at 2M triangles). Chunks of 512 neighbouring vertices keep
    // the BVH nodes they visit in cache (as ClosestPointIndex::closest does).
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, n, 512),
        [&](const tbb::blocked_range<std::size_t>& range) {
            for (std::size_t v = range.begin(); v != range.end(); ++v) {
                const ClosestPoint c = index.closest(reference.positions[v].cast<double>());
                // A reference vertex outside the examined surface (positive) means the examined
                // surface lies inside: a loss. Negate so that negative = loss, as in the atlas.
                const auto& t = exa.triangles[c.triangle];
                e.distance[v] = static_cast<float>(-(c.signed_distance - curved_offset(exa, t, c)));
                // The examined triangle's size decides how far it can cut a corner of the reference
                // (its vertices lie on the surface, its interior does not); the sharper of the two
                // surfaces there decides how much it turns.
                float h = 0.0f, theta = ref_shape.sharpness[v];
                for (const auto corner : t) {
                    h = std::max(h, exa_shape.edge[corner]);
                    theta = std::max(theta, exa_shape.sharpness[corner]);
                }
                e.tolerance[v] = static_cast<float>(kTessellationTolerance) * h * theta;
                // On the border: every corner the closest point depends on is a border vertex.
                // note: 1e-9 separates a true zero barycentric weight from rounding.
                bool on_border = c.feature != ClosestFeature::Face;
                for (std::size_t k = 0; k < 3 && on_border; ++k)
                    if (c.barycentric[static_cast<Eigen::Index>(k)] > 1e-9 && !border[t[k]])
                        on_border = false;
                e.at_border[v] = on_border ? 1 : 0;
                const Vec3d ea = exa.positions[t[0]].cast<double>();
                const Vec3d face = (exa.positions[t[1]].cast<double>() - ea)
                                       .cross(exa.positions[t[2]].cast<double>() - ea);
                e.facing_away[v] = face.dot(reference.normals[v].cast<double>()) < 0.0 ? 1 : 0;
            }
        });
    return e;
}

}  // namespace glint
