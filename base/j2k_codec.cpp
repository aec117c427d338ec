// SPDX-License-Identifier: MIT
// j2k_codec.cpp — JPEG 2000 through OpenJPEG (j2k_codec.h).
#include "base/j2k_codec.h"

#include <openjpeg.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace pem::base {
namespace {

// OpenJPEG streams over a byte vector.
struct Buffer {
    std::vector<uint8_t> bytes;
    size_t pos = 0;
};

OPJ_SIZE_T Read(void* out, OPJ_SIZE_T n, void* user) {
    Buffer* b = static_cast<Buffer*>(user);
    if (b->pos >= b->bytes.size()) return static_cast<OPJ_SIZE_T>(-1);
    const size_t k = std::min(n, b->bytes.size() - b->pos);
    std::memcpy(out, b->bytes.data() + b->pos, k);
    b->pos += k;
    return k;
}
OPJ_SIZE_T Write(void* in, OPJ_SIZE_T n, void* user) {
    Buffer* b = static_cast<Buffer*>(user);
    if (b->pos + n > b->bytes.size()) b->bytes.resize(b->pos + n);
    std::memcpy(b->bytes.data() + b->pos, in, n);
    b->pos += n;
    return n;
}
OPJ_OFF_T Skip(OPJ_OFF_T n, void* user) {
    Buffer* b = static_cast<Buffer*>(user);
    const OPJ_OFF_T to = std::clamp<OPJ_OFF_T>(static_cast<OPJ_OFF_T>(b->pos) + n, 0,
                                               static_cast<OPJ_OFF_T>(b->bytes.size()));
    const OPJ_OFF_T moved = to - static_cast<OPJ_OFF_T>(b->pos);
    b->pos = static_cast<size_t>(to);
    return moved;
}
OPJ_BOOL Seek(OPJ_OFF_T to, void* user) {
    Buffer* b = static_cast<Buffer*>(user);
    if (to < 0 || static_cast<size_t>(to) > b->bytes.size()) return OPJ_FALSE;
    b->pos = static_cast<size_t>(to);
    return OPJ_TRUE;
}

opj_stream_t* StreamOver(Buffer* b, bool input) {
    opj_stream_t* s = opj_stream_create(1 << 16, input ? OPJ_TRUE : OPJ_FALSE);
    opj_stream_set_user_data(s, b, nullptr);
    opj_stream_set_user_data_length(s, b->bytes.size());
    opj_stream_set_read_function(s, Read);
    opj_stream_set_write_function(s, Write);
    opj_stream_set_skip_function(s, Skip);
    opj_stream_set_seek_function(s, Seek);
    return s;
}

struct Owned {
    opj_codec_t* codec = nullptr;
    opj_stream_t* stream = nullptr;
    opj_image_t* image = nullptr;
    ~Owned() {
        if (stream) opj_stream_destroy(stream);
        if (codec) opj_destroy_codec(codec);
        if (image) opj_image_destroy(image);
    }
};

void Quiet(const char*, void*) {}

void Silence(opj_codec_t* codec) {
    opj_set_info_handler(codec, Quiet, nullptr);
    opj_set_warning_handler(codec, Quiet, nullptr);
    opj_set_error_handler(codec, Quiet, nullptr);
}

}  // namespace

