// SPDX-License-Identifier: MIT
// static_em.h — the baseline the papers compare against: one cube map per lens group, ray
// traced from its EM origin with the group itself left out (rays continue through it), looked
// up at run time with the exit directions of the hybrid paths (a shell at infinity).
//
//   raster::Texture map = TraceStaticMap(tracer, group, origin, 128, threads);
//
// Conventions: face size n, texel centres' directions in GL's face table (raster::FaceDirection);
// every MIP level by 2×2 means of the float level above, then rounded to 8 bits. In a 2D layout
// (parameterization.h) the texel centres' directions are LayoutDirection's, the sphere map's
// turned into the world by worldFromEye (the eye space it is drawn in).
// Not here: drawing (renderer.h).
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "raster/frame.h"
#include "runtime/parameterization.h"
#include "trace/tracer.h"

namespace pem::runtime {

raster::Texture TraceStaticMap(const trace::Tracer& tracer, int group, const glm::vec3& origin,
                               int size, int threads);  // a cube of face size `size`

// The map's textures in a layout: one, or two for the two-image layouts (chart 0, chart 1).
std::vector<raster::Texture> TraceStaticMap(const trace::Tracer& tracer, int group,
                                            const glm::vec3& origin, const MapLayout& layout,
                                            int threads,
                                            const glm::mat3& worldFromEye = glm::mat3(1.0f));

}  // namespace pem::runtime
