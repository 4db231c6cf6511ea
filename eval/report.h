// The evaluation report (docs/evaluation.md): metrics.json, metrics.csv, report.md and the error-histogram PNGs.
// Every file is a pure function of the report, so it is bitwise identical whatever the thread count.
#pragma once

#include "eval/evaluation.h"

#include <string>

namespace sward {

std::string metricsJson(const EvaluationReport& report);
std::string metricsCsv(const EvaluationReport& report);
// Links the first frame's pictures when <outDir>/frames holds them.
std::string reportMarkdown(const EvaluationReport& report);

// Writes every report file into report.outDir (which must exist).
void writeReport(const EvaluationReport& report);

} // namespace sward
