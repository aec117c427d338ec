// SPDX-License-Identifier: MIT
// error_budget.cpp — the stage-by-stage error budget (error_budget.h).
#include "viewer_tty/report/error_budget.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <utility>

#include "base/display_image.h"
#include "pipeline/display_target.h"
#include "pipeline/layout.h"
#include "runtime/lens_paths.h"
#include "runtime/parameterization.h"
#include "trace/image.h"
#include "trace/render.h"
#include "viewer_tty/report/exact_fit.h"

namespace pem::report {
namespace {

using Rgb = std::vector<float>;  // 3 floats per pixel, rows top-down

constexpr double kIdenticalPsnr = 100.0;  // DisplayPsnr of equal images

// The suffix of the stages drawn at the renderers' default t: "at t=5".
std::string AtDefaultT() {
    return "at " + TessSetting(runtime::kDefaultTessT);
}

Rgb RgbOf(const trace::FloatImage& img) {
    Rgb out(static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * 3);
    for (size_t p = 0; p < out.size() / 3; ++p)
        for (size_t c = 0; c < 3; ++c) out[3 * p + c] = img.data[p * size_t(img.channels) + c];
    return out;
}

// PSNR of the 8-bit sRGB display images (the PNG files) over the selected pixels.
double DisplayPsnr(const Rgb& a, const Rgb& b, int w, int h, const std::vector<uint8_t>& mask) {
    const base::Image8 da = base::ToDisplayImage(a, w, h, 3, 1.0f);
    const base::Image8 db = base::ToDisplayImage(b, w, h, 3, 1.0f);
    double se = 0.0;
    size_t n = 0;
    for (size_t p = 0; p < mask.size(); ++p) {
        if (!mask[p]) continue;
        for (size_t c = 0; c < 3; ++c) {
            const double d = (da.rgba[4 * p + c] - db.rgba[4 * p + c]) / 255.0;
            se += d * d;
        }
        ++n;
    }
    if (n == 0) return std::numeric_limits<double>::quiet_NaN();
    return se > 0.0 ? 10.0 * std::log10(3.0 * static_cast<double>(n) / se) : kIdenticalPsnr;
}

// A group's traced images at a sample.
struct GroupImages {
    trace::FloatImage fg[2], b[2];
    std::vector<trace::FloatImage> layers[2];  // layer_l_τ, every layer
};

GroupImages ReadGroupImages(const pipeline::TraceManifest& tm, int view,
                            const runtime::LensGroupEm& g) {
    GroupImages im;
    for (int t = 0; t < g.Terms(); ++t) {
        const std::string tn = runtime::TermName(t);
        im.fg[t] = pipeline::ReadGroupImage(tm, view, g.index, "FG_" + tn);
        im.b[t] = pipeline::ReadGroupImage(tm, view, g.index, "b_" + tn);
        for (size_t l = 0; l < g.layers.size(); ++l)
            im.layers[t].push_back(pipeline::ReadGroupImage(
                tm, view, g.index, pipeline::LayerImageName(static_cast<int>(l), t)));
    }
    return im;
}

// Premultiplied over of per-layer RGBA values, innermost first; layer(l, v) fills v[4].
template <class Layer>
void Over(size_t count, const Layer& layer, float out[3]) {
    float transmit = 1.0f;
    out[0] = out[1] = out[2] = 0.0f;
    for (size_t l = 0; l < count; ++l) {
        float v[4];
        layer(l, v);
        for (int c = 0; c < 3; ++c) out[c] += transmit * v[c];
        transmit *= 1.0f - v[3];
    }
}

// greedy with its lens part replaced: background (greedy − Σ F·G b / cov) + Σ_τ F·G_τ · over_τ,
// over_τ(p) from rgba(τ, l, p, v) (RGBA of layer l as the maps store it: coverage divided out).
template <class LayerRgba>
Rgb Recomposed(const Rgb& greedy, const GroupImages& im, int terms, size_t layers,
               const LayerRgba& rgba) {
    Rgb out = greedy;
    for (size_t p = 0; p < out.size() / 3; ++p) {
        const float cov = im.b[0].data[4 * p + 3];
        if (!(cov > 1e-6f)) continue;
        for (int t = 0; t < terms; ++t) {
            float over[3];
            Over(
                layers, [&](size_t l, float* v) { rgba(t, l, p, v); }, over);
            for (size_t c = 0; c < 3; ++c) {
                const float fg = im.fg[t].data[4 * p + c];
                out[3 * p + c] += fg * over[c] - fg * im.b[t].data[4 * p + c] / cov;
            }
        }
    }
    return out;
}

// The maps' targets: each non-empty layer's image with the lens coverage divided out; for float
// maps (`shown`: the traced frame) what the display shows of it, as inference fits them
// (pipeline/display_target.h; pixels here, subpixels there).
std::vector<std::vector<trace::FloatImage>> Targets(const GroupImages& im,
                                                    const runtime::LensGroupEm& g,
                                                    const trace::FloatImage* shown, double scale) {
    std::vector<std::vector<trace::FloatImage>> out(size_t(g.Terms()));
    std::vector<uint32_t> cells;  // the covered pixels
    for (size_t p = 0; p < im.b[0].data.size() / 4; ++p)
        if (im.b[0].data[4 * p + 3] > 1e-6f) cells.push_back(static_cast<uint32_t>(p));
    for (int t = 0; t < g.Terms(); ++t)
        for (size_t l = 0; l < g.layers.size(); ++l) {
            if (g.layers[l].Empty()) continue;
            trace::FloatImage img = im.layers[t][l];
            for (size_t p = 0; p < img.data.size() / 4; ++p) {
                const float cov = im.b[0].data[4 * p + 3];
                for (size_t c = 0; c < 4; ++c)
                    img.data[4 * p + c] = cov > 1e-6f ? img.data[4 * p + c] / cov : 0.0f;
            }
            if (shown) {  // float maps: fitted to what the display shows, in map units
                std::vector<double> b;
                for (uint32_t p : cells)
                    for (size_t c = 0; c < 4; ++c)
                        b.push_back(
                            std::max(0.0, double(img.data[4 * p + c]) / (c < 3 ? scale : 1.0)));
                pipeline::ClipToDisplay({&im.b[0], shown, &im.fg[t]}, cells, 1, scale, &b);
                for (size_t i = 0; i < cells.size(); ++i)
                    for (size_t c = 0; c < 3; ++c)
                        img.data[4 * cells[i] + c] = static_cast<float>(b[4 * i + c] * scale);
            }
            out[size_t(t)].push_back(std::move(img));
        }
    return out;
}

std::string GroupName(const runtime::LensGroupEm& g) {
    return nlohmann::json(g.objects).dump();
}

// The dB a stage cost: the PSNR before it minus with it; none after the first stage or after a
// frame identical to its comparison (DisplayPsnr's 100 dB: no finite PSNR to lose from).
double CostFrom(double before, double psnr) {
    const double none = std::numeric_limits<double>::quiet_NaN();
    return std::isfinite(before) && before < kIdenticalPsnr ? before - psnr : none;
}

// A stage against the reference, and against the two-term frame (NaN: not measured).
void AddStage(GroupBudget* b, const std::string& stage, double psnr,
              double psnrVsTarget = std::numeric_limits<double>::quiet_NaN()) {
    const double none = std::numeric_limits<double>::quiet_NaN();
    const BudgetStage* before = b->stages.empty() ? nullptr : &b->stages.back();
    b->stages.push_back({stage, psnr, CostFrom(before ? before->psnr : none, psnr), psnrVsTarget,
                         CostFrom(before ? before->psnrVsTarget : none, psnrVsTarget)});
}

// The size of the group's layer maps at the sample (the largest, when infer chose it): a cube's
// face size, a 2D layout's size parameter (runtime/parameterization.h LayoutOf).
int GroupMapResolution(const runtime::MapSet& maps, int view, const runtime::LensGroupEm& g) {
    int res = maps.res;
    for (size_t l = 0; l < g.layers.size(); ++l)
        if (const raster::Texture* t = maps.map(view, g.index, pipeline::LayerMapName(int(l))))
            for (int size = std::max(2, maps.res); size <= 2 * t->width; size *= 2)
                if (runtime::LayoutOf(maps.parameterization, size).width == t->width)
                    res = std::max(res, size);
    return res;
}

// The stages at the sample for one group.
GroupBudget SampleBudget(runtime::Renderer& renderer, const pipeline::TraceManifest& trace,
                         const runtime::LensGroupEm& g, const runtime::RenderedFrame& hybrid,
                         const runtime::RenderedFrame* hybridDefaultT,
                         const runtime::RenderSettings& s) {
    const int view = renderer.maps().inferred.front();
    const raster::Camera cam = renderer.SampleCamera(view);
    const int w = cam.width, h = cam.height;
    const Rgb ref = RgbOf(pipeline::ReadFrameImage(trace, view, "reference"));
    const Rgb greedy = RgbOf(pipeline::ReadFrameImage(trace, view, "greedy"));
    const GroupImages im = ReadGroupImages(trace, view, g);
    std::vector<uint8_t> mask(ref.size() / 3);
    for (size_t p = 0; p < mask.size(); ++p) mask[p] = im.b[0].data[4 * p + 3] > 0.5f;
    GroupBudget b{GroupName(g), "on circle", 0, {}};
    for (uint8_t m : mask) b.pixels += m;
    // Each stage against the reference and against the two-term frame (the method's target).
    const auto stage = [&](const std::string& name, const Rgb& frame) {
        AddStage(&b, name, DisplayPsnr(frame, ref, w, h, mask),
                 DisplayPsnr(frame, greedy, w, h, mask));
    };
    AddStage(&b, "two-term model", DisplayPsnr(greedy, ref, w, h, mask));
    stage("layered EM", Recomposed(greedy, im, g.Terms(), g.layers.size(),
                                   [&](int t, size_t l, size_t p, float* v) {
                                       const float cov = im.b[0].data[4 * p + 3];
                                       for (size_t c = 0; c < 4; ++c)
                                           v[c] = im.layers[t][l].data[4 * p + c] / cov;
                                   }));
    // Layer images (Renderer::LayerImages' layout) composited into the frame.
    const auto composited = [&](const std::vector<std::vector<raster::ImageF>>& layers) {
        return Recomposed(greedy, im, g.Terms(), layers.empty() ? 0 : layers[0].size(),
                          [&](int t, size_t l, size_t p, float* v) {
                              for (size_t c = 0; c < 4; ++c)
                                  v[c] = layers[size_t(t)][l].rgba[4 * p + c];
                          });
    };
    const bool bounded = renderer.maps().hardware.format == raster::TexelFormat::Rgba8;
    const double scale = static_cast<double>(renderer.maps().hardware.radianceScale);
    const trace::FloatImage shown = pipeline::ReadFrameImage(trace, view, "greedy");
    const ExactStages exact = ExactLookupStages(
        renderer.tracer(), cam, trace.spp, g, Targets(im, g, bounded ? nullptr : &shown, scale),
        im.b[0], GroupMapResolution(renderer.maps(), view, g), scale, bounded, s.threads);
    stage("best maps, exact lookups", composited(exact.unbounded));
    if (bounded) {  // 8-bit maps; float maps have neither bound
        stage("nonnegative maps", composited(exact.nonnegative));
        stage("maps' range", composited(exact.inRange));
    }
    stage("map resolution", composited(exact.ownResolution));
    stage("texgen, filtering, solve", composited(renderer.LayerImages(cam, s, g.index, view)));
    stage("hardware frame", RgbOf(hybrid.image));
    if (hybridDefaultT) stage("hardware frame " + AtDefaultT(), RgbOf(hybridDefaultT->image));
    return b;
}

// A hybrid frame against the ray tracer's at K×K on the pixels that see each of the groups.
std::vector<double> HybridVsTraced(const runtime::RenderedFrame& hybrid,
                                   const trace::FloatImage& traced, size_t groups) {
    std::vector<double> out;
    for (size_t g = 0; g < groups; ++g) {
        std::vector<uint8_t> mask(hybrid.groupOf.size());
        for (size_t p = 0; p < mask.size(); ++p) mask[p] = hybrid.groupOf[p] == int(g);
        out.push_back(
            DisplayPsnr(RgbOf(hybrid.image), RgbOf(traced), traced.width, traced.height, mask));
    }
    return out;
}

// The position's hybrid frame (at the maps' t), drawn unless the caller drew it.
runtime::RenderedFrame HybridAt(runtime::Renderer& renderer, const BudgetPosition& at,
                                const runtime::RenderSettings& s) {
    return at.hybrid ? *at.hybrid : renderer.Render(at.camera, s);
}

// The same at the renderers' default t, when the maps were fitted at another t (else nullopt).
std::optional<runtime::RenderedFrame> HybridDefaultTAt(runtime::Renderer& renderer,
                                                       const BudgetPosition& at,
                                                       runtime::RenderSettings s) {
    if (renderer.maps().tessT == runtime::kDefaultTessT) return std::nullopt;
    if (at.hybridDefaultT) return at.hybridDefaultT;
    s.t = runtime::kDefaultTessT;
    return renderer.Render(at.camera, s);
}

// Per group, a hybrid frame off the samples against the full tree and the two-term frame there.
struct OffSample {
    std::vector<double> vsFull, vsTwoTerm;
};

// The hybrid frames at an off-sample position (at the maps' t, then at the renderers' default t
// when the maps' is another) against the full tree and the two-term frame, all rendered there
// (or given).
std::vector<OffSample> HybridVsTracedAt(runtime::Renderer& renderer, const BudgetPosition& at,
                                        const runtime::RenderSettings& s, int spp) {
    runtime::RenderSettings rs = s;
    rs.method = runtime::Method::RayTraced;
    rs.spp = spp;
    const size_t groups = renderer.maps().groups.size();
    const trace::FloatImage twoTerm =
        trace::RenderFrame(renderer.tracer(), at.camera, spp, trace::Model::Greedy, s.threads)
            .image;
    const trace::FloatImage full =
        at.traced ? at.traced->image : renderer.Render(at.camera, rs).image;
    std::vector<OffSample> out;
    const auto add = [&](const runtime::RenderedFrame& hybrid) {
        out.push_back(
            {HybridVsTraced(hybrid, full, groups), HybridVsTraced(hybrid, twoTerm, groups)});
    };
    add(HybridAt(renderer, at, s));
    if (const auto other = HybridDefaultTAt(renderer, at, s)) add(*other);
    return out;
}

}  // namespace

std::vector<GroupBudget> ErrorBudget(runtime::Renderer& renderer,
                                     const pipeline::TraceManifest& trace,
                                     const std::vector<BudgetPosition>& positions, int threads) {
    runtime::RenderSettings s;
    s.method = runtime::Method::Hybrid;
    s.threads = threads;
    std::vector<GroupBudget> out;
    // Step 1: the stages at the sample.
    const runtime::RenderedFrame hybrid = HybridAt(renderer, positions[0], s);
    const std::optional<runtime::RenderedFrame> hybridDefaultT =
        HybridDefaultTAt(renderer, positions[0], s);
    for (const runtime::LensGroupEm& g : renderer.maps().groups)
        out.push_back(SampleBudget(renderer, trace, g, hybrid,
                                   hybridDefaultT ? &*hybridDefaultT : nullptr, s));
    // Step 2: off the samples, against the same measures at the sample (the trace's reference
    // and two-term frame there are the ray tracer's frames at K×K).
    const int view = renderer.maps().inferred.front();
    const size_t groups = renderer.maps().groups.size();
    const std::vector<double> atSample =
        HybridVsTraced(hybrid, pipeline::ReadFrameImage(trace, view, "reference"), groups);
    const std::vector<double> atSampleVsTarget =
        HybridVsTraced(hybrid, pipeline::ReadFrameImage(trace, view, "greedy"), groups);
    for (size_t k = 1; k < positions.size(); ++k) {
        const std::vector<OffSample> there = HybridVsTracedAt(renderer, positions[k], s, trace.spp);
        for (const runtime::LensGroupEm& g : renderer.maps().groups) {
            GroupBudget b{GroupName(g), positions[k].name, 0, {}};
            const size_t i = size_t(g.index);
            AddStage(&b, "hybrid at the sample", atSample[i], atSampleVsTarget[i]);
            AddStage(&b, "off the samples", there[0].vsFull[i], there[0].vsTwoTerm[i]);
            if (there.size() > 1)
                AddStage(&b, "off the samples " + AtDefaultT(), there[1].vsFull[i],
                         there[1].vsTwoTerm[i]);
            out.push_back(b);
        }
    }
    return out;
}

}  // namespace pem::report
