// fit.json: the registration result with its evidence and the options that reproduce it
// (written by `glint register`, read by `glint register --init` and `glint sweep --fit`).
#pragma once

#include "mesh/geometry.h"
#include "registration/icp.h"

#include <string>

namespace glint {

/// Where options came from, recorded in fit.json so that a fit can be reproduced.
struct RegistrationSources {
    std::string init_file;       ///< fit.json the initial pose was read from
    std::string landmarks_file;  ///< landmarks JSON the initial pose was fitted to
};

/// The result as JSON text (fit.json): matrices, evidence, per-iteration log, and the options
/// (ROI numbers, source files) that reproduce it.
[[nodiscard]] std::string to_json(const RegistrationResult& result,
                                  const RegistrationOptions& options,
                                  const RegistrationSources& sources = {});

/// A motion read from a fit file: reference point = reference_from_examined × (examined_scale ×
/// examined point).
struct FittedMotion {
    Rigid reference_from_examined = Rigid::Identity();
    double examined_scale = 1.0;
};

/// reference_from_examined from a fit.json (or any JSON with that 4×4 matrix), and
/// "examined_scale" when the file has one (a similarity fit; 1 otherwise).
/// \throw IoError, InputError naming the file and what is missing.
[[nodiscard]] FittedMotion read_fit(const std::string& path);

}  // namespace glint
