// SPDX-License-Identifier: MIT
// tracer_test.cpp — the ray tracer and the trace job: same bytes for 1 and 2 threads, greedy =
// full tree for a pure mirror, RenderFrame (packets, deferred shading) = the single-ray path
// sample by sample, bit for bit, the surroundings of a hybrid frame = the full tree off the
// lenses, the reference of the hybrid scene is finite, lit and shows the
// glass teapot, image channels in range (layer alpha, coverage, confidence), the segmentation's
// and the layers' sample images = the single-ray greedy path sample by sample, circle viewpoints.
#include "trace/tracer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

#include "trace/embree_scene.h"
#include "trace/layers.h"
#include "trace/render.h"
#include "trace/segment.h"

namespace pem::trace {
namespace {

const std::string kRoot = PEM_SOURCE_DIR;
const std::string kHybrid = kRoot + "/data/scenes/hybrid_glass_teapot.gltf";
const std::string kPem = kRoot + "/data/scenes/pem_mirror_teapot.gltf";

// A scene with its Embree BVH and tracer (2 threads, the pinned ISA).
struct TracedScene {
    explicit TracedScene(const std::string& file) : scene(LoadScene(file)) {}
    TracedScene(const TracedScene&) = delete;  // the tracer refers to the members
    TracedScene& operator=(const TracedScene&) = delete;
    Scene scene;
    EmbreeDevice device{{2, "auto"}};
    EmbreeScene embree{device, scene};
    Tracer tracer{scene, embree};
};

// RenderFrame traces rows in steps (camera rays and shadow rays in 8-ray packets, full-tree
// leaves shaded after the tree); the single-ray path (Tracer::Radiance / GreedyRadiance per
// sample, rtcIntersect1 / rtcOccluded1) must give the same float bits.
TEST(Tracer, RenderFrameEqualsTheSingleRayPathBitForBit) {
    for (const std::string& file : {kHybrid, kPem}) {
        const Scene scene = LoadScene(file);
        const EmbreeDevice device({2, "auto"});
        const EmbreeScene embree(device, scene);
        const Tracer tracer(scene, embree);
        const raster::Camera cam = CameraForSize(*scene.camera, 48, 36);
        const int k = 3, spp = k * k;
        for (Model model : {Model::FullTree, Model::Greedy}) {
            const FrameResult frame = RenderFrame(tracer, cam, k, model, 2);
            FloatImage expected(cam.width, cam.height, 3);
            RayCounts counts;
            for (int y = 0; y < cam.height; ++y)
                for (int x = 0; x < cam.width; ++x) {
                    glm::vec3 sum(0.0f);
                    for (int s = 0; s < spp; ++s) {
                        const glm::vec2 p = SamplePosition(x, y, k, s);
                        const Ray ray = raster::PixelRay(cam, p.x, p.y);
                        sum += model == Model::FullTree ? tracer.Radiance(ray, counts)
                                                        : tracer.GreedyRadiance(ray, counts);
                    }
                    expected.Add(x, y, sum * (1.0f / static_cast<float>(spp)));
                }
            ASSERT_EQ(frame.image.data.size(), expected.data.size());
            EXPECT_EQ(std::memcmp(frame.image.data.data(), expected.data.data(),
                                  expected.data.size() * sizeof(float)),
                      0)
                << file << (model == Model::FullTree ? " full tree" : " greedy");
            EXPECT_EQ(frame.counts.primary, counts.primary);
            EXPECT_EQ(frame.counts.secondary, counts.secondary);
            EXPECT_EQ(frame.counts.shadow, counts.shadow);
        }
    }
}

// Surroundings (the rest of a hybrid frame): at 1 sample per pixel, the single-ray full tree at
// every pixel whose camera ray misses the lens groups, black at the others, and the group of
// each pixel as a single camera ray sees it.
TEST(Tracer, SurroundingsAreTheFullTreeOffTheLenses) {
    const TracedScene traced(kHybrid);
    const auto& [scene, device, embree, tracer] = traced;
    const raster::Camera cam = CameraForSize(*scene.camera, 64, 48);
    const FrameResult frame = RenderFrame(tracer, cam, 1, Model::Surroundings, 2);
    ASSERT_EQ(frame.lensGroup.size(), static_cast<size_t>(cam.width * cam.height));
    int lens = 0;
    RayCounts counts;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const Ray ray =
                raster::PixelRay(cam, static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
            const Hit hit = embree.Intersect(ray);
            const int group = hit.valid ? tracer.GroupOf(hit.object) : -1;
            const size_t p = static_cast<size_t>(y * cam.width + x);
            EXPECT_EQ(frame.lensGroup[p], group) << x << "," << y;
            const glm::vec3 expected = group >= 0 ? glm::vec3(0.0f) : tracer.Radiance(ray, counts);
            const float* got = frame.image.At(x, y);
            EXPECT_EQ(std::memcmp(got, &expected[0], 3 * sizeof(float)), 0) << x << "," << y;
            lens += group >= 0;
        }
    EXPECT_GT(lens, 50);                           // the teapot and the cup are seen
    EXPECT_LT(lens, cam.width * cam.height - 50);  // and so is the room
    // No ray beyond the lenses' camera rays.
    EXPECT_EQ(frame.counts.Total(), counts.Total() + static_cast<uint64_t>(lens));
}

// RenderPixels (a hybrid frame's silhouettes): at k×k samples, each listed pixel is the
// single-ray full tree summed over its samples that miss the lens groups (lens samples black),
// and each sample's group is the one its camera ray sees.
TEST(Tracer, RenderPixelsAreTheSurroundingsSampleBySample) {
    const TracedScene traced(kHybrid);
    const auto& [scene, device, embree, tracer] = traced;
    const raster::Camera cam = CameraForSize(*scene.camera, 64, 48);
    const int k = 3, spp = k * k;
    std::vector<glm::ivec2> pixels;
    for (int y = 0; y < cam.height; y += 3)
        for (int x = (y / 3) % 2; x < cam.width; x += 2) pixels.emplace_back(x, y);
    for (int threads : {1, 2}) {
        const PixelSamples got = RenderPixels(tracer, cam, k, pixels, threads);
        ASSERT_EQ(got.surroundings.size(), pixels.size());
        ASSERT_EQ(got.groups.size(), pixels.size() * static_cast<size_t>(spp));
        int lens = 0;
        for (size_t i = 0; i < pixels.size(); ++i) {
            glm::vec3 sum(0.0f);
            RayCounts counts;
            for (int s = 0; s < spp; ++s) {
                const glm::vec2 p = SamplePosition(pixels[i].x, pixels[i].y, k, s);
                const Ray ray = raster::PixelRay(cam, p.x, p.y);
                const Hit hit = embree.Intersect(ray);
                const int group = hit.valid ? tracer.GroupOf(hit.object) : -1;
                EXPECT_EQ(got.groups[i * static_cast<size_t>(spp) + static_cast<size_t>(s)], group);
                if (group < 0) sum += tracer.Radiance(ray, counts);
                lens += group >= 0;
            }
            const glm::vec3 expected = sum * (1.0f / static_cast<float>(spp));
            EXPECT_EQ(std::memcmp(&got.surroundings[i][0], &expected[0], 3 * sizeof(float)), 0)
                << pixels[i].x << "," << pixels[i].y << " threads " << threads;
        }
        EXPECT_GT(lens, 50);
    }
}

TEST(Tracer, GreedyEqualsFullTreeForPureMirror) {
    const Scene scene = LoadScene(kPem);  // only a mirror teapot among diffuse objects
    const EmbreeDevice device({1, "auto"});
    const EmbreeScene embree(device, scene);
    const raster::Camera cam = CameraForSize(*scene.camera, 48, 48);
    for (int depth : {1, 3, 6}) {
        TraceOptions options;
        options.fullTreeDepth = depth;
        const Tracer tracer(scene, embree, options);
        const FrameResult full = RenderFrame(tracer, cam, 1, Model::FullTree, 1);
        const FrameResult greedy = RenderFrame(tracer, cam, 1, Model::Greedy, 1);
        float lens = 0.0f;
        for (float c : full.lensCoverage.data) lens += c;
        EXPECT_GT(lens, 100.0f);
        for (size_t i = 0; i < full.image.data.size(); ++i)
            ASSERT_NEAR(full.image.data[i], greedy.image.data[i],
                        1e-6f * std::max(1.0f, std::abs(full.image.data[i])))
                << "depth " << depth << " value " << i;
        // One branch per mirror hit: the greedy model casts no more rays than the tree.
        EXPECT_EQ(full.counts.Total(), greedy.counts.Total());
    }
}

// Mean of |a - b| over the pixels where `mask` > 0.
double MeanAbsDiff(const FloatImage& a, const FloatImage& b, const FloatImage& mask) {
    double sum = 0.0;
    size_t n = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (!(mask.At(x, y)[0] > 0.99f)) continue;
            for (int c = 0; c < 3; ++c)
                sum += static_cast<double>(std::abs(a.At(x, y)[c] - b.At(x, y)[c]));
            ++n;
        }
    return n ? sum / (3.0 * static_cast<double>(n)) : 0.0;
}

TEST(Tracer, HybridReferenceIsFiniteLitAndShowsTheGlass) {
    const TracedScene traced(kHybrid);
    const auto& [scene, device, embree, tracer] = traced;
    const raster::Camera cam = CameraForSize(*scene.camera, 80, 60);
    const FrameResult ref = RenderFrame(tracer, cam, 2, Model::FullTree, 2);
    double mean = 0.0;
    for (float v : ref.image.data) {
        ASSERT_TRUE(std::isfinite(v));
        ASSERT_GE(v, 0.0f);
        mean += static_cast<double>(v);
    }
    mean /= static_cast<double>(ref.image.data.size());
    EXPECT_GT(mean, 0.05);

    // The same scene without the glass teapot: its pixels must change.
    Scene without = scene;
    for (size_t i = 0; i < without.objects.size(); ++i)
        if (without.objects[i].name == "glass_teapot") {
            without.objects.erase(without.objects.begin() + static_cast<long>(i));
            break;
        }
    ASSERT_EQ(without.objects.size() + 1, scene.objects.size());
    without.lensGroups = FindLensGroups(without.objects, without.materials);
    const EmbreeScene embree2(device, without);
    const Tracer tracer2(without, embree2);
    const FrameResult bg = RenderFrame(tracer2, cam, 2, Model::FullTree, 2);
    FloatImage teapot(cam.width, cam.height, 1);
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const Ray ray = raster::PixelRay(cam, x + 0.5f, y + 0.5f);
            const Hit h = embree.Intersect(ray);
            teapot.At(x, y)[0] =
                h.valid && scene.objects[static_cast<size_t>(h.object)].name == "glass_teapot";
        }
    EXPECT_GT(MeanAbsDiff(ref.image, bg.image, teapot), 0.02);
}

