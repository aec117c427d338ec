// SPDX-License-Identifier: MIT
// infer_job.cpp — `pemref infer`: trace directory → PEM files (infer_job.h).
//
// Index: files of one map · the stacked system of one map · solving one map · the geometry of
// the samples in a solve · the maps of one lens group · RunInferJob.
#include "pipeline/infer_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "base/atomic_file.h"
#include "base/input_error.h"
#include "base/matrix_market.h"
#include "base/parallel.h"
#include "infer/env_map.h"
#include "infer/pem_file.h"
#include "pipeline/display_target.h"
#include "pipeline/layout.h"
#include "pipeline/map_files.h"
#include "pipeline/pem_manifest.h"
#include "raster/profile.h"
#include "raster/render.h"
#include "raster/texel_index.h"
#include "runtime/convex_hull.h"
#include "runtime/lens_paths.h"
#include "runtime/mirror_geometry.h"
#include "runtime/static_em.h"
#include "runtime/texgen.h"
#include "trace/embree_scene.h"
#include "trace/image.h"
#include "trace/scene.h"
#include "trace/tracer.h"

namespace pem::pipeline {

double DefaultSmooth(raster::TexelFormat format) {
    const double solver = infer::RegularizerWeights{}.smooth;
    return format == raster::TexelFormat::Rgba32F ? 10.0 * solver : solver;
}

float DefaultLodBias(raster::TexelFormat format) {
    return format == raster::TexelFormat::Rgba32F ? -2.5f : -4.0f;
}

infer::SolveOptions DefaultSolveOptions() {
    infer::SolveOptions s;
    s.maxIterations = 150;
    s.logEvery = 25;
    s.atol = 1e-4;
    return s;
}

namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;
using infer::Vector;

double Since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Files of one map --------------------------------------------------------------------------

void WriteMapFiles(const infer::EnvMapF& map, const raster::SamplerState& sampler,
                   const infer::SolveResult& res, const std::string& stem, int threads) {
    WriteMapImages(map, infer::ToTextures8(map, sampler), stem, threads);
    infer::WriteLogCsv(res.log, stem + ".csv");
}

// K, h and x of one solve in Matrix Market format, with the figures scipy's check needs.
void ExportSystem(const std::string& exportDir, const MapReport& rep,
                  const infer::LinearSystem& sys, const Vector& x, const char* bounds) {
    char prefix[64];
    std::snprintf(prefix, sizeof prefix, "/v%03d_g%d_%s", rep.view, rep.group, rep.name.c_str());
    const std::string stem = exportDir + prefix;
    base::WriteMatrixMarket(stem + "_K.mtx", base::MatrixView::Of(sys.k.A()), "");
    base::WriteVectorMarket(stem + "_h.mtx", sys.h, "");
    base::WriteVectorMarket(stem + "_x.mtx", x, "");
    base::WriteTextAtomic(stem + ".json", json{{"objective", rep.objective},
                                               {"bounds", bounds},
                                               {"iterations", rep.iterations},
                                               {"solve_seconds", rep.solveSeconds},
                                               {"rows", rep.rows},
                                               {"cols", rep.cols}}
                                                  .dump(2) +
                                              "\n");
}

// The stacked system of one map ------------------------------------------------------------

// One observation of a map: a texgen pass and the traced image it must reproduce.
// The images are the trace's K×K samples (K W × K H, trace/image.h SampleCell): the maps are
// fitted sample by sample, as the renderers draw them (K×K subpixels, runtime/supersampling.h).
// A sample row has one exit ray, so the hybrid paper's confidence (trace/confidence.h: the
// spread of a pixel's exit rays) is 1 for every row: the trace's confidence images, which
// weigh pixel-sized rows, are not read.
struct MapInput {
    const trace::FloatImage* layer = nullptr;     // RGBA premultiplied layer image
    const trace::FloatImage* coverage = nullptr;  // alpha = lens coverage
    const trace::FloatImage* frame = nullptr;     // the traced two-term frame (pixels)
    const trace::FloatImage* fresnel = nullptr;   // F·G of the rows' term (pixels, alpha = share)
    std::vector<raster::Pass> passes;             // the layer's, one per texture of the map
    std::optional<raster::Pass> depthPass;  // drawn before `passes`: depth only (DepthOnlyPass)
    double weight = 1.0;                    // the rows' weight (times the coverage)
    bool own = true;                        // the sample's own view (counts in rmse_8bit)
};

// Whether the maps are float (MapHardware::format): unbounded texels, RGBA32F frames.
bool FloatMaps(const InferJobOptions& opt) {
    return opt.hardware.format == raster::TexelFormat::Rgba32F;
}

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

raster::Frame UnknownFrame(int width, int height, int res, const raster::SamplerState& sampler,
                           runtime::Parameterization parameterization, const MapInput& in) {
    raster::Frame frame;
    frame.width = width;
    frame.height = height;
    frame.depthClamp = true;
    frame.depth = runtime::kLensDepth;
    if (parameterization == runtime::Parameterization::Cube) {  // any power of two, 1 included
        raster::Texture tex;
        tex.kind = raster::TextureKind::Cube;
        tex.width = tex.height = res;
        tex.sampler = sampler;
        for (int l = 0; (res >> l) >= 1; ++l)
            tex.levels.emplace_back(static_cast<size_t>(6 * (res >> l) * (res >> l) * 4), 0);
        frame.textures.push_back(std::move(tex));
    } else {  // one texture per chart
        const runtime::MapLayout layout = runtime::LayoutOf(parameterization, res);
        frame.textures.assign(static_cast<size_t>(layout.textures),
                              runtime::EmptyTexture(layout, sampler));
    }
    if (in.depthPass) frame.passes.push_back(*in.depthPass);
    frame.passes.insert(frame.passes.end(), in.passes.begin(), in.passes.end());
    return frame;
}

// The subpixels of the K× frame (row-major, top-down) that the group covers in the trace.
std::vector<uint32_t> CoveredCells(const MapInput& in) {
    std::vector<uint32_t> cells;
    const trace::FloatImage& cov = *in.coverage;
    for (int y = 0; y < cov.height; ++y)
        for (int x = 0; x < cov.width; ++x)
            if (cov.At(x, y)[3] > 1e-6f) cells.push_back(static_cast<uint32_t>(y * cov.width + x));
    return cells;
}

// Target rows of the listed subpixels, 4 each: the layer un-premultiplied by coverage, RGB in
// the maps' units (radiance / scale); `hdr`: as traced; float maps (`floats`): nonnegative, what
// the display shows (display_target.h); 8-bit maps: clamped into [0, 1], what they can reach.
// Weight · coverage.
void AppendTarget(const MapInput& in, const std::vector<uint32_t>& cells, int k, double scale,
                  bool hdr, bool floats, infer::Target* t) {
    const int width = in.coverage->width;
    std::vector<double> b(4 * cells.size());
    for (size_t i = 0; i < cells.size(); ++i) {
        const int x = static_cast<int>(cells[i]) % width, y = static_cast<int>(cells[i]) / width;
        const double cov = static_cast<double>(in.coverage->At(x, y)[3]);
        for (size_t c = 0; c < 4; ++c) {
            const double v =
                static_cast<double>(in.layer->At(x, y)[c]) / cov / (c < 3 ? scale : 1.0);
            b[4 * i + c] = hdr ? v : std::max(v, 0.0);
            if (!hdr && (c == 3 || !floats)) b[4 * i + c] = std::min(b[4 * i + c], 1.0);
        }
        for (size_t c = 0; c < 4; ++c) t->confidence.push_back(in.weight * cov);
    }
    if (floats && !hdr) ClipToDisplay({in.coverage, in.frame, in.fresnel}, cells, k, scale, &b);
    t->b.insert(t->b.end(), b.begin(), b.end());
}

// One of the sample's own observations: its K× frame, its first stacked row, its subpixels.
struct OwnRows {
    raster::Frame frame;
    int64_t first = 0;
    std::vector<uint32_t> cells;
};

// Every observation's rows of the covered subpixels stacked, the first one's frame describing
// the unknown texture.
struct StackedRows {
    raster::RenderingMatrix a;
    infer::Target target;
    raster::Frame frame;  // the first observation's, without its passes
    std::vector<OwnRows> own;
};

StackedRows StackRows(const std::vector<MapInput>& inputs, int w, int h, int k, int res,
                      const InferJobOptions& opt) {
    StackedRows s;
    // The profile's texel selection with exact weights (its LOD rule, no rounding).
    raster::RenderOptions ro = raster::ProfileNamed(opt.hardware.profile).matrix;
    ro.threads = opt.threads;
    for (size_t i = 0; i < inputs.size(); ++i) {
        raster::Frame f = UnknownFrame(k * w, k * h, res, opt.hardware.Sampler(),
                                       opt.parameterization, inputs[i]);
        std::vector<uint32_t> cells = CoveredCells(inputs[i]);
        raster::RenderingMatrix a =
            raster::BuildRenderingMatrix(raster::PreparedFrame(f), ro, &cells);
        AppendTarget(inputs[i], cells, k, static_cast<double>(opt.hardware.radianceScale), opt.hdr,
                     FloatMaps(opt), &s.target);
        if (i == 0) {
            s.a = std::move(a);
            std::vector<raster::Pass> passes = std::move(f.passes);
            s.frame = f;  // the unknown texture's shape (not the observation's passes)
            f.passes = std::move(passes);
        } else {
            AppendRows(&s.a, a);
        }
        if (inputs[i].own)
            s.own.push_back({std::move(f), i == 0 ? 0 : s.a.rows - 4 * int64_t(cells.size()),
                             std::move(cells)});
    }
    return s;
}

// The face size of a map (PEM §4 "EM Resolution") -----------------------------------------

// The share of the sample's own covered subpixels whose finest tap lies on each MIP level of a
// face-size-maxRes cube, its texgen passes drawn with no LOD bias: the "test rendering" that
// shows "the most detailed EM MIPMAP level actually accessed by the graphics system".
std::vector<double> LevelsAccessed(const std::vector<MapInput>& inputs, int w, int h, int k,
                                   int maxRes, const InferJobOptions& opt) {
    raster::RenderOptions ro = raster::ProfileNamed(opt.hardware.profile).matrix;
    ro.threads = opt.threads;
    raster::SamplerState sampler = opt.hardware.Sampler();
    sampler.lodBias = 0.0f;
    std::vector<double> share;
    double total = 0.0;
    for (const MapInput& in : inputs) {
        if (!in.own) continue;
        const raster::Frame f =
            UnknownFrame(k * w, k * h, maxRes, sampler, opt.parameterization, in);
        const raster::TexelIndexer index(f.textures);
        const std::vector<uint32_t> cells = CoveredCells(in);
        const std::vector<uint32_t> finestOf =  // levels are numbered finest first
            raster::FinestTexels(raster::PreparedFrame(f), ro, &cells);
        share.resize(f.textures[0].levels.size(), 0.0);
        for (const uint32_t finest : finestOf) {  // each subpixel's
            if (finest == raster::kNoTexel) continue;
            int chart = 0;  // the texture of the map it reads (a two-image layout has two)
            while (chart + 1 < static_cast<int>(f.textures.size()) &&
                   index.LevelBase(chart + 1, 0) <= finest)
                ++chart;
            size_t level = 0;
            while (level + 1 < share.size() &&
                   index.LevelBase(chart, static_cast<int>(level) + 1) <= finest)
                ++level;
            share[level] += 1.0;
            total += 1.0;
        }
    }
    for (double& s : share) s = total > 0.0 ? s / total : 0.0;
    return share;
}

// The face size whose level 0 is the finest level that kResolutionShare of the subpixels read
// at face size maxRes, within [minRes, maxRes]: a few magnified subpixels (silhouettes,
// caustics) do not ask for a larger map; a map that most subpixels minify is not enlarged.
inline constexpr double kResolutionShare = 0.1;

int ResolutionAccessed(const std::vector<double>& share, int minRes, int maxRes) {
    double reached = 0.0;
    for (size_t level = 0; level < share.size(); ++level) {
        reached += share[level];
        if (reached >= kResolutionShare) return std::max(minRes, maxRes >> level);
    }
    return minRes;
}

// Solving one map ----------------------------------------------------------------------------

// The hardware's copy of a map (MapHardware::format) through the target profile on the
// sample's own rows of the mask, subpixel by subpixel: the error the hardware shows (8-bit
// frames; float maps: the RGBA32F frame).
double Rmse8(const infer::EnvMapF& m, const StackedRows& s, const infer::LinearSystem& sys,
             const runtime::MapHardware& hardware, int threads) {
    const std::vector<raster::Texture> tex =
        infer::ToTextures(m, s.frame.textures[0].sampler, hardware.format);
    const bool floats = hardware.format == raster::TexelFormat::Rgba32F;
    raster::RenderOptions fo = raster::ProfileNamed(hardware.profile).options;
    fo.threads = threads;
    fo.picture8 = !floats;  // float frames are read as floats
    double sum = 0.0, weight = 0.0;
    for (const OwnRows& own : s.own) {
        raster::Frame f8 = own.frame;
        std::copy(tex.begin(), tex.end(), f8.textures.begin());
        if (floats) f8.colorFormat = raster::ColorFormat::Rgba32F;
        const raster::RenderResult rr = raster::Render(raster::PreparedFrame(f8), fo);
        const int64_t last = own.first + 4 * static_cast<int64_t>(own.cells.size());
        for (int64_t r : sys.imageRowOf) {
            if (r < own.first || r >= last) continue;  // this observation's rows
            const size_t cell = own.cells[static_cast<size_t>((r - own.first) / 4)];
            const size_t at = 4 * cell + static_cast<size_t>((r - own.first) % 4);
            const double v =
                floats ? static_cast<double>(rr.imageF.rgba[at]) : rr.image8.rgba[at] / 255.0;
            const double d = v - s.target.b[static_cast<size_t>(r)];
            weight += s.target.confidence[static_cast<size_t>(r)];
            sum += s.target.confidence[static_cast<size_t>(r)] * d * d;
        }
    }
    return weight > 0.0 ? std::sqrt(sum / weight) : 0.0;
}

// |K x - h|² of a solution.
double Objective(const infer::LinearSystem& sys, const Vector& x, int threads) {
    Vector kx;
    sys.k.Apply(x, &kx, threads);
    double obj = 0.0;
    for (size_t r = 0; r < kx.size(); ++r) obj += (kx[r] - sys.h[r]) * (kx[r] - sys.h[r]);
    return obj;
}

// The texels no sample observes (cube maps): the environment seen from the EM origin (the
// direct image's MIP chain, hybrid §4.3) instead of the smooth fill, so that what a viewpoint off
// the samples discloses is there. A level of face size m reads the direct level of that size
// (m ≤ its size n) or the level-0 texel holding its texel's centre (m > n); RGB in map units,
// within [0, 1] for 8-bit maps, for float maps within what the solve itself reached.
void FillFromDirect(const infer::LinearSystem& sys, const std::vector<std::vector<float>>& direct,
                    double scale, bool floats, Vector* full) {
    const infer::TexelLayout& lay = sys.layout;
    if (sys.active.empty() || lay.kind != raster::TextureKind::Cube) return;
    std::vector<char> observed(full->size() / 4, 0);
    double hi = floats ? 0.0 : 1.0;
    for (uint32_t t : sys.active) {
        observed[t] = 1;
        if (floats)
            for (size_t c = 0; c < 3; ++c) hi = std::max(hi, (*full)[4 * size_t(t) + c]);
    }
    const int n = static_cast<int>(std::lround(std::sqrt(double(direct[0].size()) / 24.0)));
    for (int level = 0; level < lay.levels; ++level) {
        const int m = lay.LevelSize(level);
        int k = 0;  // the direct level of size max(m, ...) read
        while ((n >> k) > m && k + 1 < static_cast<int>(direct.size())) ++k;
        const int dn = std::max(1, n >> k);
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < m; ++j)
                for (int i = 0; i < m; ++i) {
                    const uint32_t t = lay.LevelBase(level) + uint32_t((f * m + j) * m + i);
                    if (observed[t]) continue;
                    const int di = int(int64_t(i) * dn / m), dj = int(int64_t(j) * dn / m);
                    const float* d =
                        &direct[size_t(k)][((size_t(f) * dn + size_t(dj)) * dn + size_t(di)) * 4];
                    for (size_t c = 0; c < 4; ++c)
                        (*full)[4 * size_t(t) + c] =
                            std::clamp(double(d[c]) / (c < 3 ? scale : 1.0), 0.0, c < 3 ? hi : 1.0);
                }
    }
}

