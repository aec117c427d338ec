// SPDX-License-Identifier: MIT
// frame.h — the value types that describe one frame for raster/: textures (cube maps and 2D
// textures, RGBA8 or RGBA32F, every MIP level given explicitly), sampler state, passes of
// clip-space triangles, blend state, an RGBA8 or RGBA32F colour buffer, an optional depth buffer
// and per-pass depth tests. A Frame is what a raster case file
// (viewer_tty/conformance/case_file.h) holds and what both pemref's rasterizer and the OpenGL
// reference harness (pemref-gl) render.
//
// Conventions (shared by every module):
//  - Cube faces in GL order: 0 +X, 1 -X, 2 +Y, 3 -Y, 4 +Z, 5 -Z (GL 4.6 table 8.19).
//  - Texel (i, j) of a face or 2D level: i = column along s, j = row along t; byte offset
//    ((j * size + i) * 4) inside that face/level image, exactly what glTexImage2D receives.
//  - Images (Image8, ImageF) and depth buffers are stored rows top-down: row 0 is the top of the
//    picture, which is GL window y = height - 1 (glReadPixels rows reversed).
// Not here: parsing (viewer_tty/conformance/case_file.h), rendering (raster/render.h), depth
// arithmetic (raster/depth.h).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/image8.h"

namespace pem::raster {

// Texture sampling state ---------------------------------------------------------------------

enum class Filter { Nearest, Linear };
enum class MipFilter { None, Nearest, Linear };  // GL min filter = (Filter, MipFilter)
enum class Wrap { ClampToEdge, Repeat, MirroredRepeat };

struct SamplerState {
    Filter minFilter = Filter::Linear;
    MipFilter mipFilter = MipFilter::Linear;  // linear_mipmap_linear by default
    Filter magFilter = Filter::Linear;
    Wrap wrapS = Wrap::ClampToEdge, wrapT = Wrap::ClampToEdge;  // 2D only; cubes clamp
    bool seamless = true;                                       // cube maps only
    float lodBias = 0.0f, minLod = -1000.0f, maxLod = 1000.0f;
    // GL_TEXTURE_MAX_ANISOTROPY as glTexParameterf gives it: 1 = off; llvmpipe filters
    // anisotropically from 2 on (the value is clamped to 16 and truncated; aniso.h).
    float maxAnisotropy = 1.0f;
    bool operator==(const SamplerState&) const = default;
};

enum class TextureKind { Cube, Tex2D };

// A texture's internal format (glTexImage2D): GL_RGBA8, 4 unorm bytes per texel (value c / 255),
// or GL_RGBA32F, 16 bytes per texel: four little-endian float32 taken as they are (any value,
// negative or above 1; llvmpipe samples them on its float path).
enum class TexelFormat { Rgba8, Rgba32F };

// Their names in case files, PEM manifests and on the command line.
inline constexpr std::array<std::pair<std::string_view, TexelFormat>, 2> kTexelFormatNames = {{
    {"rgba8", TexelFormat::Rgba8},
    {"rgba32f", TexelFormat::Rgba32F},
}};

// A texture with every MIP level given explicitly (levels[l] has max(1, w>>l) by max(1, h>>l)
// texels per face; 6 faces for a cube, 1 for 2D). Sizes are powers of two.
struct Texture {
    TextureKind kind = TextureKind::Cube;
    int width = 1, height = 1;  // level 0; a cube has width == height
    SamplerState sampler;
    TexelFormat format = TexelFormat::Rgba8;
    std::vector<std::vector<uint8_t>> levels;  // levels[l]: faces * h_l * w_l * TexelBytes()

    int TexelBytes() const { return format == TexelFormat::Rgba32F ? 16 : 4; }
    int Faces() const { return kind == TextureKind::Cube ? 6 : 1; }
    int NumLevels() const { return static_cast<int>(levels.size()); }
    int LevelWidth(int l) const { return std::max(1, width >> l); }
    int LevelHeight(int l) const { return std::max(1, height >> l); }
    bool operator==(const Texture&) const = default;
};

// Blending -----------------------------------------------------------------------------------

enum class BlendFactor {
    Zero,
    One,
    SrcColor,
    OneMinusSrcColor,
    DstColor,
    OneMinusDstColor,
    SrcAlpha,
    OneMinusSrcAlpha,
    DstAlpha,
    OneMinusDstAlpha,
    SrcAlphaSaturate
};
enum class BlendEquation { Add, Subtract, ReverseSubtract, Min, Max };

struct BlendState {
    bool enabled = false;
    BlendFactor srcRgb = BlendFactor::One, dstRgb = BlendFactor::Zero;
    BlendFactor srcAlpha = BlendFactor::One, dstAlpha = BlendFactor::Zero;
    BlendEquation eqRgb = BlendEquation::Add, eqAlpha = BlendEquation::Add;
    bool operator==(const BlendState&) const = default;