void ExpectInRange(const FloatImage& img, int channel, float lo, float hi, const char* what) {
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float v = img.At(x, y)[channel];
            ASSERT_TRUE(v >= lo && v <= hi) << what << " (" << x << ", " << y << ") = " << v;
        }
}

// A segmentation's records as BuildLayers takes them (two layers, as pemref trace by default).
LayerInput LayerInputOf(const GroupSegmentation& s) {
    return {s.records,
            s.recordPoints,
            2,
            0.15,
            s.distantDistanceSum,
            s.distantCount,
            s.recordOrigins,
            s.localOrigins,
            s.localPoints};
}

TEST(Tracer, SegmentedImagesAndLayerAlphaInRange) {
    const TracedScene traced(kHybrid);
    const auto& [scene, device, embree, tracer] = traced;
    const raster::Camera cam = CameraForSize(*scene.camera, 64, 48);
    for (int g = 0; g < static_cast<int>(scene.lensGroups.size()); ++g) {
        const glm::vec3 origin = GroupEmOrigin(scene, g);
        const GroupSegmentation s = SegmentGroup(tracer, cam, 2, g, 0, origin, 2);
        for (int t = 0; t < s.terms; ++t) {
            ExpectInRange(s.b[t], 3, 0.0f, 1.0f, "b alpha");
            ExpectInRange(s.fg[t], 3, 0.0f, 1.0f, "FG alpha");
            for (int c = 0; c < 3; ++c) ExpectInRange(s.fg[t], c, 0.0f, 1.0f, "F G");
            ExpectInRange(s.confidence[t], 0, 0.0f, 1.0f, "confidence");
        }
        if (s.mirror) ExpectInRange(s.local, 3, 0.0f, 1.0f, "local alpha");
        ASSERT_FALSE(s.records.empty());
        ASSERT_EQ(s.recordOrigins.size(), s.records.size());
        const LayerInput in = LayerInputOf(s);
        const GroupLayers layers = BuildLayers(scene, g, s.mirror, in);
        ASSERT_FALSE(layers.clustering.layers.empty());
        for (const LayerShell& sh : layers.shells) {  // the least parallax of the tried shells
            ASSERT_FALSE(sh.candidates.empty());
            for (const auto& [kind, parallax] : sh.candidates) EXPECT_LE(sh.parallaxDeg, parallax);
        }
        const LayerImages li = RenderLayers(tracer, cam, 2, layers, 2);
        float alphaSum = 0.0f;
        for (int t = 0; t < s.terms; ++t)
            for (const FloatImage& img : li.term[t]) {
                ExpectInRange(img, 3, 0.0f, 1.0f, "layer alpha");
                for (int y = 0; y < img.height; ++y)
                    for (int x = 0; x < img.width; ++x) alphaSum += img.At(x, y)[3];
            }
        EXPECT_GT(alphaSum, 1.0f);
    }
}