std::vector<uint8_t> EncodeJ2k(const Image8Planes& img, double ratio, J2kWavelet wavelet) {
    if (img.width < 1 || img.height < 1 || img.channels < 1 || img.channels > 4 ||
        img.data.size() != static_cast<size_t>(img.width) * img.height * img.channels)
        throw std::runtime_error("j2k: bad image size");
    Owned o;
    std::vector<opj_image_cmptparm_t> parms(static_cast<size_t>(img.channels));
    for (opj_image_cmptparm_t& p : parms) {
        std::memset(&p, 0, sizeof p);
        p.dx = p.dy = 1;
        p.w = static_cast<OPJ_UINT32>(img.width);
        p.h = static_cast<OPJ_UINT32>(img.height);
        p.prec = 8;
        p.sgnd = 0;
    }
    o.image = opj_image_create(static_cast<OPJ_UINT32>(img.channels), parms.data(),
                               img.channels >= 3 ? OPJ_CLRSPC_SRGB : OPJ_CLRSPC_GRAY);
    if (!o.image) throw std::runtime_error("j2k: cannot create the image");
    o.image->x1 = static_cast<OPJ_UINT32>(img.width);
    o.image->y1 = static_cast<OPJ_UINT32>(img.height);
    const size_t n = static_cast<size_t>(img.width) * img.height;
    for (int c = 0; c < img.channels; ++c)
        for (size_t i = 0; i < n; ++i)
            o.image->comps[c].data[i] =
                img.data[i * static_cast<size_t>(img.channels) + static_cast<size_t>(c)];
    opj_cparameters_t p;
    opj_set_default_encoder_parameters(&p);
    p.irreversible = ratio > 1.0 && wavelet == J2kWavelet::Irreversible97 ? 1 : 0;
    p.tcp_mct = img.channels >= 3 ? 1 : 0;  // RCT (5/3) or ICT (9/7) of the first three channels
    int res = 1;
    while (res < 6 && (1 << res) <= std::min(img.width, img.height)) ++res;
    p.numresolution = res;
    p.tcp_numlayers = 1;
    p.tcp_rates[0] = ratio > 1.0 ? static_cast<float>(ratio) : 0.0f;
    p.cp_disto_alloc = 1;
    o.codec = opj_create_compress(OPJ_CODEC_J2K);
    Silence(o.codec);
    if (!opj_setup_encoder(o.codec, &p, o.image)) throw std::runtime_error("j2k: bad parameters");
    Buffer out;
    o.stream = StreamOver(&out, false);
    if (!opj_start_compress(o.codec, o.image, o.stream) || !opj_encode(o.codec, o.stream) ||
        !opj_end_compress(o.codec, o.stream))
        throw std::runtime_error("j2k: cannot encode");
    out.bytes.resize(out.pos);
    return out.bytes;
}

Image8Planes DecodeJ2k(std::span<const uint8_t> codestream, int width, int height, int channels) {
    Buffer in{std::vector<uint8_t>(codestream.begin(), codestream.end()), 0};
    Owned o;
    o.codec = opj_create_decompress(OPJ_CODEC_J2K);
    Silence(o.codec);
    opj_dparameters_t p;
    opj_set_default_decoder_parameters(&p);
    if (!opj_setup_decoder(o.codec, &p)) throw std::runtime_error("j2k: cannot set up");
    o.stream = StreamOver(&in, true);
    if (!opj_read_header(o.stream, o.codec, &o.image))
        throw std::runtime_error("j2k: corrupt codestream header");
    if (static_cast<int>(o.image->numcomps) != channels || o.image->x0 != 0 || o.image->y0 != 0 ||
        o.image->x1 != static_cast<OPJ_UINT32>(width) ||
        o.image->y1 != static_cast<OPJ_UINT32>(height))
        throw std::runtime_error("j2k: the codestream is not a " + std::to_string(width) + " x " +
                                 std::to_string(height) + " image of " + std::to_string(channels) +
                                 " channels");
    if (!opj_decode(o.codec, o.stream, o.image) || !opj_end_decompress(o.codec, o.stream))
        throw std::runtime_error("j2k: corrupt codestream");
    Image8Planes img;
    img.channels = static_cast<int>(o.image->numcomps);
    if (img.channels < 1 || img.channels > 4) throw std::runtime_error("j2k: bad channels");
    img.width = static_cast<int>(o.image->comps[0].w);
    img.height = static_cast<int>(o.image->comps[0].h);
    const size_t n = static_cast<size_t>(img.width) * img.height;
    img.data.resize(n * static_cast<size_t>(img.channels));
    for (int c = 0; c < img.channels; ++c) {
        const opj_image_comp_t& comp = o.image->comps[c];
        if (static_cast<int>(comp.w) != img.width || static_cast<int>(comp.h) != img.height ||
            comp.prec != 8 || !comp.data)
            throw std::runtime_error("j2k: bad component");
        for (size_t i = 0; i < n; ++i)
            img.data[i * static_cast<size_t>(img.channels) + static_cast<size_t>(c)] =
                static_cast<uint8_t>(std::clamp(comp.data[i], 0, 255));
    }
    return img;
}

}  // namespace pem::base
