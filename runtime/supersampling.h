// SPDX-License-Identifier: MIT
// supersampling.h — lens frames drawn with k×k subpixels per pixel and box-filtered back (the
// traced images' K×K sampling, the hybrid paper's subpixels): the hardware draws the frame k
// times wider and higher, and a pixel is the mean of its subpixels that hold a fragment of the
// group (its colour un-premultiplied by that coverage; the silhouettes are composited with the
// ray tracer's coverage afterwards, silhouettes.h). Inference fits the subpixels one by one to
// the trace's samples (pipeline/infer_job.h), so the maps are looked up as they are fitted.
//
//   frame.width = k * width, frame.height = k * height;        // draw
//   double rgba[4]; int n = CoveredMean(image8, covered, width, k, pixel, rgba);
//
// Subpixel s = j k + i of pixel (x, y) is pixel (k x + i, k y + j) of the k× frame: the ray
// tracer's sample s (trace/tracer.h SampleOffset), at the same position.
// Not here: which pixels a group draws (renderer.h), the silhouettes (silhouettes.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "raster/frame.h"
#include "raster/render.h"

namespace pem::runtime {

// Index of subpixel s of pixel `pixel` (y width + x) in the k× frame.
size_t SubpixelIndex(uint32_t pixel, int width, int k, int s);

// Subpixels holding a fragment: the depth buffer of a k× frame (render.h, Frame::depth set) no
// longer at the clear value.
std::vector<uint8_t> CoveredSubpixels(const std::vector<uint32_t>& depth,
                                      const raster::DepthBuffer& buffer);

// The mean RGBA of the covered subpixels of `pixel` (8-bit frame: values / 255), into rgba;
// returns how many are covered (0: rgba is 0).
int CoveredMean(const raster::Image8& image, const std::vector<uint8_t>& covered, int width, int k,
                uint32_t pixel, double rgba[4]);
int CoveredMean(const raster::ImageF& image, const std::vector<uint8_t>& covered, int width, int k,
                uint32_t pixel, double rgba[4]);

}  // namespace pem::runtime
