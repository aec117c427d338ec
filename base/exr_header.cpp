// SPDX-License-Identifier: MIT
#include "base/exr_header.h"

#include <openexr.h>

#include "base/input_error.h"

namespace pem::base {

namespace {

// The first error message OpenEXRCore gives for the file (its own, more precise than the code's).
void KeepFirstMessage(exr_const_context_t context, exr_result_t, const char* message) {
    void* user = nullptr;
    exr_get_user_data(context, &user);
    auto* out = static_cast<std::string*>(user);
    if (out && out->empty() && message) *out = message;
}

}  // namespace

void CheckExrHeader(const std::string& path) {
    // Step 1: OpenEXRCore parses and validates every header (sizes checked against the file and
    // against the image and tile limits) without reading pixels.
    std::string message;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = KeepFirstMessage;
    init.user_data = &message;
    init.max_image_width = init.max_image_height = kMaxExrSide;
    init.max_tile_width = init.max_tile_height = kMaxExrSide;
    init.flags = EXR_CONTEXT_FLAG_STRICT_HEADER;
    exr_context_t context = nullptr;
    const exr_result_t started = exr_start_read(&context, path.c_str(), &init);
    // Step 2: every part's data window within kMaxExrPixels.
    int parts = 0;
    bool windowsFit = true;
    int64_t width = 0, height = 0;
    if (started == EXR_ERR_SUCCESS && exr_get_count(context, &parts) == EXR_ERR_SUCCESS) {
        for (int p = 0; p < parts; ++p) {
            exr_attr_box2i_t dw{};
            if (exr_get_data_window(context, p, &dw) != EXR_ERR_SUCCESS) continue;
            width = int64_t{dw.max.x} - dw.min.x + 1, height = int64_t{dw.max.y} - dw.min.y + 1;
            windowsFit &= width >= 1 && height >= 1 && width <= kMaxExrPixels / height;
        }
    }
    exr_finish(&context);
    if (started != EXR_ERR_SUCCESS)
        throw InputError(
            path,
            "not a valid OpenEXR file: " +
                (message.empty() ? std::string(exr_get_default_error_message(started)) : message));
    if (!windowsFit) CheckExrSize(path, width, height);
}

void CheckExrSize(const std::string& path, int64_t width, int64_t height) {
    if (width < 1 || height < 1 || width > kMaxExrPixels / height)
        throw InputError(path, "data window " + std::to_string(width) + " x " +
                                   std::to_string(height) + " is empty or too large");
}

}  // namespace pem::base
