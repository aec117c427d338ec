// SPDX-License-Identifier: MIT
// renderer_test.cpp — the run-time renderer on the bundled mirror sphere with maps made by hand
// (runtime/map_set.h), against what those maps must give: a constant map times the mirror's
// Fresnel factor (F0 = 0.9, so within [0.9, 1] of the map), the premultiplied "over" of the
// layers, the blend of two samples as the weighted sum of each sample's frame, the background
// shared by every method, and one clear error for a missing map.
#include "runtime/renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "base/input_error.h"
#include "runtime/silhouettes.h"
#include "tests/runtime/layout_directions.h"
#include "trace/render.h"

namespace pem::runtime {
namespace {

const std::string kScene = std::string(PEM_SOURCE_DIR) + "/data/scenes/mirror_sphere.gltf";

// A cube texture of face size n, every texel (r, g, b, a) in bytes.
raster::Texture Constant(int n, uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
    raster::Texture t;
    t.kind = raster::TextureKind::Cube;
    t.width = t.height = n;
    for (int s = n; s >= 1; s /= 2) {
        std::vector<uint8_t>& level = t.levels.emplace_back();
        for (int k = 0; k < 6 * s * s; ++k) level.insert(level.end(), {r, g, b, a});
    }
    return t;
}

// Two samples 20° apart about the sphere; one lens group with two sphere layers.
struct Fixture {
    trace::Scene scene = trace::LoadScene(kScene);
    std::map<std::string, std::vector<raster::Texture>> textures;  // "<view>/<name>"

