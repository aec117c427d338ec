// SPDX-License-Identifier: MIT
// positions.h — the three camera positions the report and the study measure at: on the sample
// circle (the first inferred sample's own camera), halfway to the next sample on the circle, and
// 10° above that halfway point (hybrid paper §5's on / between / off the samples).
//
//   for (const Position& p : Positions(renderer)) renderer.Render(p.camera, settings);
//
// Not here: what is measured there (report_job.h, layout_study.h).
#pragma once

#include <string>
#include <vector>

#include "runtime/renderer.h"

namespace pem::report {

struct Position {
    std::string name, file;  // "on circle", "on_circle"; "between samples", ...; "10° above", ...
    raster::Camera camera;
};

std::vector<Position> Positions(const runtime::Renderer& renderer);

}  // namespace pem::report
