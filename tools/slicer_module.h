// glint as a 3D Slicer command-line module (Slicer Execution Model).
//
// Slicer finds a CLI module by running every program in its module paths with --xml and
// reading the XML description it prints; it builds the module's panel from it and, on Apply,
// runs the program with the parameters as flags followed by the index (positional)
// parameters, its input nodes written to temporary files and outputs read back from the
// paths it passed. Markups are passed as text (an ROI "cx,cy,cz,rx,ry,rz") or written to
// files (point lists), in the coordinate system each parameter declares (tools/slicer_markups.h).
// glint's only index parameter is the atlas: the reference and examined surfaces are each a
// model or a volume flag, and Slicer refuses to run a module whose index node is not selected. For an executable module it adds --returnparameterfile FILE when the
// description has return parameters (output-channel parameters without flag or index; the
// program writes "name = value" lines there), and it reads progress from the program's
// stdout as <filter-progress>0.5</filter-progress> lines (--processinformationaddress is
// passed to shared-library modules only: it is a pointer into Slicer's own process).
//
// `glint --xml` prints the description of the sweep; a call whose first word is one of its
// flags, --returnparameterfile or --processinformationaddress is such a Slicer call. The
// description and the parser are made from one parameter table (slicer_module.cpp), so they
// cannot disagree; tools/slicer/execution-model.xsd is the schema the description is tested
// against.
#pragma once

namespace glint::cli {

/// Whether argv is `glint --xml` or a call shaped like Slicer's (see file comment).
[[nodiscard]] bool is_slicer_call(int argc, char** argv);

/// Prints the XML, or runs the sweep and writes the outputs, return parameters and progress.
/// \throw InputError bad arguments (CLI11's message), and what the analysis throws.
void run_slicer_module(int argc, char** argv);

}  // namespace glint::cli