    MapSet Maps() {
        MapSet m;
        m.name = "test maps";
        const raster::Camera c = trace::CameraForSize(*scene.camera, 48, 36);
        const glm::vec3 centre = trace::LensCentre(scene);
        for (double deg : {-10.0, 10.0}) {
            raster::Camera s = c;
            const glm::vec3 d = c.eye - centre;
            const float a = static_cast<float>(glm::radians(deg));
            s.eye = centre + glm::vec3(d.x * std::cos(a) + d.z * std::sin(a), d.y,
                                       -d.x * std::sin(a) + d.z * std::cos(a));
            s.target = centre;
            m.samples.push_back(s);
        }
        m.inferred = {0, 1};
        LensGroupEm g;
        g.objects = {"mirror_sphere"};
        g.emOrigin = centre;
        g.layers = {
            {"sphere", trace::SphereShell{glm::dvec3(centre), 2.0}, 2.0, 5, {}, 1.0, 0.0, {}},
            {"sphere", trace::SphereShell{glm::dvec3(centre), 6.0}, 6.0, 5, {}, 1.0, 0.0, {}}};
        m.groups = {g};
        m.spp = 1;
        m.res = 8;
        m.map = [this](int view, int, const std::string& name) -> const raster::Texture* {
            auto it = textures.find(std::to_string(view) + "/" + name);
            return it == textures.end() ? nullptr : it->second.data();
        };
        return m;
    }
    void Set(int view, const std::string& name, const raster::Texture& t) {
        textures[std::to_string(view) + "/" + name] = {t};
    }
    // A map of one or two textures (a two-image layout's charts).
    void Set(int view, const std::string& name, const std::vector<raster::Texture>& t) {
        textures[std::to_string(view) + "/" + name] = t;
    }
    // The same inner and outer layer maps at both samples.
    void SetLayers(const std::vector<raster::Texture>& inner,
                   const std::vector<raster::Texture>& outer) {
        for (int v : {0, 1}) Set(v, "layer_0", inner), Set(v, "layer_1", outer);
    }
    void SetLayers(const raster::Texture& inner, const raster::Texture& outer) {
        SetLayers(std::vector{inner}, std::vector{outer});
    }
};

// An opaque outer layer of one colour under a transparent inner one, and that colour in [0, 1].
void SetOpaqueOuterLayer(Fixture* fx) {
    fx->SetLayers(Constant(8, 0, 0, 0, 0), Constant(8, 128, 64, 255, 255));
}
constexpr float kOuterColour[3] = {128 / 255.0f, 64 / 255.0f, 1.0f};

RenderSettings Settings(Method m) {
    RenderSettings s;
    s.method = m;
    s.subpixels = 1;
    s.threads = 2;
    return s;
}

raster::Camera Midway(const MapSet& m) {
    raster::Camera c = m.samples[0];
    c.eye = 0.5f * (m.samples[0].eye + m.samples[1].eye);
    return c;
}

size_t LensPixels(const RenderedFrame& f) {
    size_t n = 0;
    for (uint8_t v : f.lensMask) n += v;
    return n;
}

TEST(Renderer, ConstantMapTimesFresnel) {
    Fixture fx;
    SetOpaqueOuterLayer(&fx);
    Renderer r(fx.scene, fx.Maps(), 2);
    for (Method m : {Method::Hybrid, Method::Pem}) {
        const RenderedFrame f = r.Render(r.SampleCamera(0), Settings(m));
        EXPECT_EQ(f.stats.samples, std::vector<int>{0});
        ASSERT_GT(LensPixels(f), 100u);
        for (size_t p = 0; p < f.lensMask.size(); ++p) {
            if (!f.lensMask[p]) continue;
            const float* px = &f.image.data[3 * p];
            const float* map = kOuterColour;
            for (int c = 0; c < 3; ++c)  // F in [0.9, 1], one 8-bit step of rounding
                ASSERT_TRUE(px[c] >= 0.9f * map[c] - 1.5f / 255 && px[c] <= map[c] + 1.5f / 255)
                    << ToString(m) << " pixel " << p << " channel " << c << ": " << px[c];
        }
    }
}

// Maps that hold radiance / S (MapHardware::radianceScale) are drawn S times brighter: the
// constant map times F times S, saturating at S (the blue channel's 1.0 at S = 2 shows 2 F).
TEST(Renderer, RadianceScaleMultipliesTheLensFrames) {
    Fixture fx;
    SetOpaqueOuterLayer(&fx);
    MapSet scaled = fx.Maps();
    scaled.hardware.radianceScale = 2.0f;
    Renderer one(fx.scene, fx.Maps(), 2), two(fx.scene, std::move(scaled), 2);
    for (Method m : {Method::Hybrid, Method::Pem}) {
        const RenderedFrame f1 = one.Render(one.SampleCamera(0), Settings(m));
        const RenderedFrame f2 = two.Render(two.SampleCamera(0), Settings(m));
        ASSERT_EQ(f1.lensMask, f2.lensMask);
        size_t above = 0;
        for (size_t p = 0; p < f1.lensMask.size(); ++p) {
            if (!f1.lensMask[p]) continue;
            for (size_t c = 0; c < 3; ++c) {
                const float v1 = f1.image.data[3 * p + c], v2 = f2.image.data[3 * p + c];
                ASSERT_EQ(v2, 2.0f * v1) << ToString(m) << " pixel " << p << " channel " << c;
                above += v2 > 1.0f;
            }
        }
        EXPECT_GT(above, 100u) << ToString(m);  // the blue channel: 2 F > 1
    }
}

// `t` as an RGBA32F texture of one colour (every level).
raster::Texture FloatConstant(raster::Texture t, const std::array<float, 4>& rgba) {
    t.format = raster::TexelFormat::Rgba32F;
    for (std::vector<uint8_t>& level : t.levels) {
        std::vector<float> v(level.size());
        for (size_t i = 0; i < v.size(); ++i) v[i] = rgba[i % 4];
        level = raster::FloatBytes(v);
    }
    return t;
}

// Float maps (MapHardware::format RGBA32F) are drawn into a float colour buffer: a map value
// above 1 shows as it is (here 1.5 and 3 times F), where an 8-bit map would saturate, and the
// in-range channel as F times it, without 8-bit steps.
TEST(Renderer, FloatMapsAreDrawnUnclamped) {
    Fixture fx;
    const raster::Texture outer = Constant(8, 128, 64, 255, 255);
    fx.SetLayers(FloatConstant(Constant(8, 0, 0, 0, 0), {0, 0, 0, 0}),
                 FloatConstant(outer, {1.5f, 0.25f, 3.0f, 1.0f}));
    MapSet maps = fx.Maps();
    maps.hardware.format = raster::TexelFormat::Rgba32F;
    Renderer r(fx.scene, std::move(maps), 2);
    const float map[3] = {1.5f, 0.25f, 3.0f};
    for (Method m : {Method::Hybrid, Method::Pem}) {
        const RenderedFrame f = r.Render(r.SampleCamera(0), Settings(m));
        ASSERT_GT(LensPixels(f), 100u);
        size_t above = 0;
        for (size_t p = 0; p < f.lensMask.size(); ++p) {
            if (!f.lensMask[p]) continue;
            const float* px = &f.image.data[3 * p];
            for (int c = 0; c < 3; ++c) {  // F in [0.9, 1], float rounding only
                ASSERT_TRUE(px[c] >= 0.9f * map[c] * (1 - 1e-5f) && px[c] <= map[c] * (1 + 1e-5f))
                    << ToString(m) << " pixel " << p << " channel " << c << ": " << px[c];
                above += px[c] > 1.0f;
            }
        }
        EXPECT_GT(above, 200u) << ToString(m);  // red and blue above 1
    }
}

// With 3×3 subpixels, a pixel on the lens's border mixes the ray tracer's samples that miss it
// (trace::RenderPixels, tested on its own) with the lens colour at the samples that hit it: the
// constant map times F in [0.9, 1], weighted by those samples' share; a pixel none of whose
// samples hits the lens is the ray tracer's alone. At the maps' t and at t = 1, where the
// silhouette is refined into midpoints whose eye ray grazes past the mesh (they take their input
// edge's surface, not F = 0).
TEST(Renderer, BorderPixelsMixLensAndSurroundingsBySamples) {
    Fixture fx;
    SetOpaqueOuterLayer(&fx);
    Renderer r(fx.scene, fx.Maps(), 2);
    const raster::Camera cam = r.SampleCamera(0);
    for (double t : {0.0, 1.0}) {
        RenderSettings s = Settings(Method::Hybrid);
        s.subpixels = 3;
        s.t = t;
        const RenderedFrame f = r.Render(cam, s);
        const std::vector<glm::ivec2> border = SilhouettePixels(f.groupOf, cam.width, cam.height);
        ASSERT_GT(border.size(), 20u);
        const trace::PixelSamples traced = trace::RenderPixels(r.tracer(), cam, 3, border, 1);
        const float* map = kOuterColour;
        int mixed = 0, outside = 0;
        for (size_t b = 0; b < border.size(); ++b) {
            int lens = 0;
            for (size_t k = 0; k < 9; ++k) lens += traced.groups[9 * b + k] >= 0;
            mixed += lens > 0 && lens < 9;
            const float* px = f.image.At(border[b].x, border[b].y);
            const glm::vec3& bg = traced.surroundings[b];
            if (lens == 0) {
                ++outside;
                for (int c = 0; c < 3; ++c) EXPECT_EQ(px[c], bg[c]) << "pixel " << b;
                continue;
            }
            const float share = static_cast<float>(lens) / 9.0f;
            for (int c = 0; c < 3; ++c)
                EXPECT_TRUE(px[c] >= bg[c] + share * (0.9f * map[c] - 1.5f / 255) &&
                            px[c] <= bg[c] + share * (map[c] + 1.5f / 255))
                    << "t " << t << " pixel " << b << " (" << lens << " lens samples) channel " << c
                    << ": " << px[c];
        }
        EXPECT_GT(mixed, 10);   // not vacuous: partly covered pixels
        EXPECT_GT(outside, 0);  // and background pixels next to the lens
    }
}

TEST(Renderer, OpaqueInnerLayerHidesTheOuterOne) {
    Fixture fx;
    fx.SetLayers(Constant(8, 200, 10, 10, 255), Constant(8, 10, 10, 200, 255));
    Renderer both(fx.scene, fx.Maps(), 2);
    const RenderedFrame f = both.Render(both.SampleCamera(0), Settings(Method::Hybrid));
    for (int v : {0, 1}) fx.Set(v, "layer_1", Constant(8, 200, 10, 10, 255));
    Renderer inner(fx.scene, fx.Maps(), 2);
    const RenderedFrame g = inner.Render(inner.SampleCamera(0), Settings(Method::Hybrid));
    ASSERT_GT(LensPixels(f), 100u);
    EXPECT_EQ(f.image.data, g.image.data);  // the outer colour never shows through alpha 1
}

// A mirror drawn with the PEM paper's local/distant split: its single-layer PEM is the `single`
// map (the baseline the split is compared with), not the split again.
TEST(Renderer, SingleLayerPemOfASplitMirrorIsItsSingleMap) {
    Fixture fx;
    MapSet maps = fx.Maps();
    LensGroupEm& g = maps.groups[0];
    g.pem = true;
    g.localShell = trace::SphereShell{glm::dvec3(g.emOrigin), 1.5};
    g.distantShell = trace::SphereShell{glm::dvec3(g.emOrigin), 6.0};
    for (int v : {0, 1}) {
        fx.Set(v, "pem_distant", Constant(8, 200, 10, 10, 255));
        fx.Set(v, "single", Constant(8, 10, 10, 200, 255));
    }
    Renderer r(fx.scene, maps, 2);
    RenderSettings layered = Settings(Method::Pem), single = layered;
    single.layers = 1;
    const RenderedFrame split = r.Render(r.SampleCamera(0), layered);
    const RenderedFrame one = r.Render(r.SampleCamera(0), single);
    ASSERT_GT(LensPixels(split), 100u);
    size_t red = 0, blue = 0;
    for (size_t p = 0; p < split.lensMask.size(); ++p) {
        if (!split.lensMask[p]) continue;
        red += split.image.data[3 * p] > 0.5f && split.image.data[3 * p + 2] < 0.2f;
        blue += one.image.data[3 * p + 2] > 0.5f && one.image.data[3 * p] < 0.2f;
    }
    EXPECT_GT(red, LensPixels(split) * 9 / 10);   // the distant map
    EXPECT_GT(blue, LensPixels(split) * 9 / 10);  // the single map
}

TEST(Renderer, TwoSamplesBlendAsTheirWeightedFrames) {
    Fixture fx;
    auto frameWith = [&](uint8_t v0, uint8_t v1) {
        for (auto [v, value] : {std::pair{0, v0}, std::pair{1, v1}}) {
            fx.Set(v, "layer_0", Constant(8, 0, 0, 0, 0));
            fx.Set(v, "layer_1", Constant(8, value, value, value, 255));
        }
        Renderer r(fx.scene, fx.Maps(), 2);
        return r.Render(Midway(r.maps()), Settings(Method::Pem));
    };
    const RenderedFrame low = frameWith(40, 40), high = frameWith(240, 240);
    const RenderedFrame mixed = frameWith(40, 240);
    ASSERT_EQ(mixed.stats.samples.size(), 2u);
    const double w0 = mixed.stats.sampleWeights[0], w1 = mixed.stats.sampleWeights[1];
    EXPECT_NEAR(w0 + w1, 1.0, 1e-12);
    EXPECT_NEAR(w0, 0.5, 1e-3);  // midway
    const size_t s0 = static_cast<size_t>(mixed.stats.samples[0]);
    const RenderedFrame& a = s0 == 0 ? low : high;
    const RenderedFrame& b = s0 == 0 ? high : low;
    ASSERT_GT(LensPixels(mixed), 100u);
    for (size_t p = 0; p < mixed.lensMask.size(); ++p)
        for (size_t c = 0; c < 3; ++c) {
            const size_t k = 3 * p + c;
            const double expected =
                mixed.lensMask[p] ? w0 * double{a.image.data[k]} + w1 * double{b.image.data[k]}
                                  : static_cast<double>(low.image.data[k]);
            ASSERT_NEAR(double{mixed.image.data[k]}, expected, 1e-6) << p;
        }
}

TEST(Renderer, EveryMethodSharesTheBackground) {
    Fixture fx;
    for (int v : {0, 1}) {
        fx.Set(v, "layer_0", Constant(8, 0, 0, 0, 0));
        fx.Set(v, "layer_1", Constant(8, 90, 90, 90, 255));
    }
    Renderer r(fx.scene, fx.Maps(), 2);
    const raster::Camera cam = Midway(r.maps());
    const RenderedFrame h = r.Render(cam, Settings(Method::Hybrid));
    const RenderedFrame s = r.Render(cam, Settings(Method::StaticEm));
    ASSERT_EQ(h.lensMask, s.lensMask);
    for (size_t p = 0; p < h.lensMask.size(); ++p) {
        if (h.lensMask[p]) continue;
        for (size_t c = 0; c < 3; ++c) ASSERT_EQ(h.image.data[3 * p + c], s.image.data[3 * p + c]);
    }
}

// One smooth environment stored in each of the five layouts (texels filled from its direction,
// tests/runtime/layout_directions.h): every layout's hybrid frame shows what the cube's does,
// on most of the lens (median within 0.01; the layouts differ where they filter across their
// seams and chart borders, lat-long's seam a curve of wrong colours); a lat-long map stored
// mirrored does not. Measured (16-size maps): median 1/255 for all four; 90 % 0.02 for the
// sphere map, 0.016 for the paraboloid, 0.04 for the tennis ball (two textures each), 0.13 for
// lat-long.
TEST(Renderer, EveryLayoutDrawsTheSameEnvironment) {
    auto env = [](glm::dvec3 d) { return glm::dvec4(0.5 + 0.4 * d, 1.0); };
    auto none = [](glm::dvec3) { return glm::dvec4(0.0); };
    auto frameWith = [&](Parameterization p, bool mirrored) {
        Fixture fx;
        MapSet maps = fx.Maps();
        maps.parameterization = p;
        Renderer probe(fx.scene, maps, 2);
        const raster::Camera cam = probe.SampleCamera(0);
        const glm::dmat3 worldFromEye = glm::transpose(glm::dmat3(raster::ViewMatrix(cam)));
        auto shown = [&](glm::dvec3 d) { return env(mirrored ? glm::dvec3(-d.x, d.y, d.z) : d); };
        fx.SetLayers(testing::FilledMap(p, 16, none, worldFromEye),
                     testing::FilledMap(p, 16, shown, worldFromEye));
        Renderer r(fx.scene, maps, 2);
        return r.Render(cam, Settings(Method::Hybrid));
    };
    const RenderedFrame cube = frameWith(Parameterization::Cube, false);
    ASSERT_GT(LensPixels(cube), 100u);
    // Per lens pixel the largest channel difference to the cube's frame, sorted.
    auto errors = [&](const RenderedFrame& f) {
        std::vector<double> e;
        for (size_t p = 0; p < cube.lensMask.size(); ++p) {
            if (!cube.lensMask[p]) continue;
            double d = 0.0;
            for (size_t c = 0; c < 3; ++c)
                d = std::max(d, std::fabs(double{f.image.data[3 * p + c]} -
                                          double{cube.image.data[3 * p + c]}));
            e.push_back(d);
        }
        std::sort(e.begin(), e.end());
        return e;
    };
    auto quantile = [](const std::vector<double>& e, double q) {
        return e[static_cast<size_t>(q * static_cast<double>(e.size() - 1))];
    };
    for (Parameterization p : kParameterizations) {
        if (p == Parameterization::Cube) continue;
        const std::vector<double> e = errors(frameWith(p, false));
        std::printf("[measure] %s vs cube: median %.4f, 90%% %.4f, max %.4f\n",
                    ParameterizationName(p).data(), quantile(e, 0.5), quantile(e, 0.9), e.back());
        EXPECT_LT(quantile(e, 0.5), 0.01) << ParameterizationName(p);
        // Lat-long: triangles across the seam interpolate s across the whole map (the notes'
        // warning), a thin curve of wrong colours.
        if (p == Parameterization::LatLong) {
            EXPECT_GT(e.back(), 0.2);
        }
    }
    EXPECT_GT(quantile(errors(frameWith(Parameterization::LatLong, true)), 0.5), 0.05);
}

TEST(Renderer, MissingMapNamesTheSet) {
    Fixture fx;
    fx.Set(0, "layer_0", Constant(8, 0, 0, 0, 0));  // layer_1 and sample 1 missing
    Renderer r(fx.scene, fx.Maps(), 1);
    try {
        r.Render(r.SampleCamera(0), Settings(Method::Hybrid));
        FAIL() << "no exception";
    } catch (const base::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("test maps: missing maps for viewpoint sample 0"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace pem::runtime
