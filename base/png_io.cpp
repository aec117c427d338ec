// SPDX-License-Identifier: MIT
// png_io.cpp — WritePng with libpng's setjmp/longjmp error protocol kept inside one function.
// Conventions: 8-bit RGBA, no interlace, zlib level 1 (fast; the files are previews and
// copies, not archives); temp file + rename(2).
// Not here: anything that could leave a partially written `path`.
#include "base/png_io.h"

#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "base/atomic_file.h"

namespace pem::base {

namespace {

// libpng error callback: remember the message, unwind to the setjmp in EncodeRows.
void OnPngError(png_structp png, png_const_charp message) {
    auto* error = static_cast<std::string*>(png_get_error_ptr(png));
    *error = message;
    png_longjmp(png, 1);
}

void OnPngWarning(png_structp, png_const_charp) {}

// Writes the PNG stream to `file`; on failure sets *error (owned by the caller, so it is not an
// automatic object of the function that calls setjmp).
void EncodeRows(FILE* file, const Image8& image, std::string* error) {
    png_structp png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, error, OnPngError, OnPngWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info) {
        png_destroy_write_struct(&png, nullptr);
        *error = "libpng initialisation failed";
        return;
    }
    std::vector<png_bytep> rows(size_t(image.height));
    for (size_t y = 0; y < rows.size(); ++y)
        rows[y] = const_cast<png_bytep>(image.rgba.data() + y * size_t(image.width) * 4);
    if (setjmp(png_jmpbuf(png)) == 0) {
        png_init_io(png, file);
        png_set_IHDR(png, info, png_uint_32(image.width), png_uint_32(image.height), 8,
                     PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                     PNG_FILTER_TYPE_DEFAULT);
        png_set_compression_level(png, 1);
        png_write_info(png, info);
        png_write_image(png, rows.data());
        png_write_end(png, nullptr);
    } else if (error->empty()) {
        *error = "libpng error";
    }
    png_destroy_write_struct(&png, &info);
}

// Reads the PNG stream of `file` into *image; on failure sets *error (as EncodeRows). Every
// object the decode changes belongs to the caller, so none is an automatic object of the
// function that calls setjmp.
void DecodeRows(FILE* file, Image8* image, std::vector<png_bytep>* rows, std::string* error) {
    png_structp png =
        png_create_read_struct(PNG_LIBPNG_VER_STRING, error, OnPngError, OnPngWarning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!png || !info) {
        png_destroy_read_struct(&png, nullptr, nullptr);
        *error = "libpng initialisation failed";
        return;
    }
    if (setjmp(png_jmpbuf(png)) == 0) {
        png_init_io(png, file);
        png_set_user_limits(png, 16384, 16384);
        png_read_info(png, info);
        png_set_expand(png);  // palette, grey < 8 bits, tRNS → 8-bit channels with alpha
        png_set_strip_16(png);
        png_set_gray_to_rgb(png);
        png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
        png_read_update_info(png, info);
        image->width = static_cast<int>(png_get_image_width(png, info));
        image->height = static_cast<int>(png_get_image_height(png, info));
        image->rgba.assign(size_t(image->width) * size_t(image->height) * 4, 0);
        rows->resize(size_t(image->height));
        for (size_t y = 0; y < rows->size(); ++y)
            (*rows)[y] = image->rgba.data() + y * size_t(image->width) * 4;
        png_read_image(png, rows->data());
        png_read_end(png, nullptr);
    } else if (error->empty()) {
        *error = "libpng error";
    }
    png_destroy_read_struct(&png, &info, nullptr);
}

}  // namespace

Image8 ReadPng(const std::string& path) {
    FILE* file = std::fopen(path.c_str(), "rb");
    if (!file) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
    Image8 image;
    std::vector<png_bytep> rows;
    std::string error;
    DecodeRows(file, &image, &rows, &error);
    std::fclose(file);
    if (!error.empty()) throw InputError(path, "not a readable PNG: " + error);
    return image;
}

void WritePng(const std::string& path, const Image8& image) {
    // Step 1: validate the image.
    if (image.width <= 0 || image.height <= 0 ||
        image.rgba.size() != size_t(image.width) * size_t(image.height) * 4)
        throw InputError(path, "image is empty or its pixel buffer has the wrong size");
    // Step 2: encode into a temporary file next to the target, published when complete.
    WriteAtomically(path, [&](const std::string& tmp) {
        FILE* file = std::fopen(tmp.c_str(), "wb");
        if (!file) throw std::runtime_error(std::string("cannot create: ") + std::strerror(errno));
        std::string error;
        EncodeRows(file, image, &error);
        if (std::fflush(file) != 0 && error.empty()) error = std::strerror(errno);
        if (std::fclose(file) != 0 && error.empty()) error = std::strerror(errno);
        if (!error.empty()) throw std::runtime_error(error);
    });
}

}  // namespace pem::base
