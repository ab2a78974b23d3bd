// Fault injection for the fault suite (tests/faults): a run can be made to receive a signal,
// be killed, or stall at a named point of its work, so that tests can show what is left after
// a fault at every stage boundary without racing a clock from outside.
//
// The environment variable GLINT_FAULT lists "<point>[#<n>]:<action>" entries, comma-separated:
//   point   a name passed to fault_point(): "fit", "distance", "sweep", "decide", "export"
//           (the analysis stages), "view" (each rendered view), "commit" (an output folder
//           about to move into place), "committed" (just after), "file-commit" (a single
//           file or a set of files about to be renamed into place);
//   #n      the n-th time the point is reached (1-based; default the first);
//   action  "term" or "int" (raises SIGTERM / SIGINT: the cooperative stop must follow),
//           "kill" (SIGKILL: nothing can clean up), "stall" (sleeps 30 s without polling
//           cancellation, as a library call that never returns would), "pause" (sleeps 2 s:
//           room for another process to act, for races).
// Without GLINT_FAULT a fault point costs two atomic loads.
#pragma once

#include <string_view>

namespace glint {

/// Marks a point of the work where the fault suite may inject a fault (see above).
void fault_point(std::string_view point);

}  // namespace glint