MapReport SolveMap(const std::vector<MapInput>& inputs, const InferJobOptions& opt,
                   const TraceManifest& tm, const std::string& dir, MapReport rep,
                   const std::vector<std::vector<float>>* direct) {
    // Step 1: the rendering matrices of the texgen passes and the stacked system.
    const auto t0 = Clock::now();
    rep.res = opt.res;
    if (opt.maxRes > opt.res) {
        rep.levelsAccessed = LevelsAccessed(inputs, tm.width, tm.height, tm.spp, opt.maxRes, opt);
        rep.res = ResolutionAccessed(rep.levelsAccessed, opt.res, opt.maxRes);
    }
    StackedRows s = StackRows(inputs, tm.width, tm.height, tm.spp, rep.res, opt);
    rep.matrixSeconds = Since(t0);
    infer::SystemOptions systemOptions = opt.system;  // the map's textures: its charts
    systemOptions.charts = runtime::MapTextures(opt.parameterization);
    const infer::LinearSystem sys =
        infer::BuildSystem(std::move(s.a), s.frame, 0, s.target, opt.weights, systemOptions);
    rep.buildSeconds = Since(t0);
    rep.rows = sys.k.Rows(), rep.cols = sys.Cols(), rep.nnz = sys.k.NonZeros();
    rep.observedTexels = static_cast<int64_t>(sys.active.size());
    // Step 2: the solve.
    infer::SolveOptions so = opt.solve;
    so.threads = opt.threads;
    so.bounds = FloatMaps(opt) ? infer::Bounds::None()
                : opt.hdr      ? infer::Bounds::Hdr()
                               : infer::Bounds::Unit();
    const infer::SolveResult res = infer::SolveIterative(
        sys, infer::SplatGuess(sys, so.bounds.lo, so.bounds.hi, opt.threads), so);
    rep.solveSeconds = res.seconds, rep.iterations = res.iterations;
    rep.stop = infer::ToString(res.stop);
    rep.rmse = infer::MaskedImageRmse(sys, res.x, opt.threads);
    rep.objective = Objective(sys, res.x, opt.threads);
    // Step 3: the texels no pixel samples, and the range.
    const auto tFill = Clock::now();
    Vector full = infer::FillUnobserved(sys, res.x, &rep.filledTexels);
    if (direct)
        FillFromDirect(sys, *direct, static_cast<double>(opt.hardware.radianceScale),
                       FloatMaps(opt), &full);
    const infer::EnvMapF map = infer::EnvMapFromSolution(full, sys.layout);
    rep.texelMin = rep.texelMax = full.empty() ? 0.0 : full[0];
    for (double v : full)
        rep.texelMin = std::min(rep.texelMin, v), rep.texelMax = std::max(rep.texelMax, v);
    rep.fillSeconds = Since(tFill);
    // Step 4: rmse_8bit (and the direct optimum's, when asked and small enough).
    const auto tRender = Clock::now();
    rep.rmse8 = Rmse8(map, s, sys, opt.hardware, opt.threads);
    rep.renderSeconds = Since(tRender);
    if (opt.direct && sys.Cols() <= opt.directMaxCols) {
        const infer::SolveResult d =
            infer::SolveDirect(sys, infer::InitialGuess(sys), so.columnFloor);
        rep.directSeconds = d.seconds;
        rep.directRmse8 =
            Rmse8(infer::EnvMapFromSolution(infer::FillUnobserved(sys, d.x), sys.layout), s, sys,
                  opt.hardware, opt.threads);
    }
    // Step 5: files.
    const auto tWrite = Clock::now();
    WriteMapFiles(map, s.frame.textures[0].sampler, res, dir + "/" + rep.name, opt.threads);
    if (!opt.exportDir.empty())
        ExportSystem(opt.exportDir, rep, sys, res.x,
                     FloatMaps(opt) ? "none"
                     : opt.hdr      ? "hdr"
                                    : "unit");
    rep.writeSeconds = Since(tWrite);
    return rep;
}

