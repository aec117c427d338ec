// SPDX-License-Identifier: MIT
// supersampling.h — lens frames drawn with k×k subpixels per pixel and box-filtered back (the
// traced images' K×K sampling, the hybrid paper's subpixels): the hardware draws the frame k
// times wider and higher, and a pixel is the mean of its subpixels that hold a fragment of the
// group (its colour un-premultiplied by that coverage; the silhouettes are composited with the
// ray tracer's coverage afterwards, silhouettes.h). Inference fits the subpixels one by one to
// the trace's samples (pipeline/infer_job.h), so the maps are looked up as they are fitted.
//
//   frame.width = k * width, frame.height = k * height;        // draw
//   double rgba[4];
//   int n = CoveredMean(image8, covered, WholeFrame(width, height, k), pixel, rgba);
//
// Subpixel s = j k + i of pixel (x, y) is pixel (k x + i, k y + j) of the k× frame: the ray
// tracer's sample s (trace/tracer.h SampleOffset), at the same position. A caller that reads
// only some pixels draws only the box of their subpixels (SubpixelBox, raster Frame::scissor):
// the images then hold that box, and SubpixelLayout says where each subpixel is.
// Not here: which pixels a group draws (renderer.h), the silhouettes (silhouettes.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "raster/frame.h"
#include "raster/render.h"

namespace pem::runtime {

// Where the subpixels of a k× frame of a width × height-pixel frame are stored: the images of
// the k× frame's box `box` (raster/render.h RenderResult), rows top-down.
struct SubpixelLayout {
    int width = 0, height = 0;  // pixels of the 1× frame
    int k = 1;
    raster::PixelBox box;  // the k× frame's pixels held (GL window coordinates)
};

// The whole k× frame.
SubpixelLayout WholeFrame(int width, int height, int k);

// The box of the k× frame holding every subpixel of pixels lo..hi (inclusive; x right, y down)
// of a frame `height` pixels high.
raster::PixelBox SubpixelBox(int height, int k, glm::ivec2 lo, glm::ivec2 hi);

// Index of subpixel s of pixel `pixel` (y width + x) in images of the layout (the pixel's
// subpixels must be in its box).
size_t SubpixelIndex(uint32_t pixel, const SubpixelLayout& layout, int s);

// Subpixels holding a fragment: the depth buffer of a k× frame (render.h, Frame::depth set) no
// longer at the clear value.
std::vector<uint8_t> CoveredSubpixels(const std::vector<uint32_t>& depth,
                                      const raster::DepthBuffer& buffer);

// The mean RGBA of the covered subpixels of `pixel` (8-bit frame: values / 255), into rgba;
// returns how many are covered (0: rgba is 0).
int CoveredMean(const raster::Image8& image, const std::vector<uint8_t>& covered,
                const SubpixelLayout& layout, uint32_t pixel, double rgba[4]);
int CoveredMean(const raster::ImageF& image, const std::vector<uint8_t>& covered,
                const SubpixelLayout& layout, uint32_t pixel, double rgba[4]);

}  // namespace pem::runtime