    static BlendState None() { return {}; }
    static BlendState Over();      // SRC_ALPHA, ONE_MINUS_SRC_ALPHA for rgb and alpha
    static BlendState Additive();  // ONE, ONE
    static BlendState Multiply();  // DST_COLOR, ZERO
};

// Depth ----------------------------------------------------------------------------------------
//
//   frame.depth = DepthBuffer{DepthFormat::Z24, 1.0f};  // GL_DEPTH_COMPONENT24, glClearDepth(1)
//   pass.depthTest = DepthTest{DepthFunc::Less, true};  // glDepthFunc(GL_LESS), glDepthMask(1)
//   later.depthTest = DepthTest{DepthFunc::Equal, false};  // same geometry again (multipass)
//   other.depthTest.reset();  // glDisable(GL_DEPTH_TEST): neither tests nor writes
// The arithmetic (llvmpipe's) is in raster/depth.h.

// The depth renderbuffer's internal format: GL_DEPTH_COMPONENT16 (Z16_UNORM),
// GL_DEPTH_COMPONENT24 (llvmpipe: Z24X8_UNORM, 24-bit unorm in a 32-bit word) or
// GL_DEPTH_COMPONENT32F (Z32_FLOAT).
enum class DepthFormat { Z16, Z24, Z32F };

// glDepthFunc: the fragment passes when `fragment FUNC stored` holds.
enum class DepthFunc { Never, Less, Equal, LEqual, Greater, NotEqual, GEqual, Always };

// A frame's depth buffer: its format and glClearDepth value (in [0, 1]), cleared with the colour.
struct DepthBuffer {
    DepthFormat format = DepthFormat::Z24;
    float clear = 1.0f;
    bool operator==(const DepthBuffer&) const = default;
};

// A pass's depth test (GL_DEPTH_TEST enabled): compare function and glDepthMask.
struct DepthTest {
    DepthFunc func = DepthFunc::Less;
    bool write = true;
    bool operator==(const DepthTest&) const = default;
};

// Geometry -----------------------------------------------------------------------------------

constexpr int kMaxUnits = 2;  // textures sampled per pass (the papers' two-texture hardware)

// One vertex: clip-space position, one texture coordinate per unit (a cube direction rx,ry,rz,
// any length; or 2D s,t with the third component ignored), and the modulating colour.
struct Vertex {
    glm::vec4 pos{0.0f, 0.0f, 0.0f, 1.0f};
    std::array<glm::vec3, kMaxUnits> coord{};
    glm::vec4 color{1.0f};
    bool operator==(const Vertex&) const = default;
};

// A draw call: triangles (index triples, or consecutive vertex triples when indices is empty),
// fragment colour = texture(unit0) * texture(unit1) * colour, units that are absent dropped
// (GLSL: o_col = texture(u0, c0) * texture(u1, c1) * v_col, evaluated left to right).
// A depth test applies when the frame has a depth buffer (without one GL passes every fragment).
struct Pass {
    int numUnits = 1;                          // 0, 1 or 2
    std::array<int, kMaxUnits> texture{0, 0};  // index into Frame::textures per unit
    BlendState blend;
    std::optional<DepthTest> depthTest;  // absent: GL_DEPTH_TEST disabled (no test, no writes)
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    int NumTriangles() const {
        return static_cast<int>((indices.empty() ? vertices.size() : indices.size()) / 3);
    }
    bool operator==(const Pass&) const = default;
};

// The colour renderbuffer's internal format: GL_RGBA8 (fragment colours clamped to [0, 1] and
// converted to unorm8, 8-bit blending) or GL_RGBA32F (colours stored and blended as floats,
// unclamped).
enum class ColorFormat { Rgba8, Rgba32F };

// A rectangle of framebuffer pixels in GL window coordinates (x right, y up from the bottom row).
struct PixelBox {
    int x = 0, y = 0, width = 0, height = 0;
    bool operator==(const PixelBox&) const = default;
};

// One frame: a cleared colour buffer (and depth buffer, if any) and passes drawn in order,
// no culling, viewport (0, 0, width, height), depth range [0, 1], clip volume
// -w <= x, y, z <= w (z not clipped with depthClamp).
struct Frame {
    int width = 1, height = 1;
    ColorFormat colorFormat = ColorFormat::Rgba8;
    std::array<uint8_t, 4> clear{0, 0, 0, 0};  // glClearColor(c / 255.0f): RGBA32F stores those
    bool depthClamp = false;
    std::optional<DepthBuffer> depth;  // absent: no depth buffer (depth tests pass everything)
    // glScissor: fragments outside the box are discarded, so every pixel inside is what the whole
    // frame would hold there; the results (render.h) hold only the box's pixels. A caller that
    // reads part of a large frame draws, clears and stores only that part. Absent: the whole
    // framebuffer. Must lie inside it and hold a pixel.
    std::optional<PixelBox> scissor;
    std::vector<Texture> textures;  // cube maps and 2D textures, referenced by Pass::texture
    std::vector<Pass> passes;
    bool operator==(const Frame&) const = default;
};

// The pixels a frame draws and its results hold: the scissor box, or the whole framebuffer.
inline PixelBox DrawnBox(const Frame& frame) {
    return frame.scissor ? *frame.scissor : PixelBox{0, 0, frame.width, frame.height};
}

// Images -------------------------------------------------------------------------------------

// RGBA8 pixels, rows top-down, 4 bytes per pixel (base/image8.h).
using Image8 = base::Image8;

// Float RGBA pixels, rows top-down (an RGBA32F colour buffer, or the `linear` profile's float
// framebuffer).
struct ImageF {
    int width = 0, height = 0;
    std::vector<float> rgba;
    bool operator==(const ImageF&) const = default;
};

// Component i (texel i / 4, channel i % 4) of level `level` as the value it stands for: c / 255
// (RGBA8, in double) or the float (RGBA32F).
double TexelValue(const Texture& texture, int level, size_t i);

// Floats from their little-endian bytes (an RGBA32F level), and back (a level, or the bytes an
// RGBA32F colour buffer's identity is computed over).
std::vector<float> FloatsFromBytes(const std::vector<uint8_t>& bytes);
std::vector<uint8_t> FloatBytes(std::span<const float> values);

}  // namespace pem::raster
