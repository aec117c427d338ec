// SPDX-License-Identifier: MIT
// clip.h — vertex post-processing as Mesa's draw module does it for llvmpipe: view-volume
// clipping of clip-space triangles, perspective divide and viewport transform.
// Not here: snapping and setup (triangle_setup.h).
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "raster/triangle_setup.h"

namespace pem::raster {

struct ClipVertex {
    glm::vec4 pos;                        // clip space
    std::array<float, kMaxAttribs> attr;  // interpolated attributes
};

using WindowTriangle = std::array<WindowVertex, 3>;

// Clips triangle (a, b, c) against the view volume (-w <= x, y <= w, and -w <= z <= w unless
// depthClamp) and appends the resulting window-space triangles, in the order the reference
// draws them, to `out`. The viewport is (0, 0, width, height), depth range [0, 1].
void ClipTriangle(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c, int numAttribs,
                  bool depthClamp, int width, int height, std::vector<WindowTriangle>* out);

// ClipTriangle's fast path one vertex at a time: a triangle whose three vertices are inside the
// view volume is passed on as (ToWindow(a), ToWindow(b), ToWindow(c)), bit for bit.
bool InsideViewVolume(const glm::vec4& pos, bool depthClamp);
WindowVertex ToWindow(const ClipVertex& v, int numAttribs, int width, int height);

}  // namespace pem::raster
