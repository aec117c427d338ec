// SPDX-License-Identifier: MIT
// trace_job.cpp — RunTraceJob (trace_job.h).
#include "pipeline/trace_job.h"

#include <chrono>
#include <filesystem>

#include "base/display_image.h"
#include "base/input_error.h"
#include "base/png_io.h"
#include "pipeline/layout.h"
#include "pipeline/viewpoints.h"
#include "trace/embree_scene.h"
#include "trace/layers.h"
#include "trace/render.h"
#include "trace/segment.h"

namespace pem::pipeline {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Progress over the job's stages: each stage is one pass over a frame's rows.
struct Progress {
    const TraceJobOptions& options;
    int stages = 1, stage = 0;
    std::function<void(int, int)> For(const std::string& name) {
        const int s = stage++;
        if (!options.progress) return {};
        return [this, s, name](int done, int total) {
            options.progress(name, (s + static_cast<double>(done) / total) / stages);
        };
    }
};

// The images that get a PNG preview next to their EXR file.
bool WantsPreview(const std::string& name) {
    for (const char* n : {"reference", "greedy", "b_R", "b_T", "local", "distant"})
        if (name == n) return true;
    return false;
}

struct Job {
    const trace::Scene& scene;
    const TraceJobOptions& options;
    const trace::Tracer& tracer;
    TraceManifest& manifest;
    std::vector<trace::GroupLayers> groupLayers;
    Progress progress;
    std::vector<std::vector<trace::HitRecord>> records;  // per group
    std::vector<std::vector<glm::vec3>> recordPoints;    // per group
    std::vector<std::vector<glm::vec3>> recordOrigins;   // per group
    std::vector<double> distantSum;                      // per group
    std::vector<size_t> distantCount;
    std::vector<std::vector<glm::vec3>> localOrigins, localPoints;  // per group

    const raster::Camera& Camera(size_t v) const { return manifest.views[v].camera; }

    void Write(const std::string& path, const std::string& name, const trace::FloatImage& image) {
        trace::WriteExr(path, image);
        if (WantsPreview(name))
            base::WritePng(PreviewPath(path),
                           base::ToDisplayImage(image.data, image.width, image.height,
                                                image.channels, options.exposure));
    }
    void WriteFrame(size_t v, const std::string& name, const trace::FloatImage& image) {
        Write(FrameImagePath(options.outDir, static_cast<int>(v), name), name, image);
    }
    void WriteGroup(size_t v, int g, const std::string& name, const trace::FloatImage& image) {
        Write(GroupImagePath(options.outDir, static_cast<int>(v), g, name), name, image);
    }
    // A group image's K×K samples (K > 1; with K = 1 they are the image itself).
    void WriteSamples(size_t v, int g, const std::string& name, const trace::FloatImage& image) {
        if (options.spp == 1) return;
        const std::string path = GroupSampleImagePath(options.outDir, static_cast<int>(v), g, name);
        std::filesystem::create_directories(std::filesystem::path(path).parent_path());
        trace::WriteExr(path, image);
    }

    // Step 1 of a viewpoint: the reference (full tree) and the greedy two-term frame.
    void Frames(size_t v) {
        TracedView& r = manifest.views[v];
        std::filesystem::create_directories(ViewDir(options.outDir, static_cast<int>(v)));
        auto t0 = Clock::now();
        const trace::FrameResult ref =
            trace::RenderFrame(tracer, Camera(v), options.spp, trace::Model::FullTree,
                               options.threads, progress.For("reference"));
        r.referenceSeconds = SecondsSince(t0);
        t0 = Clock::now();
        const trace::FrameResult greedy =
            trace::RenderFrame(tracer, Camera(v), options.spp, trace::Model::Greedy,
                               options.threads, progress.For("greedy"));
        r.greedySeconds = SecondsSince(t0);
        r.reference = ref.counts, r.greedy = greedy.counts;
        r.frame = trace::CompareImages(greedy.image, ref.image, {});
        r.lens = trace::CompareImages(greedy.image, ref.image, ref.lensCoverage);
        r.frameHdr = trace::CompareImages(greedy.image, ref.image, {}, true);
        r.lensHdr = trace::CompareImages(greedy.image, ref.image, ref.lensCoverage, true);
        WriteFrame(v, "reference", ref.image);
        WriteFrame(v, "greedy", greedy.image);
    }

