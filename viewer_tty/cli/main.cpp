// SPDX-License-Identifier: MIT
// main.cpp — the `pemref` command line: one subcommand per cmd_<name>.h of this folder.
// Every failure prints one line `pemref: <file>: <cause>` and exits non-zero; outputs are
// written to temporary files and renamed, so a failed run leaves none behind.
#include <malloc.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "viewer_tty/cli/args.h"
#include "viewer_tty/cli/cmd_bake.h"
#include "viewer_tty/cli/cmd_demo.h"
#include "viewer_tty/cli/cmd_golden.h"
#include "viewer_tty/cli/cmd_infer.h"
#include "viewer_tty/cli/cmd_pack.h"
#include "viewer_tty/cli/cmd_raster.h"
#include "viewer_tty/cli/cmd_render.h"
#include "viewer_tty/cli/cmd_report.h"
#include "viewer_tty/cli/cmd_stability.h"
#include "viewer_tty/cli/cmd_study.h"
#include "viewer_tty/cli/cmd_trace.h"
#include "viewer_tty/cli/cmd_view.h"

namespace {

// glibc backs the heap with transparent huge pages only when told before the process starts
// (the tunable glibc.malloc.hugetlb; the machine's THP mode is usually "madvise"): restart once
// with it set. Page faults then touch 2 MB instead of 4 kB: the demo's inference of one
// viewpoint sample takes 33 s instead of 61 s (2 cores, a virtual machine, where every fault
// is costly); frames and maps are the same bytes. If the restart fails, run as we are.
void RestartWithHugePages(char** argv) {
#ifdef __GLIBC__
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    if (tunables && std::strstr(tunables, "glibc.malloc.hugetlb")) return;
    std::string value = tunables && *tunables ? std::string(tunables) + ":" : std::string();
    value += "glibc.malloc.hugetlb=1";
    if (setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0) return;
    execv("/proc/self/exe", argv);
#else
    (void)argv;
#endif
}

}  // namespace

int main(int argc, char** argv) {
    RestartWithHugePages(argv);
    // Frames allocate and free buffers of a few MB each (passes, images, meshes), the solver
    // vectors of tens to hundreds of MB (A x, A^T y, its iterates): keep them all in the heap and
    // keep freed memory there, rather than mapping, faulting in and zeroing fresh pages at every
    // allocation (a third of an inference's time with mapped allocations above 32 MB). -1: never
    // trim (mallopt(3)); the largest int still let an inference map of 72 M entries hand 3 GB back
    // when freed, which the next map faulted in again (a demo inference 71 → 67 s, system time
    // 16 → 9–13 s).
    mallopt(M_MMAP_MAX, 0);
    mallopt(M_TRIM_THRESHOLD, -1);
    CLI::App app{"pemref — parameterized, layered environment maps, CPU reference"};
    app.require_subcommand(1);
    app.set_version_flag("--version", pem::cli::VersionText());
    pem::cli::AddRasterCommand(app);
    pem::cli::AddTraceCommand(app);
    pem::cli::AddInferCommand(app);
    pem::cli::AddRenderCommand(app);
    pem::cli::AddViewCommand(app);
    pem::cli::AddBakeCommand(app);
    pem::cli::AddPackCommands(app);
    pem::cli::AddReportCommand(app);
    pem::cli::AddStudyCommand(app);
    pem::cli::AddDemoCommand(app);
    pem::cli::AddStabilityCommand(app);
    pem::cli::AddGoldenCommand(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "pemref: %s (see pemref --help)\n", e.what());
        return 2;
    }
    try {
        if (app.got_subcommand("raster")) return pem::cli::RunRasterCommand();
        if (app.got_subcommand("trace")) return pem::cli::RunTraceCommand();
        if (app.got_subcommand("infer")) return pem::cli::RunInferCommand();
        if (app.got_subcommand("render")) return pem::cli::RunRenderCommand();
        if (app.got_subcommand("view")) return pem::cli::RunViewCommand();
        if (app.got_subcommand("bake")) return pem::cli::RunBakeCommand();
        if (app.got_subcommand("pack")) return pem::cli::RunPackCommand();
        if (app.got_subcommand("unpack")) return pem::cli::RunUnpackCommand();
        if (app.got_subcommand("report")) return pem::cli::RunReportCommand();
        if (app.got_subcommand("study")) return pem::cli::RunStudyCommand();
        if (app.got_subcommand("demo")) return pem::cli::RunDemoCommand();
        if (app.got_subcommand("stability")) return pem::cli::RunStabilityCommand();
        if (app.got_subcommand("golden")) return pem::cli::RunGoldenCommand(app);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pemref: %s\n", e.what());
        return 1;
    }
    return 0;
}
