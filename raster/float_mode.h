// SPDX-License-Identifier: MIT
// float_mode.h — llvmpipe shades fragments with denormals flushed to zero (MXCSR DAZ|FTZ on its
// rasterizer threads). ScopedFlushToZero sets the same mode for the current thread (x86-64:
// MXCSR DAZ and FTZ; aarch64: FPCR.FZ, which flushes inputs and outputs) and restores the
// previous mode on exit. Only the fragment stage runs under it; setup and clipping do not.
#pragma once

#include <cstdint>

namespace pem::raster {

class ScopedFlushToZero {
  public:
    ScopedFlushToZero();
    ~ScopedFlushToZero();
    ScopedFlushToZero(const ScopedFlushToZero&) = delete;
    ScopedFlushToZero& operator=(const ScopedFlushToZero&) = delete;

  private:
    uint64_t saved_ = 0;
};

}  // namespace pem::raster
