// SPDX-License-Identifier: MIT
// render.h — draw a Frame the way the target graphics system does, and report texel taps.
//
//   RenderOptions opt;                       // profile llvmpipe, 1 thread
//   PreparedFrame prepared(frame);           // texel conversion, done once (like a GL upload)
//   Image8 img = Render(prepared, opt).image8;
//   RenderingMatrix A = BuildRenderingMatrix(prepared, opt);   // same code path, with taps
//
// Profiles:
//  - Llvmpipe: bit-exact to Mesa 22.3.6 llvmpipe (LLVM 15, x86-64 host with FMA) rendering the
//    frame into an RGBA8 FBO (docs/raster-model.md lists every rule and its source).
//  - Linear: the same rasterization, texel selection and weights, but no intermediate rounding:
//    float texels c/255, float filtering, float framebuffer and float blending; the result is
//    exactly linear in the texels (ImageF), and Image8 is its RNE conversion.
//  - Softpipe: bit-exact to Mesa 22.3.6 softpipe (softpipe_render.h): its own float setup,
//    interpolation, sampler, depth test and blending; one thread.
// Depth (Frame::depth, Pass::depthTest): Llvmpipe and Linear decide visibility with llvmpipe's
// depth arithmetic (depth.h), Softpipe with softpipe's; a fragment that fails writes nothing and
// has no row entries in A.
// Threads split the frame into bands of whole 2x2-quad rows; each pixel (colour and depth) is
// written by one thread in primitive order, so the bytes do not depend on the thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "raster/frame.h"
#include "raster/lod.h"
#include "raster/texel_index.h"

namespace pem::raster {

enum class Profile { Llvmpipe, Linear, Softpipe };
enum class UnormRounding { HalfEven, HalfUp };  // RNE(f*255) (GL/llvmpipe) or D3D's floor(+0.5)
enum class CubeLod { Llvmpipe, Exact };         // llvmpipe's fast log2 / GL-spec exact log2

struct RenderOptions {
    Profile profile = Profile::Llvmpipe;
    UnormRounding rounding = UnormRounding::HalfEven;
    CubeLod cubeLod = CubeLod::Llvmpipe;
    int threads = 1;
    // A float colour buffer's 8-bit picture too (RenderResult::image8); false: image8 is left
    // empty for callers that read only the floats (8-bit colour buffers have image8 always).
    bool picture8 = true;
};

// Whether a frame is drawn into a float colour buffer: its own is RGBA32F, or the profile is
// Linear (which draws every frame in float).
inline bool FloatTarget(const Frame& frame, const RenderOptions& options) {
    return options.profile == Profile::Linear || frame.colorFormat == ColorFormat::Rgba32F;
}

// Textures converted once for sampling (float copies for the float paths).
struct PreparedTexture {
    const Texture* source = nullptr;
    PipeLodState lod;  // the sampler's LOD controls as llvmpipe receives them
    // RGBA8: c * fl(1/255) per byte (llvmpipe's conversion) and c / 255 in float (linear
    // profile); RGBA32F: the floats, in both.
    std::vector<std::vector<float>> levelsF;
    std::vector<std::vector<float>> levelsExact;
};

// One texture converted (the float copies are what PreparedFrame would make of it); `texture`
// must outlive the result. Lets a caller drawing many frames with the same maps convert once.
std::shared_ptr<const PreparedTexture> PrepareTexture(const Texture& texture);

class PreparedFrame {
  public:
    explicit PreparedFrame(const Frame& frame);
    // With textures prepared earlier: prepared[i] must be PrepareTexture of a texture with the
    // kind, size and level count of frame.textures[i] (the frame's own copies are used only for
    // the texel numbering: their texel bytes may be left empty).
    PreparedFrame(const Frame& frame, std::vector<std::shared_ptr<const PreparedTexture>> prepared);
    const Frame& frame() const { return *frame_; }
    const PreparedTexture& texture(int i) const { return *textures_[static_cast<size_t>(i)]; }
    const TexelIndexer& indexer() const { return indexer_; }

