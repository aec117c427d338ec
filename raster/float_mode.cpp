// SPDX-License-Identifier: MIT
#include "raster/float_mode.h"

#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>
#endif

namespace pem::raster {

#if defined(__x86_64__) || defined(__i386__)
ScopedFlushToZero::ScopedFlushToZero() : saved_(_mm_getcsr()) {
    _mm_setcsr(static_cast<unsigned>(saved_) | 0x8040u);  // FTZ (bit 15) | DAZ (bit 6)
}
ScopedFlushToZero::~ScopedFlushToZero() {
    _mm_setcsr(static_cast<unsigned>(saved_));
}
#elif defined(__aarch64__)
ScopedFlushToZero::ScopedFlushToZero() {
    uint64_t fpcr;
    __asm__ volatile("mrs %0, fpcr" : "=r"(fpcr));
    saved_ = fpcr;
    fpcr |= (1ull << 24);  // FZ
    __asm__ volatile("msr fpcr, %0" : : "r"(fpcr));
}
ScopedFlushToZero::~ScopedFlushToZero() {
    __asm__ volatile("msr fpcr, %0" : : "r"(saved_));
}
#else
ScopedFlushToZero::ScopedFlushToZero() {}
ScopedFlushToZero::~ScopedFlushToZero() {}
#endif

}  // namespace pem::raster