// The K× sample images that inference fits: each cell is its own camera sample's greedy path
// (IncomingHit + TraceGreedy, one ray, bit for bit), and box-filtered they are the pixel images.
TEST(Tracer, SampleImagesAreTheSamplesOneByOne) {
    const TracedScene traced(kHybrid);
    const auto& [scene, device, embree, tracer] = traced;
    const int k = 2;
    const raster::Camera cam = CameraForSize(*scene.camera, 48, 36);
    for (int g = 0; g < static_cast<int>(scene.lensGroups.size()); ++g) {
        const GroupSegmentation s = SegmentGroup(tracer, cam, k, g, 0, GroupEmOrigin(scene, g), 2);
        int covered = 0;
        for (int y = 0; y < cam.height; ++y)
            for (int x = 0; x < cam.width; ++x)
                for (int i = 0; i < k * k; ++i) {
                    const glm::vec2 pos = SamplePosition(x, y, k, i);
                    const Ray ray = raster::PixelRay(cam, pos.x, pos.y);
                    RayCounts counts;
                    const Hit hit = IncomingHit(tracer, ray, g, counts);
                    const glm::ivec2 cell = SampleCell(x, y, k, i);
                    covered += hit.valid;
                    const GreedySample gs =
                        hit.valid ? tracer.TraceGreedy(ray, hit, g, counts) : GreedySample{};
                    const TermSample* terms[2] = {&gs.reflection, &gs.refraction};
                    for (int t = 0; t < s.terms; ++t) {
                        const float* v = s.bSamples[t].At(cell.x, cell.y);
                        const glm::vec3 b = hit.valid ? terms[t]->b : glm::vec3(0.0f);
                        ASSERT_EQ(v[0], b.x) << g << " " << x << " " << y << " " << i;
                        ASSERT_EQ(v[1], b.y);
                        ASSERT_EQ(v[2], b.z);
                        ASSERT_EQ(v[3], hit.valid ? 1.0f : 0.0f);
                    }
                }
        EXPECT_GT(covered, 20) << g;  // not vacuous
        for (int t = 0; t < s.terms; ++t) EXPECT_EQ(BoxFilter(s.bSamples[t], k), s.b[t]);
        if (s.mirror) {
            EXPECT_EQ(BoxFilter(s.localSamples, k), s.local);
            EXPECT_EQ(BoxFilter(s.distantSamples, k), s.distant);
            // The self hits: one per pixel whose first sample's reflected ray meets the group
            // again (local alpha 1 in that sample's cell), each a point of the group.
            size_t selfHits = 0;
            for (int y = 0; y < cam.height; ++y)
                for (int x = 0; x < cam.width; ++x) {
                    const glm::ivec2 cell = SampleCell(x, y, k, 0);
                    selfHits += s.localSamples.At(cell.x, cell.y)[3] == 1.0f;
                }
            ASSERT_EQ(s.localOrigins.size(), selfHits);
            ASSERT_EQ(s.localPoints.size(), selfHits);
            EXPECT_GT(selfHits, 0u);  // the cup sees itself
            const Bounds& box = scene.lensGroups[static_cast<size_t>(g)].bounds;
            for (const glm::vec3& p : s.localPoints)
                ASSERT_TRUE(glm::all(glm::greaterThanEqual(p, box.lo - 1e-4f)) &&
                            glm::all(glm::lessThanEqual(p, box.hi + 1e-4f)));
        }
        const LayerInput in = LayerInputOf(s);
        const LayerImages li = RenderLayers(tracer, cam, k, BuildLayers(scene, g, s.mirror, in), 2);
        for (int t = 0; t < s.terms; ++t)
            for (size_t l = 0; l < li.term[t].size(); ++l) {
                ASSERT_EQ(li.samples[t][l].width, k * cam.width);
                EXPECT_EQ(BoxFilter(li.samples[t][l], k), li.term[t][l]);
                const FloatImage& img = li.samples[t][l];  // one sample: alpha 0 or 1
                for (size_t p = 0; p < img.data.size() / 4; ++p)
                    ASSERT_TRUE(img.data[4 * p + 3] == 0.0f || img.data[4 * p + 3] == 1.0f);
            }
    }
}

}  // namespace
}  // namespace pem::trace
