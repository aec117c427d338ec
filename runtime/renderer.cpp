// SPDX-License-Identifier: MIT
// renderer.cpp — frames from inferred maps and the baselines (renderer.h).
#include "runtime/renderer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>

#include "raster/cube_lookup.h"
#include "raster/render.h"
#include "runtime/convex_hull.h"
#include "runtime/lens_paths.h"
#include "runtime/texgen.h"
#include "trace/embree_scene.h"
#include "trace/parallel.h"
#include "trace/render.h"
#include "trace/scene.h"
#include "trace/segment.h"
#include "trace/trace_run.h"
#include "viewer_tty/input_error.h"

namespace pem::runtime {
namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The direction of face coordinates (s, t) in [0, 1] (raster::FaceDirection).
glm::vec3 FaceDirection(int face, float s, float t) {
    const raster::Vec3f d = raster::FaceDirection(face, 2.0f * s - 1.0f, 2.0f * t - 1.0f);
    return {d[0], d[1], d[2]};
}

raster::BlendState PremultipliedOver() {
    raster::BlendState b;
    b.enabled = true;
    b.srcRgb = b.srcAlpha = raster::BlendFactor::One;
    b.dstRgb = b.dstAlpha = raster::BlendFactor::OneMinusSrcAlpha;
    return b;
}

// Adds weight · frame / 255 to acc at the listed pixels (RGB per listed pixel); the 256 terms
// are computed once (the same expression, so the same bits).
void Accumulate(const raster::Image8& img, double weight, const std::vector<uint32_t>& pixels,
                std::vector<double>* acc) {
    std::array<double, 256> term;
    for (int b = 0; b < 256; ++b) term[static_cast<size_t>(b)] = weight * b / 255.0;
    for (size_t k = 0; k < pixels.size(); ++k)
        for (size_t c = 0; c < 3; ++c)
            (*acc)[3 * k + c] += term[img.rgba[4 * size_t{pixels[k]} + c]];
}

// What a PreparedFrame needs of a texture it is given prepared: kind, size, sampler and level
// count, without copying the texel bytes (render.h).
raster::Texture Shape(const raster::Texture& t) {
    raster::Texture s;
    s.kind = t.kind;
    s.width = t.width;
    s.height = t.height;
    s.sampler = t.sampler;
    s.levels.resize(t.levels.size());
    return s;
}

}  // namespace

const char* ToString(Method m) {
    switch (m) {
        case Method::Hybrid:
            return "hybrid";
        case Method::Pem:
            return "pem";
        case Method::StaticEm:
            return "static";
        case Method::RayTraced:
            return "traced";
    }
    return "?";
}

struct Renderer::Impl {
    PemSet set;
    trace::Scene scene;
    std::unique_ptr<trace::EmbreeDevice> device;
    std::unique_ptr<trace::EmbreeScene> embree;
    std::unique_ptr<trace::Tracer> tracer;
    std::map<int, raster::Texture> staticMaps;
    std::map<const raster::Texture*, std::shared_ptr<const raster::PreparedTexture>> prepared;
    std::map<int, std::vector<uint8_t>> hullOf;  // per mirror group: triangles on its hull
    glm::vec3 lensCentre{0.0f};
    int threads = 1;

    const raster::Texture& StaticMap(int group);
    void DrawGroup(const raster::Camera& camera, const RenderSettings& s, int group,
                   const std::vector<int>& samples, const std::vector<double>& weights,
                   const std::vector<uint32_t>& pixels, std::vector<double>* acc,
                   FrameStats* stats);
};

Renderer::Renderer(PemSet set, int threads) : impl_(std::make_unique<Impl>()) {
    impl_->set = std::move(set);
    impl_->threads = threads;
    impl_->scene = trace::LoadScene(impl_->set.scenePath);
    if (!impl_->scene.camera) throw InputError(impl_->set.scenePath, "no camera node");
    if (impl_->scene.lensGroups.size() != impl_->set.groups.size())
        throw InputError(impl_->set.dir + "/manifest.json", "lens groups differ from the scene's");
    impl_->device = std::make_unique<trace::EmbreeDevice>(trace::EmbreeOptions{threads, "auto"});
    impl_->embree = std::make_unique<trace::EmbreeScene>(*impl_->device, impl_->scene);
    impl_->tracer = std::make_unique<trace::Tracer>(impl_->scene, *impl_->embree);
    impl_->lensCentre = trace::LensCentre(impl_->scene);
}

