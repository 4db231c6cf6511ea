// The realism instrument's report (docs/evaluation.md, "Realism statistics"): look.json, look.csv, report.md and,
// unless left out, the pictures (per-region histograms of grey and saturation and radial spectra, sward against
// the real images). Every file is a pure function of the result, so it is bitwise identical whatever the thread
// count.
#pragma once

#include "eval/look.h"

#include <string>

namespace sward {

std::string lookJson(const LookResult& result);
std::string lookCsv(const LookResult& result);
// Links the pictures when `pictures` is set.
std::string lookMarkdown(const LookResult& result, bool pictures);

// Writes the files into `outDir` (which must exist), each atomically.
void writeLookReport(const LookResult& result, const std::string& outDir, bool pictures);

// eval/look_plots.cpp: look_<region>.png per region with pixels: grey and saturation histograms and the mean
// radial spectrum (log-log), sward's curve against the real images'.
void writeLookPictures(const LookResult& result, const std::string& outDir);
// The regions writeLookPictures draws, in report order.
std::vector<std::string> lookPictureRegions(const LookResult& result);

} // namespace sward
