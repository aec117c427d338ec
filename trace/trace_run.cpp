// SPDX-License-Identifier: MIT
// trace_run.cpp — RunTrace and the viewpoint helpers (trace_run.h).
#include "trace/trace_run.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "trace/segment.h"

namespace pem::trace {

namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string ViewDir(const std::string& out, size_t v) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%03zu", v);
    return out + "/" + name;
}

std::string GroupDir(const std::string& out, size_t v, int g) {
    return ViewDir(out, v) + "/group_" + std::to_string(g);
}

const char* const kTermName[2] = {"R", "T"};

// Progress over the job's stages: each stage is one pass over a frame's rows.
struct Progress {
    const TraceRunOptions& options;
    int stages = 1, stage = 0;
    std::function<void(int, int)> For(const std::string& name) {
        const int s = stage++;
        if (!options.progress) return {};
        return [this, s, name](int done, int total) {
            options.progress(name, (s + static_cast<double>(done) / total) / stages);
        };
    }
};

struct Job {
    const Scene& scene;
    const TraceRunOptions& options;
    const Tracer& tracer;
    TraceRunReport& report;
    Progress progress;
    std::vector<std::vector<HitRecord>> records;       // per group
    std::vector<std::vector<glm::vec3>> recordPoints;  // per group
    std::vector<double> distantSum;                    // per group
    std::vector<size_t> distantCount;

    void Write(const std::string& path, const FloatImage& image) const {
        WriteExr(path, image);
        if (options.written) options.written(path, image);
    }

    void Frames(size_t v, ViewReport& r) {
        const raster::Camera& cam = options.views[v];
        const std::string dir = ViewDir(options.outDir, v);
        std::filesystem::create_directories(dir);
        auto t0 = Clock::now();
        const FrameResult ref = RenderFrame(tracer, cam, options.k, Model::FullTree,
                                            options.threads, progress.For("reference"));
        r.referenceSeconds = SecondsSince(t0);
        t0 = Clock::now();
        const FrameResult greedy = RenderFrame(tracer, cam, options.k, Model::Greedy,
                                               options.threads, progress.For("greedy"));
        r.greedySeconds = SecondsSince(t0);
        r.reference = ref.counts, r.greedy = greedy.counts;
        r.frame = CompareImages(greedy.image, ref.image, {});
        r.lens = CompareImages(greedy.image, ref.image, ref.lensCoverage);
        r.frameHdr = CompareImages(greedy.image, ref.image, {}, true);
        r.lensHdr = CompareImages(greedy.image, ref.image, ref.lensCoverage, true);
        Write(dir + "/reference.exr", ref.image);
        Write(dir + "/greedy.exr", greedy.image);
    }

    void Segment(size_t v, int g, ViewReport& r) {
        const std::string dir = GroupDir(options.outDir, v, g);
        std::filesystem::create_directories(dir);
        const GroupSegmentation s =
            SegmentGroup(tracer, options.views[v], options.k, g, static_cast<uint32_t>(v),
                         report.groups[static_cast<size_t>(g)].layers.emOrigin, options.threads,
                         progress.For("segment"));
        for (int t = 0; t < s.terms; ++t) {
            Write(dir + "/b_" + kTermName[t] + ".exr", s.b[t]);
            Write(dir + "/FG_" + kTermName[t] + ".exr", s.fg[t]);
            Write(dir + "/confidence_" + kTermName[t] + ".exr", s.confidence[t]);
        }
        if (s.mirror) {
            Write(dir + "/local.exr", s.local);
            Write(dir + "/distant.exr", s.distant);
            Write(dir + "/fresnel1.exr", s.fresnel1);
        }
        const auto gi = static_cast<size_t>(g);
        records[gi].insert(records[gi].end(), s.records.begin(), s.records.end());
        recordPoints[gi].insert(recordPoints[gi].end(), s.recordPoints.begin(),
                                s.recordPoints.end());
        distantSum[gi] += s.distantDistanceSum;
        distantCount[gi] += s.distantCount;
        r.segmentation += s.counts;
    }

    void Layers(int g) {
        const auto gi = static_cast<size_t>(g);
        GroupReport& gr = report.groups[gi];
        LayerInput in{records[gi], recordPoints[gi], options.layers,
                      0.15,        distantSum[gi],   distantCount[gi]};
        gr.layers = BuildLayers(scene, g, !gr.glass, in);
        gr.records = records[gi].size();
    }

