// SPDX-License-Identifier: MIT
// renderer.cpp — frames from inferred maps and the baselines (renderer.h).
//
// Index: helpers · GroupGeometry (vertex paths and texgen input) · FrameBatch (one group's
// raster frames, drawn together and blended) · LayerUses (which maps, on which shells) ·
// Renderer (one function per method, then Render).
#include "runtime/renderer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <span>

#include "base/input_error.h"
#include "raster/profile.h"
#include "raster/render.h"
#include "runtime/convex_hull.h"
#include "runtime/lens_paths.h"
#include "runtime/mirror_geometry.h"
#include "runtime/silhouettes.h"
#include "runtime/static_em.h"
#include "runtime/supersampling.h"
#include "runtime/texgen.h"
#include "trace/embree_scene.h"
#include "trace/render.h"

namespace pem::runtime {
namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

raster::BlendState PremultipliedOver() {
    raster::BlendState b;
    b.enabled = true;
    b.srcRgb = b.srcAlpha = raster::BlendFactor::One;
    b.dstRgb = b.dstAlpha = raster::BlendFactor::OneMinusSrcAlpha;
    return b;
}

// A frame's value at index i in [0, 1] units: an RGBA8 frame's bytes / 255, or the floats.
double ValueAt(const raster::Image8& img, size_t i) {
    return img.rgba[i] / 255.0;
}
double ValueAt(const raster::ImageF& img, size_t i) {
    return static_cast<double>(img.rgba[i]);
}

// Adds weight · (the mean of the covered subpixels of a k× frame, supersampling.h) to acc at
// the listed pixels (RGB per listed pixel).
template <class Image>
void Accumulate(const Image& img, const std::vector<uint8_t>& covered, const SubpixelLayout& layout,
                double weight, const std::vector<uint32_t>& pixels, std::vector<double>* acc) {
    double rgba[4];
    for (size_t p = 0; p < pixels.size(); ++p) {
        CoveredMean(img, covered, layout, pixels[p], rgba);
        for (size_t c = 0; c < 3; ++c) (*acc)[3 * p + c] += weight * rgba[c];
    }
}

// Adds weight · frame at every subpixel of the border pixels to the group's samples
// (silhouettes.h), and marks the covered ones.
template <class Image>
void AccumulateBorder(const Image& img, const std::vector<uint8_t>& covered,
                      const SubpixelLayout& layout, double weight,
                      const std::vector<glm::ivec2>& border, GroupSamples* samples) {
    const size_t kk = static_cast<size_t>(layout.k) * static_cast<size_t>(layout.k);
    samples->rgb.resize(border.size() * kk * 3, 0.0);
    samples->covered.resize(border.size() * kk, 0);
    for (size_t b = 0; b < border.size(); ++b)
        for (size_t s = 0; s < kk; ++s) {
            const uint32_t pixel = static_cast<uint32_t>(border[b].y * layout.width + border[b].x);
            const size_t i = SubpixelIndex(pixel, layout, static_cast<int>(s));
            samples->covered[b * kk + s] = covered[i];
            for (size_t c = 0; c < 3; ++c)
                samples->rgb[3 * (b * kk + s) + c] += weight * ValueAt(img, 4 * i + c);
        }
}

// What a PreparedFrame needs of a texture it is given prepared: kind, size, sampler and level
// count, without copying the texel bytes (render.h).
raster::Texture Shape(const raster::Texture& t) {
    raster::Texture s;
    s.kind = t.kind;
    s.width = t.width;
    s.height = t.height;
    s.sampler = t.sampler;
    s.format = t.format;
    s.levels.resize(t.levels.size());
    return s;
}

using PreparedCache =
    std::map<const raster::Texture*, std::shared_ptr<const raster::PreparedTexture>>;

// GroupGeometry --------------------------------------------------------------------------------

// One lens group's vertices for one frame: their exit rays per term (texgen's input) and the
// triangles to draw (DrawOrder).
struct GroupGeometry {
    LensPaths paths;        // hybrid, and PEM on the model's vertices
    MirrorGeometry mirror;  // PEM split (mirror-only groups in PEM mode)
    PassMesh mesh;
    std::vector<ExitRay> exits[2];  // per term
    std::vector<uint32_t> order;
    glm::mat4 viewProjection{1.0f};
    PassGeometry all, offHull;  // every front-facing triangle; those off the hull (PEM split)
};

void CountPaths(const LensPaths& lp, FrameStats* stats) {
    stats->traceSeconds += lp.traceSeconds;
    stats->tessSeconds += lp.tessSeconds;
    stats->vertexRays += lp.counts.Total();
    stats->trianglesIn += lp.tess.stats.trianglesIn;
    stats->trianglesOut += lp.tess.triangles.size();
    stats->backFacingTriangles += lp.tess.stats.backFacingTriangles;
    stats->untracedVertices += lp.tess.stats.untracedVertices;
    stats->tracedVertices += lp.tess.stats.vertexRays;
}

// FrameBatch -----------------------------------------------------------------------------------

// The frames of one lens group, one per (sample, term): built first, rendered together (the
// samples' passes share their setup), then added in the order they were built.
class FrameBatch {
  public:
    // k: subpixels per pixel side (supersampling.h).
    // parameterization: the maps' layout.
    FrameBatch(const raster::Camera& camera, int k, const raster::RenderOptions& hardware,
               int threads, PreparedCache* prepared, FrameStats* stats,
               Parameterization parameterization = Parameterization::Cube)
        : camera_(camera),
          parameterization_(parameterization),
          k_(k),
          hardware_(hardware),
          threads_(threads),
          prepared_(prepared),
          stats_(stats) {}

