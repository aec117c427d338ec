// SPDX-License-Identifier: MIT
// silhouettes.cpp — SilhouettePixels and ResolveSilhouettes (silhouettes.h).
#include "runtime/silhouettes.h"

#include <array>
#include <cstddef>
#include <optional>

#include "trace/render.h"

namespace pem::runtime {

namespace {

// The 8 neighbours, 4-neighbours first.
constexpr std::array<glm::ivec2, 8> kNeighbours{
    {{-1, 0}, {1, 0}, {0, -1}, {0, 1}, {-1, -1}, {1, -1}, {-1, 1}, {1, 1}}};

size_t Index(glm::ivec2 p, int width) {
    return static_cast<size_t>(p.y) * static_cast<size_t>(width) + static_cast<size_t>(p.x);
}

bool Inside(glm::ivec2 p, int width, int height) {
    return p.x >= 0 && p.y >= 0 && p.x < width && p.y < height;
}

// Group g's drawn colour at pixel p: p's own if its centre sees g, else the first neighbour's
// that does; p's own colour when none does.
glm::vec3 GroupColour(const trace::FloatImage& drawn, const std::vector<int>& groupOf, glm::ivec2 p,
                      int g) {
    const int w = drawn.width, h = drawn.height;
    glm::ivec2 from = p;
    if (groupOf[Index(p, w)] != g)
        for (const glm::ivec2 d : kNeighbours)
            if (Inside(p + d, w, h) && groupOf[Index(p + d, w)] == g) {
                from = p + d;
                break;
            }
    const float* c = drawn.At(from.x, from.y);
    return {c[0], c[1], c[2]};
}

// Group g's draw at subpixel s of border pixel b: there when covered, else the mean of the
// pixel's covered subpixels; none when the draw covers none of them. Clamped to 1 as the
// renderer's lens pixels are.
std::optional<glm::vec3> LensSample(const GroupSamples& g, size_t b, size_t s, size_t kk) {
    if (g.covered.empty()) return std::nullopt;
    const auto at = [&](size_t i) {
        return glm::vec3(glm::min(glm::dvec3(g.rgb[3 * i], g.rgb[3 * i + 1], g.rgb[3 * i + 2]),
                                  glm::dvec3(1.0)));
    };
    if (g.covered[b * kk + s]) return at(b * kk + s);
    glm::vec3 sum(0.0f);
    int n = 0;
    for (size_t t = 0; t < kk; ++t)
        if (g.covered[b * kk + t]) sum += at(b * kk + t), ++n;
    if (n == 0) return std::nullopt;
    return sum / static_cast<float>(n);
}

}  // namespace

std::vector<glm::ivec2> SilhouettePixels(const std::vector<int>& groupOf, int width, int height) {
    std::vector<glm::ivec2> out;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::ivec2 p(x, y);
            const int g = groupOf[Index(p, width)];
            for (const glm::ivec2 d : kNeighbours) {
                if (!Inside(p + d, width, height)) continue;
                const int n = groupOf[Index(p + d, width)];
                if (n != g && (n >= 0 || g >= 0)) {
                    out.push_back(p);
                    break;
                }
            }
        }
    return out;
}

void ResolveSilhouettes(const trace::Tracer& tracer, const raster::Camera& camera, int k,
                        const std::vector<glm::ivec2>& border, const std::vector<int>& groupOf,
                        const std::vector<GroupSamples>& samples, int threads,
                        trace::FloatImage* image, trace::RayCounts* counts) {
    if (k <= 1 || border.empty()) return;
    // Step 1: the ray tracer's samples of the border pixels.
    const trace::PixelSamples traced = trace::RenderPixels(tracer, camera, k, border, threads);
    *counts += traced.counts;
    // Step 2: each border pixel from its samples, reading the colours drawn before this step.
    const trace::FloatImage drawn = *image;
    const size_t kk = static_cast<size_t>(k) * static_cast<size_t>(k);
    const float invSamples = 1.0f / static_cast<float>(kk);
    for (size_t b = 0; b < border.size(); ++b) {
        glm::vec3 lens(0.0f);
        for (size_t s = 0; s < kk; ++s) {
            const int g = traced.groups[b * kk + s];
            if (g < 0) continue;
            lens += LensSample(samples[static_cast<size_t>(g)], b, s, kk)
                        .value_or(GroupColour(drawn, groupOf, border[b], g));
        }
        const glm::vec3 c = traced.surroundings[b] + lens * invSamples;
        float* out = image->At(border[b].x, border[b].y);
        out[0] = c.x, out[1] = c.y, out[2] = c.z;
    }
}

}  // namespace pem::runtime
