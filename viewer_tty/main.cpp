// SPDX-License-Identifier: MIT
// main.cpp — the `pemref` command line. Subcommands:
//   pemref raster CASE.json [-o out.png] [--profile llvmpipe|linear] [--threads N] [--repeat N]
//                 [--matrix out.mtx] [--rounding rne|d3d] [--cube-lod llvmpipe|exact] [--quiet]
// Every failure prints one line `pemref: <file>: <cause>` and exits non-zero; outputs are
// written to temporary files and renamed, so a failed run leaves none behind.
#include <malloc.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "raster/render.h"
#include "viewer_tty/case_file.h"
#include "viewer_tty/cmd_bake.h"
#include "viewer_tty/cmd_demo.h"
#include "viewer_tty/cmd_infer.h"
#include "viewer_tty/cmd_render.h"
#include "viewer_tty/cmd_report.h"
#include "viewer_tty/cmd_stability.h"
#include "viewer_tty/cmd_trace.h"
#include "viewer_tty/cmd_view.h"
#include "viewer_tty/input_error.h"
#include "viewer_tty/matrix_market.h"
#include "viewer_tty/png_io.h"
#include "viewer_tty/sha256.h"

namespace {

using namespace pem;

struct RasterArgs {
    std::string casePath, pngPath, matrixPath, profile = "llvmpipe", rounding = "rne";
    std::string cubeLod = "llvmpipe";
    int threads = 1, repeat = 0;
};

raster::RenderOptions ParseOptions(const RasterArgs& a) {
    raster::RenderOptions o;
    o.profile = a.profile == "linear" ? raster::Profile::Linear : raster::Profile::Llvmpipe;
    o.rounding =
        a.rounding == "d3d" ? raster::UnormRounding::HalfUp : raster::UnormRounding::HalfEven;
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

int RunRaster(const RasterArgs& args) {
    // Load the case and convert its texels (not timed).
    const raster::Frame frame = cli::LoadCaseFile(args.casePath);
    const raster::PreparedFrame prepared(frame);
    const raster::RenderOptions options = ParseOptions(args);

    // Render (timed when --repeat is given).
    raster::RenderResult result = raster::Render(prepared, options);
    std::vector<double> ms;
    for (int i = 0; i < args.repeat; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        result = raster::Render(prepared, options);
        const auto t1 = std::chrono::steady_clock::now();
        ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    }

    // Outputs: matrix first (it may refuse a non-linear frame), then the picture.
    if (!args.matrixPath.empty()) {
        raster::RenderingMatrix a;
        try {
            a = raster::BuildRenderingMatrix(prepared, options);
        } catch (const std::invalid_argument& e) {
            throw InputError(args.casePath, e.what());
        }
        const std::string stem = MatrixStem(args.matrixPath);
        cli::WriteMatrixMarket(args.matrixPath, a);
        cli::WriteVectorMarket(stem + ".rendered.mtx", a.rendered, "rendered frame per row");
        cli::WriteVectorMarket(stem + ".offset.mtx", a.offset, "constant term per row");
    }
    if (!args.pngPath.empty()) cli::WritePng(args.pngPath, result.image8);

    const auto& px = result.image8.rgba;
    std::printf("sha256: %s\n", cli::Sha256Hex(px.data(), px.size()).c_str());
    if (args.repeat > 0) std::printf("frame_ms_median: %.3f\n", Median(ms));
    return 0;
}

void AddRaster(CLI::App& app, RasterArgs& a) {
    CLI::App* sub = app.add_subcommand("raster", "render a raster case file (gl_ref_case/1)");
    sub->add_option("case", a.casePath, "case file (JSON)")->required();
    sub->add_option("-o,--output", a.pngPath, "write the RGBA8 frame as PNG");
    sub->add_option("--profile", a.profile, "hardware profile")
        ->check(CLI::IsMember({"llvmpipe", "linear"}));
    sub->add_option("--rounding", a.rounding, "float->unorm8 rule: rne (GL) or d3d (+0.5, floor)")
        ->check(CLI::IsMember({"rne", "d3d"}));
    sub->add_option("--cube-lod", a.cubeLod, "cube LOD: llvmpipe (fast log2) or exact (GL spec)")
        ->check(CLI::IsMember({"llvmpipe", "exact"}));
    sub->add_option("--threads", a.threads, "worker threads")->check(CLI::Range(1, 256));
    sub->add_option("--repeat", a.repeat, "render N more times, print frame_ms_median")
        ->check(CLI::Range(0, 100000));
    sub->add_option("--matrix", a.matrixPath, "write the rendering matrix (Matrix Market)");
}

}  // namespace

int main(int argc, char** argv) {
    // Frames allocate and free buffers of a few MB each (passes, images, meshes): keep them in
    // the heap rather than mapping and unmapping them every frame (page faults, TLB shootdowns).
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
    CLI::App app{"pemref — parameterized, layered environment maps, CPU reference"};
    app.require_subcommand(1);
    RasterArgs rasterArgs;
    AddRaster(app, rasterArgs);
    cli::AddTraceCommand(app);
    cli::AddInferCommand(app);
    cli::AddRenderCommand(app);
    cli::AddViewCommand(app);
    cli::AddBakeCommand(app);
    cli::AddReportCommand(app);
    cli::AddDemoCommand(app);
    cli::AddStabilityCommand(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "pemref: %s (see pemref --help)\n", e.what());
        return 2;
    }
    try {
        if (app.got_subcommand("raster")) return RunRaster(rasterArgs);
        if (app.got_subcommand("trace")) return cli::RunTraceCommand();
        if (app.got_subcommand("infer")) return cli::RunInferCommand();
        if (app.got_subcommand("render")) return cli::RunRenderCommand();
        if (app.got_subcommand("view")) return cli::RunViewCommand();
        if (app.got_subcommand("bake")) return cli::RunBakeCommand();
        if (app.got_subcommand("report")) return cli::RunReportCommand();
        if (app.got_subcommand("demo")) return cli::RunDemoCommand();
        if (app.got_subcommand("stability")) return cli::RunStabilityCommand();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pemref: %s\n", e.what());
        return 1;
    }
    return 0;
}
