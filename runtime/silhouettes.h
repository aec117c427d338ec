// SPDX-License-Identifier: MIT
// silhouettes.h — antialiased borders of the lens objects in a run-time frame. The lens objects
// are drawn one sample per pixel (the pixel centre decides which group a pixel shows), while
// the ray tracer the maps are fitted to averages k×k samples; so a pixel on a group's border
// shows the group or the surroundings whole where the traced frame mixes them. Here each such
// pixel takes its k×k camera samples (trace/render.h RenderPixels): the samples that miss every
// lens group keep the ray tracer's radiance, each sample on a lens group takes that group's
// drawn colour at the same subpixel (the groups are drawn with k×k subpixels) or, where the
// draw and the ray tracer disagree on the silhouette, the group's colour nearest to it.
//
//   std::vector<glm::ivec2> border = SilhouettePixels(groupOf, width, height);
//   ResolveSilhouettes(tracer, camera, k, border, groupOf, groupSamples, threads, &image, &rays);
//
// Not here: drawing the groups (renderer.h), the surroundings elsewhere (trace/render.h).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "raster/camera.h"
#include "trace/image.h"
#include "trace/tracer.h"

namespace pem::runtime {

// Pixels whose 8-neighbourhood (inside the frame) holds a pixel of another group, where at
// least one of the two is a lens group (groupOf: the group each pixel centre sees, -1 none).
// Row-major order.
std::vector<glm::ivec2> SilhouettePixels(const std::vector<int>& groupOf, int width, int height);

// One lens group's draw at the subpixels of the border pixels (supersampling.h: subpixel s
// of a pixel is the ray tracer's sample s), summed over the group's frames with their weights.
struct GroupSamples {
    std::vector<double> rgb;       // border × k² × 3 (empty: the group was not drawn)
    std::vector<uint8_t> covered;  // border × k²: the draw holds a fragment there
};

// Re-composites `border` in `image` (RGB, the lens groups already drawn) from k×k samples; a
// lens sample of group g takes samples[g] at that subpixel when covered, else the mean of g's
// covered subpixels of the pixel, else the neighbour rule above.
void ResolveSilhouettes(const trace::Tracer& tracer, const raster::Camera& camera, int k,
                        const std::vector<glm::ivec2>& border, const std::vector<int>& groupOf,
                        const std::vector<GroupSamples>& samples, int threads,
                        trace::FloatImage* image, trace::RayCounts* counts);

}  // namespace pem::runtime