// The geometry of the samples in a solve ---------------------------------------------------

// The traced images of one sample's view of a lens group, read once for every tessellation of
// that view.
struct ViewImages {
    trace::FloatImage cov[2];  // per term: b_τ's samples (alpha = coverage)
    trace::FloatImage frame;   // the traced two-term frame (what the display shows)
    trace::FloatImage fg[2];   // per term: F·G (pixels)
};

// One sample's view of a lens group: vertex paths, draw order, projection and the traced
// images of each term.
struct ViewGeometry {
    int view = 0;
    raster::Camera camera;
    runtime::LensPaths lp;  // its mesh and counts; the paths are released once exits holds them
    std::vector<uint32_t> order;
    glm::mat4 vp{1.0f};
    double weight = 1.0;
    bool own = false;  // the sample's view at the maps' t (MapInput::own)
    std::shared_ptr<const ViewImages> images;
    std::vector<runtime::ExitRay> exits[2];
};

// The face size of the direct images that fill the texels no sample observes.
inline constexpr int kDirectImageSize = 128;

struct Context {
    const InferJobOptions& opt;
    const TraceManifest& tm;
    const trace::Scene& scene;
    const trace::EmbreeScene& embree;
    const trace::Tracer& tracer;
    std::vector<raster::Camera> cameras;  // per sample, as traced
    InferJobResult* result;
    int mapsDone = 0, mapsTotal = 0;
    std::map<int, runtime::DirectImages> direct;  // per group, traced when first needed

