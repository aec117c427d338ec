// SPDX-License-Identifier: MIT
// infer_run.cpp — `pemref infer`: trace directory → PEM files (infer_run.h).
#include "infer/infer_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <nlohmann/json.hpp>

#include "infer/cube_map.h"
#include "infer/pem_file.h"
#include "raster/render.h"
#include "runtime/convex_hull.h"
#include "runtime/lens_paths.h"
#include "runtime/pem_set.h"
#include "runtime/texgen.h"
#include "trace/embree_scene.h"
#include "trace/image.h"
#include "trace/scene.h"
#include "trace/tracer.h"
#include "viewer_tty/input_error.h"
#include "viewer_tty/png_io.h"

namespace pem::infer {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// trace.json ------------------------------------------------------------------------------------

glm::dvec3 Vec3(const json& j) {
    return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}

// Files ------------------------------------------------------------------------------------------

std::string ViewDir(int v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "view_%03d", v);
    return buf;
}

// The 8-bit copy as one PNG: each level's six faces side by side, levels stacked.
void WriteTexturePng(const raster::Texture& tex, const std::string& path) {
    int height = 0;
    for (int l = 0; l < tex.NumLevels(); ++l) height += tex.LevelHeight(l);
    raster::Image8 img{6 * tex.width, height, {}};
    img.rgba.assign(static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 4, 0);
    int y0 = 0;
    for (int l = 0; l < tex.NumLevels(); ++l) {
        const int n = tex.LevelWidth(l);
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i)
                    for (int c = 0; c < 4; ++c)
                        img.rgba[(static_cast<size_t>(y0 + j) * static_cast<size_t>(img.width) +
                                  static_cast<size_t>(f * n + i)) *
                                     4 +
                                 static_cast<size_t>(c)] =
                            tex.levels[static_cast<size_t>(l)]
                                      [((static_cast<size_t>(f) * n + j) * n + i) * 4 + c];
        y0 += n;
    }
    cli::WritePng(path, img);
}

void WriteMatrixMarket(const std::string& path, const CsrMatrix& m) {
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp);
        f << "%%MatrixMarket matrix coordinate real general\n";
        f << m.rows << " " << m.cols << " " << m.NonZeros() << "\n";
        f.precision(17);
        for (int64_t r = 0; r < m.rows; ++r)
            for (int64_t k = m.rowPtr[static_cast<size_t>(r)];
                 k < m.rowPtr[static_cast<size_t>(r) + 1]; ++k)
                f << r + 1 << " " << m.col[static_cast<size_t>(k)] + 1 << " "
                  << m.val[static_cast<size_t>(k)] << "\n";
        if (!f) throw InputError(path, "cannot write");
    }
    std::filesystem::rename(tmp, path);
}

void WriteVectorMarket(const std::string& path, const Vector& v) {
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp);
        f << "%%MatrixMarket matrix array real general\n" << v.size() << " 1\n";
        f.precision(17);
        for (double x : v) f << x << "\n";
        if (!f) throw InputError(path, "cannot write");
    }
    std::filesystem::rename(tmp, path);
}

// One map's solve ----------------------------------------------------------------------------

struct MapInput {
    const trace::FloatImage* layer = nullptr;     // RGBA premultiplied layer image
    const trace::FloatImage* coverage = nullptr;  // alpha = lens coverage
    const trace::FloatImage* confidence = nullptr;
    raster::Pass pass;
    double weight = 1.0;               // multiplies the confidence
    bool own = true;                   // the sample's own view (counts in rmse_8bit)
    std::vector<MapInput> neighbours;  // the same map seen by the other term and nearby samples
};

// Rows of b appended to a (the same columns).
void AppendRows(raster::RenderingMatrix* a, const raster::RenderingMatrix& b) {
    const int64_t base = a->rowPtr.back();
    for (size_t r = 1; r < b.rowPtr.size(); ++r) a->rowPtr.push_back(base + b.rowPtr[r]);
    a->col.insert(a->col.end(), b.col.begin(), b.col.end());
    a->val.insert(a->val.end(), b.val.begin(), b.val.end());
    a->offset.insert(a->offset.end(), b.offset.begin(), b.offset.end());
    a->rendered.insert(a->rendered.end(), b.rendered.begin(), b.rendered.end());
    a->rows += b.rows;
}