Renderer::~Renderer() = default;

const PemSet& Renderer::pems() const {
    return impl_->set;
}
const trace::Scene& Renderer::scene() const {
    return impl_->scene;
}
const trace::Tracer& Renderer::tracer() const {
    return *impl_->tracer;
}

raster::Camera Renderer::SampleCamera(int v) const {
    raster::Camera c =
        trace::CameraForSize(*impl_->scene.camera, impl_->set.width, impl_->set.height);
    c.eye = impl_->set.views.at(static_cast<size_t>(v)).eye;
    c.target = impl_->set.views.at(static_cast<size_t>(v)).target;
    return c;
}

raster::Camera Renderer::Orbit(double azimuthDeg, double elevationDeg, double distanceScale) const {
    raster::Camera c = SampleCamera(impl_->set.inferred.front());
    const glm::dvec3 centre(impl_->lensCentre);
    const glm::dvec3 d = glm::dvec3(c.eye) - centre;
    const double dist = glm::length(d) * distanceScale;
    const double az0 = std::atan2(d.x, d.z);
    const double el0 = std::asin(std::clamp(d.y / glm::length(d), -1.0, 1.0));
    const double az = az0 + glm::radians(azimuthDeg);
    const double el = std::clamp(el0 + glm::radians(elevationDeg), -1.5, 1.5);
    c.eye = glm::vec3(centre + dist * glm::dvec3(std::sin(az) * std::cos(el), std::sin(el),
                                                 std::cos(az) * std::cos(el)));
    c.target = glm::vec3(centre);
    return c;
}

const raster::Texture& Renderer::Impl::StaticMap(int group) {
    auto it = staticMaps.find(group);
    if (it != staticMaps.end()) return it->second;
    // One cube map from the EM origin, the group itself left out (rays continue through it).
    const int n = std::min(set.res, 128);
    const glm::vec3 origin = set.groups[static_cast<size_t>(group)].emOrigin;
    std::vector<float> level0(static_cast<size_t>(6 * n * n) * 4, 0.0f);
    trace::ParallelRows(6 * n, threads, [&](int row) {
        const int f = row / n, j = row % n;
        trace::RayCounts counts;
        for (int i = 0; i < n; ++i) {
            const glm::vec3 d = glm::normalize(
                FaceDirection(f, (static_cast<float>(i) + 0.5f) / static_cast<float>(n),
                              (static_cast<float>(j) + 0.5f) / static_cast<float>(n)));
            const raster::Ray ray{origin, d};
            const std::vector<trace::Hit> hits =
                trace::EnvironmentHits(*tracer, ray, group, counts);
            const trace::Hit hit = hits.empty() ? trace::Hit{} : hits.front();
            const glm::vec3 l =
                tracer->HitRadiance(ray, hit, tracer->options().fullTreeDepth, 1.0, counts);
            float* p = &level0[((static_cast<size_t>(f) * n + j) * n + i) * 4];
            p[0] = l.x, p[1] = l.y, p[2] = l.z, p[3] = 1.0f;
        }
    });
    // Every MIP level by 2×2 means, then the 8-bit copy.
    raster::Texture tex;
    tex.kind = raster::TextureKind::Cube;
    tex.width = tex.height = n;
    std::vector<float> cur = level0;
    for (int m = n; m >= 1; m /= 2) {
        std::vector<uint8_t> bytes(cur.size());
        for (size_t k = 0; k < cur.size(); ++k)
            bytes[k] =
                static_cast<uint8_t>(std::nearbyint(std::clamp(cur[k], 0.0f, 1.0f) * 255.0f));
        tex.levels.push_back(std::move(bytes));
        if (m == 1) break;
        const int h = m / 2;
        std::vector<float> next(static_cast<size_t>(6 * h * h) * 4, 0.0f);
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < h; ++j)
                for (int i = 0; i < h; ++i)
                    for (int c = 0; c < 4; ++c) {
                        float s = 0.0f;
                        for (int dj = 0; dj < 2; ++dj)
                            for (int di = 0; di < 2; ++di)
                                s += cur[((static_cast<size_t>(f) * m + 2 * j + dj) * m + 2 * i +
                                          di) *
                                             4 +
                                         c];
                        next[((static_cast<size_t>(f) * h + j) * h + i) * 4 + c] = 0.25f * s;
                    }
        cur.swap(next);
    }
    return staticMaps.emplace(group, std::move(tex)).first->second;
}

