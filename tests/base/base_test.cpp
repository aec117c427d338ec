// SPDX-License-Identifier: MIT
// base_test.cpp — base/: SHA-256 (FIPS 180-4 / NIST vectors), PNG output, atomic files and the
// parallel loop.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/atomic_file.h"
#include "base/directory_lock.h"
#include "base/exr_header.h"
#include "base/input_error.h"
#include "base/parallel.h"
#include "base/png_io.h"
#include "base/sha256.h"
#include "base/xml_text.h"

namespace pem::base {
namespace {

std::string HashOf(const std::string& text) {
    return Sha256Hex(reinterpret_cast<const uint8_t*>(text.data()), text.size());
}

std::filesystem::path FreshDir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("pem_base_test_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

size_t FilesIn(const std::filesystem::path& dir) {
    return static_cast<size_t>(std::distance(std::filesystem::directory_iterator(dir),
                                             std::filesystem::directory_iterator{}));
}

TEST(Sha256, FipsVectors) {
    EXPECT_EQ(HashOf(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    EXPECT_EQ(HashOf("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    EXPECT_EQ(HashOf("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
              "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
    EXPECT_EQ(
        HashOf("abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmnoijklmnopjklmnopq"
               "klmnopqrlmnopqrsmnopqrstnopqrstu"),
        "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1");
}

TEST(Sha256, MillionA) {
    EXPECT_EQ(HashOf(std::string(1000000, 'a')),
              "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, NullPointerEmpty) {
    EXPECT_EQ(Sha256Hex(nullptr, 0),
              "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

// PNG ------------------------------------------------------------------------------------------

TEST(XmlText, EscapesMarkupAndQuotesOnly) {
    EXPECT_EQ(base::XmlEscaped(R"(a<b & "c"> it's)"), "a&lt;b &amp; &quot;c&quot;&gt; it's");
    EXPECT_EQ(base::XmlEscaped("10\xc2\xb0 above"), "10\xc2\xb0 above");  // UTF-8 kept
    EXPECT_EQ(base::XmlEscaped(""), "");
}

// The one-line error CheckExrHeader gives, or "" when it accepts the file.
std::string ExrHeaderError(const std::string& path) {
    try {
        CheckExrHeader(path);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(ExrHeader, AcceptsRealFilesRefusesClaimsBeyondTheFile) {
    const std::string src = PEM_SOURCE_DIR;
    EXPECT_EQ(ExrHeaderError(src + "/data/env/sky.exr"), "");
    EXPECT_EQ(ExrHeaderError(src + "/data/env/studio.exr"), "");
    // The fuzzer's files (an attribute claiming 1,768,685,682 bytes in a 44-byte file, a channel
    // list that desynchronizes the C++ parser, a data window at 0x3e3e3e3e): refused up front.
    for (const char* name : {"attribute_size_1768685682.exr", "data_window_huge_269_bytes.exr",
                             "data_window_origin_overflow.exr"}) {
        const std::string fuzzed = src + "/tests/data/fuzz_regressions/exr/" + name;
        EXPECT_EQ(ExrHeaderError(fuzzed).rfind(fuzzed + ": not a valid OpenEXR file: ", 0), 0u)
            << ExrHeaderError(fuzzed);
    }
    // Cut anywhere inside the header, a real file is refused with one line naming it.
    std::ifstream in(src + "/data/env/sky.exr", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string cut = (std::filesystem::temp_directory_path() / "pem_cut.exr").string();
    for (size_t n : {size_t{0}, size_t{3}, size_t{8}, size_t{20}, size_t{100}}) {
        std::ofstream(cut, std::ios::binary) << bytes.substr(0, n);
        EXPECT_EQ(ExrHeaderError(cut).rfind(cut + ": ", 0), 0u) << n;
    }
    std::filesystem::remove(cut);
    EXPECT_THROW(CheckExrSize("x.exr", 16385, 8192), InputError);
    EXPECT_THROW(CheckExrSize("x.exr", 0, 1), InputError);
    EXPECT_NO_THROW(CheckExrSize("x.exr", 4096, 6 * 4096));
}

TEST(Png, WritesSignatureAndLeavesNoTemp) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("pem_png_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "a.png").string();
    Image8 image{3, 2, std::vector<uint8_t>(3 * 2 * 4, 77)};
    WritePng(path, image);
    std::ifstream in(path, std::ios::binary);
    char signature[8] = {};
    in.read(signature, 8);
    EXPECT_EQ(std::string(signature + 1, 3), "PNG");
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                            std::filesystem::directory_iterator{}),
              1);
    std::filesystem::remove_all(dir);
}

TEST(Png, BadPathThrowsWithPath) {
    const std::string path = "/nonexistent_dir_pem/x.png";
    try {
        WritePng(path, Image8{1, 1, {0, 0, 0, 0}});
        FAIL() << "no exception";
    } catch (const base::InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
    }
}

TEST(Png, ReadsBackWhatWasWrittenAndRefusesGarbage) {
    const auto dir = FreshDir("png_read");
    Image8 image{5, 3, {}};
    for (int k = 0; k < 5 * 3 * 4; ++k) image.rgba.push_back(uint8_t(k * 17 % 251));
    WritePng((dir / "a.png").string(), image);
    EXPECT_EQ(ReadPng((dir / "a.png").string()), image);
    std::ofstream(dir / "bad.png") << "\x89PNG\r\n\x1a\n garbage";
    EXPECT_THROW(ReadPng((dir / "bad.png").string()), InputError);
    EXPECT_THROW(ReadPng((dir / "none.png").string()), InputError);
    std::filesystem::remove_all(dir);
}

// Atomic files ---------------------------------------------------------------------------------

TEST(AtomicFile, WriterThatThrowsLeavesNothing) {
    const auto dir = FreshDir("atomic");
    const std::string path = (dir / "a.txt").string();
    WriteTextAtomic(path, "old");
    EXPECT_THROW(WriteAtomically(path,
                                 [](const std::string& tmp) {
                                     std::ofstream(tmp) << "half";
                                     throw std::runtime_error("disk full");
                                 }),
                 InputError);
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    EXPECT_EQ(text, "old");       // the old file is untouched
    EXPECT_EQ(FilesIn(dir), 1u);  // and no temporary is left
    std::filesystem::remove_all(dir);
}

TEST(AtomicFile, SeveralFilesAllOrNone) {
    const auto dir = FreshDir("atomic_many");
    const std::string a = (dir / "a.txt").string();
    EXPECT_THROW(WriteTextsAtomic({{a, "A"}, {(dir / "no_such_dir" / "b.txt").string(), "B"}}),
                 InputError);
    EXPECT_EQ(FilesIn(dir), 0u);
    WriteTextsAtomic({{a, "A"}, {(dir / "b.txt").string(), "B"}});
    EXPECT_EQ(FilesIn(dir), 2u);
    std::filesystem::remove_all(dir);
}

// A directory output: refused over a directory that is not an earlier output, left untouched
// when the writer throws, replaced whole when it returns.
TEST(AtomicFile, DirectoryAllOrNone) {
    const auto dir = FreshDir("atomic_dir");
    const std::string out = (dir / "study").string();
    std::filesystem::create_directories(out);
    std::ofstream(out + "/notes.txt") << "mine";
    int calls = 0;
    const auto write = [&](const std::string& tmp) {
        ++calls;
        WriteTextAtomic(tmp + "/study.json", "new");
    };
    EXPECT_THROW(WriteDirectoryAtomically(out, "study.json", write), InputError);
    EXPECT_EQ(calls, 0);  // refused before any work
    std::filesystem::remove(out + "/notes.txt");
    WriteDirectoryAtomically(out, "study.json", write);  // an empty directory is taken
    EXPECT_EQ(FilesIn(out), 1u);
    EXPECT_THROW(WriteDirectoryAtomically(out, "study.json",
                                          [](const std::string& tmp) {
                                              std::ofstream(tmp + "/half") << "x";
                                              throw std::runtime_error("disk full");
                                          }),
                 InputError);
    EXPECT_EQ(FilesIn(dir), 1u);  // the earlier output only, no temporary directory
    EXPECT_TRUE(std::filesystem::exists(out + "/study.json"));
    WriteDirectoryAtomically(out, "study.json", [](const std::string& tmp) {
        WriteTextAtomic(tmp + "/study.json", "newer");
    });
    std::ifstream in(out + "/study.json");
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), {}), "newer");
    std::filesystem::remove_all(dir);
}

TEST(AtomicFile, RemoveTemporariesClearsKilledRuns) {
    const auto dir = FreshDir("stale");
    std::filesystem::create_directories(dir / "sub");
    std::ofstream(dir / "sub" / "x.exr.tmp.123") << "stale";
    std::ofstream(dir / "sub" / "x.exr") << "kept";
    RemoveTemporaries(dir.string());
    EXPECT_FALSE(std::filesystem::exists(dir / "sub" / "x.exr.tmp.123"));
    EXPECT_TRUE(std::filesystem::exists(dir / "sub" / "x.exr"));
    std::filesystem::remove_all(dir);
}

// Directory lock ----------------------------------------------------------------------------------

TEST(DirectoryLock, SecondHolderRefusedUntilTheFirstIsGone) {
    const auto dir = FreshDir("lock");
    {
        const DirectoryLock first(dir.string());
        try {
            const DirectoryLock second(dir.string());
            FAIL() << "a second lock was granted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("another pemref job"), std::string::npos);
            EXPECT_NE(std::string(e.what()).find(std::to_string(getpid())), std::string::npos);
        }
    }
    EXPECT_NO_THROW(DirectoryLock again(dir.string()));  // released with its holder
    std::filesystem::remove_all(dir);
}

// Parallel loop --------------------------------------------------------------------------------

TEST(ParallelFor, EveryItemOnceAnyThreadCount) {
    for (int threads : {1, 2, 3, 8}) {
        std::vector<std::atomic<int>> seen(1000);
        ParallelFor(1000, threads, [&](int i) { ++seen[static_cast<size_t>(i)]; });
        for (const auto& s : seen) ASSERT_EQ(s.load(), 1) << threads << " threads";
    }
}

TEST(ParallelFor, LowestFailingItemIsRethrown) {
    try {
        ParallelFor(100, 3, [](int i) {
            if (i == 17 || i == 60) throw std::runtime_error(std::to_string(i));
        });
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "17");
    }
}

TEST(ParallelFor, NestedLoopRunsInline) {
    std::atomic<int> total{0};
    ParallelFor(4, 2, [&](int) { ParallelFor(10, 4, [&](int) { ++total; }); });
    EXPECT_EQ(total.load(), 40);
}

TEST(ForRanges, SplitDependsOnlyOnArguments) {
    for (int threads : {1, 2, 5}) {
        std::vector<int> owner(1000, -1);
        ForRanges(1000, threads, 100, [&](int64_t b, int64_t e) {
            for (int64_t k = b; k < e; ++k) owner[static_cast<size_t>(k)] = static_cast<int>(b);
        });
        for (size_t k = 0; k < owner.size(); ++k) ASSERT_GE(owner[k], 0);
        const int64_t chunk = (1000 + threads - 1) / threads;
        for (size_t k = 0; k < owner.size(); ++k)
            ASSERT_EQ(owner[k], static_cast<int>(static_cast<int64_t>(k) / chunk * chunk));
    }
}

}  // namespace
}  // namespace pem::base