raster::Frame UnknownFrame(int width, int height, int res) {
    raster::Frame frame;
    frame.width = width;
    frame.height = height;
    frame.depthClamp = true;
    raster::Texture tex;
    tex.kind = raster::TextureKind::Cube;
    tex.width = tex.height = res;
    for (int l = 0; (res >> l) >= 1; ++l)
        tex.levels.emplace_back(static_cast<size_t>(6 * (res >> l) * (res >> l) * 4), 0);
    frame.textures.push_back(std::move(tex));
    return frame;
}

// Target rows 4 * (y W + x) + c: the layer un-premultiplied by coverage (clamped into [0, 1]
// for 8-bit maps: what they can reach), weight conf · coverage.
Target MakeTarget(const MapInput& in, int width, int height, bool hdr) {
    Target t;
    const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
    t.b.assign(n * 4, 0.0);
    t.confidence.assign(n * 4, 0.0);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t p =
                static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
            const double cov = static_cast<double>(in.coverage->At(x, y)[3]);
            if (!(cov > 1e-6)) continue;
            const double conf =
                in.confidence ? static_cast<double>(in.confidence->At(x, y)[0]) : 1.0;
            for (size_t c = 0; c < 4; ++c) {
                const double v = static_cast<double>(in.layer->At(x, y)[c]) / cov;
                t.b[4 * p + c] = hdr ? v : std::clamp(v, 0.0, 1.0);
                t.confidence[4 * p + c] = in.weight * conf * cov;
            }
        }
    return t;
}

// Writes one map's files while the next map is solved (at most one write in flight, so memory
// stays bounded); Wait() rethrows a failed write. The files do not depend on the overlap.
class Writer {
  public:
    ~Writer() {
        if (pending_.valid()) pending_.wait();
    }
    void Submit(std::function<void()> job) {
        Wait();
        pending_ = std::async(std::launch::async, std::move(job));
    }
    void Wait() {
        if (pending_.valid()) pending_.get();
    }

  private:
    std::future<void> pending_;
};

