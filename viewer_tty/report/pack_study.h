// SPDX-License-Identifier: MIT
// pack_study.h — the rate–distortion of packed PEMs (pipeline/pem_pack.h) in `pemref report`:
// the PEM directory packed at several settings (lossless, closed-loop quantized, JPEG 2000 at
// several ratios), each pack's bytes per sample and ratios against the directory's EXR and PNG
// maps, and the frames drawn from it — hybrid, layered and single-layer PEM at the report's
// positions — scored against the same references as the directory's frames.
//
//   std::vector<PackRow> rows = StudyPacks(pemDir, scratchDir, references, data.results, 2, log);
//
// The packs are written to scratchDir and removed. Not here: the documents (report_writer.h).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "raster/camera.h"
#include "viewer_tty/report/image_metrics.h"
#include "viewer_tty/report/report_writer.h"

namespace pem::report {

// A report position's reference frame and its lens pixels.
struct PackReference {
    std::string position;
    raster::Camera camera;
    MetricImage reference;
    std::vector<uint8_t> mask;
};

std::vector<PackRow> StudyPacks(const std::string& pemDir, const std::string& scratchDir,
                                const std::vector<PackReference>& references,
                                const std::vector<MethodResult>& unpacked, int threads,
                                const std::function<void(const std::string&)>& log);

}  // namespace pem::report