    // A frame drawing maps[k] (innermost first; the first of the map's textures, MapSet::map)
    // on geometries[k] with coords[k]: the outermost layer replaces, the inner ones go over it.
    // sameAs >= 0: that frame drew the same passes with another sample's maps (they are copied,
    // not filled again).
    int Add(const std::vector<const raster::Texture*>& maps,
            const std::vector<std::vector<glm::vec3>>& coords, const std::vector<ExitRay>& exits,
            double weight, const std::vector<const PassGeometry*>& geometries, int sameAs = -1) {
        const auto t0 = Clock::now();
        raster::Frame& frame = frames_.emplace_back();
        if (sameAs >= 0) frame.passes = frames_[static_cast<size_t>(sameAs)].passes;
        auto& frameReady = ready_.emplace_back();
        weights_.push_back(weight);
        frame.width = k_ * camera_.width;
        frame.height = k_ * camera_.height;
        frame.depthClamp = true;
        frame.depth = kLensDepth;
        // Float maps are drawn into a float colour buffer (map_set.h MapHardware::format).
        if (!maps.empty() && maps[0]->format == raster::TexelFormat::Rgba32F)
            frame.colorFormat = raster::ColorFormat::Rgba32F;
        // A map of a two-image layout is two textures and two passes (parameterization.h).
        const size_t perMap = static_cast<size_t>(MapTextures(parameterization_));
        frame.passes.resize(maps.size() * perMap);  // no-op when copied
        for (size_t k = maps.size(); k-- > 0;) {
            const size_t slot = maps.size() - 1 - k;
            PassOptions po;
            po.texture = static_cast<int>(slot * perMap);
            po.modulate = true;
            po.blend = slot == 0 ? raster::BlendState::None() : PremultipliedOver();
            po.depthTest = LayerDepthTest(slot == 0);
            po.parameterization = parameterization_;
            po.eyeFromWorld = EyeFromWorld(camera_);
            for (size_t c = 0; c < perMap; ++c) {
                frame.textures.push_back(Shape(maps[k][c]));
                frameReady.push_back(Prepared(&maps[k][c]));
            }
            if (sameAs < 0)
                FillLayerPass(*geometries[k], coords[k], exits, po,
                              std::span(frame.passes).subspan(slot * perMap, perMap), threads_);
        }
        stats_->texgenSeconds += Since(t0);
        return static_cast<int>(frames_.size()) - 1;
    }

