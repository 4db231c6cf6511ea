// The optical-flow evaluation's report (docs/evaluation.md, "Optical flow"): metrics.json, metrics.csv and
// report.md. Every file is a pure function of the evaluation, so it is bitwise identical whatever the thread count.
#pragma once

#include "eval/flow_evaluation.h"

#include <string>

namespace sward {

std::string flowMetricsJson(const FlowEvaluation& evaluation);
std::string flowMetricsCsv(const FlowEvaluation& evaluation);
// Links the first frame's pictures when <outDir>/frames holds them.
std::string flowReportMarkdown(const FlowEvaluation& evaluation);

// Writes the three files into evaluation.outDir (which must exist), each atomically.
void writeFlowReport(const FlowEvaluation& evaluation);

} // namespace sward