void Renderer::Impl::DrawGroup(const raster::Camera& camera, const RenderSettings& s, int group,
                               const std::vector<int>& samples, const std::vector<double>& weights,
                               const std::vector<uint32_t>& pixels, std::vector<double>* acc,
                               FrameStats* stats) {
    const PemGroup& g = set.groups[static_cast<size_t>(group)];
    const bool pemSplit = s.method == Method::Pem && g.pem;
    // Step 1: vertex paths (hybrid: adaptive; PEM: the model's vertices).
    LensPaths lp;
    LensMesh base;
    std::vector<ExitRay> termExits[2];
    PassMesh mesh;
    if (pemSplit) {
        const auto t0 = Clock::now();
        base = GroupMesh(scene, group);
        mesh = MeshOf(base);
        const trace::Material& mat = scene.materials[static_cast<size_t>(
            scene
                .objects[static_cast<size_t>(
                    scene.lensGroups[static_cast<size_t>(group)].objects[0])]
                .material)];
        termExits[0] = ReflectionExits(mesh, camera.eye, mat.baseColor);
        stats->texgenSeconds += Since(t0);
        stats->trianglesIn += base.triangles.size();
        stats->trianglesOut += base.triangles.size();
    } else {
        LensPathsOptions lo;
        lo.tess.maxEdgeSubpixels = s.t;
        lo.supersampling = s.subpixels > 0 ? s.subpixels : set.spp;
        lo.adaptive = s.method != Method::Pem;
        lo.threads = s.threads;
        lp = TraceLensPaths(*tracer, *embree, camera, group, lo);
        stats->traceSeconds += lp.traceSeconds;
        stats->tessSeconds += lp.tessSeconds;
        stats->vertexRays += lp.counts.Total();
        stats->trianglesIn += lp.tess.stats.trianglesIn;
        stats->trianglesOut += lp.tess.triangles.size();
        stats->backFacingTriangles += lp.tess.stats.backFacingTriangles;
        stats->untracedVertices += lp.tess.stats.untracedVertices;
        stats->tracedVertices += lp.tess.stats.vertexRays;
        mesh = MeshOf(lp.tess);
        const auto t0 = Clock::now();
        for (int term = 0; term < (g.glass ? 2 : 1); ++term)
            termExits[term] = TermExits(lp.tess.paths, term, s.threads);
        stats->texgenSeconds += Since(t0);
    }
    const auto t1 = Clock::now();
    const std::vector<uint32_t> order = DrawOrder(mesh, camera, s.threads);
    const glm::mat4 viewProjection = PassViewProjection(mesh, camera);
    const PassGeometry geometry = MakePassGeometry(mesh, order, viewProjection, s.threads);
    // PEM split: polygons on the reflector's convex hull cannot see it, so the local layer is
    // drawn on the other polygons only (PEM §4); the distant layer on all of them.
    PassGeometry localGeometry;
    if (pemSplit) {
        auto it = hullOf.find(group);
        if (it == hullOf.end()) it = hullOf.emplace(group, HullTriangles(base)).first;
        std::vector<uint32_t> inner;
        for (uint32_t t : order)
            if (!it->second[t]) inner.push_back(t);
        localGeometry = MakePassGeometry(mesh, inner, viewProjection, s.threads);
    }
    stats->texgenSeconds += Since(t1);

    // Step 2: one frame per (sample, term): the layers outermost first, inner ones over them.
    // The frames are built first and rendered together (the samples' passes share their setup),
    // then added in (sample, term) order.
    raster::RenderOptions ro;
    ro.threads = s.threads;
    std::vector<raster::Frame> frames;
    std::vector<std::vector<std::shared_ptr<const raster::PreparedTexture>>> ready;
    std::vector<double> frameWeights;
    auto addFrame = [&](std::vector<const raster::Texture*> maps,
                        const std::vector<std::vector<glm::vec3>>& coords,
                        const std::vector<ExitRay>& exits, double weight,
                        const std::vector<const PassGeometry*>& geometries, int sameAs = -1) {
        const auto tt = Clock::now();
        raster::Frame& frame = frames.emplace_back();
        // sameAs >= 0: that frame drew the same passes with another sample's maps (copied).
        if (sameAs >= 0) frame.passes = frames[static_cast<size_t>(sameAs)].passes;
        auto& frameReady = ready.emplace_back();
        frameWeights.push_back(weight);
        frame.width = camera.width;
        frame.height = camera.height;
        frame.depthClamp = true;
        frame.passes.resize(maps.size());  // no-op when copied
        for (size_t k = maps.size(); k-- > 0;) {
            const size_t slot = maps.size() - 1 - k;
            PassOptions po;
            po.texture = static_cast<int>(slot);
            po.modulate = true;
            po.blend = slot == 0 ? raster::BlendState::None() : PremultipliedOver();
            frame.textures.push_back(Shape(*maps[k]));
            auto it = prepared.find(maps[k]);
            if (it == prepared.end())
                it = prepared.emplace(maps[k], raster::PrepareTexture(*maps[k])).first;
            frameReady.push_back(it->second);
            if (sameAs < 0)
                FillLayerPass(*geometries[k], coords[k], exits, po, &frame.passes[slot], s.threads);
        }
        stats->texgenSeconds += Since(tt);
    };
    auto drawFrames = [&]() {
        const auto tr = Clock::now();
        std::vector<raster::PreparedFrame> pf;
        pf.reserve(frames.size());
        for (size_t f = 0; f < frames.size(); ++f) pf.emplace_back(frames[f], std::move(ready[f]));
        std::vector<const raster::PreparedFrame*> ptrs;
        for (const raster::PreparedFrame& p : pf) ptrs.push_back(&p);
        const std::vector<raster::RenderResult> rr = raster::RenderFrames(ptrs, ro);
        for (size_t f = 0; f < rr.size(); ++f)
            Accumulate(rr[f].image8, frameWeights[f], pixels, acc);
        stats->rasterSeconds += Since(tr);
    };
    const int layers = static_cast<int>(g.layers.size());
    const int firstLayer = s.layers == 1 ? layers - 1 : 0;
    if (s.method == Method::StaticEm) {
        const raster::Texture& map = StaticMap(group);
        for (int term = 0; term < (g.glass ? 2 : 1); ++term) {
            std::vector<glm::vec3> dirs(termExits[term].size());
            for (size_t v = 0; v < dirs.size(); ++v) dirs[v] = termExits[term][v].dir;
            addFrame({&map}, {dirs}, termExits[term], 1.0, {&geometry});
        }
        drawFrames();
        return;
    }
    // The layers drawn, innermost first: a shell and the map each term looks up (one map per
    // layer serves both terms: it was inferred from both). PEM split: local over distant (no
    // local map: a convex reflector); single layer: the `single` map on its sphere (without it:
    // the outermost layer); layers of empty clusters have no maps.
    struct LayerUse {
        const trace::Shell* shell;
        std::string name[2];
    };
    std::vector<LayerUse> uses;
    const int s0 = samples.front();
    if (pemSplit) {
        if (set.Map(s0, group, "pem_local")) uses.push_back({&g.localShell, {"pem_local", ""}});
        uses.push_back({&g.distantShell, {"pem_distant", ""}});
    } else if (s.layers == 1 && set.Map(s0, group, "single")) {
        uses.push_back({&g.singleShell, {"single", "single"}});
    } else {
        for (int l = firstLayer; l < layers; ++l)
            if (!g.layerEmpty[static_cast<size_t>(l)])
                uses.push_back({&g.layers[static_cast<size_t>(l)],
                                {"layer_" + std::to_string(l), "layer_" + std::to_string(l)}});
    }
    std::vector<const PassGeometry*> useGeometry(uses.size(), &geometry);
    if (pemSplit && uses.size() == 2) useGeometry[0] = &localGeometry;  // local, then distant
    // Texture coordinates per term and layer (shared by the samples).
    const auto tc = Clock::now();
    std::vector<std::vector<glm::vec3>> coords[2];
    for (int term = 0; term < (g.glass ? 2 : 1); ++term)
        for (const LayerUse& u : uses)
            coords[term].push_back(ShellCoords(termExits[term], *u.shell, g.emOrigin, s.threads));
    stats->texgenSeconds += Since(tc);
    int firstFrameOf[2] = {-1, -1};  // per term: the first sample's frame
    for (size_t k = 0; k < samples.size(); ++k) {
        for (int term = 0; term < (g.glass ? 2 : 1); ++term) {
            std::vector<const raster::Texture*> maps;
            for (const LayerUse& u : uses) maps.push_back(set.Map(samples[k], group, u.name[term]));
            if (maps.empty() || std::count(maps.begin(), maps.end(), nullptr) > 0)
                throw InputError(set.dir, "missing maps for viewpoint sample " +
                                              std::to_string(samples[k]) + ", group " +
                                              std::to_string(group));
            const int sameAs = firstFrameOf[term];
            if (sameAs < 0) firstFrameOf[term] = static_cast<int>(frames.size());
            addFrame(maps, coords[term], termExits[term], weights[k], useGeometry, sameAs);
        }
    }
    drawFrames();
}