    // Renders every frame and adds weight · frame at the listed pixels to acc, and at the
    // border pixels' subpixels to `border` (when given). The frames share their geometry, so
    // the first one's depth buffer says which subpixels the group covers. Only the box of the
    // subpixels read is drawn (a scissor box: the frames hold nothing else).
    void Draw(const std::vector<uint32_t>& pixels, std::vector<double>* acc,
              const std::vector<glm::ivec2>& borderPixels, GroupSamples* border) {
        const auto t0 = Clock::now();
        const SubpixelLayout layout = ReadLayout(pixels, borderPixels);
        for (raster::Frame& f : frames_) f.scissor = layout.box;
        std::vector<raster::PreparedFrame> pf;
        pf.reserve(frames_.size());
        for (size_t f = 0; f < frames_.size(); ++f)
            pf.emplace_back(frames_[f], std::move(ready_[f]));
        std::vector<const raster::PreparedFrame*> ptrs;
        for (const raster::PreparedFrame& p : pf) ptrs.push_back(&p);
        raster::RenderOptions ro = hardware_;
        ro.threads = threads_;
        ro.picture8 = false;  // float frames are read as floats (AddFrame)
        const std::vector<raster::RenderResult> rr = raster::RenderFrames(ptrs, ro);
        const std::vector<uint8_t> covered =
            rr.empty() ? std::vector<uint8_t>() : CoveredSubpixels(rr[0].depth, kLensDepth);
        for (size_t f = 0; f < rr.size(); ++f) {
            if (frames_[f].colorFormat == raster::ColorFormat::Rgba32F)
                AddFrame(rr[f].imageF, covered, layout, weights_[f], pixels, acc, borderPixels,
                         border);
            else
                AddFrame(rr[f].image8, covered, layout, weights_[f], pixels, acc, borderPixels,
                         border);
        }
        stats_->rasterSeconds += Since(t0);
    }

  private:
    // The k× frame's box holding the subpixels of the listed and the border pixels (the whole
    // frame when there are none).
    SubpixelLayout ReadLayout(const std::vector<uint32_t>& pixels,
                              const std::vector<glm::ivec2>& borderPixels) const {
        const int width = camera_.width, height = camera_.height;
        SubpixelLayout layout = WholeFrame(width, height, k_);
        if (pixels.empty() && borderPixels.empty()) return layout;
        glm::ivec2 lo(width, height), hi(-1, -1);
        for (uint32_t p : pixels) {
            const glm::ivec2 at(static_cast<int>(p % static_cast<uint32_t>(width)),
                                static_cast<int>(p / static_cast<uint32_t>(width)));
            lo = glm::min(lo, at);
            hi = glm::max(hi, at);
        }
        for (const glm::ivec2& at : borderPixels) {
            lo = glm::min(lo, at);
            hi = glm::max(hi, at);
        }
        layout.box = SubpixelBox(height, k_, lo, hi);
        return layout;
    }

    template <class Image>
    void AddFrame(const Image& img, const std::vector<uint8_t>& covered,
                  const SubpixelLayout& layout, double weight, const std::vector<uint32_t>& pixels,
                  std::vector<double>* acc, const std::vector<glm::ivec2>& borderPixels,
                  GroupSamples* border) const {
        Accumulate(img, covered, layout, weight, pixels, acc);
        if (border) AccumulateBorder(img, covered, layout, weight, borderPixels, border);
    }

    std::shared_ptr<const raster::PreparedTexture> Prepared(const raster::Texture* map) {
        auto it = prepared_->find(map);
        if (it == prepared_->end())
            it = prepared_->emplace(map, raster::PrepareTexture(*map)).first;
        return it->second;
    }