    // The group's direct images (cube maps only; nullptr otherwise).
    const runtime::DirectImages* Direct(const runtime::LensGroupEm& g) {
        if (opt.parameterization != runtime::Parameterization::Cube) return nullptr;
        auto it = direct.find(g.index);
        if (it == direct.end())
            it = direct
                     .emplace(g.index,
                              runtime::TraceDirectImages(tracer, g, kDirectImageSize, opt.threads))
                     .first;
        return &it->second;
    }

    void Progress(const std::string& name) const {
        if (opt.progress) opt.progress(name, static_cast<double>(mapsDone) / mapsTotal);
    }
};

// The images of view u, the files decoded in parallel.
std::shared_ptr<const ViewImages> ReadViewImages(const Context& c, int u,
                                                 const runtime::LensGroupEm& g) {
    auto images = std::make_shared<ViewImages>();
    base::ParallelFor(1 + 2 * g.Terms(), c.opt.threads, [&](int k) {
        if (k == 0) {
            images->frame = ReadFrameImage(c.tm, u, "greedy");
            return;
        }
        const int term = (k - 1) / 2;
        const std::string tn = runtime::TermName(term);
        if ((k - 1) % 2 == 0)
            images->cov[term] = ReadGroupSamples(c.tm, u, g.index, "b_" + tn);
        else
            images->fg[term] = ReadGroupImage(c.tm, u, g.index, "FG_" + tn);
    });
    return images;
}