MapReport SolveMap(const MapInput& in, const InferRunOptions& opt, const TraceManifest& tm,
                   const std::string& dir, MapReport rep, Writer* writer, double* writeSeconds) {
    const int w = tm.width, h = tm.height;
    // Step 1: the rendering matrix of the texgen pass.
    const auto t0 = Clock::now();
    raster::Frame frame = UnknownFrame(w, h, opt.res);
    frame.passes.push_back(in.pass);
    raster::RenderOptions ro;
    ro.profile = raster::Profile::Linear;
    ro.threads = opt.threads;
    raster::RenderingMatrix a = raster::BuildRenderingMatrix(raster::PreparedFrame(frame), ro);
    // The sample's own observations (their frame and first row) for rmse_8bit.
    std::vector<std::pair<raster::Frame, int64_t>> own{{frame, 0}};
    Target target = MakeTarget(in, w, h, opt.hdr);
    // The other term's and the nearby samples' rows below (the simultaneous solve).
    for (const MapInput& nb : in.neighbours) {
        raster::Frame nf = UnknownFrame(w, h, opt.res);
        nf.passes.push_back(nb.pass);
        if (nb.own) own.emplace_back(nf, a.rows);
        AppendRows(&a, raster::BuildRenderingMatrix(raster::PreparedFrame(nf), ro));
        const Target t = MakeTarget(nb, w, h, opt.hdr);
        target.b.insert(target.b.end(), t.b.begin(), t.b.end());
        target.confidence.insert(target.confidence.end(), t.confidence.begin(), t.confidence.end());
    }
    rep.matrixSeconds = Since(t0);
    // Step 2: the stacked system over the active texels.
    const LinearSystem sys = BuildSystem(a, frame, 0, target, opt.weights, opt.system);
    rep.buildSeconds = Since(t0);
    rep.rows = sys.k.Rows();
    rep.cols = sys.Cols();
    rep.nnz = sys.k.A().NonZeros();
    rep.observedTexels = static_cast<int64_t>(sys.active.size());
    // Step 3: the solve.
    SolveOptions so = opt.solve;
    so.threads = opt.threads;
    so.bounds = opt.hdr ? Bounds::Hdr() : Bounds::Unit();
    const SolveResult res =
        SolveIterative(sys, SplatGuess(sys, so.bounds.lo, so.bounds.hi, opt.threads), so);
    rep.solveSeconds = res.seconds;
    rep.iterations = res.iterations;
    rep.stop = ToString(res.stop);
    rep.rmse = MaskedImageRmse(sys, res.x, opt.threads);
    {
        Vector kx;
        sys.k.Apply(res.x, &kx, opt.threads);
        double obj = 0.0;
        for (size_t r = 0; r < kx.size(); ++r) obj += (kx[r] - sys.h[r]) * (kx[r] - sys.h[r]);
        rep.objective = obj;
    }
    const auto tFill = Clock::now();
    const Vector full = FillUnobserved(sys, res.x, &rep.filledTexels);
    const CubeMapF map = CubeMapFromSolution(full, sys.layout);
    rep.texelMin = rep.texelMax = full.empty() ? 0.0 : full[0];
    for (double v : full)
        rep.texelMin = std::min(rep.texelMin, v), rep.texelMax = std::max(rep.texelMax, v);
    rep.fillSeconds = Since(tFill);
    // Step 4: rmse_8bit — the 8-bit copy through the llvmpipe profile, on the system's mask.
    const int64_t frameRows = int64_t{4} * w * h;
    auto rmse8 = [&](const CubeMapF& m) {
        const raster::Texture tex8 = ToTexture8(m, frame.textures[0].sampler);
        raster::RenderOptions fo;
        fo.threads = opt.threads;
        double sum = 0.0, weight = 0.0;
        for (const auto& [ownFrame, first] : own) {
            raster::Frame f8 = ownFrame;
            f8.textures[0] = tex8;
            const raster::RenderResult rr = raster::Render(raster::PreparedFrame(f8), fo);
            for (int64_t r : sys.imageRowOf) {
                if (r < first || r >= first + frameRows) continue;  // this observation's rows
                weight += target.confidence[static_cast<size_t>(r)];
                const double d = rr.image8.rgba[static_cast<size_t>(r - first)] / 255.0 -
                                 target.b[static_cast<size_t>(r)];
                sum += target.confidence[static_cast<size_t>(r)] * d * d;
            }
        }
        return weight > 0.0 ? std::sqrt(sum / weight) : 0.0;
    };
    const auto tRender = Clock::now();
    rep.rmse8 = rmse8(map);
    rep.renderSeconds = Since(tRender);
    if (opt.direct && sys.Cols() <= opt.directMaxCols) {
        const SolveResult d = SolveDirect(sys, InitialGuess(sys), so.columnFloor);
        rep.directSeconds = d.seconds;
        rep.directRmse8 = rmse8(CubeMapFromSolution(FillUnobserved(sys, d.x), sys.layout));
    }
    // Step 5: files (in the background; the exported system now, it is large).
    const std::string stem = dir + "/" + rep.name;
    writer->Submit([map, sampler = frame.textures[0].sampler, log = res.log, stem, writeSeconds,
                    threads = opt.threads]() {
        const auto tWrite = Clock::now();
        WriteCubeMapExr(map, stem + ".exr", threads);
        WriteTexturePng(ToTexture8(map, sampler), stem + ".png");
        WriteLogCsv(log, stem + ".csv");
        *writeSeconds = Since(tWrite);
    });
    if (!opt.exportDir.empty()) {
        char prefix[64];
        std::snprintf(prefix, sizeof prefix, "/v%03d_g%d_%s", rep.view, rep.group,
                      rep.name.c_str());
        const std::string base = opt.exportDir + prefix;
        WriteMatrixMarket(base + "_K.mtx", sys.k.A());
        WriteVectorMarket(base + "_h.mtx", sys.h);
        WriteVectorMarket(base + "_x.mtx", res.x);
        std::ofstream(base + ".json") << json{{"objective", rep.objective},
                                              {"bounds", opt.hdr ? "hdr" : "unit"},
                                              {"iterations", rep.iterations},
                                              {"solve_seconds", rep.solveSeconds},
                                              {"rows", rep.rows},
                                              {"cols", rep.cols}}
                                             .dump(2)
                                      << "\n";
    }
    return rep;
}

}  // namespace