    const raster::Camera& camera_;
    Parameterization parameterization_;
    int k_;
    raster::RenderOptions hardware_;
    int threads_;
    PreparedCache* prepared_;
    FrameStats* stats_;
    std::vector<raster::Frame> frames_;
    std::vector<std::vector<std::shared_ptr<const raster::PreparedTexture>>> ready_;
    std::vector<double> weights_;
};

// LayerUses ------------------------------------------------------------------------------------

// One layer drawn: its shell and the map each term looks up (one map per layer serves both
// terms: it was inferred from both).
struct LayerUse {
    const trace::Shell* shell;
    std::string name[2];
};

// The layers drawn, innermost first. Single layer: the `single` map on its sphere (without it:
// the outermost layer, or the PEM split's distant map); PEM split: local over distant (no local
// map: a convex reflector); layers of empty clusters have no maps.
std::vector<LayerUse> LayerUses(const MapSet& maps, const LensGroupEm& g,
                                const trace::Shell& single, int layersSetting, bool pemSplit,
                                int sample) {
    std::vector<LayerUse> uses;
    if (layersSetting == 1 && maps.map(sample, g.index, "single")) {
        uses.push_back({&single, {"single", "single"}});
        return uses;
    }
    if (pemSplit) {
        if (layersSetting != 1 && maps.map(sample, g.index, "pem_local"))
            uses.push_back({&g.localShell, {"pem_local", ""}});
        uses.push_back({&g.distantShell, {"pem_distant", ""}});
        return uses;
    }
    const int layers = static_cast<int>(g.layers.size());
    for (int l = layersSetting == 1 ? layers - 1 : 0; l < layers; ++l)
        if (!g.layers[static_cast<size_t>(l)].Empty())
            uses.push_back({&g.layers[static_cast<size_t>(l)].shell,
                            {"layer_" + std::to_string(l), "layer_" + std::to_string(l)}});
    return uses;
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

// Renderer -------------------------------------------------------------------------------------

struct Renderer::Impl {
    MapSet maps;
    trace::Scene scene;
    std::unique_ptr<trace::EmbreeDevice> device;
    std::unique_ptr<trace::EmbreeScene> embree;
    std::unique_ptr<trace::Tracer> tracer;
    std::vector<trace::Shell> singleShells;  // per group (SingleLayerShell)
    // Static EMs by (group, layout); a sphere map with the eye space it was traced for.
    struct StaticMap {
        std::vector<raster::Texture> textures;  // one, or two (a two-image layout)
        glm::mat3 eyeFromWorld{1.0f};
    };
    std::map<std::pair<int, Parameterization>, StaticMap> staticMaps;
    PreparedCache prepared;
    std::map<int, std::vector<uint8_t>> hullOf;  // per mirror group: triangles on its hull
    glm::vec3 lensCentre{0.0f};
    int threads = 1;

    // The pixels of each lens group, blended over the samples by `weights`.
    struct GroupDraw {
        const raster::Camera& camera;
        const RenderSettings& s;
        int group;
        const std::vector<int>& samples;
        const std::vector<double>& weights;
        const std::vector<uint32_t>& pixels;
        std::vector<double>* acc;
        int k;                                  // subpixels per pixel side
        const std::vector<glm::ivec2>* border;  // the frame's border pixels (k > 1)
        GroupSamples* borderSamples;            // this group's colours there, or null
        FrameStats* stats;
    };
    GroupGeometry Geometry(const GroupDraw& d, bool pemSplit);
    // Subpixels per pixel side of the lens frames: the setting, else the traced images' K.
    int Subpixels(const RenderSettings& s) const {
        return s.subpixels > 0 ? s.subpixels : maps.spp;
    }
    raster::RenderOptions Hardware(const RenderSettings& s) const {
        return raster::ProfileNamed(s.profile.empty() ? maps.hardware.profile : s.profile).options;
    }
    // What the lens frames' values are multiplied by (map_set.h: the maps hold radiance / it;
    // the static EM's traced maps hold radiance), and so where a lens pixel saturates.
    double RadianceScale(const RenderSettings& s) const {
        return s.method == Method::StaticEm ? 1.0
                                            : static_cast<double>(maps.hardware.radianceScale);
    }
    std::vector<LayerUse> Uses(const GroupDraw& d, bool pemSplit) const;
    const raster::Texture* StaticTexture(const GroupDraw& d);
    void DrawStatic(const GroupDraw& d, const GroupGeometry& gg);
    void DrawMaps(const GroupDraw& d, const GroupGeometry& gg, bool pemSplit);
    void DrawGroup(const GroupDraw& d);
};

// Step 1 of a group: its vertex paths (hybrid: adaptive; PEM: the model's vertices; PEM split:
// reflected eye rays), the draw order and the pass geometry.
GroupGeometry Renderer::Impl::Geometry(const GroupDraw& d, bool pemSplit) {
    const LensGroupEm& g = maps.groups[static_cast<size_t>(d.group)];
    GroupGeometry gg;
    auto t0 = Clock::now();  // texgen's time: all but the vertex paths
    if (pemSplit) {
        gg.mirror = MakeMirrorGeometry(scene, d.group, d.camera, d.s.threads);
        gg.mesh = gg.mirror.Pass();
        gg.exits[0] = gg.mirror.exits;
        gg.order = gg.mirror.order;
        d.stats->trianglesIn += gg.mirror.mesh.triangles.size();
        d.stats->trianglesOut += gg.mirror.mesh.triangles.size();
    } else {
        LensPathsOptions lo;
        lo.tess.maxEdgeSubpixels = d.s.t > 0.0 ? d.s.t : maps.tessT;
        lo.tess.maxTopologyEdgeSubpixels = d.s.topologyT.value_or(maps.topologyT);
        lo.supersampling = d.s.subpixels > 0 ? d.s.subpixels : maps.spp;
        lo.adaptive = d.s.method != Method::Pem;
        lo.threads = d.s.threads;
        gg.paths = TraceLensPaths(*tracer, *embree, d.camera, d.group, lo);
        CountPaths(gg.paths, d.stats);
        t0 = Clock::now();
        gg.mesh = MeshOf(gg.paths.tess);
        for (int term = 0; term < g.Terms(); ++term)
            gg.exits[term] = TermExits(gg.paths.tess.paths, term, d.s.threads);
        gg.order = DrawOrder(gg.mesh, d.camera, d.s.threads);
    }
    gg.viewProjection = PassViewProjection(gg.mesh, d.camera);
    gg.all = MakePassGeometry(gg.mesh, gg.order, gg.viewProjection, d.s.threads);
    // PEM split: polygons on the reflector's convex hull cannot see it, so the local layer is
    // drawn on the other polygons only (PEM §4); the distant layer on all of them.
    if (pemSplit) {
        auto it = hullOf.find(d.group);
        if (it == hullOf.end()) it = hullOf.emplace(d.group, HullTriangles(gg.mirror.mesh)).first;
        gg.offHull = MakePassGeometry(gg.mesh, OffHull(gg.order, it->second), gg.viewProjection,
                                      d.s.threads);
    }
    d.stats->texgenSeconds += Since(t0);
    return gg;
}

// Static EM: one traced map per group (a cube unless the settings name another layout), looked up
// with the exit directions; a sphere map is traced again when the eye space changes.
const raster::Texture* Renderer::Impl::StaticTexture(const GroupDraw& d) {
    const Parameterization p = d.s.staticLayout;
    const glm::mat3 eyeFromWorld =
        p == Parameterization::Sphere ? EyeFromWorld(d.camera) : glm::mat3(1.0f);
    auto it = staticMaps.find({d.group, p});
    if (it != staticMaps.end() && it->second.eyeFromWorld == eyeFromWorld)
        return it->second.textures.data();
    if (it != staticMaps.end())  // their addresses are reused
        for (const raster::Texture& t : it->second.textures) prepared.erase(&t);
    const glm::vec3 origin = maps.groups[static_cast<size_t>(d.group)].emOrigin;
    const int size = std::min(maps.res, 128);
    StaticMap m;
    m.eyeFromWorld = eyeFromWorld;
    if (p == Parameterization::Cube)
        m.textures.push_back(TraceStaticMap(*tracer, d.group, origin, size, threads));
    else
        m.textures = TraceStaticMap(*tracer, d.group, origin, LayoutOf(p, std::max(2, size)),
                                    threads, glm::transpose(eyeFromWorld));
    return (staticMaps[{d.group, p}] = std::move(m)).textures.data();
}

void Renderer::Impl::DrawStatic(const GroupDraw& d, const GroupGeometry& gg) {
    const raster::Texture* map = StaticTexture(d);
    FrameBatch batch(d.camera, d.k, Hardware(d.s), d.s.threads, &prepared, d.stats,
                     d.s.staticLayout);
    for (int term = 0; term < maps.groups[static_cast<size_t>(d.group)].Terms(); ++term) {
        std::vector<glm::vec3> dirs(gg.exits[term].size());
        for (size_t v = 0; v < dirs.size(); ++v) dirs[v] = gg.exits[term][v].dir;
        batch.Add({map}, {dirs}, gg.exits[term], 1.0, {&gg.all});
    }
    batch.Draw(d.pixels, d.acc, *d.border, d.borderSamples);
}

// Hybrid, layered PEM, single-layer PEM and the PEM split: per (sample, term) one frame of the
// layers' passes, the samples blended by their weights.
void Renderer::Impl::DrawMaps(const GroupDraw& d, const GroupGeometry& gg, bool pemSplit) {
    const LensGroupEm& g = maps.groups[static_cast<size_t>(d.group)];
    const std::vector<LayerUse> uses =
        LayerUses(maps, g, singleShells[static_cast<size_t>(d.group)], d.s.layers, pemSplit,
                  d.samples.front());
    std::vector<const PassGeometry*> geometry(uses.size(), &gg.all);
    if (pemSplit && uses.size() == 2) geometry[0] = &gg.offHull;  // local, then distant
    // Texture coordinates per term and layer (shared by the samples).
    const auto t0 = Clock::now();
    std::vector<std::vector<glm::vec3>> coords[2];
    for (int term = 0; term < g.Terms(); ++term)
        for (const LayerUse& u : uses)
            coords[term].push_back(ShellCoords(gg.exits[term], *u.shell, g.emOrigin, d.s.threads));
    d.stats->texgenSeconds += Since(t0);
    FrameBatch batch(d.camera, d.k, Hardware(d.s), d.s.threads, &prepared, d.stats,
                     maps.parameterization);
    int firstFrameOf[2] = {-1, -1};  // per term: the first sample's frame
    for (size_t k = 0; k < d.samples.size(); ++k) {
        for (int term = 0; term < g.Terms(); ++term) {
            std::vector<const raster::Texture*> textures;
            for (const LayerUse& u : uses)
                textures.push_back(maps.map(d.samples[k], d.group, u.name[term]));
            if (textures.empty() || std::count(textures.begin(), textures.end(), nullptr) > 0)
                throw base::InputError(maps.name, "missing maps for viewpoint sample " +
                                                      std::to_string(d.samples[k]) + ", group " +
                                                      std::to_string(d.group));
            const int f =
                batch.Add(textures, coords[term], gg.exits[term], d.weights[k] * RadianceScale(d.s),
                          geometry, firstFrameOf[term]);
            if (firstFrameOf[term] < 0) firstFrameOf[term] = f;
        }
    }
    batch.Draw(d.pixels, d.acc, *d.border, d.borderSamples);
}

std::vector<LayerUse> Renderer::Impl::Uses(const GroupDraw& d, bool pemSplit) const {
    return LayerUses(maps, maps.groups[static_cast<size_t>(d.group)],
                     singleShells[static_cast<size_t>(d.group)], d.s.layers, pemSplit,
                     d.samples.front());
}

void Renderer::Impl::DrawGroup(const GroupDraw& d) {
    const bool pemSplit =
        d.s.method == Method::Pem && maps.groups[static_cast<size_t>(d.group)].pem;
    const GroupGeometry gg = Geometry(d, pemSplit);
    if (d.s.method == Method::StaticEm)
        DrawStatic(d, gg);
    else
        DrawMaps(d, gg, pemSplit);
}

Renderer::Renderer(trace::Scene scene, MapSet maps, int threads, const std::string& embreeIsa)
    : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.maps = std::move(maps);
    m.scene = std::move(scene);
    m.threads = threads;
    if (m.scene.lensGroups.size() != m.maps.groups.size())
        throw base::InputError(m.maps.name, "lens groups differ from the scene's");
    if (m.maps.samples.empty() || m.maps.inferred.empty())
        throw base::InputError(m.maps.name, "no viewpoint samples");
    for (const LensGroupEm& g : m.maps.groups) m.singleShells.push_back(SingleLayerShell(g));
    m.device = std::make_unique<trace::EmbreeDevice>(trace::EmbreeOptions{threads, embreeIsa});
    m.embree = std::make_unique<trace::EmbreeScene>(*m.device, m.scene);
    m.tracer = std::make_unique<trace::Tracer>(m.scene, *m.embree, m.maps.tracing);
    m.lensCentre = trace::LensCentre(m.scene);
}

Renderer::~Renderer() = default;

const MapSet& Renderer::maps() const {
    return impl_->maps;
}
const trace::Scene& Renderer::scene() const {
    return impl_->scene;
}
const trace::Tracer& Renderer::tracer() const {
    return *impl_->tracer;
}

raster::Camera Renderer::SampleCamera(int v) const {
    return impl_->maps.samples.at(static_cast<size_t>(v));
}

raster::Camera Renderer::Orbit(double azimuthDeg, double elevationDeg, double distanceScale) const {
    raster::Camera c = SampleCamera(impl_->maps.inferred.front());
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

namespace {

// The two viewpoint samples nearest to the eye, weighted by the other's distance.
void NearestSamples(const MapSet& maps, const glm::vec3& eye, FrameStats* stats) {
    std::vector<std::pair<double, int>> byDistance;
    for (int v : maps.inferred)
        byDistance.emplace_back(
            glm::length(glm::dvec3(eye) - glm::dvec3(maps.samples[static_cast<size_t>(v)].eye)), v);
    std::sort(byDistance.begin(), byDistance.end());
    stats->samples = {byDistance[0].second};
    stats->sampleWeights = {1.0};
    if (byDistance.size() > 1 && byDistance[0].first > 1e-9) {
        const double d0 = byDistance[0].first, d1 = byDistance[1].first;
        stats->samples.push_back(byDistance[1].second);
        stats->sampleWeights = {d1 / (d0 + d1), d0 / (d0 + d1)};
    }
}

// The ray tracer's frame (full tree) at spp × spp.
RenderedFrame RenderTraced(const trace::Tracer& tracer, const raster::Camera& camera,
                           const RenderSettings& s) {
    RenderedFrame out;
    const trace::FrameResult fr =
        trace::RenderFrame(tracer, camera, s.spp, trace::Model::FullTree, s.threads);
    out.image = fr.image;
    out.lensMask.assign(static_cast<size_t>(camera.width) * static_cast<size_t>(camera.height), 0);
    for (size_t p = 0; p < out.lensMask.size(); ++p)
        out.lensMask[p] = fr.lensCoverage.data[p] > 0.0f ? 1 : 0;
    out.stats.tracerRays = fr.counts.Total();
    return out;
}

// A k× float frame box-filtered over its covered subpixels (supersampling.h).
raster::ImageF BoxFiltered(const raster::RenderResult& rr, const raster::Camera& camera, int k) {
    const std::vector<uint8_t> covered = CoveredSubpixels(rr.depth, kLensDepth);
    raster::ImageF out{camera.width, camera.height, {}};
    out.rgba.resize(4 * static_cast<size_t>(camera.width) * static_cast<size_t>(camera.height));
    double rgba[4];
    const SubpixelLayout layout = WholeFrame(camera.width, camera.height, k);
    for (uint32_t p = 0; p < out.rgba.size() / 4; ++p) {
        CoveredMean(rr.imageF, covered, layout, p, rgba);
        for (size_t c = 0; c < 4; ++c) out.rgba[4 * p + c] = static_cast<float>(rgba[c]);
    }
    return out;
}

}  // namespace

std::vector<std::vector<raster::ImageF>> Renderer::LayerImages(const raster::Camera& camera,
                                                               const RenderSettings& s, int group,
                                                               int sample) {
    Impl& m = *impl_;
    FrameStats stats;
    std::vector<double> acc;
    const std::vector<int> samples{sample};
    const std::vector<double> weights{1.0};
    const std::vector<uint32_t> pixels;
    const std::vector<glm::ivec2> border;
    const int sub = m.Subpixels(s);
    const Impl::GroupDraw d{camera, s,   group,   samples, weights, pixels,
                            &acc,   sub, &border, nullptr, &stats};
    const LensGroupEm& g = m.maps.groups[static_cast<size_t>(group)];
    const bool pemSplit = s.method == Method::Pem && g.pem;
    const GroupGeometry gg = m.Geometry(d, pemSplit);
    const std::vector<LayerUse> uses = m.Uses(d, pemSplit);
    raster::RenderOptions ro = m.Hardware(s);
    ro.profile = raster::Profile::Linear;
    ro.threads = s.threads;
    std::vector<std::vector<raster::ImageF>> out(static_cast<size_t>(g.Terms()));
    for (int term = 0; term < g.Terms(); ++term)
        for (size_t k = 0; k < uses.size(); ++k) {
            const raster::Texture* map = m.maps.map(sample, group, uses[k].name[term]);
            if (!map) throw base::InputError(m.maps.name, "missing map " + uses[k].name[term]);
            raster::Frame frame;
            frame.width = sub * camera.width, frame.height = sub * camera.height;
            frame.depthClamp = true;
            frame.depth = kLensDepth;
            const int perMap = MapTextures(m.maps.parameterization);
            frame.textures.assign(map, map + perMap);
            frame.passes.resize(static_cast<size_t>(perMap));
            const PassGeometry& geo = pemSplit && uses.size() == 2 && k == 0 ? gg.offHull : gg.all;
            PassOptions po;
            po.depthTest = LayerDepthTest(true);
            po.parameterization = m.maps.parameterization;
            po.eyeFromWorld = EyeFromWorld(camera);
            FillLayerPass(geo, ShellCoords(gg.exits[term], *uses[k].shell, g.emOrigin, s.threads),
                          gg.exits[term], po, frame.passes, s.threads);
            const raster::RenderResult rr = raster::Render(raster::PreparedFrame(frame), ro);
            raster::ImageF img = BoxFiltered(rr, camera, sub);
            const auto scale = static_cast<float>(m.RadianceScale(s));
            for (size_t i = 0; i < img.rgba.size(); ++i)
                if (i % 4 != 3) img.rgba[i] *= scale;
            out[static_cast<size_t>(term)].push_back(std::move(img));
        }
    return out;
}

RenderedFrame Renderer::Render(const raster::Camera& camera, const RenderSettings& s) {
    Impl& m = *impl_;
    const auto tStart = Clock::now();
    if (s.method == Method::RayTraced) {
        RenderedFrame out = RenderTraced(*m.tracer, camera, s);
        out.stats.totalSeconds = Since(tStart);
        return out;
    }
    // Step 1: the rest of the frame, one camera ray per pixel (trace/render.h's rows: camera and
    // shadow rays in packets); which group each pixel sees.
    RenderedFrame out;
    const auto tb = Clock::now();
    trace::FrameResult surroundings =
        trace::RenderFrame(*m.tracer, camera, 1, trace::Model::Surroundings, s.threads);
    out.image = std::move(surroundings.image);
    out.lensMask.assign(static_cast<size_t>(camera.width) * static_cast<size_t>(camera.height), 0);
    out.groupOf = surroundings.lensGroup;
    const std::vector<int>& groupOf = out.groupOf;
    out.stats.backgroundRays = surroundings.counts.Total();
    out.stats.backgroundSeconds = Since(tb);
    // Step 2: the two nearest viewpoint samples.
    NearestSamples(m.maps, camera.eye, &out.stats);
    // Step 3: each lens group seen, from its maps (a group no pixel sees costs nothing), drawn
    // with k×k subpixels; at the border pixels every subpixel's colour is kept for step 4.
    const int sub = m.Subpixels(s);
    const std::vector<glm::ivec2> border =
        sub > 1 ? SilhouettePixels(groupOf, camera.width, camera.height)
                : std::vector<glm::ivec2>();
    std::vector<GroupSamples> borderSamples(m.maps.groups.size());
    std::vector<std::vector<uint32_t>> pixelsOf(m.maps.groups.size());
    for (size_t p = 0; p < groupOf.size(); ++p)
        if (groupOf[p] >= 0)
            pixelsOf[static_cast<size_t>(groupOf[p])].push_back(static_cast<uint32_t>(p));
    for (int g = 0; g < static_cast<int>(m.maps.groups.size()); ++g) {
        const std::vector<uint32_t>& pixels = pixelsOf[static_cast<size_t>(g)];
        if (pixels.empty()) {
            ++out.stats.groupsSkipped;
            continue;
        }
        std::vector<double> acc(pixels.size() * 3, 0.0);
        m.DrawGroup({camera, s, g, out.stats.samples, out.stats.sampleWeights, pixels, &acc, sub,
                     &border, border.empty() ? nullptr : &borderSamples[static_cast<size_t>(g)],
                     &out.stats});
        // The terms added in one framebuffer: an 8-bit one saturates at the scale, a float one
        // (float maps) does not.
        const bool floatMaps =
            s.method != Method::StaticEm && m.maps.hardware.format == raster::TexelFormat::Rgba32F;
        const double saturation =
            floatMaps ? std::numeric_limits<double>::infinity() : m.RadianceScale(s);
        for (size_t k = 0; k < pixels.size(); ++k) {
            out.lensMask[pixels[k]] = 1;
            for (size_t c = 0; c < 3; ++c)
                out.image.data[3 * size_t{pixels[k]} + c] =
                    static_cast<float>(std::min(saturation, acc[3 * k + c]));
        }
    }
    // Step 4: the groups' borders from k×k samples of the ray tracer (silhouettes.h).
    const auto te = Clock::now();
    trace::RayCounts edgeRays;
    ResolveSilhouettes(*m.tracer, camera, sub, border, groupOf, borderSamples, s.threads,
                       &out.image, &edgeRays);
    out.stats.backgroundRays += edgeRays.Total();
    out.stats.backgroundSeconds += Since(te);
    out.stats.lensSeconds = out.stats.traceSeconds + out.stats.tessSeconds +
                            out.stats.texgenSeconds + out.stats.rasterSeconds;
    out.stats.totalSeconds = Since(tStart);
    return out;
}

}  // namespace pem::runtime