// View u of group g tessellated at tessT; `images` when they are already read (the same view at
// another t), else read here.
ViewGeometry SampleGeometry(const Context& c, int u, const runtime::LensGroupEm& g, double weight,
                            SampleReport* sample, double tessT,
                            std::shared_ptr<const ViewImages> images = nullptr) {
    const int group = g.index, terms = g.Terms();
    const auto t0 = Clock::now();
    ViewGeometry vg;
    vg.view = u;
    vg.camera = c.cameras[static_cast<size_t>(u)];
    runtime::LensPathsOptions lo;
    lo.tess.maxEdgeSubpixels = tessT;
    lo.tess.maxTopologyEdgeSubpixels = c.opt.topologyT;
    lo.supersampling = c.tm.spp;
    lo.threads = c.opt.threads;
    vg.lp = runtime::TraceLensPaths(c.tracer, c.embree, vg.camera, group, lo);
    const runtime::PassMesh m = runtime::MeshOf(vg.lp.tess);
    vg.order = runtime::DrawOrder(m, vg.camera);
    vg.vp = runtime::PassViewProjection(m, vg.camera);
    vg.weight = weight;
    sample->pathSeconds += Since(t0);
    sample->vertexRays += vg.lp.counts.Total();
    vg.images = images ? std::move(images) : ReadViewImages(c, u, g);
    for (int term = 0; term < terms; ++term)
        vg.exits[term] = runtime::TermExits(vg.lp.tess.paths, term);
    // The paths themselves (each vertex's events, several hundred bytes a vertex, GBs at t = 1)
    // are not read again: their memory goes to the rendering matrices.
    std::vector<std::optional<trace::VertexPaths>>().swap(vg.lp.tess.paths);
    return vg;
}

