// SPDX-License-Identifier: MIT
// image.cpp — FloatImage helpers and the OpenEXR writer (see image.h).
#include "trace/image.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>

#include "base/atomic_file.h"
#include "base/exr_header.h"
#include "base/input_error.h"

namespace pem::trace {

void FloatImage::Add(int x, int y, const glm::vec3& rgb, float alpha) {
    float* p = At(x, y);
    if (channels == 1) {
        p[0] += rgb.x;
        return;
    }
    p[0] += rgb.x, p[1] += rgb.y, p[2] += rgb.z;
    if (channels == 4) p[3] += alpha;
}

void FloatImage::Scale(float s) {
    for (float& v : data) v *= s;
}

glm::ivec2 SampleCell(int x, int y, int k, int s) {
    return {k * x + s % k, k * y + s / k};
}

FloatImage BoxFilter(const FloatImage& samples, int k) {
    FloatImage out(samples.width / k, samples.height / k, samples.channels);
    const size_t ch = static_cast<size_t>(samples.channels);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            float* p = out.At(x, y);
            for (int s = 0; s < k * k; ++s) {
                const glm::ivec2 cell = SampleCell(x, y, k, s);
                const float* q = samples.At(cell.x, cell.y);
                for (size_t c = 0; c < ch; ++c) p[c] += q[c];
            }
        }
    out.Scale(1.0f / static_cast<float>(k * k));
    return out;
}

namespace {

const char* ChannelName(int channels, int c) {
    static const char* const kRgba[] = {"R", "G", "B", "A"};
    return channels == 1 ? "Y" : kRgba[c];
}

void WriteExrFile(const std::string& path, const FloatImage& image) {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer frame;
    const size_t xStride = sizeof(float) * static_cast<size_t>(image.channels);
    for (int c = 0; c < image.channels; ++c) {
        header.channels().insert(ChannelName(image.channels, c), Imf::Channel(Imf::FLOAT));
        // OpenEXR wants a non-const base pointer; it only reads through it when writing.
        char* base = reinterpret_cast<char*>(const_cast<float*>(image.data.data() + c));
        frame.insert(ChannelName(image.channels, c),
                     Imf::Slice(Imf::FLOAT, base, xStride, xStride * image.width));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(image.height);
}

}  // namespace

void WriteExr(const std::string& path, const FloatImage& image) {
    if (image.width <= 0 || image.height <= 0) throw base::InputError(path, "empty image");
    base::WriteAtomically(path, [&](const std::string& tmp) {
        try {
            WriteExrFile(tmp, image);
        } catch (const std::exception& e) {
            throw std::runtime_error(std::string("cannot write OpenEXR: ") + e.what());
        }
    });
}

FloatImage ReadExr(const std::string& path) {
    base::CheckExrHeader(path);
    FloatImage image;
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        base::CheckExrSize(path, int64_t{dw.max.x} - dw.min.x + 1,
                           int64_t{dw.max.y} - dw.min.y + 1);
        const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
        const Imf::ChannelList& ch = file.header().channels();
        int channels = 0;
        if (ch.findChannel("R") && ch.findChannel("G") && ch.findChannel("B"))
            channels = ch.findChannel("A") ? 4 : 3;
        else if (ch.findChannel("Y"))
            channels = 1;
        else
            throw base::InputError(path, "no Y or R,G,B channels");
        image = FloatImage(w, h, channels);
        Imf::FrameBuffer frame;
        const size_t xStride = sizeof(float) * static_cast<size_t>(channels);
        // Slice::Make places the data window's origin at the buffer's start without pointer
        // arithmetic outside it (any origin a file claims).
        for (int c = 0; c < channels; ++c)
            frame.insert(ChannelName(channels, c),
                         Imf::Slice::Make(Imf::FLOAT, image.data.data() + c, dw, xStride,
                                          xStride * static_cast<size_t>(w)));
        file.setFrameBuffer(frame);
        file.readPixels(dw.min.y, dw.max.y);
    } catch (const base::InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw base::InputError(path, std::string("cannot read OpenEXR: ") + e.what());
    }
    for (float v : image.data)
        if (!std::isfinite(v)) throw base::InputError(path, "non-finite pixel value");
    return image;
}

}  // namespace pem::trace
