// SPDX-License-Identifier: MIT
// sha256.h — our own SHA-256 (FIPS 180-4), used to name rendered frames by their RGBA8 bytes.
// Convention: the digest is returned as 64 lowercase hex digits.
// Not here: HMAC, streaming over files, any other hash.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace pem::base {

// SHA-256 of `size` bytes at `data` (data may be null when size == 0), lowercase hex.
std::string Sha256Hex(const uint8_t* data, size_t size);

// The raw 32-byte digest.
std::array<uint8_t, 32> Sha256(const uint8_t* data, size_t size);

}  // namespace pem::base