    void LayerImagesOf(size_t v, int g, ViewReport& r) {
        const GroupLayers& layers = report.groups[static_cast<size_t>(g)].layers;
        const LayerImages li = RenderLayers(tracer, options.views[v], options.k, layers,
                                            options.threads, progress.For("layers"));
        const std::string dir = GroupDir(options.outDir, v, g);
        for (int t = 0; t < 2; ++t)
            for (size_t l = 0; l < li.term[t].size(); ++l)
                Write(dir + "/layer_" + std::to_string(l) + "_" + kTermName[t] + ".exr",
                      li.term[t][l]);
        r.layers += li.counts;
    }
};

}  // namespace

glm::vec3 LensCentre(const Scene& scene) {
    Bounds b;
    for (const LensGroup& g : scene.lensGroups) b.Extend(g.bounds);
    if (b.Empty())
        for (const Object& o : scene.objects) b.Extend(o.bounds);
    return b.Empty() ? glm::vec3(0.0f) : b.Center();
}

std::vector<raster::Camera> CircleViews(const raster::Camera& camera, const glm::vec3& centre,
                                        int n, double stepDeg) {
    std::vector<raster::Camera> views;
    const glm::dvec3 c(centre), e(camera.eye);
    const glm::dvec2 offset(e.x - c.x, e.z - c.z);
    for (int i = 0; i < n; ++i) {
        const double a = i * stepDeg * std::numbers::pi / 180.0;
        const double ca = std::cos(a), sa = std::sin(a);
        raster::Camera cam = camera;
        // Rotation about +Y: (x, z) -> (x cos a + z sin a, −x sin a + z cos a).
        cam.eye = glm::vec3(glm::dvec3(c.x + offset.x * ca + offset.y * sa, e.y,
                                       c.z - offset.x * sa + offset.y * ca));
        cam.target = centre;
        cam.up = {0.0f, 1.0f, 0.0f};
        views.push_back(cam);
    }
    return views;
}

TraceRunReport RunTrace(const Scene& scene, const TraceRunOptions& options) {
    const auto t0 = Clock::now();
    TraceRunReport report;
    report.triangles = scene.NumTriangles();
    const EmbreeDevice device({options.threads, "auto"});
    report.embreeConfig = device.config();
    const EmbreeScene embree(device, scene);
    report.buildSeconds = SecondsSince(t0);
    const Tracer tracer(scene, embree, options.trace);

    const int groups = options.segment ? static_cast<int>(scene.lensGroups.size()) : 0;
    const int views = static_cast<int>(options.views.size());
    Job job{scene, options, tracer, report, {options, views * (2 + 2 * groups)}, {}, {}, {}, {}};
    job.records.resize(static_cast<size_t>(groups));
    job.recordPoints.resize(static_cast<size_t>(groups));
    job.distantSum.assign(static_cast<size_t>(groups), 0.0);
    job.distantCount.assign(static_cast<size_t>(groups), 0);
    for (int g = 0; g < groups; ++g) {
        GroupReport gr;
        gr.group = g;
        gr.glass = tracer.GroupHasGlass(g);
        for (int o : scene.lensGroups[static_cast<size_t>(g)].objects)
            gr.objects.push_back(scene.objects[static_cast<size_t>(o)].name);
        gr.layers.emOrigin = GroupEmOrigin(scene, g);
        report.groups.push_back(gr);
    }
    report.views.resize(options.views.size());
    for (size_t v = 0; v < options.views.size(); ++v) {
        job.Frames(v, report.views[v]);
        for (int g = 0; g < groups; ++g) job.Segment(v, g, report.views[v]);
    }
    for (int g = 0; g < groups; ++g) job.Layers(g);
    for (size_t v = 0; v < options.views.size(); ++v)
        for (int g = 0; g < groups; ++g) job.LayerImagesOf(v, g, report.views[v]);
    for (const ViewReport& r : report.views) {
        report.total += r.reference;
        report.total += r.greedy;
        report.total += r.segmentation;
        report.total += r.layers;
    }
    report.seconds = SecondsSince(t0);
    return report;
}

}  // namespace pem::trace