TraceManifest ReadTraceManifest(const std::string& traceDir) {
    const std::string path = traceDir + "/trace.json";
    std::ifstream f(path);
    if (!f) throw InputError(path, "cannot open (run pemref trace first)");
    TraceManifest tm;
    tm.dir = traceDir;
    try {
        const json j = json::parse(f);
        tm.scenePath = j.at("scene").get<std::string>();
        const std::string size = j.at("size").get<std::string>();
        if (std::sscanf(size.c_str(), "%dx%d", &tm.width, &tm.height) != 2 || tm.width < 1 ||
            tm.height < 1)
            throw std::runtime_error("bad size \"" + size + "\"");
        tm.spp = j.at("spp").get<int>();
        for (const json& v : j.at("views")) {
            raster::Camera c;
            c.eye = glm::vec3(Vec3(v.at("eye")));
            c.target = glm::vec3(Vec3(v.at("target")));
            tm.views.push_back(c);
        }
        int index = 0;
        for (const json& g : j.at("lens_groups")) {
            TracedGroup tg;
            tg.index = index++;
            tg.objects = g.at("objects").get<std::vector<std::string>>();
            tg.glass = g.at("glass").get<bool>();
            tg.emOrigin = glm::vec3(Vec3(g.at("em_origin")));
            std::vector<double> radii;
            std::vector<int64_t> records;
            for (const json& l : g.at("layers")) {
                tg.layers.push_back({runtime::ShellFromJson(l.at("shell").dump()),
                                     l.at("shell").at("type").get<std::string>(),
                                     l.at("radius").get<double>(), l.at("records").get<int64_t>()});
                radii.push_back(tg.layers.back().radius);
                records.push_back(tg.layers.back().records);
            }
            tg.singleShell = runtime::SingleLayerShell(glm::dvec3(tg.emOrigin), radii, records);
            if (g.contains("pem_local_distant")) {
                tg.pem = true;
                tg.localShell =
                    runtime::ShellFromJson(g.at("pem_local_distant").at("local").dump());
                tg.distantShell =
                    runtime::ShellFromJson(g.at("pem_local_distant").at("distant").dump());
            }
            tm.groups.push_back(std::move(tg));
        }
    } catch (const json::exception& e) {
        throw InputError(path, std::string("malformed trace.json: ") + e.what());
    } catch (const std::runtime_error& e) {
        throw InputError(path, e.what());
    }
    return tm;
}

