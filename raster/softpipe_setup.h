// SPDX-License-Identifier: MIT
// softpipe_setup.h — the softpipe profile's triangle setup and scan conversion, as Mesa 22.3.6
// softpipe's sp_setup.c does them (restated in our own words; docs/raster-model.md §12).
//
//   SpTriangle t;
//   if (SetupSoftpipeTriangle(v0, v1, v2, numAttribs, width, height, &t))
//       ScanSoftpipeTriangle(t, width, height, [&](int x, int y, unsigned mask) { ... });
//
// Unlike llvmpipe (fixed-point edge functions, triangle_setup.h), softpipe works in float:
//  - The vertices are sorted by window y (vmin, vmid, vmax); area = emaj.dx * ebot.dy -
//    ebot.dx * emaj.dy; a triangle whose 1/area is Inf or NaN is not drawn.
//  - Rows: each edge starts at sy = ceil(y - 0.5) and spans ceil(y_end - 0.5 - sy) rows; its
//    x at a row is sx + row * dx/dy with sx = (x + 0.5) + (sy - (y - 0.5)) * dx/dy, truncated
//    toward zero: pixels [left, right) of the row are covered. The long edge continues into the
//    upper half from where the lower half left it (sx += lines * dx/dy).
//  - Quads: rows are gathered in pairs and emitted as 2x2 quads at even (x, y) with a 4-bit
//    mask (bit 0 (x, y), 1 (x+1, y), 2 (x, y+1), 3 (x+1, y+1)).
//  - Planes: a0 = v_min - (dadx * (x_min - 0.5) + dady * (y_min - 0.5)); z and 1/w linear,
//    the other attributes premultiplied by 1/w (perspective-correct), all in plain float.
// Raster y is GL window y (an FBO is not flipped), as for llvmpipe.
// Not here: clipping and the viewport transform (clip.h), shading and blending
// (softpipe_render.h).
#pragma once

#include <array>
#include <functional>

#include "raster/triangle_setup.h"

namespace pem::raster {

// One edge of the scan conversion (sp_setup.c's struct edge).
struct SpEdge {
    float dx, dy, dxdy, sx, sy;
    int lines;
};

struct SpTriangle {
    SpEdge emaj, ebot, etop;              // vmin->vmax, vmin->vmid, vmid->vmax
    bool majorLeft = false;               // 1/area < 0: the long edge is on the left
    Plane z, oow;                         // window z and 1/w, linear
    std::array<Plane, kMaxAttribs> attr;  // premultiplied by 1/w
    int numAttribs = 0;
};

// Sorts and sets up a triangle; false when softpipe draws nothing (1/area Inf or NaN).
bool SetupSoftpipeTriangle(const WindowVertex& v0, const WindowVertex& v1, const WindowVertex& v2,
                           int numAttribs, SpTriangle* out);

// Calls quad(x, y, mask) for every 2x2 quad with a covered pixel, inside the framebuffer
// [0, width) x [0, height), in softpipe's order (row pairs bottom-up, left to right).
void ScanSoftpipeTriangle(const SpTriangle& t, int width, int height,
                          const std::function<void(int, int, unsigned)>& quad);

}  // namespace pem::raster
