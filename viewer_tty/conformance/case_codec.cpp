// SPDX-License-Identifier: MIT
// case_codec.cpp — base64/hex codecs and texel generators for gl_ref_case/1.
// Conventions: generators loop level, face, row j, column i (the documented stream order);
// random_box on non-square levels clamps the 2x2 footprint to the previous level's edge.
// Not here: validation of sizes (the caller passes powers of two and valid level counts).
#include "viewer_tty/conformance/case_codec.h"

#include <algorithm>
#include <array>

namespace pem::conformance {

namespace {

constexpr std::string_view kBase64Alphabet =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

int Base64Value(char c) {
    size_t pos = kBase64Alphabet.find(c);
    return pos == std::string_view::npos ? -1 : static_cast<int>(pos);
}

int HexValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

// Number of '=' at the end of a base64 text (0..2), or -1 if padding is malformed.
int Base64Padding(std::string_view text) {
    int pad = 0;
    while (pad < static_cast<int>(text.size()) && text[text.size() - 1 - size_t(pad)] == '=') ++pad;
    return pad > 2 ? -1 : pad;
}

using Level = std::vector<uint8_t>;

// One `random` level: one splitmix64 draw per texel, faces x rows x columns.
Level RandomLevel(SplitMix64* rng, int faces, int w, int h, int alpha) {
    Level out;
    out.reserve(size_t(faces) * size_t(w) * size_t(h) * 4);
    for (int t = 0; t < faces * w * h; ++t) {
        uint64_t v = rng->Next();
        out.push_back(static_cast<uint8_t>(v & 255));
        out.push_back(static_cast<uint8_t>((v >> 8) & 255));
        out.push_back(static_cast<uint8_t>((v >> 16) & 255));
        out.push_back(alpha < 0 ? static_cast<uint8_t>((v >> 24) & 255)
                                : static_cast<uint8_t>(alpha));
    }
    return out;
}

// 2x2 box filter of `src` (w x h per face) into a level of max(1,w/2) x max(1,h/2).
Level BoxLevel(const Level& src, int faces, int w, int h) {
    const int dw = std::max(1, w / 2), dh = std::max(1, h / 2);
    Level out(size_t(faces) * size_t(dw) * size_t(dh) * 4);
    auto at = [&](int f, int i, int j, int c) {
        i = std::min(i, w - 1);
        j = std::min(j, h - 1);
        return int{
            src[((size_t(f) * size_t(h) + size_t(j)) * size_t(w) + size_t(i)) * 4 + size_t(c)]};
    };
    size_t k = 0;
    for (int f = 0; f < faces; ++f)
        for (int j = 0; j < dh; ++j)
            for (int i = 0; i < dw; ++i)
                for (int c = 0; c < 4; ++c)
                    out[k++] = static_cast<uint8_t>(
                        (at(f, 2 * i, 2 * j, c) + at(f, 2 * i + 1, 2 * j, c) +
                         at(f, 2 * i, 2 * j + 1, c) + at(f, 2 * i + 1, 2 * j + 1, c) + 2) >>
                        2);
    return out;
}

// round(255 * x / (n - 1)) in integers, 128 for a one-texel edge.
uint8_t GradientRamp(int x, int n) {
    return n > 1 ? static_cast<uint8_t>((510 * x + (n - 1)) / (2 * (n - 1))) : uint8_t{128};
}

Level GradientLevel(int faces, int w, int h, int level, int alpha) {
    const int a = alpha >= 0 ? alpha : std::max(0, 255 - 16 * level);
    Level out;
    out.reserve(size_t(faces) * size_t(w) * size_t(h) * 4);
    for (int f = 0; f < faces; ++f)
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) {
                out.push_back(GradientRamp(i, w));
                out.push_back(GradientRamp(j, h));
                out.push_back(faces == 6 ? static_cast<uint8_t>(51 * f) : uint8_t{0});
                out.push_back(static_cast<uint8_t>(a));
            }
    return out;
}

}  // namespace

std::string Base64Encode(const std::vector<uint8_t>& bytes) {
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (size_t k = 0; k < bytes.size(); k += 3) {
        const size_t n = std::min<size_t>(3, bytes.size() - k);
        uint32_t group = uint32_t{bytes[k]} << 16;
        if (n > 1) group |= uint32_t{bytes[k + 1]} << 8;
        if (n > 2) group |= bytes[k + 2];
        for (size_t c = 0; c < 4; ++c)
            out.push_back(c <= n ? kBase64Alphabet[(group >> (18 - 6 * c)) & 63] : '=');
    }
    return out;
}

DecodeResult Base64Decode(std::string_view text) {
    DecodeResult result;
    const int pad = Base64Padding(text);
    if (text.size() % 4 != 0 || pad < 0) {
        result.error = "base64 length is not a padded multiple of 4";
        return result;
    }
    // Step 1: every non-padding character must be in the alphabet.
    const size_t dataChars = text.size() - size_t(pad);
    uint32_t group = 0;
    for (size_t k = 0; k < text.size(); ++k) {
        int v = k < dataChars ? Base64Value(text[k]) : 0;
        if (v < 0) {
            result.error = "invalid base64 character at offset " + std::to_string(k);
            return result;
        }
        group = (group << 6) | uint32_t(v);
        if (k % 4 != 3) continue;
        // Step 2: emit the 3 (or fewer, at the padded end) bytes of each 4-character group.
        const size_t keep = k + 1 == text.size() ? 3 - size_t(pad) : 3;
        for (size_t b = 0; b < keep; ++b)
            result.bytes.push_back(static_cast<uint8_t>(group >> (16 - 8 * b)));
        group = 0;
    }
    return result;
}

DecodeResult HexDecode(std::string_view text) {
    DecodeResult result;
    if (text.size() % 2 != 0) {
        result.error = "hex length is odd";
        return result;
    }
    for (size_t k = 0; k < text.size(); k += 2) {
        int hi = HexValue(text[k]), lo = HexValue(text[k + 1]);
        if (hi < 0 || lo < 0) {
            result.error = "invalid hex character at offset " + std::to_string(hi < 0 ? k : k + 1);
            return result;
        }
        result.bytes.push_back(static_cast<uint8_t>(hi * 16 + lo));
    }
    return result;
}

uint64_t SplitMix64::Next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

std::vector<std::vector<uint8_t>> GenerateTexels(raster::TextureKind kind, int width, int height,
                                                 int numLevels, const TexelGen& gen) {
    const int faces = kind == raster::TextureKind::Cube ? 6 : 1;
    SplitMix64 rng(gen.seed);
    std::vector<Level> levels;
    for (int l = 0; l < numLevels; ++l) {
        const int w = std::max(1, width >> l), h = std::max(1, height >> l);
        if (gen.kind == TexelGenKind::Gradient) {
            levels.push_back(GradientLevel(faces, w, h, l, gen.alpha));
        } else if (gen.kind == TexelGenKind::Random || l == 0) {
            levels.push_back(RandomLevel(&rng, faces, w, h, gen.alpha));
        } else {
            levels.push_back(BoxLevel(levels.back(), faces, std::max(1, width >> (l - 1)),
                                      std::max(1, height >> (l - 1))));
        }
    }
    return levels;
}

std::vector<uint8_t> FloatLevelFromBytes(const std::vector<uint8_t>& bytes) {
    std::vector<float> values(bytes.size());
    for (size_t i = 0; i < bytes.size(); ++i)
        values[i] = (static_cast<float>(bytes[i]) - 64.0f) / 64.0f;
    return raster::FloatBytes(values);
}

}  // namespace pem::conformance
