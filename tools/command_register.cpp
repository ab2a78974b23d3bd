// glint register REF EXA … -o fit.json: rigid fit of the examined mesh onto the reference.
#include "mesh/atomic_file.h"
#include "mesh/error.h"
#include "mesh/io.h"
#include "mesh/write.h"
#include "registration/closest_point.h"
#include "registration/icp.h"
#include "scanner/landmarks.h"
#include "tools/command.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>

namespace glint::cli {
namespace {

struct RegisterArgs {
    std::string reference;
    std::string examined;
    std::string roi;
    std::string roi_mask;
    std::string landmarks;
    std::string init;
    std::string loss = "cauchy";
    int samples = 20000;
    int max_iterations = 60;
    bool symmetric = false;
    bool no_coarse = false;
    std::string output;
    std::string apply;
};

void run(const RegisterArgs& a) {
    RegistrationOptions o;
    o.loss = parse_loss(a.loss);
    o.samples = a.samples;
    o.max_iterations = a.max_iterations;
    o.symmetric = a.symmetric;
    o.coarse = !a.no_coarse;
    if (!a.roi.empty()) o.roi = parse_registration_roi(a.roi);
    o.validate();
    // note: both would set the starting pose; composing them (landmarks picked on an
    // already-moved mesh?) has no single obvious meaning, so the user must choose.
    if (!a.landmarks.empty() && !a.init.empty())
        throw InputError("--landmarks \"" + a.landmarks + "\" and --init \"" + a.init +
                         "\" both set the starting pose: give one of them");
    RegistrationSources sources;
    const LoadedMesh ref = load_mesh(a.reference);
    const LoadedMesh exa = load_mesh(a.examined);
    if (!a.roi_mask.empty()) {
        // FILE.ply[:SCALAR]: a mesh with the reference's vertices whose labels (or the named
        // scalar) are non-zero on the stable region.
        const auto colon = a.roi_mask.rfind(':');
        const bool named = colon != std::string::npos && colon > 1;
        const std::string file = named ? a.roi_mask.substr(0, colon) : a.roi_mask;
        const std::string field = named ? a.roi_mask.substr(colon + 1) : "";
        LoadOptions keep;
        keep.weld = keep.drop_degenerate = keep.drop_unused = false;
        const LoadedMesh mask = load_mesh(file, keep);
        if (mask.mesh.vertex_count() != ref.mesh.vertex_count())
            throw InputError("--roi-mask \"" + file + "\": " + std::to_string(mask.mesh.vertex_count()) +
                             " vertices, the reference has " + std::to_string(ref.mesh.vertex_count()));
        o.roi.shape = RegistrationRoi::Shape::VertexMask;
        sources.roi_mask_file = file;
        sources.roi_mask_property = field.empty() ? "label" : field;
        if (field.empty()) {
            if (mask.mesh.labels.empty())
                throw InputError("--roi-mask \"" + file + "\": no 'label' property; name a scalar as FILE:SCALAR");
            for (auto l : mask.mesh.labels) o.roi.vertex_mask.push_back(l != 0);
        } else {
            const ScalarField* s = mask.mesh.find_scalar(field);
            if (!s) throw InputError("--roi-mask \"" + file + "\": no scalar '" + field + "'");
            for (float x : s->values) o.roi.vertex_mask.push_back(x != 0.0f);
        }
    }
    if (!a.init.empty()) {
        o.initial = read_fit(a.init);
        sources.init_file = a.init;
    }
    if (!a.landmarks.empty()) {
        const std::vector<LandmarkPair> pairs = read_landmarks(a.landmarks);
        sources.landmarks_file = a.landmarks;
        const std::string source = "landmarks \"" + a.landmarks + "\"";
        // Indexes only when some side is a picked pixel (building one costs a BVH).
        const bool has_pixels = std::any_of(pairs.begin(), pairs.end(), [](const LandmarkPair& p) {
            return !p.examined.point || !p.reference.point;
        });
        ResolvedLandmarks points;
        if (has_pixels) {
            points = resolve_landmarks(pairs, ClosestPointIndex(ref.mesh), ClosestPointIndex(exa.mesh), source);
        } else {
            for (const auto& p : pairs) {
                points.examined.push_back(*p.examined.point);
                points.reference.push_back(*p.reference.point);
            }
        }
        try {
            o.initial = fit_landmarks(points.examined, points.reference);
        } catch (const InputError& e) {
            throw InputError(source + ": " + e.what());
        }
    }
    const RegistrationResult r = register_meshes(ref.mesh, exa.mesh, o);
    write_file_atomically(a.output, to_json(r, o, sources));
    if (!a.apply.empty()) {
        Mesh moved = exa.mesh;
        transform_mesh(moved, r.reference_from_examined);
        write_mesh(moved, a.apply);
    }
    if (global_flags().json) {
        std::cout << to_json(r, o, sources);
    } else if (!global_flags().quiet) {
        std::printf("%s after %d iterations (%s start): rotation %.6f°, translation (%.6g, %.6g, %.6g), RMS %.4g, "
                    "inliers %.1f%%, overlap %.1f%%; wrote %s\n",
                    r.converged ? "converged" : "did NOT converge", r.iterations, r.coarse.c_str(),
                    rotation_angle_deg(r.reference_from_examined), r.reference_from_examined.translation().x(),
                    r.reference_from_examined.translation().y(), r.reference_from_examined.translation().z(), r.rms,
                    100 * r.inlier_fraction, 100 * r.overlap, a.output.c_str());
        if (!r.converged) std::printf("  %s\n", r.termination_detail.c_str());
    }
    if (!r.converged) throw CheckFailed("registration did not converge: " + r.termination_detail);
}

void setup(CLI::App& app) {
    static RegisterArgs a;
    auto* cmd = app.add_subcommand("register", "Fit the examined mesh onto the reference (robust ICP)");
    cmd->add_option("REF", a.reference, "Reference mesh")->required();
    cmd->add_option("EXA", a.examined, "Examined mesh")->required();
    cmd->add_option("--roi", a.roi, "Fit only on this stable region of the reference: sphere:x,y,z,r or box:…");
    cmd->add_option("--roi-mask", a.roi_mask, "Fit only where FILE.ply[:SCALAR] (the reference's vertices) has a "
                                               "non-zero label (or scalar)")
        ->excludes("--roi");
    cmd->add_option("--landmarks", a.landmarks, "JSON with ≥ 3 pairs: {\"pairs\": [{\"examined\": SIDE, \"reference\": SIDE}]}, SIDE = [x,y,z] or "
                    "{\"view\": {\"azimuth\": A, \"elevation\": E, \"size\": N}, \"pixel\": [u,v]} (as glint pick)");
    cmd->add_option("--init", a.init, "Start from this fit.json");
    cmd->add_option("--loss", a.loss, "Robust loss: cauchy | huber | tukey | none")->capture_default_str();
    cmd->add_option("--samples", a.samples, "Samples on the examined surface")->capture_default_str();
    cmd->add_option("--max-iterations", a.max_iterations, "ICP iterations")->capture_default_str();
    cmd->add_flag("--symmetric", a.symmetric, "Symmetric ICP (both directions)");
    cmd->add_flag("--no-coarse", a.no_coarse, "Skip the principal-axes hypotheses");
    cmd->add_option("-o,--output", a.output, "fit.json")->required();
    cmd->add_option("--apply", a.apply, "Also write the fitted examined mesh (.ply or .vtk)");
    cmd->callback([] { run(a); });
}

const CommandRegistrar registrar(40, setup);

}  // namespace
}  // namespace glint::cli
