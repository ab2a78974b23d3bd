// Command-line options that choose how the examined mesh is fitted (shared by sweep and run).
#pragma once

#include "scanner/fit.h"

#include <CLI/CLI.hpp>

#include <string>

namespace glint::cli {

struct FitArgs {
    std::string fit_file;
    bool do_register = false;
    std::string loss = "cauchy";
    std::string roi;
    bool symmetric = false;
};

inline void add_fit_options(CLI::App& cmd, FitArgs& a) {
    auto* file = cmd.add_option("--fit", a.fit_file, "fit.json from glint register (examined → reference)");
    auto* reg = cmd.add_flag("--register", a.do_register, "Fit the examined mesh now (robust ICP)");
    file->excludes(reg);
    cmd.add_option("--loss", a.loss, "--register: robust loss cauchy | huber | tukey | none")->capture_default_str();
    cmd.add_option("--fit-roi", a.roi, "--register: fit only on this stable region (sphere:/box:)");
    cmd.add_flag("--symmetric", a.symmetric, "--register: symmetric ICP (both directions)");
}

/// Without --fit or --register the meshes are taken as already aligned.
inline FitRequest to_request(const FitArgs& a) {
    FitRequest r;
    if (!a.fit_file.empty()) {
        r.mode = FitRequest::Mode::File;
        r.fit_file = a.fit_file;
    } else if (a.do_register) {
        r.mode = FitRequest::Mode::Register;
    }
    r.loss = a.loss;
    r.roi = a.roi;
    r.symmetric = a.symmetric;
    return r;
}

}  // namespace glint::cli
