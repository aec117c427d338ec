// SPDX-License-Identifier: MIT
// viewer_test.cpp — the terminal viewer without a terminal: key decoding (arrow escape
// sequences, a lone Escape), ApplyKey's steps and clamps, the status line, and scripted runs of
// RunViewer with a fake renderer whose colour follows the state, written into a tmpfile().
// Conventions: small screens (a few rows). Not here: the interactive loop (tests/viewer_tmux.sh).
#include "viewer_tty/tty/viewer.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

namespace pem::tty {
namespace {

// Viewer output of a scripted run, with everything the fake renderer was asked for.
struct ScriptedRun {
    int rc = -1;
    std::string text;
    std::vector<ViewState> states;
    std::vector<std::pair<int, int>> sizes;
};

// A 2 × 2 image whose red channel is the mode and green channel the azimuth / 5.
ViewFrame FakeFrame(const ViewState& s) {
    const auto red = static_cast<uint8_t>(40 * static_cast<int>(s.mode));
    const auto green = static_cast<uint8_t>(s.azimuthDeg / 5.0);
    const uint8_t pixel[4] = {red, green, 7, 255};
    base::Image8 img{2, 2, std::vector<uint8_t>(16)};
    for (size_t i = 0; i < img.rgba.size(); ++i) img.rgba[i] = pixel[i % 4];
    return {img, "fake info"};
}

ScriptedRun RunScripted(const ViewerOptions& options, ViewState initial = ViewState{}) {
    ScriptedRun run;
    std::FILE* out = std::tmpfile();
    EXPECT_NE(out, nullptr);
    run.rc = RunViewer(
        options, initial,
        [&](const ViewState& s, int w, int h) {
            run.states.push_back(s);
            run.sizes.emplace_back(w, h);
            return FakeFrame(s);
        },
        out);
    std::rewind(out);
    char buf[4096];
    for (size_t n; (n = std::fread(buf, 1, sizeof buf, out)) > 0;) run.text.append(buf, n);
    std::fclose(out);
    return run;
}

std::vector<std::string> Lines(const std::string& text) {
    std::vector<std::string> lines;
    for (size_t at = 0; at < text.size();) {
        const size_t end = text.find('\n', at);
        lines.push_back(text.substr(at, end - at));
        at = end == std::string::npos ? text.size() : end + 1;
    }
    return lines;
}

// The frames of a scripted run: the lines after each "--- frame N ---" separator.
std::vector<std::vector<std::string>> Frames(const std::string& text) {
    std::vector<std::vector<std::string>> frames;
    for (const std::string& line : Lines(text)) {
        if (line == "--- frame " + std::to_string(frames.size()) + " ---")
            frames.emplace_back();
        else if (!frames.empty())
            frames.back().push_back(line);
    }
    return frames;
}

TEST(ViewerKeys, DecodesBytesAndArrows) {
    const std::vector<int> expected = {'h', kKeyUp, kKeyDown, kKeyRight, kKeyLeft, 'q'};
    EXPECT_EQ(DecodeKeys("h\x1b[A\x1b[B\x1b[C\x1b[Dq"), expected);
    EXPECT_EQ(DecodeKeys("\x1bOA"), std::vector<int>{kKeyUp});        // application mode
    EXPECT_EQ(DecodeKeys("\x1b[1;5C"), std::vector<int>{kKeyRight});  // with a modifier
    EXPECT_EQ(DecodeKeys("\x1b[5~x"), std::vector<int>{'x'});         // Page Up: dropped
    EXPECT_EQ(DecodeKeys("\x03"), std::vector<int>{kKeyCtrlC});
}

TEST(ViewerKeys, LoneEscapeWaitsForFlush) {
    KeyDecoder decoder;
    EXPECT_TRUE(decoder.Feed("\x1b").empty());
    EXPECT_TRUE(decoder.Pending());
    EXPECT_EQ(decoder.Flush(), std::vector<int>{kKeyEscape});
    EXPECT_FALSE(decoder.Pending());
    // A sequence split across reads still decodes; ESC followed by a plain key is Escape + key.
    EXPECT_TRUE(decoder.Feed("\x1b[").empty());
    EXPECT_EQ(decoder.Feed("D"), std::vector<int>{kKeyLeft});
    EXPECT_EQ(decoder.Feed("\x1bq"), (std::vector<int>{kKeyEscape, 'q'}));
}

TEST(ViewerKeys, AzimuthWrapsElevationClamps) {
    ViewState s;
    EXPECT_TRUE(ApplyKey(&s, kKeyLeft));
    EXPECT_DOUBLE_EQ(s.azimuthDeg, 355.0);
    EXPECT_TRUE(ApplyKey(&s, 'l'));
    EXPECT_DOUBLE_EQ(s.azimuthDeg, 0.0);
    for (int i = 0; i < 17; ++i) EXPECT_TRUE(ApplyKey(&s, 'k'));
    EXPECT_DOUBLE_EQ(s.elevationDeg, 85.0);
    EXPECT_FALSE(ApplyKey(&s, kKeyUp));  // clamped: no change, no redraw
    EXPECT_TRUE(ApplyKey(&s, kKeyDown));
    EXPECT_DOUBLE_EQ(s.elevationDeg, 80.0);
    EXPECT_TRUE(ApplyKey(&s, 'u'));
    EXPECT_TRUE(ApplyKey(&s, 'd'));
    EXPECT_TRUE(ApplyKey(&s, 'd'));
    EXPECT_DOUBLE_EQ(s.heightOffsetDeg, -5.0);
}

TEST(ViewerKeys, ZoomAndThresholdClamp) {
    ViewState s;
    EXPECT_TRUE(ApplyKey(&s, '+'));
    EXPECT_DOUBLE_EQ(s.distanceScale, 0.9);
    EXPECT_TRUE(ApplyKey(&s, '-'));
    EXPECT_NEAR(s.distanceScale, 1.0, 1e-12);
    for (int i = 0; i < 100; ++i) ApplyKey(&s, '=');
    EXPECT_DOUBLE_EQ(s.distanceScale, 0.2);
    EXPECT_FALSE(ApplyKey(&s, '+'));
    for (int i = 0; i < 100; ++i) ApplyKey(&s, '-');
    EXPECT_DOUBLE_EQ(s.distanceScale, 10.0);
    for (int i = 0; i < 100; ++i) ApplyKey(&s, '[');
    EXPECT_DOUBLE_EQ(s.t, 1.0);
    EXPECT_FALSE(ApplyKey(&s, '['));
    for (int i = 0; i < 100; ++i) ApplyKey(&s, ']');
    EXPECT_DOUBLE_EQ(s.t, 64.0);
}

TEST(ViewerKeys, ModesResetAndQuit) {
    ViewState s;
    EXPECT_TRUE(ApplyKey(&s, '4'));
    EXPECT_EQ(s.mode, ViewMode::RayTraced);
    EXPECT_FALSE(ApplyKey(&s, '4'));
    EXPECT_TRUE(ApplyKey(&s, 'm'));
    EXPECT_EQ(s.mode, ViewMode::Difference);
    EXPECT_TRUE(ApplyKey(&s, 'm'));
    EXPECT_EQ(s.mode, ViewMode::Hybrid);
    EXPECT_FALSE(ApplyKey(&s, '6'));
    EXPECT_FALSE(ApplyKey(&s, 'x'));
    // Reset returns pose and t to `home` and keeps the mode.
    const ViewState home{30.0, 10.0, 2.0, 0.0, ViewMode::Hybrid, 3.0, false};
    ApplyKey(&s, '2');
    ApplyKey(&s, 'h');
    ApplyKey(&s, ']');
    EXPECT_TRUE(ApplyKey(&s, 'r', home));
    EXPECT_EQ(s, (ViewState{30.0, 10.0, 2.0, 0.0, ViewMode::Pem, 3.0, false}));
    for (int key : {int{'q'}, kKeyEscape, kKeyCtrlC}) {
        ViewState t;
        EXPECT_TRUE(ApplyKey(&t, key));
        EXPECT_TRUE(t.quit) << key;
    }
}

TEST(ViewerStatus, ContentAndCut) {
    ViewState s;
    s.azimuthDeg = 15.0;
    s.mode = ViewMode::StaticEm;
    const std::string line = StatusLine(s, 12.25, "err\t3.5", 200);
    EXPECT_NE(StatusLine(s, 3.46, "", 200).find("| 3.5 fps"), std::string::npos);
    EXPECT_EQ(line,
              "static-em az 15\xc2\xb0 el 0\xc2\xb0 dist 1 off 0\xc2\xb0 t 5 | 12 fps | err 3.5");
    EXPECT_EQ(StatusLine(s, -1.0, "", 200).find("fps"), std::string::npos);
    EXPECT_EQ(StatusLine(s, -1.0, "", 15), "static-em az 15");
    EXPECT_EQ(StatusLine(s, -1.0, "", 16), "static-em az 15\xc2\xb0");  // ° is one column
    // Fractions show only where they exist; the distance with 3 significant digits.
    const ViewState odd{352.5, -85.0, 0.729, 12.5, ViewMode::Pem, 64.0, false};
    EXPECT_EQ(StatusLine(odd, 1234.4, "", 200),
              "pem az 352.5\xc2\xb0 el -85\xc2\xb0 dist 0.729 off 12.5\xc2\xb0 t 64 | 1234 fps");
}

TEST(ViewerScripted, OneFramePerKey) {
    ViewerOptions options;
    options.keys = "l3\x1b[A";
    options.cols = 60;
    options.rows = 4;
    const ScriptedRun run = RunScripted(options);
    EXPECT_EQ(run.rc, 0);
    const auto frames = Frames(run.text);
    ASSERT_EQ(frames.size(), 4u);
    for (const auto& frame : frames) {
        ASSERT_EQ(frame.size(), 4u);  // 3 image rows + the status line
        for (int row = 0; row < 3; ++row)
            EXPECT_NE(frame[static_cast<size_t>(row)].find("\xe2\x96\x80"), std::string::npos);
    }
    // The renderer saw cols × 2·(rows − 1) pixels and the state after each key.
    ASSERT_EQ(run.states.size(), 4u);
    for (const auto& size : run.sizes) EXPECT_EQ(size, std::make_pair(60, 6));
    EXPECT_DOUBLE_EQ(run.states[1].azimuthDeg, 5.0);
    EXPECT_EQ(run.states[1].mode, ViewMode::Hybrid);
    EXPECT_EQ(run.states[2].mode, ViewMode::StaticEm);
    EXPECT_DOUBLE_EQ(run.states[3].elevationDeg, 5.0);
    // The mode key changed the picture (red = 40·mode) and the status line.
    EXPECT_NE(frames[1][0].find("\x1b[38;2;0;1;7m"), std::string::npos);
    EXPECT_NE(frames[2][0].find("\x1b[38;2;80;1;7m"), std::string::npos);
    EXPECT_EQ(frames[1][3].rfind("hybrid az 5\xc2\xb0", 0), 0u);
    EXPECT_EQ(frames[2][3].rfind("static-em", 0), 0u);
    EXPECT_NE(frames[3][3].find("el 5\xc2\xb0"), std::string::npos);
    EXPECT_EQ(frames[3][3].find("fps"), std::string::npos);  // deterministic text
}

TEST(ViewerScripted, DefaultSizeAndQuitKey) {
    ViewerOptions options;
    options.keys = "lqll";
    const ScriptedRun run = RunScripted(options);
    EXPECT_EQ(run.rc, 0);
    const auto frames = Frames(run.text);
    ASSERT_EQ(frames.size(), 2u);  // the initial frame and 'l'; 'q' ends the run
    EXPECT_EQ(frames[0].size(), 24u);
    EXPECT_EQ(run.sizes[0], std::make_pair(80, 46));
}

TEST(ViewerScripted, FramesWithoutKeysRepeatTheState) {
    ViewerOptions options;
    options.frames = 3;
    options.cols = 80;
    options.rows = 2;
    ViewState initial;
    initial.mode = ViewMode::Difference;
    const ScriptedRun run = RunScripted(options, initial);
    EXPECT_EQ(run.rc, 0);
    const auto frames = Frames(run.text);
    ASSERT_EQ(frames.size(), 3u);
    for (const auto& frame : frames) {
        ASSERT_EQ(frame.size(), 2u);
        EXPECT_EQ(frame, frames[0]);
        EXPECT_EQ(frame[1],
                  "difference az 0\xc2\xb0 el 0\xc2\xb0 dist 1 off 0\xc2\xb0 t 5 | fake info");
    }
    for (const ViewState& s : run.states) EXPECT_EQ(s, initial);
    // frames < keys: stops early; frames > keys: the last state repeats.
    options.keys = "lll";
    options.frames = 2;
    EXPECT_EQ(Frames(RunScripted(options).text).size(), 2u);
    options.frames = 6;
    const ScriptedRun longer = RunScripted(options);
    ASSERT_EQ(longer.states.size(), 6u);
    EXPECT_DOUBLE_EQ(longer.states[5].azimuthDeg, 15.0);
}

TEST(ViewerScripted, QuietPrintsOnlyStatusLines) {
    ViewerOptions options;
    options.frames = 2;
    options.quiet = true;
    const auto frames = Frames(RunScripted(options).text);
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(frames[0].size(), 1u);
    EXPECT_EQ(frames[0][0].rfind("hybrid", 0), 0u);
    options.cols = 8;  // the status line is cut to the screen width
    EXPECT_EQ(Frames(RunScripted(options).text)[0][0], "hybrid a");
}

TEST(ViewerInteractive, NotATerminal) {
    std::FILE* out = std::tmpfile();
    ASSERT_NE(out, nullptr);
    testing::internal::CaptureStderr();
    const int rc = RunViewer(
        ViewerOptions{}, ViewState{}, [](const ViewState& s, int, int) { return FakeFrame(s); },
        out);
    const std::string err = testing::internal::GetCapturedStderr();
    std::fclose(out);
    EXPECT_EQ(rc, 2);
    EXPECT_EQ(err, "pemref view: not a terminal (use --keys/--frames)\n");
}

}  // namespace
}  // namespace pem::tty
