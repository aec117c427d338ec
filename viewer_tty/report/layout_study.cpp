// SPDX-License-Identifier: MIT
// layout_study.cpp — the parameterization study's measurements (layout_study.h).
#include "viewer_tty/report/layout_study.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "base/input_error.h"
#include "pipeline/infer_job.h"
#include "pipeline/layout.h"
#include "pipeline/pem_set.h"
#include "pipeline/trace_job.h"
#include "viewer_tty/report/image_metrics.h"
#include "viewer_tty/report/positions.h"

namespace pem::report {
namespace {

namespace fs = std::filesystem;

std::string SceneName(const std::string& path) {
    return fs::path(path).stem().string();
}

// The first element equal to an earlier one, or end.
template <typename T>
typename std::vector<T>::const_iterator FirstRepeat(const std::vector<T>& v) {
    for (auto it = v.begin(); it != v.end(); ++it)
        if (std::find(v.begin(), it, *it) != it) return it;
    return v.end();
}

void CheckOptions(const LayoutStudyOptions& o) {
    if (o.scenes.empty()) throw base::InputError("pemref study", "no scene given");
    if (o.layouts.empty()) throw base::InputError("--layouts", "no layout given");
    if (o.sizes.empty()) throw base::InputError("--sizes", "no size given");
    for (int s : o.sizes)
        if (s < 2 || s > 1024 || (s & (s - 1)) != 0)
            throw base::InputError("--sizes " + std::to_string(s),
                                   "expected powers of two in [2, 1024]");
    if (auto it = FirstRepeat(o.sizes); it != o.sizes.end())
        throw base::InputError("--sizes " + std::to_string(*it), "given twice");
    if (auto it = FirstRepeat(o.layouts); it != o.layouts.end())
        throw base::InputError("--layouts " + std::string(runtime::ParameterizationName(*it)),
                               "given twice");
    std::vector<std::string> names;  // each scene's folder
    for (const std::string& scene : o.scenes) {
        if (!fs::is_regular_file(scene)) throw base::InputError(scene, "scene not found");
        names.push_back(SceneName(scene));
    }
    if (auto it = FirstRepeat(names); it != names.end())
        throw base::InputError(o.scenes[static_cast<size_t>(it - names.begin())],
                               "another scene of the study has the same name (" + *it +
                                   "): they would share a folder");
}

// The renderer's method of each of kStudyMethods.
constexpr runtime::Method kMethodOf[] = {runtime::Method::Hybrid, runtime::Method::Pem,
                                         runtime::Method::StaticEm};
static_assert(std::size(kMethodOf) == std::size(kStudyMethods));

// The reference frame of each position (the ray tracer, full tree, K×K) and its lens pixels.
struct Reference {
    MetricImage image;
    std::vector<uint8_t> mask;
};

std::vector<Reference> References(runtime::Renderer& renderer, const std::vector<Position>& at,
                                  const LayoutStudyOptions& o) {
    std::vector<Reference> refs;
    for (const Position& p : at) {
        runtime::RenderSettings s;
        s.method = runtime::Method::RayTraced;
        s.spp = o.referenceSpp;
        s.threads = o.threads;
        const runtime::RenderedFrame f = renderer.Render(p.camera, s);
        refs.push_back({ToMetric(f.image), f.lensMask});
    }
    return refs;
}

// The first map of the first inferred sample, in the renderers' preference (outer layer first).
std::string PictureOf(const std::string& studyDir, const std::string& pemRel, int view) {
    for (const char* name : {"layer_0", "layer_1", "pem_distant", "pem_local"}) {
        const std::string png = pipeline::GroupDir(pemRel, view, 0) + "/" + name + ".png";
        if (fs::exists(studyDir + "/" + png)) return png;
    }
    return "";
}

// Step: the maps of one layout and size, inferred from the scene's trace.
LayoutPoint InferPoint(const std::string& scene, const std::string& traceDir,
                       runtime::Parameterization p, int size, const LayoutStudyOptions& o) {
    LayoutPoint pt;
    pt.scene = scene;
    pt.layout = p;
    pt.size = size;
    pt.texels = runtime::LayoutOf(p, size).Texels();
    pt.pemDir =
        scene + "/" + std::string(runtime::ParameterizationName(p)) + "_" + std::to_string(size);
    pipeline::InferJobOptions io;
    io.traceDir = traceDir;
    io.outDir = o.outDir + "/" + pt.pemDir;
    io.res = size;
    io.parameterization = p;
    io.threads = o.threads;
    const pipeline::InferJobResult r = pipeline::RunInferJob(io);
    pipeline::WriteInferOutputs(io, r);
    pt.maps = static_cast<int>(r.maps.size());
    double sum = 0.0;
    for (const pipeline::MapReport& m : r.maps) sum += m.rmse8;
    pt.rmse8 = r.maps.empty() ? std::numeric_limits<double>::quiet_NaN() : sum / pt.maps;
    pt.inferSeconds = r.seconds / static_cast<double>(std::max<size_t>(1, r.samples.size()));
    pt.picture = PictureOf(o.outDir, pt.pemDir, r.samples.empty() ? 0 : r.samples.front().view);
    return pt;
}

// Step: its frames at every position, scored against the references.
void ScorePoint(runtime::Renderer& renderer, const std::vector<Position>& at,
                const std::vector<Reference>& refs, const LayoutStudyOptions& o, LayoutPoint* pt) {
    for (size_t k = 0; k < at.size(); ++k)
        for (size_t m = 0; m < std::size(kStudyMethods); ++m) {
            runtime::RenderSettings s;
            s.method = kMethodOf[m];
            s.staticLayout = pt->layout;
            s.threads = o.threads;
            renderer.Render(at[k].camera, s);  // warm: maps loaded, passes prepared
            const runtime::RenderedFrame f = renderer.Render(at[k].camera, s);
            const ImageScores q = Compare8Bit(ToMetric(f.image), refs[k].image, &refs[k].mask);
            pt->scores.push_back({at[k].name, kStudyMethods[m], q.psnr, f.stats.totalSeconds});
        }
}

}  // namespace

double LayoutPoint::Psnr(const std::string& position, const std::string& method) const {
    for (const LayoutScore& s : scores)
        if (s.position == position && s.method == method) return s.psnr;
    return std::numeric_limits<double>::quiet_NaN();
}

LayoutStudy RunLayoutStudy(const LayoutStudyOptions& o) {
    CheckOptions(o);
    LayoutStudy study;
    study.options = o;
    const double total = static_cast<double>(o.scenes.size() * o.layouts.size() * o.sizes.size());
    double done = 0.0;
    auto progress = [&](const std::string& stage) {
        if (o.progress) o.progress(stage, done / total);
    };
    for (const std::string& scenePath : o.scenes) {
        // Step 1: the scene's trace, shared by every layout.
        const std::string scene = SceneName(scenePath);
        study.scenes.push_back(scene);
        pipeline::TraceJobOptions t;
        t.scene = scenePath;
        t.outDir = o.outDir + "/" + scene + "/trace";
        t.views = o.views;
        t.width = o.width, t.height = o.height, t.spp = o.spp, t.threads = o.threads;
        progress(scene + ": trace");
        pipeline::RunTraceJob(t);
        // Step 2: per layout and size, the maps, then their frames at the three positions
        // against references traced once per scene.
        std::vector<Reference> refs;
        for (runtime::Parameterization p : o.layouts)
            for (int size : o.sizes) {
                progress(scene + ": " + std::string(runtime::ParameterizationName(p)) + " " +
                         std::to_string(size));
                LayoutPoint pt = InferPoint(scene, t.outDir, p, size, o);
                const std::unique_ptr<runtime::Renderer> renderer =
                    pipeline::OpenPemDirectory(o.outDir + "/" + pt.pemDir, o.threads);
                const std::vector<Position> at = Positions(*renderer);
                if (refs.empty()) refs = References(*renderer, at, o);
                if (study.positions.empty())
                    for (const Position& pos : at) study.positions.push_back(pos.name);
                ScorePoint(*renderer, at, refs, o, &pt);
                study.points.push_back(std::move(pt));
                done += 1.0;
            }
    }
    progress("done");
    return study;
}

}  // namespace pem::report