// The sample's own view first (at t, counted in rmse_8bit), the same view at each further t, then
// its neighbours in the simultaneous solve.
std::vector<ViewGeometry> SolveGeometry(const Context& c, int v, const runtime::LensGroupEm& g,
                                        SampleReport* sample) {
    std::vector<ViewGeometry> geo;
    geo.push_back(SampleGeometry(c, v, g, 1.0, sample, c.opt.tessT));
    geo[0].own = true;
    sample->triangles += geo[0].lp.tess.triangles.size();
    for (double t : c.opt.alsoTessT)  // the same view drawn at another t: not its own rows
        if (t != c.opt.tessT)
            geo.push_back(SampleGeometry(c, v, g, kAlsoTessWeight, sample, t, geo[0].images));
    for (int u = v - c.opt.neighbours; u <= v + c.opt.neighbours; ++u)
        if (u != v && u >= 0 && u < static_cast<int>(c.cameras.size()))
            geo.push_back(SampleGeometry(c, u, g, c.opt.neighbourWeight, sample, c.opt.tessT));
    return geo;
}

// The maps of one lens group ---------------------------------------------------------------

// A map's texgen pass as the renderers' first pass draws it from `camera`: the visible surface
// only, with the maps' layout (the sphere map's coordinates in that camera's eye space).
runtime::PassOptions DepthTested(const InferJobOptions& opt, const raster::Camera& camera) {
    runtime::PassOptions po;
    po.depthTest = runtime::LayerDepthTest(true);
    po.parameterization = opt.parameterization;
    po.eyeFromWorld = runtime::EyeFromWorld(camera);
    return po;
}

// Observations of a map on `shell`: per term and view, images[term][view] as the target.
std::vector<MapInput> Observations(const InferJobOptions& opt, const std::vector<ViewGeometry>& geo,
                                   int terms,
                                   const std::vector<std::vector<const trace::FloatImage*>>& images,
                                   const trace::Shell& shell, const glm::vec3& emOrigin) {
    std::vector<MapInput> inputs;
    for (int term = 0; term < terms; ++term)
        for (size_t k = 0; k < geo.size(); ++k) {
            const ViewGeometry& vg = geo[k];
            MapInput in{images[static_cast<size_t>(term)][k],
                        &vg.images->cov[term],
                        &vg.images->frame,
                        &vg.images->fg[term],
                        {},
                        {},
                        vg.weight,
                        vg.own};
            in.passes = runtime::LayerPass(runtime::MeshOf(vg.lp.tess), vg.order,
                                           runtime::ShellCoords(vg.exits[term], shell, emOrigin),
                                           vg.exits[term], vg.vp, DepthTested(opt, vg.camera));
            inputs.push_back(std::move(in));
        }
    return inputs;
}

void Solve(Context& c, const std::vector<MapInput>& inputs, const std::string& dir,
           const MapReport& rep, const std::vector<std::vector<float>>* direct = nullptr) {
    c.Progress(rep.name);
    c.result->maps.push_back(SolveMap(inputs, c.opt, c.tm, dir, rep, direct));
    ++c.mapsDone;
}

MapReport Report(int v, const runtime::LensGroupEm& g, int layer, const std::string& term,
                 const std::string& name) {
    MapReport rep;
    rep.view = v, rep.group = g.index, rep.layer = layer, rep.term = term, rep.name = name;
    return rep;
}

