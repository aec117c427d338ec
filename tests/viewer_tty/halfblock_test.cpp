// SPDX-License-Identifier: MIT
// halfblock_test.cpp — the truecolor half-block printer (exact bytes of a 2×4 image, integer
// box-filter resampling down and up, one escape per colour change) and the progress line (text
// format; silent on a non-terminal; written on a pseudo-terminal).
// Conventions: tiny inline images. Not here: a tmux capture of the output.
#include "viewer_tty/tty/halfblock.h"

#include <gtest/gtest.h>
#include <pty.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "viewer_tty/tty/progress.h"

namespace pem::tty {
namespace {

using Rgb = std::array<uint8_t, 3>;

base::Image8 MakeImage(int width, int height, const std::vector<Rgb>& pixels) {
    base::Image8 img{width, height, {}};
    for (const Rgb& p : pixels) img.rgba.insert(img.rgba.end(), {p[0], p[1], p[2], 255});
    return img;
}

size_t Count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

const std::string kBlock = "\xe2\x96\x80";

TEST(HalfBlock, ExactTwoByFour) {
    const Rgb red{255, 0, 0}, green{0, 255, 0}, blue{0, 0, 255}, grey{7, 8, 9};
    // Rows top-down: (red, green) / (blue, blue) / (red, red) / (grey, grey).
    const base::Image8 img = MakeImage(2, 4, {red, green, blue, blue, red, red, grey, grey});
    const std::string expected =
        "\x1b[38;2;255;0;0m\x1b[48;2;0;0;255m" + kBlock +  // cell (0, 0): red over blue
        "\x1b[38;2;0;255;0m" + kBlock +                    // cell (1, 0): only fg changes
        "\x1b[0m\n" +                                      // row end
        "\x1b[38;2;255;0;0m\x1b[48;2;7;8;9m" + kBlock +    // row 1 starts afresh
        kBlock + "\x1b[0m";                                // same colours: no escape
    EXPECT_EQ(HalfBlockFrame(img, 2, 2), expected);
}

TEST(HalfBlock, BoxFilterDownsamples) {
    // 4×2 → 2 cells × 1 row (2×2 pixels): each target averages a 2×1 block, rounding half up.
    const base::Image8 img = MakeImage(4, 2,
                                       {{0, 10, 255},
                                        {1, 11, 0},
                                        {1, 10, 0},
                                        {1, 11, 0},
                                        {0, 0, 0},
                                        {0, 0, 0},
                                        {200, 0, 0},
                                        {201, 0, 0}});
    const std::string expected = "\x1b[38;2;1;11;128m\x1b[48;2;0;0;0m" + kBlock +
                                 "\x1b[38;2;1;11;0m\x1b[48;2;201;0;0m" + kBlock + "\x1b[0m";
    EXPECT_EQ(HalfBlockFrame(img, 2, 1), expected);
}

TEST(HalfBlock, BoxFilterNonIntegerRatio) {
    // 3 → 2 columns: weights (2, 1) and (1, 2) over 3.
    const base::Image8 img = MakeImage(
        3, 2, {{0, 0, 0}, {255, 255, 255}, {30, 30, 30}, {0, 0, 0}, {255, 255, 255}, {30, 30, 30}});
    const std::string expected = "\x1b[38;2;85;85;85m\x1b[48;2;85;85;85m" + kBlock +
                                 "\x1b[38;2;105;105;105m\x1b[48;2;105;105;105m" + kBlock +
                                 "\x1b[0m";
    EXPECT_EQ(HalfBlockFrame(img, 2, 1), expected);
}

TEST(HalfBlock, UpsamplesOnePixel) {
    const base::Image8 img = MakeImage(1, 1, {{1, 2, 3}});
    EXPECT_EQ(HalfBlockFrame(img, 3, 2),
              "\x1b[38;2;1;2;3m\x1b[48;2;1;2;3m" + kBlock + kBlock + kBlock + "\x1b[0m\n" +
                  "\x1b[38;2;1;2;3m\x1b[48;2;1;2;3m" + kBlock + kBlock + kBlock + "\x1b[0m");
    EXPECT_EQ(HalfBlockFrame(img, 0, 2), "");
    EXPECT_EQ(HalfBlockFrame(base::Image8{}, 3, 2), "");
}

TEST(HalfBlock, OneEscapePerColourChange) {
    // 8×8 at 1:1 (8 cols × 4 rows): stripes change every 3 columns on top rows, every 2 below.
    std::vector<Rgb> pixels;
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 8; ++x) {
            const int band = y % 2 == 0 ? x / 3 : x / 2;
            pixels.push_back({static_cast<uint8_t>(40 * band), static_cast<uint8_t>(y), 0});
        }
    }
    const std::string frame = HalfBlockFrame(MakeImage(8, 8, pixels), 8, 4);
    // Per row: fg runs 3 (bands 0,1,2), bg runs 4 (bands 0..3).
    EXPECT_EQ(Count(frame, "\x1b[38;2;"), 4u * 3u);
    EXPECT_EQ(Count(frame, "\x1b[48;2;"), 4u * 4u);
    EXPECT_EQ(Count(frame, kBlock), 8u * 4u);
    EXPECT_EQ(Count(frame, "\x1b[0m"), 4u);
    EXPECT_EQ(Count(frame, "\n"), 3u);
}

