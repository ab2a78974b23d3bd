// AnalysisOptions: checking every option before anything is loaded.
#include "analysis/analysis.h"

#include "mesh/error.h"

namespace glint {

void AnalysisOptions::validate() const {
    units.validate();
    fit.validate();
    sweep.validate();
    decision.validate();
    const MetricDescriptor& m = describe(sweep.metric);
    if (decision.threshold && *decision.threshold > m.max_value)
        throw OptionError("threshold.deg", *decision.threshold,
                          "must be in (0, " + std::to_string(static_cast<int>(m.max_value)) + "] " +
                              std::string(m.unit) + " (metric " + std::string(m.name) + ")");
}

}  // namespace glint