    // Step 2: a lens group's segmented images at a viewpoint, and its hit records.
    void Segment(size_t v, int g) {
        std::filesystem::create_directories(GroupDir(options.outDir, static_cast<int>(v), g));
        const auto gi = static_cast<size_t>(g);
        const trace::GroupSegmentation s =
            trace::SegmentGroup(tracer, Camera(v), options.spp, g, static_cast<uint32_t>(v),
                                groupLayers[gi].emOrigin, options.threads, progress.For("segment"));
        for (int t = 0; t < s.terms; ++t) {
            const std::string tn = runtime::TermName(t);
            WriteGroup(v, g, "b_" + tn, s.b[t]);
            WriteSamples(v, g, "b_" + tn, s.bSamples[t]);
            WriteGroup(v, g, "FG_" + tn, s.fg[t]);
            WriteGroup(v, g, "confidence_" + tn, s.confidence[t]);
        }
        if (s.mirror) {
            WriteGroup(v, g, "local", s.local);
            WriteGroup(v, g, "distant", s.distant);
            WriteSamples(v, g, "local", s.localSamples);
            WriteSamples(v, g, "distant", s.distantSamples);
            WriteGroup(v, g, "fresnel1", s.fresnel1);
        }
        records[gi].insert(records[gi].end(), s.records.begin(), s.records.end());
        recordPoints[gi].insert(recordPoints[gi].end(), s.recordPoints.begin(),
                                s.recordPoints.end());
        recordOrigins[gi].insert(recordOrigins[gi].end(), s.recordOrigins.begin(),
                                 s.recordOrigins.end());
        localOrigins[gi].insert(localOrigins[gi].end(), s.localOrigins.begin(),
                                s.localOrigins.end());
        localPoints[gi].insert(localPoints[gi].end(), s.localPoints.begin(), s.localPoints.end());
        distantSum[gi] += s.distantDistanceSum;
        distantCount[gi] += s.distantCount;
        manifest.views[v].segmentation += s.counts;
    }

    // Step 3: a group's layers over all viewpoints' records.
    void Layers(int g) {
        const auto gi = static_cast<size_t>(g);
        const trace::LayerInput in{
            records[gi],      recordPoints[gi],  options.layers,   0.15,           distantSum[gi],
            distantCount[gi], recordOrigins[gi], localOrigins[gi], localPoints[gi]};
        groupLayers[gi] = trace::BuildLayers(scene, g, !manifest.groups[gi].glass, in);
        manifest.groups[gi].records = static_cast<int64_t>(records[gi].size());
    }

    // Step 4: a group's layer images at a viewpoint.
    void LayerImagesOf(size_t v, int g) {
        const trace::LayerImages li =
            trace::RenderLayers(tracer, Camera(v), options.spp, groupLayers[static_cast<size_t>(g)],
                                options.threads, progress.For("layers"));
        for (int t = 0; t < 2; ++t)
            for (size_t l = 0; l < li.term[t].size(); ++l) {
                WriteGroup(v, g, LayerImageName(static_cast<int>(l), t), li.term[t][l]);
                WriteSamples(v, g, LayerImageName(static_cast<int>(l), t), li.samples[t][l]);
            }
        manifest.views[v].layers += li.counts;
    }
};

// The EM geometry trace.json stores for a group (runtime/lens_group_em.h).
void StoreLayers(const trace::Scene& scene, const trace::GroupLayers& l, runtime::LensGroupEm* g) {
    g->emOrigin = l.emOrigin;
    g->lbgIterations = l.clustering.iterations;
    g->lbgConverged = l.clustering.converged;
    for (size_t i = 0; i < l.clustering.layers.size(); ++i) {
        const trace::LayerCluster& c = l.clustering.layers[i];
        runtime::EmLayer layer;
        layer.kind = l.shells[i].kind;
        layer.shell = l.shells[i].shell;
        layer.radius = c.radius;
        layer.records = static_cast<int64_t>(c.recordCount);
        for (uint32_t o : c.objects) layer.objects.push_back(scene.objects[o].name);
        layer.occupancy = l.shells[i].occupancy;
        layer.parallaxDeg = l.shells[i].parallaxDeg;
        layer.candidates = l.shells[i].candidates;
        g->layers.push_back(layer);
    }
    g->pem = l.mirror;
    if (l.mirror) {
        g->localShell = l.localShell;
        g->localParallaxDeg = l.localParallaxDeg;
        g->distantShell = l.distantShell;
        g->distantMeanDistance = l.distantMeanDistance;
    }
}

// What the manifest knows before the work: settings, cameras, groups.
TraceManifest StartManifest(const trace::Scene& scene, const TraceJobOptions& o,
                            const trace::Tracer& tracer) {
    TraceManifest m;
    m.dir = o.outDir;
    m.scene = SceneForStorage(o.outDir, o.scene);
    m.sceneGiven = AbsolutePath(o.scene);
    m.width = o.width, m.height = o.height, m.spp = o.spp, m.threads = o.threads;
    m.fullTreeDepth = o.trace.fullTreeDepth;
    m.minWeight = o.trace.minWeight;
    m.fresnel = o.trace.fresnel == trace::FresnelModel::Schlick ? "schlick" : "exact";
    m.triangles = scene.NumTriangles();
    for (const raster::Camera& c : SampleViews(scene, o.views, o.width, o.height))
        m.views.push_back({c, 0.0, 0.0, {}, {}, {}, {}, {}, {}, {}, {}});
    const int groups = o.segment ? static_cast<int>(scene.lensGroups.size()) : 0;
    for (int g = 0; g < groups; ++g) {
        runtime::LensGroupEm gr;
        gr.index = g;
        gr.glass = tracer.GroupHasGlass(g);
        for (int obj : scene.lensGroups[static_cast<size_t>(g)].objects)
            gr.objects.push_back(scene.objects[static_cast<size_t>(obj)].name);
        m.groups.push_back(gr);
    }
    m.leftOut = {"T-term images for mirror-only groups",
                 "local/distant split for groups with glass",
                 "caustics and light through glass (shadow rays are opaque)"};
    return m;
}

}  // namespace

