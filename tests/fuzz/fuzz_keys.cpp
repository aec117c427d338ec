// SPDX-License-Identifier: MIT
// fuzz_keys.cpp — the viewer's key script (`pemref view --keys`): decoded and applied to the
// view state; the state must stay finite and within its limits.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "viewer_tty/tty/viewer.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace pem::tty;
    ViewState state;
    for (int key : DecodeKeys(std::string_view(reinterpret_cast<const char*>(data), size))) {
        ApplyKey(&state, key);
        // The limits viewer.h documents.
        if (!(state.azimuthDeg >= 0.0 && state.azimuthDeg < 360.0) ||
            !(std::abs(state.elevationDeg) <= 85.0) || !(std::abs(state.heightOffsetDeg) <= 85.0) ||
            !(state.distanceScale >= 0.2 && state.distanceScale <= 10.0) ||
            !(state.t >= 1.0 && state.t <= 64.0))
            std::abort();
    }
    return 0;
}
