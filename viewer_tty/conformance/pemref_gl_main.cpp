// SPDX-License-Identifier: MIT
// pemref_gl_main.cpp — `pemref-gl CASE.json [-o out.png] [--repeat N] [--info]
// [--driver llvmpipe|softpipe] [--software]`: renders a raster case through the system's OpenGL
// driver (or Mesa's software driver named by --driver) and prints `sha256: <hex>` of the RGBA8
// pixels (rows top-down), plus `frame_ms_median: <ms>` with --repeat.
// Exit codes: 0 ok, 1 bad case or output path, 2 OpenGL unavailable, 3 GL driver failure.
// Not here: pemref's own rasterizer (that is `pemref`).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "base/png_io.h"
#include "base/sha256.h"
#include "viewer_tty/conformance/case_file.h"
#include "viewer_tty/conformance/gl_reference.h"

namespace {

struct Options {
    std::string casePath, outPath, driver;
    int repeat = 0;
    bool info = false, software = false;
};

double Median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

int Run(const Options& options) {
    // Step 1: the case (before GL, so a bad case is reported even without a driver).
    const pem::raster::Frame frame = pem::conformance::LoadCaseFile(options.casePath);
    // Step 2: the GL context.
    if (options.software || !options.driver.empty()) setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
    if (!options.driver.empty()) setenv("GALLIUM_DRIVER", options.driver.c_str(), 1);
    if (auto reason = pem::conformance::GlAvailable()) {
        std::cerr << "pemref-gl: OpenGL unavailable: " << *reason << "\n";
        return 2;
    }
    if (!options.driver.empty() &&
        pem::conformance::GlRendererString().find(options.driver) == std::string::npos) {
        std::cerr << "pemref-gl: --driver " << options.driver
                  << ": the GL renderer is not Mesa's: " << pem::conformance::GlRendererString()
                  << "\n";
        return 2;
    }
    if (options.info) std::cerr << "GL: " << pem::conformance::GlRendererString() << "\n";
    // Step 3: render, hash, report.
    std::vector<double> frameMs;
    pem::raster::ImageF floats;
    const pem::raster::Image8 image = pem::conformance::RenderWithGl(
        frame, std::max(1, options.repeat), &frameMs, nullptr, &floats);
    if (!options.outPath.empty()) pem::base::WritePng(options.outPath, image);
    // The identity: the colour buffer's bytes (RGBA32F: its floats, little-endian).
    const std::vector<uint8_t> bytes = frame.colorFormat == pem::raster::ColorFormat::Rgba32F
                                           ? pem::raster::FloatBytes(floats.rgba)
                                           : image.rgba;
    std::cout << "sha256: " << pem::base::Sha256Hex(bytes.data(), bytes.size()) << "\n";
    if (options.repeat > 0) {
        char text[64];
        std::snprintf(text, sizeof text, "%.3f", Median(frameMs));
        std::cout << "frame_ms_median: " << text << "\n";
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"pemref-gl: render a gl_ref_case/1 raster case with the system OpenGL driver"};
    Options options;
    app.add_option("case", options.casePath, "case file (JSON)")->required();
    app.add_option("-o,--output", options.outPath, "write the frame as PNG");
    app.add_option("--repeat", options.repeat, "draw the frame N times, report the median time")
        ->check(CLI::Range(1, 1000000));
    app.add_flag("--info", options.info, "print GL_RENDERER and GL_VERSION to stderr");
    app.add_flag("--software", options.software,
                 "set LIBGL_ALWAYS_SOFTWARE=1 before EGL init (Mesa llvmpipe)");
    app.add_option("--driver", options.driver,
                   "Mesa's software driver: llvmpipe or softpipe (sets LIBGL_ALWAYS_SOFTWARE=1 "
                   "and GALLIUM_DRIVER before EGL init)")
        ->check(CLI::IsMember({"llvmpipe", "softpipe"}));
    CLI11_PARSE(app, argc, argv);
    try {
        return Run(options);
    } catch (const pem::base::InputError& e) {
        std::cerr << "pemref-gl: " << e.what() << "\n";
        return 1;
    } catch (const pem::conformance::GlError& e) {
        std::cerr << "pemref-gl: " << e.what() << "\n";
        return 3;
    }
}
