// SPDX-License-Identifier: MIT
// infer_frames.cpp — test frames for infer/ (infer_frames.h).
#include "tests/infer/infer_frames.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "tests/case_generator.h"

namespace pem::test {
namespace {

using raster::Frame;
using raster::Pass;
using raster::Texture;
using raster::Vertex;

// splitmix64 bytes (case_generator.h's stream).
struct Bytes {
    Rng rng;
    uint8_t Next() { return static_cast<uint8_t>(rng.Next() >> 24); }
};

Texture RandomCube(int size, uint64_t seed) {
    Texture t;
    t.kind = raster::TextureKind::Cube;
    t.width = t.height = size;
    Bytes rng{{seed}};
    for (int n = size; n >= 1; n /= 2) {
        std::vector<uint8_t> level(static_cast<size_t>(6 * n * n * 4));
        for (size_t k = 0; k < level.size(); ++k) level[k] = k % 4 == 3 ? 255 : rng.Next();
        t.levels.push_back(std::move(level));
    }
    return t;
}

Frame Blank(int width, int height) {
    Frame f;
    f.width = width;
    f.height = height;
    f.clear = {0, 0, 0, 255};
    return f;
}

Vertex At(const glm::vec4& pos, const glm::vec3& dir, const glm::vec4& colour = glm::vec4(1.0f)) {
    Vertex v;
    v.pos = pos;
    v.coord[0] = dir;
    v.color = colour;
    return v;
}

void AddQuad(Pass* p, const glm::vec3 dirs[4], const glm::vec4& colour) {
    const glm::vec4 pos[4] = {{-1, -1, 0, 1}, {1, -1, 0, 1}, {1, 1, 0, 1}, {-1, 1, 0, 1}};
    for (int k : {0, 1, 2, 0, 2, 3}) p->vertices.push_back(At(pos[k], dirs[k], colour));
}

}  // namespace

Frame MirrorSphere(int width, int height, int cubeSize) {
    Frame f = BenchmarkFrame(width, height, 24, 32, cubeSize);
    f.passes.erase(f.passes.begin());  // the sky quad
    return f;
}

Frame RandomSphere(const SphereSpec& s) {
    Frame f = Blank(s.width, s.height);
    f.textures.push_back(RandomCube(s.cubeSize, s.seed));
    const glm::mat4 vp =
        glm::perspective(glm::radians(40.0f),
                         static_cast<float>(s.width) / static_cast<float>(s.height), 0.1f, 100.0f) *
        glm::lookAt(s.eye, glm::vec3(0.0f), glm::vec3(0, 1, 0));
    // Vertex (ring i, segment j): position, normal, reflected view ray.
    auto vertex = [&](int i, int j, float* facing) {
        const float th = 3.14159265f * static_cast<float>(i) / static_cast<float>(s.rings);
        const float ph = 6.28318531f * static_cast<float>(j) / static_cast<float>(s.segments);
        const glm::vec3 n(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
        const glm::vec3 pos = s.radius * n;
        const glm::vec3 in = glm::normalize(pos - s.eye);
        if (facing) *facing = std::fabs(glm::dot(n, in));
        return At(vp * glm::vec4(pos, 1.0f), in - 2.0f * glm::dot(n, in) * n);
    };
    Pass p;
    for (int i = 0; i < s.rings; ++i)
        for (int j = 0; j < s.segments; ++j) {
            float facing = 0.0f;
            const Vertex a = vertex(i, j, nullptr), b = vertex(i + 1, j, nullptr),
                         c = vertex(i + 1, j + 1, &facing), d = vertex(i, j + 1, nullptr);
            if (facing >= s.rimBand) continue;
            for (const Vertex& v : {a, b, c, a, c, d}) p.vertices.push_back(v);
        }
    f.passes.push_back(p);
    return f;
}

Frame FaceQuad(int width, int height, int cubeSize, float e, uint64_t seed) {
    Frame f = Blank(width, height);
    f.textures.push_back(RandomCube(cubeSize, seed));
    Pass p;
    const glm::vec3 dirs[4] = {{-e, -e, 1}, {e, -e, 1}, {e, e, 1}, {-e, e, 1}};
    AddQuad(&p, dirs, glm::vec4(1.0f));
    f.passes.push_back(p);
    return f;
}

void AddFaintPass(Frame* f, float weight) {
    Pass p;
    p.blend = raster::BlendState::Additive();
    const glm::vec3 dirs[4] = {
        {-1.5f, -1.2f, -1}, {1.5f, -1.2f, -1}, {1.5f, 1.2f, -1}, {-1.5f, 1.2f, -1}};
    AddQuad(&p, dirs, glm::vec4(weight, weight, weight, 0.0f));
    f->passes.push_back(p);
}

}  // namespace pem::test