  private:
    const Frame* frame_;
    std::vector<std::shared_ptr<const PreparedTexture>> textures_;
    TexelIndexer indexer_;
};

// Every image and the depth buffer hold the frame's drawn box (frame.h DrawnBox: the scissor box,
// or the whole framebuffer), rows top-down.
struct RenderResult {
    // From a float colour buffer its RNE(clamp(v, 0, 1) * 255) (pemref's view of it, not a
    // driver's readback), unless RenderOptions::picture8 is false; always from an 8-bit one.
    Image8 image8;
    ImageF imageF;  // a float colour buffer (FloatTarget): its values, unclamped
    // Frame::depth set: the depth buffer after the last pass, one value per pixel, rows
    // top-down (depth.h: Z16/Z24 unorm integers, Z32F float bits); else empty.
    std::vector<uint32_t> depth;
};

RenderResult Render(const PreparedFrame& frame, const RenderOptions& options);

// Several frames at once, each result equal to Render(*frames[i], options): pass p of frames
// whose pass p has the same geometry (frame size and depth clamp, vertices, indices, units; the
// textures and blending may differ) is clipped and set up once for all of them; a layer pass
// pair (LESS with writes, replacing; then EQUAL without writes at the same positions) is drawn
// in one traversal, and frames whose depth buffers stay equal share one (docs/raster-model.md
// §6).
std::vector<RenderResult> RenderFrames(const std::vector<const PreparedFrame*>& frames,
                                       const RenderOptions& options);

// The rendering matrix of a frame whose passes are linear in the texels (texel_index.h numbers
// rows and columns): rendered = A * x + offset, x = the texel values over all textures (bytes /
// 255, or the floats of RGBA32F textures), rows per (pixel, channel). A pass contributes the taps
// of its unit 0; unit 1 and the vertex colour are folded into the weights. Passes must blend with
// "none" (the pass replaces the row) or "add" (it adds to it); anything else throws
// std::invalid_argument. Depth tests are allowed: they only choose which fragments count (fragments
// hidden by the depth buffer have no entries). In the Linear profile `rendered` equals A * x +
// offset to float rounding; in the Llvmpipe profile it is the 8-bit frame / 255, within the bound
// of docs/raster-model.md §9 (an RGBA32F colour buffer: its floats, A * x + offset to float
// rounding); in the Softpipe profile the 8-bit frame / 255, A * x + offset rounded once
// (softpipe_render.h). A frame with a scissor box throws std::invalid_argument (keep pixels by
// listing them).
struct RenderingMatrix {
    int64_t rows = 0, cols = 0;
    std::vector<int64_t> rowPtr;  // CSR, rows + 1 entries
    std::vector<uint32_t> col;
    std::vector<double> val;
    std::vector<double> offset;       // constant term per row (clear colour, untextured passes)
    std::vector<double> rendered;     // the frame as rendered, per row, in [0, 1] units
    std::vector<uint16_t> fragments;  // per pixel: fragments written since the last unblended one
};

// `pixels`, when given, lists the pixels whose rows are kept (row-major indices, increasing;
// none is allowed): rows 4i..4i+3 (and offset, rendered, fragments[i]) are then pixel
// (*pixels)[i]'s, the same values as the whole frame's rows of that pixel. Null: every pixel.
RenderingMatrix BuildRenderingMatrix(const PreparedFrame& frame, const RenderOptions& options,
                                     const std::vector<uint32_t>* pixels = nullptr);

// The least texel index (texel_index.h: finest level first) among the taps of each kept pixel's
// rows, kNoTexel for a pixel without taps: which MIP level a pixel's finest tap reads, from the
// same draw as BuildRenderingMatrix without forming the matrix (a test rendering).
inline constexpr uint32_t kNoTexel = 0xFFFFFFFFu;
std::vector<uint32_t> FinestTexels(const PreparedFrame& frame, const RenderOptions& options,
                                   const std::vector<uint32_t>* pixels = nullptr);

}  // namespace pem::raster
