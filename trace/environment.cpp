// SPDX-License-Identifier: MIT
// environment.cpp — OpenEXR → float RGB environment, and the bilinear direction lookup
// (conventions in environment.h). Reading goes through Imf::RgbaInputFile, which handles
// scanline and tiled files, every compression (DWAB included) and half/float channels.
// Not here: writing EXRs, MIP levels.
#include "trace/environment.h"

#include <ImfEnvmap.h>
#include <ImfRgbaFile.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "base/input_error.h"

namespace pem::trace {

namespace {

constexpr long long kMaxPixels = 1LL << 26;  // 64 Mpixels: far above any environment we use

// Reads every pixel as RGB float (negative values clamped to 0; NaN/Inf rejected).
void ReadPixels(const std::string& path, Environment* env, Imath::Box2i* dataWindow) {
    Imf::RgbaInputFile file(path.c_str());
    const Imath::Box2i dw = file.dataWindow();
    const long long w = static_cast<long long>(dw.max.x) - dw.min.x + 1;
    const long long h = static_cast<long long>(dw.max.y) - dw.min.y + 1;
    if (w <= 0 || h <= 0 || w * h > kMaxPixels)
        throw pem::base::InputError(path, "data window " + std::to_string(w) + "x" +
                                              std::to_string(h) + " is empty or too large");
    std::vector<Imf::Rgba> px(static_cast<size_t>(w * h));
    // The frame buffer is addressed with data-window coordinates (OpenEXR convention).
    file.setFrameBuffer(px.data() - dw.min.x - static_cast<long long>(dw.min.y) * w, 1,
                        static_cast<size_t>(w));
    file.readPixels(dw.min.y, dw.max.y);
    env->width = static_cast<int>(w);
    env->height = static_cast<int>(h);
    env->rgb.resize(3 * px.size());
    for (size_t i = 0; i < px.size(); ++i) {
        const float c[3] = {px[i].r, px[i].g, px[i].b};
        for (int k = 0; k < 3; ++k) {
            if (!std::isfinite(c[k]))
                throw pem::base::InputError(
                    path, "non-finite texel at (" + std::to_string(i % static_cast<size_t>(w)) +
                              ", " + std::to_string(i / static_cast<size_t>(w)) + ")");
            env->rgb[3 * i + static_cast<size_t>(k)] = std::max(c[k], 0.0f);
        }
    }
    *dataWindow = dw;
}

glm::vec3 Texel(const Environment& env, int x, int y) {
    const size_t at =
        3 * (static_cast<size_t>(y) * static_cast<size_t>(env.width) + static_cast<size_t>(x));
    return {env.rgb[at], env.rgb[at + 1], env.rgb[at + 2]};
}

glm::vec3 Bilerp(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
                 float fx, float fy) {
    return (1.0f - fy) * ((1.0f - fx) * a + fx * b) + fy * ((1.0f - fx) * c + fx * d);
}

glm::vec3 LatLongLookup(const Environment& env, const glm::vec3& d) {
    // Step 1: direction → continuous pixel position (pixel-edge form, data/README.md).
    const double pi = std::numbers::pi;
    const double u =
        0.5 - std::atan2(static_cast<double>(d.x), static_cast<double>(d.z)) / (2.0 * pi);
    const double v = 0.5 - std::asin(std::clamp(static_cast<double>(d.y), -1.0, 1.0)) / pi;
    const double x = u * env.width - 0.5, y = v * env.height - 0.5;
    // Step 2: bilinear taps, columns wrap, rows clamp.
    const double x0 = std::floor(x), y0 = std::floor(y);
    const float fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
    auto col = [&](double i) {
        return static_cast<int>((static_cast<long long>(i) % env.width + env.width) % env.width);
    };
    auto row = [&](double j) { return std::clamp(static_cast<int>(j), 0, env.height - 1); };
    return Bilerp(Texel(env, col(x0), row(y0)), Texel(env, col(x0 + 1), row(y0)),
                  Texel(env, col(x0), row(y0 + 1)), Texel(env, col(x0 + 1), row(y0 + 1)), fx, fy);
}

glm::vec3 CubeLookup(const Environment& env, const glm::vec3& d) {
    // Step 1: face and position in it (OpenEXR: pixel centres at integers 0 .. s-1).
    const Imath::Box2i dw(Imath::V2i(0, 0), Imath::V2i(env.width - 1, env.height - 1));
    const int s = Imf::CubeMap::sizeOfFace(dw);
    Imf::CubeMapFace face;
    Imath::V2f pif;
    Imf::CubeMap::faceAndPixelPosition(Imath::V3f(d.x, d.y, d.z), dw, face, pif);
    // Step 2: bilinear inside the face, clamped at its edges.
    const float x0 = std::floor(pif.x), y0 = std::floor(pif.y);
    auto tap = [&](float i, float j) {
        const Imath::V2f q(std::clamp(i, 0.0f, float(s - 1)), std::clamp(j, 0.0f, float(s - 1)));
        const Imath::V2f p = Imf::CubeMap::pixelPosition(face, dw, q);
        return Texel(env, std::clamp(static_cast<int>(std::lround(p.x)), 0, env.width - 1),
                     std::clamp(static_cast<int>(std::lround(p.y)), 0, env.height - 1));
    };
    return Bilerp(tap(x0, y0), tap(x0 + 1, y0), tap(x0, y0 + 1), tap(x0 + 1, y0 + 1), pif.x - x0,
                  pif.y - y0);
}

}  // namespace

Environment LoadEnvironment(const std::string& exrPath, Environment::Mapping mapping,
                            float intensity) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(exrPath, ec))
        throw pem::base::InputError(exrPath, "cannot open file (missing or not a regular file)");
    Environment env;
    env.path = exrPath;
    env.mapping = mapping;
    env.intensity = intensity;
    Imath::Box2i dw;
    try {
        ReadPixels(exrPath, &env, &dw);
    } catch (const pem::base::InputError&) {
        throw;
    } catch (const std::exception& e) {  // Iex::BaseExc and std::bad_alloc
        throw pem::base::InputError(exrPath, std::string("OpenEXR: ") + e.what());
    }
    if (mapping == Environment::Mapping::Cube && env.height != 6 * env.width)
        throw pem::base::InputError(exrPath, "cube map must be N wide and 6N tall, got " +
                                                 std::to_string(env.width) + "x" +
                                                 std::to_string(env.height));
    return env;
}

glm::vec3 EnvRadiance(const Environment& env, const glm::vec3& dir) {
    if (env.mapping == Environment::Mapping::None || env.rgb.empty()) return glm::vec3(0.0f);
    const float len = glm::length(dir);
    if (!(len > 0.0f) || !std::isfinite(len)) return glm::vec3(0.0f);
    const glm::vec3 d = dir / len;
    const glm::vec3 c =
        env.mapping == Environment::Mapping::LatLong ? LatLongLookup(env, d) : CubeLookup(env, d);
    return c * env.intensity;
}

}  // namespace pem::trace
