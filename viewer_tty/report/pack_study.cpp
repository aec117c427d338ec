// SPDX-License-Identifier: MIT
// pack_study.cpp — packed PEMs in the report (pack_study.h).
#include "viewer_tty/report/pack_study.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>

#include "base/atomic_file.h"
#include "pipeline/pem_pack.h"
#include "pipeline/pem_set.h"

namespace pem::report {
namespace {

struct Setting {
    std::string name;
    pipeline::PackOptions options;
};

// Lossless, quantized to ±4, and JPEG 2000 (9/7) from 16:1 to 64:1 (the smallest levels ±31).
std::vector<Setting> Settings() {
    std::vector<Setting> out;
    out.push_back({"lossless", {}});
    pipeline::PackOptions q;
    q.map.maxError = 4;
    out.push_back({"--max-error 4", q});
    for (int ratio : {16, 32, 48, 64}) {
        pipeline::PackOptions j;
        j.map.maxError = 31;
        j.map.ratio = ratio;
        out.push_back({"--max-error 31 --ratio " + std::to_string(ratio), j});
    }
    return out;
}

// The methods drawn from each pack: (report method, setting, render settings).
struct Drawn {
    std::string method, setting;
    runtime::Method m;
    int layers;
};
const Drawn kDrawn[] = {{"hybrid", "", runtime::Method::Hybrid, 0},  // at the maps' t
                        {"layered PEM", "", runtime::Method::Pem, 0},
                        {"single-layer PEM", "", runtime::Method::Pem, 1}};

double UnpackedPsnr(const std::vector<MethodResult>& results, const Drawn& d,
                    const std::string& position) {
    for (const MethodResult& r : results)
        if (r.method == d.method && r.setting == d.setting && r.position == position)
            return r.floatScores.psnr;
    return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

std::vector<PackRow> StudyPacks(const std::string& pemDir, const std::string& scratchDir,
                                const std::vector<PackReference>& references,
                                const std::vector<MethodResult>& unpacked, int threads,
                                const std::function<void(const std::string&)>& log) {
    std::vector<PackRow> rows;
    const std::string pack = base::TemporaryPath(scratchDir + "/study.pempack");
    // The scratch pack goes when the study ends, also when a setting fails.
    struct Remove {
        const std::string& path;
        ~Remove() {
            std::error_code ec;
            std::filesystem::remove(path, ec);
        }
    } remove{pack};
    for (const Setting& s : Settings()) {
        if (log) log("packed PEM " + s.name);
        // Step 1: pack, timed.
        const auto t0 = std::chrono::steady_clock::now();
        const pipeline::PackStats st = pipeline::PackPem(pemDir, pack, s.options);
        PackRow row;
        row.setting = s.name;
        row.packSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        row.bytesPerSample = double(st.packBytes) / std::max(1, st.samples);
        row.vsExr = double(st.exrBytes) / double(st.packBytes);
        row.vsPng = double(st.pngBytes) / double(st.packBytes);
        row.maxError = st.maxError;
        // Step 2: the frames drawn from the pack against the references.
        std::unique_ptr<runtime::Renderer> renderer = pipeline::OpenPemDirectory(pack, threads);
        for (const PackReference& ref : references)
            for (Drawn d : kDrawn) {
                if (d.m == runtime::Method::Hybrid) d.setting = TessSetting(renderer->maps().tessT);
                runtime::RenderSettings rs;
                rs.method = d.m, rs.layers = d.layers, rs.threads = threads;
                const runtime::RenderedFrame f = renderer->Render(ref.camera, rs);
                const double psnr = CompareFloat(ToMetric(f.image), ref.reference, &ref.mask).psnr;
                row.deltas.push_back(
                    {d.method, ref.position, psnr, psnr - UnpackedPsnr(unpacked, d, ref.position)});
            }
        rows.push_back(std::move(row));
    }
    return rows;
}

}  // namespace pem::report