TEST(HalfBlock, TerminalSizeIsPositive) {
    const TermSize size = TerminalSize();
    EXPECT_GT(size.cols, 0);
    EXPECT_GT(size.rows, 0);
}

TEST(Progress, Text) {
    EXPECT_EQ(ProgressText("render", 0.42, 12.0), "\rrender 42% ETA 0:12\x1b[K");
    EXPECT_EQ(ProgressText("bake", 1.0, 0.0), "\rbake 100% ETA 0:00\x1b[K");
    EXPECT_EQ(ProgressText("bake", 0.0, -1.0), "\rbake 0% ETA -:--\x1b[K");
    EXPECT_EQ(ProgressText("x", 0.999, 754.4), "\rx 99% ETA 12:34\x1b[K");
}

std::string ReadAll(std::FILE* f) {
    std::rewind(f);
    std::string text;
    for (int c = std::fgetc(f); c != EOF; c = std::fgetc(f)) text += static_cast<char>(c);
    return text;
}

TEST(Progress, SilentUnlessTerminal) {
    std::FILE* file = std::tmpfile();
    ASSERT_NE(file, nullptr);
    {
        ProgressLine line("work", false, file);
        EXPECT_FALSE(line.Enabled());
        line.Update(0.5);
    }
    EXPECT_EQ(ReadAll(file), "");
    std::fclose(file);
}

TEST(Progress, WritesOnTerminalAndEndsLine) {
    int master = -1, slave = -1;
    if (openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) GTEST_SKIP() << "no pty";
    std::FILE* tty = fdopen(slave, "w");
    ASSERT_NE(tty, nullptr);
    {
        ProgressLine quiet("work", true, tty);
        EXPECT_FALSE(quiet.Enabled());
        ProgressLine line("work", false, tty);
        EXPECT_TRUE(line.Enabled());
        line.Update(0.5);
        line.Update(0.6);  // within 100 ms: rate-limited
        line.Finish();
    }
    std::fclose(tty);
    // Everything written, however the pty splits it: read until the closed slave gives EOF/EIO.
    std::string text;
    char buffer[512];
    for (ssize_t n; (n = read(master, buffer, sizeof buffer)) > 0;)
        text.append(buffer, static_cast<size_t>(n));
    close(master);
    ASSERT_FALSE(text.empty());
    EXPECT_EQ(text.rfind("\rwork 50% ETA ", 0), 0u) << text;
    EXPECT_NE(text.find("\rwork 60% ETA "), std::string::npos) << text;  // Finish shows the last
    EXPECT_EQ(Count(text, "\r"), 2u + 1u) << text;  // the pty turns "\n" into "\r\n"
}

}  // namespace
}  // namespace pem::tty