RenderedFrame Renderer::Render(const raster::Camera& camera, const RenderSettings& s) {
    Impl& m = *impl_;
    const auto tStart = Clock::now();
    RenderedFrame out;
    const int w = camera.width, h = camera.height;
    out.image = trace::FloatImage(w, h, 3);
    out.lensMask.assign(static_cast<size_t>(w) * static_cast<size_t>(h), 0);
    if (s.method == Method::RayTraced) {
        const trace::FrameResult fr =
            trace::RenderFrame(*m.tracer, camera, s.spp, trace::Model::FullTree, s.threads);
        out.image = fr.image;
        for (size_t p = 0; p < out.lensMask.size(); ++p)
            out.lensMask[p] = fr.lensCoverage.data[p] > 0.0f ? 1 : 0;
        out.stats.tracerRays = fr.counts.Total();
        out.stats.totalSeconds = Since(tStart);
        return out;
    }
    // Step 1: the rest of the frame, one camera ray per pixel (trace/render.h's rows: camera and
    // shadow rays in packets); which group each pixel sees.
    const auto tb = Clock::now();
    trace::FrameResult surroundings =
        trace::RenderFrame(*m.tracer, camera, 1, trace::Model::Surroundings, s.threads);
    out.image = std::move(surroundings.image);
    const std::vector<int>& groupOf = surroundings.lensGroup;
    out.stats.backgroundRays = surroundings.counts.Total();
    out.stats.backgroundSeconds = Since(tb);

    // Step 2: the two nearest viewpoint samples, weighted by the other's distance.
    std::vector<std::pair<double, int>> byDistance;
    for (int v : m.set.inferred)
        byDistance.emplace_back(glm::length(glm::dvec3(camera.eye) -
                                            glm::dvec3(m.set.views[static_cast<size_t>(v)].eye)),
                                v);
    std::sort(byDistance.begin(), byDistance.end());
    std::vector<int> samples{byDistance[0].second};
    std::vector<double> weights{1.0};
    if (byDistance.size() > 1 && byDistance[0].first > 1e-9) {
        const double d0 = byDistance[0].first, d1 = byDistance[1].first;
        samples.push_back(byDistance[1].second);
        weights = {d1 / (d0 + d1), d0 / (d0 + d1)};
    }
    out.stats.samples = samples;
    out.stats.sampleWeights = weights;

    // Step 3: each lens group seen, from its maps; other groups ray traced.
    std::vector<std::vector<uint32_t>> pixelsOf(m.set.groups.size());
    for (size_t p = 0; p < groupOf.size(); ++p)
        if (groupOf[p] >= 0)
            pixelsOf[static_cast<size_t>(groupOf[p])].push_back(static_cast<uint32_t>(p));
    for (int g = 0; g < static_cast<int>(m.set.groups.size()); ++g) {
        const std::vector<uint32_t>& pixels = pixelsOf[static_cast<size_t>(g)];
        if (pixels.empty()) {
            ++out.stats.groupsSkipped;  // hidden or off screen: no vertex rays, no passes
            continue;
        }
        std::vector<double> acc(pixels.size() * 3, 0.0);
        m.DrawGroup(camera, s, g, samples, weights, pixels, &acc, &out.stats);
        for (size_t k = 0; k < pixels.size(); ++k) {
            out.lensMask[pixels[k]] = 1;
            for (size_t c = 0; c < 3; ++c)
                out.image.data[3 * size_t{pixels[k]} + c] =
                    static_cast<float>(std::min(1.0, acc[3 * k + c]));
        }
    }
    out.stats.lensSeconds = out.stats.traceSeconds + out.stats.tessSeconds +
                            out.stats.texgenSeconds + out.stats.rasterSeconds;
    out.stats.totalSeconds = Since(tStart);
    return out;
}

}  // namespace pem::runtime
