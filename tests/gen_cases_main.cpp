// SPDX-License-Identifier: MIT
// gen_cases — writes the conformance corpus (case_generator.h) as case files, one per case, and
// the benchmark frames as bench.json and lens.json:  gen_cases OUTDIR [--bench-only | --rgba8-only]
// (--rgba8-only: the cases whose textures and colour buffer are all RGBA8, what the softpipe
// profile draws).
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "tests/case_generator.h"
#include "viewer_tty/conformance/case_file.h"

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: gen_cases OUTDIR [--bench-only | --rgba8-only]\n");
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    const bool benchOnly = argc > 2 && std::strcmp(argv[2], "--bench-only") == 0;
    const bool rgba8Only = argc > 2 && std::strcmp(argv[2], "--rgba8-only") == 0;
    std::filesystem::create_directories(dir);
    auto write = [&](const std::string& name, const pem::raster::Frame& f) {
        std::ofstream(dir / (name + ".json")) << pem::conformance::CaseToJson(f);
    };
    // 640x480, sky quad + 200x100 UV sphere (40k triangles), 256^2 cube, trilinear, seamless.
    write("bench", pem::test::BenchmarkFrame(640, 480, 100, 200, 256));
    // 640x480 RGBA32F + Z24, two layer passes over a 200x100 UV sphere of two-pixel triangles,
    // 128^2 RGBA32F cubes (not with --rgba8-only).
    if (!rgba8Only) write("lens", pem::test::LensFrame(640, 480, 100, 200, 128));
    if (benchOnly) return 0;
    int n = 0;
    for (const auto& c : pem::test::ConformanceCases()) {
        bool rgba8 = c.frame.colorFormat == pem::raster::ColorFormat::Rgba8;
        for (const auto& t : c.frame.textures) rgba8 &= t.format == pem::raster::TexelFormat::Rgba8;
        if (rgba8Only && !rgba8) continue;
        write(c.name, c.frame);
        ++n;
    }
    std::printf("wrote %d cases, bench.json and lens.json to %s\n", n, dir.c_str());
    return 0;
}
