// SPDX-License-Identifier: MIT
// cmd_raster.cpp — `pemref raster`: one case file through raster/ (cmd_raster.h).
#include "viewer_tty/cli/cmd_raster.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/input_error.h"
#include "base/matrix_market.h"
#include "base/png_io.h"
#include "base/sha256.h"
#include "raster/profile.h"
#include "raster/render.h"
#include "viewer_tty/cli/args.h"
#include "viewer_tty/conformance/case_file.h"

namespace pem::cli {
namespace {

struct RasterArgs {
    std::string casePath, pngPath, matrixPath, profile = "llvmpipe", rounding, cubeLod;
    int threads = 1, repeat = 0;
};

RasterArgs& Args() {
    static RasterArgs args;
    return args;
}

raster::RenderOptions ParseOptions(const RasterArgs& a) {
    raster::RenderOptions o = raster::ProfileNamed(a.profile).options;
    if (!a.rounding.empty())  // the profile's rule, unless asked otherwise
        o.rounding =
            a.rounding == "d3d" ? raster::UnormRounding::HalfUp : raster::UnormRounding::HalfEven;
    if (!a.cubeLod.empty())
        o.cubeLod = a.cubeLod == "exact" ? raster::CubeLod::Exact : raster::CubeLod::Llvmpipe;
    o.threads = a.threads;
    return o;
}

double Median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string MatrixStem(const std::string& path) {
    const std::string ext = ".mtx";
    if (path.size() > ext.size() && path.compare(path.size() - ext.size(), ext.size(), ext) == 0)
        return path.substr(0, path.size() - ext.size());
    return path;
}

// The matrix files and the picture; a failure removes the ones already written.
void WriteOutputs(const RasterArgs& args, const raster::RenderingMatrix& a,
                  const raster::Image8& image) {
    std::vector<std::string> written;
    try {
        if (!args.matrixPath.empty()) {
            const std::string stem = MatrixStem(args.matrixPath);
            base::WriteMatrixMarket(args.matrixPath, base::MatrixView::Of(a),
                                    "pemref rendering matrix: row 4*(y*width+x)+channel (rows "
                                    "top-down), column 4*texel+channel (raster/texel_index.h)");
            written.push_back(args.matrixPath);
            base::WriteVectorMarket(stem + ".rendered.mtx", a.rendered, "rendered frame per row");
            written.push_back(stem + ".rendered.mtx");
            base::WriteVectorMarket(stem + ".offset.mtx", a.offset, "constant term per row");
            written.push_back(stem + ".offset.mtx");
        }
        if (!args.pngPath.empty()) base::WritePng(args.pngPath, image);
    } catch (...) {
        for (const std::string& f : written) std::remove(f.c_str());
        throw;
    }
}

int RunRaster(const RasterArgs& args) {
    // Load the case and convert its texels (not timed).
    const raster::Frame frame = conformance::LoadCaseFile(args.casePath);
    const raster::PreparedFrame prepared(frame);
    const raster::RenderOptions options = ParseOptions(args);

    // Render (timed when --repeat is given); a frame the profile refuses names the case.
    raster::RenderResult result;
    try {
        result = raster::Render(prepared, options);
    } catch (const std::invalid_argument& e) {
        throw base::InputError(args.casePath, e.what());
    }
    // The timed repeats draw the colour buffer as the driver's timed frames do: a float buffer
    // without its 8-bit picture (the outputs come from the first render).
    std::vector<double> ms;
    raster::RenderOptions timed = options;
    timed.picture8 = false;
    for (int i = 0; i < args.repeat; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        const raster::RenderResult again = raster::Render(prepared, timed);
        const auto t1 = std::chrono::steady_clock::now();
        ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    }

    // Outputs: matrix first (it may refuse a non-linear frame), then the picture; all or none.
    raster::RenderingMatrix a;
    if (!args.matrixPath.empty()) {
        try {
            a = raster::BuildRenderingMatrix(prepared, options);
        } catch (const std::invalid_argument& e) {
            throw base::InputError(args.casePath, e.what());
        }
    }
    WriteOutputs(args, a, result.image8);

    // The identity: the colour buffer's bytes (RGBA32F: its floats, little-endian).
    const std::vector<uint8_t> px = prepared.frame().colorFormat == raster::ColorFormat::Rgba32F
                                        ? raster::FloatBytes(result.imageF.rgba)
                                        : result.image8.rgba;
    std::printf("sha256: %s\n", base::Sha256Hex(px.data(), px.size()).c_str());
    if (args.repeat > 0) std::printf("frame_ms_median: %.3f\n", Median(ms));
    return 0;
}

}  // namespace

void AddRasterCommand(CLI::App& app) {
    RasterArgs& a = Args();
    CLI::App* sub = app.add_subcommand("raster", "render a raster case file (gl_ref_case/1)");
    sub->add_option("case", a.casePath, "case file (JSON)")->required();
    sub->add_option("-o,--output", a.pngPath, "write the RGBA8 frame as PNG");
    AddProfileOption(sub, &a.profile);
    sub->add_option("--rounding", a.rounding, "float->unorm8 rule: rne (GL) or d3d (+0.5, floor)")
        ->check(CLI::IsMember({"rne", "d3d"}));
    sub->add_option("--cube-lod", a.cubeLod, "cube LOD: llvmpipe (fast log2) or exact (GL spec)")
        ->check(CLI::IsMember({"llvmpipe", "exact"}));
    sub->add_option("--threads", a.threads, "worker threads")->check(CLI::Range(1, 256));
    sub->add_option("--repeat", a.repeat, "render N more times, print frame_ms_median")
        ->check(CLI::Range(0, 100000));
    sub->add_option("--matrix", a.matrixPath, "write the rendering matrix (Matrix Market)");
}

int RunRasterCommand() {
    return RunRaster(Args());
}

}  // namespace pem::cli
