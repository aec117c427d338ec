// SPDX-License-Identifier: MIT
// cmd_pack.cpp — `pemref pack` / `pemref unpack` (cmd_pack.h).
#include "viewer_tty/cli/cmd_pack.h"

#include <cstdio>
#include <string>

#include "base/input_error.h"
#include "pipeline/map_coding.h"
#include "pipeline/pem_pack.h"
#include "viewer_tty/tty/progress.h"

namespace pem::cli {
namespace {

struct PackArgs {
    std::string in, out, codec = "zstd", wavelet = "97";
    int maxError = 0, threads = 1;
    double ratio = 0.0;
    bool quiet = false;
};

PackArgs& Args() {
    static PackArgs args;
    return args;
}

double Ratio(uint64_t a, uint64_t b) {
    return b ? static_cast<double>(a) / static_cast<double>(b) : 0.0;
}

}  // namespace

void AddPackCommands(CLI::App& app) {
    PackArgs& a = Args();
    CLI::App* pack = app.add_subcommand("pack", "a PEM directory as one compressed file");
    pack->add_option("pem_dir", a.in, "output directory of pemref infer or bake")->required();
    pack->add_option("-o,--out", a.out, "the packed PEM to write")->required();
    pack->add_option("--codec", a.codec, "byte codec: zstd | xz")
        ->check(CLI::IsMember({"zstd", "xz"}));
    pack->add_option("--max-error", a.maxError, "largest change of an 8-bit texel (0: lossless)")
        ->check(CLI::Range(0, pipeline::kMaxMapError));
    pack->add_option(
            "--ratio", a.ratio,
            "levels of faces >= 8 wide and tall by JPEG 2000 at this compression ratio (0: "
            "predictive; 1: JPEG 2000 lossless)")
        ->check(CLI::Range(0.0, 1000.0));
    pack->add_option("--wavelet", a.wavelet,
                     "JPEG 2000 wavelet of --ratio > 1: 97 (irreversible, smaller) or 53 "
                     "(integer decoding)")
        ->check(CLI::IsMember({"97", "53"}));
    pack->add_flag("--quiet", a.quiet, "no progress or summary line");
    CLI::App* unpack = app.add_subcommand("unpack", "a packed PEM as a PEM directory again");
    unpack->add_option("pack", a.in, "the packed PEM")->required();
    unpack->add_option("-o,--out", a.out, "the PEM directory to make (must not exist)")->required();
    unpack->add_option("--threads", a.threads, "worker threads")->check(CLI::Range(1, 256));
}

int RunPackCommand() {
    const PackArgs& a = Args();
    pipeline::PackOptions opt;
    opt.codec = base::ByteCodecNamed(a.codec);
    opt.map.maxError = a.maxError;
    opt.map.ratio = a.ratio;
    opt.map.wavelet =
        a.wavelet == "53" ? base::J2kWavelet::Reversible53 : base::J2kWavelet::Irreversible97;
    tty::ProgressLine line("pemref pack", a.quiet);
    if (line.Enabled()) opt.progress = [&line](double f) { line.Update(f); };
    const pipeline::PackStats s = pipeline::PackPem(a.in, a.out, opt);
    line.Finish();
    if (!a.quiet)
        std::printf(
            "%s: %d maps of %d samples, %llu bytes (%.0f per sample), max error %d; "
            "%.1f:1 against the EXR maps, %.1f:1 against the PNG maps, %.1f:1 against the raw "
            "8-bit maps\n",
            a.out.c_str(), s.maps, s.samples, static_cast<unsigned long long>(s.packBytes),
            static_cast<double>(s.packBytes) / std::max(1, s.samples), s.maxError,
            Ratio(s.exrBytes, s.packBytes), Ratio(s.pngBytes, s.packBytes),
            Ratio(s.rawBytes, s.packBytes));
    return 0;
}

int RunUnpackCommand() {
    const PackArgs& a = Args();
    pipeline::UnpackPem(a.in, a.out, a.threads);
    return 0;
}

}  // namespace pem::cli
