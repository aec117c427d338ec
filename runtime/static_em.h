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
#include "runtime/lens_group_em.h"
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

// The direct images of a lens group's layers (hybrid §4.3: the environment seen from the EM
// origin, the group left out): per layer a cube of face size n, every MIP level (2×2 means),
// RGBA floats in radiance, premultiplied, alpha 1 where the layer has a hit along the texel
// centre's direction (trace::LayerColours; the outermost layer the environment where it has
// none); after the layers, the whole environment (the nearest hit: the static map's floats, as
// the single-layer map sees it). Inference fills the texels no sample observes from them.
struct DirectImages {
    int size = 0;
    std::vector<std::vector<std::vector<float>>> levels;  // [layer or single][level] faces×n×n×4
};
DirectImages TraceDirectImages(const trace::Tracer& tracer, const LensGroupEm& group, int size,
                               int threads);

}  // namespace pem::runtime