// One map per layer over both terms, [A_R; A_T] x = [b_R; b_T] (hybrid §4.3), with the rows of
// every view in `geo`; then the single-layer map (the whole exit radiance b_τ on one sphere).
void SolveLayerMaps(Context& c, int v, const runtime::LensGroupEm& g,
                    const std::vector<ViewGeometry>& geo, const std::string& odir) {
    const std::string term = g.glass ? "R+T" : "R";
    for (size_t l = 0; l < g.layers.size(); ++l) {
        if (g.layers[l].Empty()) {  // an empty cluster: no hits to match
            c.result->leftOut.push_back(
                {v, g.index, "layer " + std::to_string(l), "its cluster is empty"});
            ++c.mapsDone;
            continue;
        }
        // The layer's image per term and view (each file once, decoded in parallel), then the
        // image of every geometry's view.
        std::vector<int> views;
        for (const ViewGeometry& vg : geo)
            if (std::find(views.begin(), views.end(), vg.view) == views.end())
                views.push_back(vg.view);
        const auto n = static_cast<int>(views.size());
        std::vector<trace::FloatImage> owned(static_cast<size_t>(g.Terms() * n));
        base::ParallelFor(g.Terms() * n, c.opt.threads, [&](int k) {
            owned[static_cast<size_t>(k)] =
                ReadGroupSamples(c.tm, views[static_cast<size_t>(k % n)], g.index,
                                 LayerImageName(static_cast<int>(l), k / n));
        });
        std::vector<std::vector<const trace::FloatImage*>> images(2);
        for (int t = 0; t < g.Terms(); ++t)
            for (const ViewGeometry& vg : geo) {
                const auto at = std::find(views.begin(), views.end(), vg.view) - views.begin();
                images[static_cast<size_t>(t)].push_back(&owned[static_cast<size_t>(t * n + at)]);
            }
        const runtime::DirectImages* direct = c.Direct(g);
        Solve(c, Observations(c.opt, geo, g.Terms(), images, g.layers[l].shell, g.emOrigin), odir,
              Report(v, g, static_cast<int>(l), term, LayerMapName(static_cast<int>(l))),
              direct ? &direct->levels[l] : nullptr);
    }
    if (!c.opt.single) return;
    std::vector<std::vector<const trace::FloatImage*>> images(2);
    for (int t = 0; t < g.Terms(); ++t)
        for (const ViewGeometry& vg : geo)
            images[static_cast<size_t>(t)].push_back(&vg.images->cov[t]);
    const runtime::DirectImages* direct = c.Direct(g);
    Solve(c, Observations(c.opt, geo, g.Terms(), images, runtime::SingleLayerShell(g), g.emOrigin),
          odir, Report(v, g, 0, term, "single"), direct ? &direct->levels.back() : nullptr);
}

// Mirror-only groups: the PEM paper's local/distant split on the model's own vertices; a
// reflector whose polygons all lie on its convex hull cannot see itself: no local layer.
void SolvePemMaps(Context& c, int v, const runtime::LensGroupEm& g, const std::string& odir) {
    const runtime::MirrorGeometry m =
        runtime::MakeMirrorGeometry(c.scene, g.index, c.cameras[static_cast<size_t>(v)]);
    trace::FloatImage distant, local, frame, fresnel;  // the files decoded in parallel
    base::ParallelFor(4, c.opt.threads, [&](int k) {
        if (k == 0) distant = ReadGroupSamples(c.tm, v, g.index, "distant");
        if (k == 1) local = ReadGroupSamples(c.tm, v, g.index, "local");
        if (k == 2) frame = ReadFrameImage(c.tm, v, "greedy");
        if (k == 3) fresnel = ReadGroupImage(c.tm, v, g.index, "fresnel1");
    });
    const std::vector<uint8_t> hull = runtime::HullTriangles(m.mesh);
    const bool convex = runtime::AllOnHull(hull);
    if (convex) {
        c.result->leftOut.push_back(
            {v, g.index, "PEM local layer", "every polygon lies on the reflector's convex hull"});
        ++c.mapsDone;
    }
    // The local map is drawn, and so fitted, as the renderer draws it: only on the polygons off
    // the hull, where they are the visible surface (EQUAL after a depth pass of every polygon).
    // Fitted on every polygon, the hull's, which cannot see the reflector, pulled its coverage
    // to 0 at the shell points they share with the concave side.
    const std::vector<uint32_t> offHull = runtime::OffHull(m.order, hull);
    for (int which = convex ? 1 : 0; which < 2; ++which) {
        const trace::Shell& shell = which == 0 ? g.localShell : g.distantShell;
        MapInput in{which == 0 ? &local : &distant, &distant, &frame, &fresnel, {}, {}, 1.0, true};
        runtime::PassOptions po = DepthTested(c.opt, c.cameras[static_cast<size_t>(v)]);
        if (which == 0) {
            in.depthPass = runtime::DepthOnlyPass(m.Pass(), m.order, m.viewProjection);
            po.depthTest = runtime::LayerDepthTest(false);
        }
        in.passes = runtime::LayerPass(m.Pass(), which == 0 ? offHull : m.order,
                                       runtime::ShellCoords(m.exits, shell, g.emOrigin), m.exits,
                                       m.viewProjection, po);
        Solve(c, {in}, odir, Report(v, g, which, "pem", which == 0 ? "pem_local" : "pem_distant"));
    }
}

