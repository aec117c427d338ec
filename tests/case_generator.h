// SPDX-License-Identifier: MIT
// case_generator.h — the raster conformance corpus: deterministic frames that exercise every
// rule of the llvmpipe model (reflective spheres, cube edges and corners, minification and
// magnification, every filter and wrap mode, LOD bias and clamps, multi-pass blending, blend
// and conversion probes, tie directions, extreme magnitudes, clipping, two-texture passes).
// Each case is small (<= 128x128) so the whole corpus renders through llvmpipe in seconds.
#pragma once

#include <string>
#include <vector>

#include "raster/frame.h"

namespace pem::test {

struct NamedCase {
    std::string name;
    raster::Frame frame;
};

std::vector<NamedCase> ConformanceCases();

// The benchmark frame of bench/: width x height, a full-screen sky quad and a UV sphere of
// `rings` x `segments` quads with reflection vectors, one `cubeSize` cube, trilinear, seamless.
raster::Frame BenchmarkFrame(int width, int height, int rings, int segments, int cubeSize);

}  // namespace pem::test
