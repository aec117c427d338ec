// SPDX-License-Identifier: MIT
// triangle_setup.h — from three window-space vertices to coverage edges and attribute planes,
// as llvmpipe's lp_setup_tri.c and its generated setup function compute them.
//
// Raster space: x right, y = GL window y (an FBO is not flipped); pixel (X, Y) is sampled at
// window (X + 0.5, Y + 0.5), which is the integer point (X, Y) after the 0.5 offset.
//  - Coverage: vertex positions minus 0.5, times 256, rounded half to even (8 subpixel bits);
//    64-bit edge functions; pixel (X, Y) is inside when every edge E(X, Y) > 0, where edges are
//    made inclusive for left edges and, for horizontal edges, bottom edges (GL FBO rule).
//  - A clockwise triangle (negative fixed-point area) is drawn as (v1, v0, v2).
//  - Attribute planes use the unsnapped float positions: a(X, Y) =
//    fma(dady, Y, fma(dadx, X, a0)); perspective attributes are premultiplied by 1/w and divided
//    by the interpolated 1/w per pixel.
// Not here: clipping and the viewport transform (clip.h), the pixel loop (rasterizer.h).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "raster/frame.h"
#include "raster/numeric.h"

namespace pem::raster {

constexpr int kSubpixelBits = 8;
constexpr int kMaxAttribs = 12;  // interpolated floats per vertex: 2 coords x 3 + colour 4 (+2)

// A vertex after the viewport transform: window x, y, z, 1/w_clip, and the attributes.
struct WindowVertex {
    float x, y, z, oow;
    std::array<float, kMaxAttribs> attr;
};

struct Edge {
    int64_t c, dcdx, dcdy;  // inside when c - dcdx * X + dcdy * Y > 0 (X, Y pixel integers)
};

struct Plane {
    float a0, dadx, dady;
};

struct TriangleSetup {
    // Fields are left unset (SetupTriangle sets every one that is read): render.cpp makes a
    // batch's setups in place, and value-initialising them zeroed 264 bytes per triangle.
    TriangleSetup() {}  // NOLINT(modernize-use-equals-default): "= default" would zero them
    std::array<Edge, 3> edge;
    int x0, x1, y0, y1;                   // pixel bounding box, inclusive, clipped to the drawn box
    Plane oow;                            // interpolated 1/w (llvmpipe's position.w channel)
    Plane z;                              // window z: the fragment depth (depth.h FragmentDepth)
    std::array<Plane, kMaxAttribs> attr;  // premultiplied by 1/w (perspective-correct)
    int numAttribs = 0;
    bool swapped = false;  // clockwise: set up as (v1, v0, v2)
};

// Sets up a triangle drawn into the pixels of `drawn` (the framebuffer, or its scissor box).
// Returns false when nothing is drawn (zero fixed-point area, the bounding box misses `drawn`,
// or a small triangle covers no pixel centre in it).
bool SetupTriangle(const WindowVertex& v0, const WindowVertex& v1, const WindowVertex& v2,
                   int numAttribs, const PixelBox& drawn, TriangleSetup* out);

// The attribute planes of `out`, set up by SetupTriangle from vertices at the same positions,
// for other attributes: (v0, v1, v2) are those vertices with the other attributes.
void SetupAttributePlanes(const WindowVertex& v0, const WindowVertex& v1, const WindowVertex& v2,
                          int numAttribs, TriangleSetup* out);

// Edge test of one pixel.
inline bool Inside(const TriangleSetup& t, int x, int y) {
    for (const Edge& e : t.edge)
        if (WrapAdd64(WrapSub64(e.c, e.dcdx * x), e.dcdy * y) <= 0) return false;
    return true;
}

// Interpolated value of a plane at pixel (X, Y), llvmpipe's fused form.
inline float EvalPlane(const Plane& p, float x, float y) {
    return std::fma(p.dady, y, std::fma(p.dadx, x, p.a0));
}

}  // namespace pem::raster