// RunInferJob -------------------------------------------------------------------------------

SampleReport InferSample(Context& c, int v) {
    const auto t0 = Clock::now();
    SampleReport sample;
    sample.view = v;
    for (const runtime::LensGroupEm& g : c.tm.groups) {
        const std::string odir = GroupDir(c.opt.outDir, v, g.index);
        std::filesystem::create_directories(odir);
        const std::vector<ViewGeometry> geo = SolveGeometry(c, v, g, &sample);
        SolveLayerMaps(c, v, g, geo, odir);
        if (g.pem) SolvePemMaps(c, v, g, odir);
    }
    sample.seconds = Since(t0);
    return sample;
}

std::vector<int> SamplesToInfer(const InferJobOptions& opt, const TraceManifest& tm) {
    std::vector<int> views = opt.views;
    if (views.empty())
        for (int v = 0; v < static_cast<int>(tm.views.size()); ++v) views.push_back(v);
    for (int v : views)
        if (v < 0 || v >= static_cast<int>(tm.views.size()))
            throw base::InputError("--view " + std::to_string(v), "no such viewpoint in the trace");
    return views;
}

}  // namespace

InferJobResult RunInferJob(const InferJobOptions& opt) {
    const auto tStart = Clock::now();
    try {
        raster::ProfileNamed(opt.hardware.profile);
    } catch (const std::invalid_argument& e) {
        throw base::InputError("--profile " + opt.hardware.profile, e.what());
    }
    if (opt.res < 1 || (opt.res & (opt.res - 1)) != 0 || opt.res > 4096)
        throw base::InputError("--res " + std::to_string(opt.res),
                               "expected a power of two in [1, 4096]");
    if (opt.parameterization != runtime::Parameterization::Cube && opt.res < 2)
        throw base::InputError("--res " + std::to_string(opt.res),
                               "a 2D layout needs a size of at least 2");
    if (opt.maxRes != 0 &&
        (opt.maxRes < opt.res || (opt.maxRes & (opt.maxRes - 1)) != 0 || opt.maxRes > 4096))
        throw base::InputError("--max-res " + std::to_string(opt.maxRes),
                               "expected a power of two in [--res, 4096]");
    for (double t : opt.alsoTessT)
        if (!(t >= 0.25 && t <= 1e4))
            throw base::InputError("--also-t " + std::to_string(t), "expected t in [0.25, 1e4]");
    InferJobResult result;
    result.trace = ReadTraceManifest(opt.traceDir);
    const TraceManifest& tm = result.trace;
    // Step 1: the scene, its BVH and the tracer (as the trace was made).
    const std::string scenePath = ResolveScene(tm.dir, tm.scene, tm.sceneGiven);
    if (!std::filesystem::exists(scenePath))
        throw base::InputError(scenePath, "scene of the trace not found");
    const trace::Scene scene = trace::LoadScene(scenePath);
    if (scene.lensGroups.size() != tm.groups.size())
        throw base::InputError(opt.traceDir + "/" + kTraceJson,
                               "lens groups differ from the scene's");
    const trace::EmbreeDevice device({opt.threads, "auto"});
    const trace::EmbreeScene embree(device, scene);
    const trace::Tracer tracer(scene, embree, tm.Tracing());
    // Step 2: every sample, one after the other.
    const std::vector<int> views = SamplesToInfer(opt, tm);
    Context c{opt, tm, scene, embree, tracer, tm.Cameras(), &result, 0, 0, {}};
    for (const runtime::LensGroupEm& g : tm.groups)
        c.mapsTotal += static_cast<int>(g.layers.size()) + (opt.single ? 1 : 0) + (g.pem ? 2 : 0);
    c.mapsTotal *= static_cast<int>(views.size());
    for (int v : views) result.samples.push_back(InferSample(c, v));
    if (opt.progress) opt.progress("done", 1.0);
    result.seconds = Since(tStart);
    return result;
}

void WriteInferOutputs(const InferJobOptions& o, const InferJobResult& r) {
    InferRecord rec;
    rec.dir = o.outDir;
    rec.traceDir = o.traceDir;
    rec.res = o.res, rec.threads = o.threads, rec.neighbours = o.neighbours, rec.hdr = o.hdr;
    rec.lambda = o.weights;
    rec.seconds = r.seconds;
    rec.samples = r.samples;
    rec.maps = r.maps;
    rec.leftOut = r.leftOut;
    WriteInferJson(rec);
    PemManifest m = PemManifestFor(r.trace, o.outDir, o.res, o.hdr, o.views, o.hardware,
                                   std::max(o.res, o.maxRes), o.parameterization);
    m.tessT = o.tessT;
    m.topologyT = o.topologyT;
    m.alsoTessT = o.alsoTessT;
    WritePemManifest(m);
}

}  // namespace pem::pipeline
