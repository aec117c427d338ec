// SPDX-License-Identifier: MIT
// render.h — whole frames from the tracer: the reference (full ray tree) and the same frame
// with the greedy two-term model at lens objects.
//
// Conventions: k×k supersamples per pixel at SamplePosition (tracer.h), box-filtered (the mean);
// RGB float image, linear HDR radiance. Rows are traced in parallel (parallel.h) and each pixel
// depends only on its own samples, so the bytes are the same for any thread count. Within a row,
// camera and shadow rays go in 8-ray packets and full-tree leaves are shaded after the trees
// (Tracer::RadianceTape); the values are bit for bit those of Tracer::Radiance / GreedyRadiance
// sample by sample (tracer_test.cpp).
// Not here: per-lens-group segmentation (segment.h), files (pipeline/trace_job.h).
#pragma once

#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "raster/camera.h"
#include "trace/image.h"
#include "trace/tracer.h"

namespace pem::trace {

// FullTree: every sample's full ray tree. Greedy: the two-term model at lens objects.
// Surroundings: the full tree everywhere but at lens objects, whose samples stay black (the rest
// of a hybrid frame, renderer.h); `lensGroup` says which group each pixel's first sample hits.
enum class Model { FullTree, Greedy, Surroundings };

struct FrameResult {
    FloatImage image;         // RGB
    FloatImage lensCoverage;  // Y: fraction of the pixel's samples whose camera ray hits a lens
    RayCounts counts;
    std::vector<int> lensGroup;  // Surroundings: per pixel, the first sample's group (-1: none)
};

FrameResult RenderFrame(const Tracer& tracer, const raster::Camera& camera, int k, Model model,
                        int threads, const std::function<void(int, int)>& progress = {});

// The Surroundings model at k×k for the listed pixels only (a hybrid frame's silhouettes,
// renderer.h): per pixel the box-filtered radiance of its samples with the lens samples black,
// and per sample (pixel-major, SampleOffset order) the lens group its camera ray hits (-1: none).
// Each value is the one RenderFrame gives that sample; any thread count gives the same bytes.
struct PixelSamples {
    std::vector<glm::vec3> surroundings;  // per pixel
    std::vector<int> groups;              // per pixel, k² samples
    RayCounts counts;
};
PixelSamples RenderPixels(const Tracer& tracer, const raster::Camera& camera, int k,
                          const std::vector<glm::ivec2>& pixels, int threads);

// Mean squared error and PSNR between two RGB images over the pixels where mask (one channel,
// may be empty = all pixels) is > 0. Values are clamped to [0, 1] first (display range, peak 1)
// unless `hdr` is set (then the RMSE is of the raw radiance and the PSNR uses peak 1 anyway).
struct ImageError {
    double rmse = 0.0;
    double psnr = 0.0;  // dB; +inf when equal
    size_t pixels = 0;
};
ImageError CompareImages(const FloatImage& a, const FloatImage& b, const FloatImage& mask,
                         bool hdr = false);

}  // namespace pem::trace