TraceManifest RunTraceJob(const TraceJobOptions& o) {
    const auto t0 = Clock::now();
    const trace::Scene scene = trace::LoadScene(o.scene);
    std::error_code ec;
    std::filesystem::create_directories(o.outDir, ec);
    if (ec) throw base::InputError(o.outDir, "cannot create the directory: " + ec.message());
    const trace::EmbreeDevice device({o.threads, "auto"});
    const trace::EmbreeScene embree(device, scene);
    const double bvhSeconds = SecondsSince(t0);
    const trace::Tracer tracer(scene, embree, o.trace);
    TraceManifest m = StartManifest(scene, o, tracer);
    m.embreeConfig = device.config();
    m.bvhSeconds = bvhSeconds;
    const int groups = static_cast<int>(m.groups.size());
    const int views = static_cast<int>(m.views.size());
    Job job{scene, o, tracer, m, {}, {o, views * (2 + 2 * groups)}, {}, {}, {}, {}, {}, {}, {}};
    job.groupLayers.resize(static_cast<size_t>(groups));
    job.records.resize(static_cast<size_t>(groups));
    job.recordPoints.resize(static_cast<size_t>(groups));
    job.recordOrigins.resize(static_cast<size_t>(groups));
    job.distantSum.assign(static_cast<size_t>(groups), 0.0);
    job.distantCount.assign(static_cast<size_t>(groups), 0);
    job.localOrigins.resize(static_cast<size_t>(groups));
    job.localPoints.resize(static_cast<size_t>(groups));
    for (int g = 0; g < groups; ++g)
        job.groupLayers[static_cast<size_t>(g)].emOrigin = trace::GroupEmOrigin(scene, g);
    for (size_t v = 0; v < m.views.size(); ++v) {
        job.Frames(v);
        for (int g = 0; g < groups; ++g) job.Segment(v, g);
    }
    for (int g = 0; g < groups; ++g) job.Layers(g);
    for (size_t v = 0; v < m.views.size(); ++v)
        for (int g = 0; g < groups; ++g) job.LayerImagesOf(v, g);
    for (int g = 0; g < groups; ++g)
        StoreLayers(scene, job.groupLayers[static_cast<size_t>(g)],
                    &m.groups[static_cast<size_t>(g)]);
    for (const TracedView& r : m.views) {
        m.rays += r.reference;
        m.rays += r.greedy;
        m.rays += r.segmentation;
        m.rays += r.layers;
    }
    m.seconds = SecondsSince(t0);
    WriteTraceManifest(m);
    return m;
}

}  // namespace pem::pipeline
