// SPDX-License-Identifier: MIT
// clip.h — vertex post-processing as Mesa's draw module does it: view-volume clipping of
// clip-space triangles, perspective divide and viewport transform. The two drivers differ only in
// the viewport transform of unclipped vertices: llvmpipe's JIT code fuses it (fma), softpipe's
// draw module (no LLVM) runs it as plain C, as the clipper does for new vertices.
// Not here: snapping and setup (triangle_setup.h).
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "raster/frame.h"
#include "raster/triangle_setup.h"

namespace pem::raster {

struct ClipVertex {
    glm::vec4 pos;                        // clip space
    std::array<float, kMaxAttribs> attr;  // interpolated attributes
};

// Vertex `index` of a pass as the clipper takes it: attributes are the units' coordinates (3 per
// unit) followed by the colour (4), from PassColourAttrib(pass) on.
ClipVertex PassClipVertex(const Pass& pass, uint32_t index);
inline int PassColourAttrib(const Pass& pass) {
    return 3 * pass.numUnits;
}
// The vertex index of corner i (3 per triangle) of a pass.
inline uint32_t PassIndex(const Pass& pass, size_t i) {
    return pass.indices.empty() ? static_cast<uint32_t>(i) : pass.indices[i];
}

using WindowTriangle = std::array<WindowVertex, 3>;

// How unclipped vertices are mapped to the window: fma(p * (1/w), scale, translate) (llvmpipe)
// or (p * (1/w)) * scale + translate (softpipe).
enum class ViewportForm { Fused, Plain };

// Clips triangle (a, b, c) against the view volume (-w <= x, y <= w, and -w <= z <= w unless
// depthClamp) and appends the resulting window-space triangles, in the order the reference
// draws them, to `out`. The viewport is (0, 0, width, height), depth range [0, 1].
void ClipTriangle(const ClipVertex& a, const ClipVertex& b, const ClipVertex& c, int numAttribs,
                  bool depthClamp, int width, int height, ViewportForm form,
                  std::vector<WindowTriangle>* out);

// ClipTriangle's fast path one vertex at a time: a triangle whose three vertices are inside the
// view volume is passed on as (ToWindow(a), ToWindow(b), ToWindow(c)), bit for bit.
bool InsideViewVolume(const glm::vec4& pos, bool depthClamp, ViewportForm form);
WindowVertex ToWindow(const ClipVertex& v, int numAttribs, int width, int height,
                      ViewportForm form);

}  // namespace pem::raster