InferRunReport RunInfer(const InferRunOptions& opt) {
    const auto tStart = Clock::now();
    if (opt.res < 1 || (opt.res & (opt.res - 1)) != 0 || opt.res > 4096)
        throw InputError("--res " + std::to_string(opt.res),
                         "expected a power of two in [1, 4096]");
    InferRunReport report;
    report.trace = ReadTraceManifest(opt.traceDir);
    const TraceManifest& tm = report.trace;

    // Step 1: the scene, its BVH and the tracer (as the trace was made).
    std::string scenePath = tm.scenePath;
    if (!std::filesystem::exists(scenePath))
        throw InputError(scenePath, "scene of the trace not found");
    const trace::Scene scene = trace::LoadScene(scenePath);
    if (!scene.camera) throw InputError(scenePath, "no camera node");
    if (scene.lensGroups.size() != tm.groups.size())
        throw InputError(opt.traceDir + "/trace.json", "lens groups differ from the scene's");
    const trace::EmbreeDevice device({opt.threads, "auto"});
    const trace::EmbreeScene embree(device, scene);
    const trace::Tracer tracer(scene, embree);

    std::vector<int> views = opt.views;
    if (views.empty())
        for (int v = 0; v < static_cast<int>(tm.views.size()); ++v) views.push_back(v);
    int mapsTotal = 0;
    for (const TracedGroup& g : tm.groups)
        mapsTotal += static_cast<int>(g.layers.size()) + (opt.single ? 1 : 0) + (g.pem ? 2 : 0);
    mapsTotal *= static_cast<int>(views.size());
    int mapsDone = 0;
    // Per map: the background write's seconds (filled in when the write finishes).
    std::vector<double> writeSeconds(static_cast<size_t>(mapsTotal) + 1, 0.0);
    Writer writer;

    for (int v : views) {
        if (v < 0 || v >= static_cast<int>(tm.views.size()))
            throw InputError("--view " + std::to_string(v), "no such viewpoint in the trace");
        const auto tView = Clock::now();
        SampleReport sample;
        sample.view = v;
        raster::Camera camera = trace::CameraForSize(*scene.camera, tm.width, tm.height);
        camera.eye = tm.views[static_cast<size_t>(v)].eye;
        camera.target = tm.views[static_cast<size_t>(v)].target;
        for (const TracedGroup& g : tm.groups) {
            const std::string gdir =
                opt.traceDir + "/" + ViewDir(v) + "/group_" + std::to_string(g.index);
            const std::string odir =
                opt.outDir + "/" + ViewDir(v) + "/group_" + std::to_string(g.index);
            std::filesystem::create_directories(odir);
            // Step 2: the vertex paths at this sample and at its neighbours in the solve.
            struct ViewGeometry {
                int view = 0;
                raster::Camera camera;
                runtime::LensPaths lp;
                std::vector<uint32_t> order;
                glm::mat4 vp{1.0f};
                double weight = 1.0;
            };
            std::vector<ViewGeometry> geo;
            for (int u = v - opt.neighbours; u <= v + opt.neighbours; ++u) {
                if (u < 0 || u >= static_cast<int>(tm.views.size())) continue;
                const auto tPaths = Clock::now();
                ViewGeometry vg;
                vg.view = u;
                vg.camera = camera;
                vg.camera.eye = tm.views[static_cast<size_t>(u)].eye;
                vg.camera.target = tm.views[static_cast<size_t>(u)].target;
                runtime::LensPathsOptions lo;
                lo.tess.maxEdgeSubpixels = opt.tessT;
                lo.supersampling = tm.spp;
                lo.threads = opt.threads;
                vg.lp = runtime::TraceLensPaths(tracer, embree, vg.camera, g.index, lo);
                const runtime::PassMesh m = runtime::MeshOf(vg.lp.tess);
                vg.order = runtime::DrawOrder(m, vg.camera);
                vg.vp = runtime::PassViewProjection(m, vg.camera);
                vg.weight = u == v ? 1.0 : opt.neighbourWeight;
                sample.pathSeconds += Since(tPaths);
                sample.vertexRays += vg.lp.counts.Total();
                if (u == v) sample.triangles += vg.lp.tess.triangles.size();
                geo.push_back(std::move(vg));
            }
            // The sample's own geometry first.
            std::stable_partition(geo.begin(), geo.end(),
                                  [v](const ViewGeometry& x) { return x.view == v; });
            // Step 3: one map per layer over both terms, [A_R; A_T] x = [b_R; b_T] (hybrid
            // §4.3), with the rows of every view in `geo` (the sample's own first).
            const int terms = g.glass ? 2 : 1;
            struct TermImages {
                trace::FloatImage cov, conf;
                std::vector<runtime::ExitRay> exits;
            };
            std::vector<TermImages> ti[2];  // [term][view in geo]
            for (int term = 0; term < terms; ++term)
                for (const ViewGeometry& vg : geo) {
                    const std::string d =
                        opt.traceDir + "/" + ViewDir(vg.view) + "/group_" + std::to_string(g.index);
                    const char* tn = term == 0 ? "R" : "T";
                    ti[term].push_back({trace::ReadExr(d + "/b_" + tn + ".exr"),
                                        trace::ReadExr(d + "/confidence_" + tn + ".exr"),
                                        runtime::TermExits(vg.lp.tess.paths, term)});
                }
            // One observation: (term, view k) against `image` on `shell`.
            auto observe = [&](int term, size_t k, const trace::FloatImage* image,
                               const trace::Shell& shell) {
                const TermImages& t = ti[term][k];
                MapInput in{image, &t.cov, &t.conf, {}, geo[k].weight, geo[k].view == v, {}};
                in.pass = runtime::LayerPass(runtime::MeshOf(geo[k].lp.tess), geo[k].order,
                                             runtime::ShellCoords(t.exits, shell, g.emOrigin),
                                             t.exits, geo[k].vp, {});
                return in;
            };
            auto solve = [&](const std::string& name, int layer,
                             const std::vector<std::vector<trace::FloatImage>>& images,
                             const trace::Shell& shell) {
                MapInput in = observe(0, 0, &images[0][0], shell);
                for (int term = 0; term < terms; ++term)
                    for (size_t k = 0; k < geo.size(); ++k)
                        if (term > 0 || k > 0)
                            in.neighbours.push_back(observe(term, k, &images[term][k], shell));
                MapReport rep;
                rep.view = v, rep.group = g.index, rep.layer = layer;
                rep.term = terms == 2 ? "R+T" : "R";
                rep.name = name;
                if (opt.progress) opt.progress(name, static_cast<double>(mapsDone) / mapsTotal);
                report.maps.push_back(
                    SolveMap(in, opt, tm, odir, rep, &writer, &writeSeconds[report.maps.size()]));
                ++mapsDone;
            };
            for (size_t l = 0; l < g.layers.size(); ++l) {
                if (g.layers[l].records == 0) {  // an empty cluster: no hits to match
                    report.leftOut.push_back(
                        {v, g.index, "layer " + std::to_string(l), "its cluster is empty"});
                    ++mapsDone;
                    continue;
                }
                std::vector<std::vector<trace::FloatImage>> images(static_cast<size_t>(terms));
                for (int term = 0; term < terms; ++term)
                    for (const ViewGeometry& vg : geo)
                        images[static_cast<size_t>(term)].push_back(
                            trace::ReadExr(opt.traceDir + "/" + ViewDir(vg.view) + "/group_" +
                                           std::to_string(g.index) + "/layer_" + std::to_string(l) +
                                           "_" + (term == 0 ? "R" : "T") + ".exr"));
                solve("layer_" + std::to_string(l), static_cast<int>(l), images, g.layers[l].shell);
            }
            // Step 4: the single-layer map: all the exit radiance (b_τ) on one sphere.
            if (opt.single) {
                std::vector<std::vector<trace::FloatImage>> images(static_cast<size_t>(terms));
                for (int term = 0; term < terms; ++term)
                    for (size_t k = 0; k < geo.size(); ++k)
                        images[static_cast<size_t>(term)].push_back(ti[term][k].cov);
                solve("single", 0, images, g.singleShell);
            }
            // Step 5: mirror-only groups: the PEM paper's local/distant split; a reflector whose
            // polygons all lie on its convex hull cannot see itself: no local layer.
            if (g.pem) {
                const runtime::LensMesh base = runtime::GroupMesh(scene, g.index);
                const runtime::PassMesh bm = runtime::MeshOf(base);
                const trace::Material& mat = scene.materials[static_cast<size_t>(
                    scene
                        .objects[static_cast<size_t>(
                            scene.lensGroups[static_cast<size_t>(g.index)].objects[0])]
                        .material)];
                const std::vector<runtime::ExitRay> exits =
                    runtime::ReflectionExits(bm, camera.eye, mat.baseColor);
                const std::vector<uint32_t> border = runtime::DrawOrder(bm, camera);
                const glm::mat4 bvp = runtime::PassViewProjection(bm, camera);
                const trace::FloatImage distant = trace::ReadExr(gdir + "/distant.exr");
                const trace::FloatImage local = trace::ReadExr(gdir + "/local.exr");
                const trace::FloatImage conf = trace::ReadExr(gdir + "/confidence_R.exr");
                const bool convex = runtime::AllOnHull(runtime::HullTriangles(base));
                if (convex)
                    report.leftOut.push_back({v, g.index, "PEM local layer",
                                              "every polygon lies on the reflector's convex hull"});
                for (int which = convex ? 1 : 0; which < 2; ++which) {
                    MapInput in{which == 0 ? &local : &distant, &distant, &conf, {}, 1.0, true, {}};
                    in.pass = runtime::LayerPass(
                        bm, border,
                        runtime::ShellCoords(exits, which == 0 ? g.localShell : g.distantShell,
                                             g.emOrigin),
                        exits, bvp, {});
                    MapReport rep;
                    rep.view = v, rep.group = g.index, rep.layer = which, rep.term = "pem";
                    rep.name = which == 0 ? "pem_local" : "pem_distant";
                    if (opt.progress)
                        opt.progress(rep.name, static_cast<double>(mapsDone) / mapsTotal);
                    report.maps.push_back(SolveMap(in, opt, tm, odir, rep, &writer,
                                                   &writeSeconds[report.maps.size()]));
                    ++mapsDone;
                }
                if (convex) ++mapsDone;
            }
        }
        writer.Wait();  // the sample is done when its files are
        sample.seconds = Since(tView);
        report.samples.push_back(sample);
    }
    writer.Wait();
    for (size_t k = 0; k < report.maps.size(); ++k) report.maps[k].writeSeconds = writeSeconds[k];
    if (opt.progress) opt.progress("done", 1.0);
    report.seconds = Since(tStart);
    return report;
}

}  // namespace pem::infer
