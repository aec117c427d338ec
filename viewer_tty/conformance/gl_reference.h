// SPDX-License-Identifier: MIT
// gl_reference.h — render a Frame through a real OpenGL driver (EGL surfaceless, desktop GL 3.3
// core, offscreen RGBA8 or RGBA32F FBO with a depth renderbuffer when the frame has one), exactly
// as gl_ref_case/1 prescribes; the oracle pemref's rasterizer is compared against (Mesa llvmpipe on
// machines without a GPU).
// Conventions: output rows top-down (frame.h); one process-wide EGL context, created lazily on
// the calling thread and used only from it. Not here: case parsing, hashing, PNG output.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "raster/frame.h"

namespace pem::conformance {

// A failure of the GL driver (context creation, shader compilation, limits); not an input error.
class GlError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// nullopt when a GL 3.3 core context can be created, else a one-line reason. Initialises the
// context on first call. If no driver works and LIBGL_ALWAYS_SOFTWARE is unset, retries once with
// LIBGL_ALWAYS_SOFTWARE=1 (Mesa's software rasterizer); a working GPU driver is never overridden.
std::optional<std::string> GlAvailable();

// "<GL_RENDERER> | <GL_VERSION>"; throws GlError if GL is unavailable.
std::string GlRendererString();

// Renders `frame` `repeat` (>= 1) times: textures and programs are created once, then each repeat
// clears and draws all passes between two glFinish() calls; its wall time in milliseconds is
// appended to *frameMs (if not null). Returns the pixels of the last repeat; *depth (if not null)
// gets its depth buffer, rows top-down, in raster/depth.h's stored values (empty without one),
// and *floatPixels (if not null) an RGBA32F colour buffer's floats (glReadPixels GL_FLOAT; empty
// for RGBA8). The returned pixels are glReadPixels(GL_UNSIGNED_BYTE) (the driver's conversion
// for a float buffer). Throws GlError.
raster::Image8 RenderWithGl(const raster::Frame& frame, int repeat, std::vector<double>* frameMs,
                            std::vector<uint32_t>* depth = nullptr,
                            raster::ImageF* floatPixels = nullptr);

}  // namespace pem::conformance
