// SPDX-License-Identifier: MIT
// layout_study_writer.h — the parameterization study's documents: study.md (per scene, a table
// of every layout and size: texels, fit residual, inference time, hybrid, layered-PEM and static-EM
// PSNR on, between and above the samples, frame time; then a picture of each layout's map),
// study.svg (hybrid PSNR against texels, one curve per layout, one panel per scene and position)
// and study.json (every figure). Each file appears atomically.
//
//   WriteLayoutStudy(RunLayoutStudy(options), "out/study");
//
// Not here: the measurements (layout_study.h).
#pragma once

#include <string>

#include "viewer_tty/report/layout_study.h"

namespace pem::report {

void WriteLayoutStudy(const LayoutStudy& study, const std::string& dir);

// The documents' text (exposed for tests).
std::string LayoutStudyMarkdown(const LayoutStudy& study);
std::string LayoutStudySvg(const LayoutStudy& study);
std::string LayoutStudyJson(const LayoutStudy& study);

}  // namespace pem::report
