// SPDX-License-Identifier: MIT
// image.h — float images of the tracer (HDR, linear) and their OpenEXR output.
//
// Conventions: rows top-down (row 0 is the top, as raster/camera.h), pixels interleaved with
// `channels` floats each (1 = Y, 3 = RGB, 4 = RGBA with PREMULTIPLIED alpha). Supersamples: the
// caller accumulates sums and calls Scale, or keeps one sample per cell of a K× image (tracer.h
// SampleCell) and box-filters it with BoxFilter.
// Files: 32-bit float channels, ZIP compression, no time stamps, so equal images give equal bytes;
// written to `<path>.tmp.<pid>` and renamed, so a failed write leaves no file behind.
// Reading: ReadExr takes R,G,B(,A) or Y float/half channels (missing A = 1 is not assumed: an
// image with R,G,B only reads as 3 channels).
// Not here: tone mapping for previews (base/display_image.h, pipeline/trace_job.h).
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace pem::trace {

struct FloatImage {
    int width = 0, height = 0, channels = 3;
    std::vector<float> data;  // width · height · channels
    bool operator==(const FloatImage&) const = default;

    FloatImage() = default;
    FloatImage(int w, int h, int c)
        : width(w), height(h), channels(c), data(static_cast<size_t>(w) * h * c, 0.0f) {}

    float* At(int x, int y) {
        return data.data() + (static_cast<size_t>(y) * width + x) * channels;
    }
    const float* At(int x, int y) const {
        return data.data() + (static_cast<size_t>(y) * width + x) * channels;
    }
    // Adds rgb (and `alpha` when the image has 4 channels) to a pixel.
    void Add(int x, int y, const glm::vec3& rgb, float alpha = 0.0f);
    void Scale(float s);
};

// Where sample s (tracer.h SampleOffset: row-major in the pixel) of pixel (x, y) is kept in a K×
// sample image: the cell (k x + s mod k, k y + s / k).
glm::ivec2 SampleCell(int x, int y, int k, int s);

// The W×H image of a K× sample image (K W × K H, sample s of pixel (x, y) in the cell
// SampleCell(x, y, k, s)): per pixel the sum of its samples in sample order, times 1/K² — the
// bits that adding them to a pixel with Add and then Scale(1/K²) give.
FloatImage BoxFilter(const FloatImage& samples, int k);

// Writes channels R,G,B(,A) (or Y for one channel) as 32-bit float OpenEXR. Throws
// pem::base::InputError("<path>: <cause>") when the file cannot be written.
void WriteExr(const std::string& path, const FloatImage& image);

// Reads a scanline or tiled OpenEXR image written by WriteExr (or any with Y / R,G,B(,A)).
// Throws pem::base::InputError("<path>: <cause>") for a missing or malformed file or non-finite
// data.
FloatImage ReadExr(const std::string& path);

}  // namespace pem::trace
