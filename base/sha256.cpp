// SPDX-License-Identifier: MIT
// sha256.cpp — SHA-256 per FIPS 180-4 §6.2: pad to 512-bit blocks, 64 rounds per block.
// Conventions: big-endian words, message length in bits appended as a 64-bit big-endian integer.
// Not here: incremental (init/update/final) hashing; every input fits in memory.
#include "base/sha256.h"

#include <vector>

namespace pem::base {

namespace {

constexpr std::array<uint32_t, 64> kRoundConstants = {
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
    0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
    0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
    0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2};

constexpr std::array<uint32_t, 8> kInitialHash = {0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a,
                                                  0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};

constexpr uint32_t Rotr(uint32_t x, int n) {
    return (x >> n) | (x << (32 - n));
}

// Expand one 64-byte block into the 64-word message schedule (FIPS 180-4 §6.2.2 step 1).
std::array<uint32_t, 64> Schedule(const uint8_t* block) {
    std::array<uint32_t, 64> w{};
    for (int t = 0; t < 16; ++t) {
        const uint8_t* p = block + 4 * t;
        w[t] = (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | p[3];
    }
    for (int t = 16; t < 64; ++t) {
        uint32_t s0 = Rotr(w[t - 15], 7) ^ Rotr(w[t - 15], 18) ^ (w[t - 15] >> 3);
        uint32_t s1 = Rotr(w[t - 2], 17) ^ Rotr(w[t - 2], 19) ^ (w[t - 2] >> 10);
        w[t] = w[t - 16] + s0 + w[t - 7] + s1;
    }
    return w;
}

// Steps 2-4: the 64 compression rounds and the feed-forward into the hash state.
void Compress(std::array<uint32_t, 8>* state, const uint8_t* block) {
    const std::array<uint32_t, 64> w = Schedule(block);
    std::array<uint32_t, 8> v = *state;  // a b c d e f g h
    for (int t = 0; t < 64; ++t) {
        uint32_t s1 = Rotr(v[4], 6) ^ Rotr(v[4], 11) ^ Rotr(v[4], 25);
        uint32_t ch = (v[4] & v[5]) ^ (~v[4] & v[6]);
        uint32_t t1 = v[7] + s1 + ch + kRoundConstants[t] + w[t];
        uint32_t s0 = Rotr(v[0], 2) ^ Rotr(v[0], 13) ^ Rotr(v[0], 22);
        uint32_t maj = (v[0] & v[1]) ^ (v[0] & v[2]) ^ (v[1] & v[2]);
        for (int k = 7; k > 0; --k) v[k] = v[k - 1];
        v[4] += t1;
        v[0] = t1 + s0 + maj;
    }
    for (int k = 0; k < 8; ++k) (*state)[k] += v[k];
}

// The final one or two blocks: the tail of the message, 0x80, zeros, 64-bit bit length.
std::vector<uint8_t> PaddedTail(const uint8_t* tail, size_t tailSize, size_t totalSize) {
    std::vector<uint8_t> out(tail, tail + tailSize);
    out.push_back(0x80);
    while (out.size() % 64 != 56) out.push_back(0);
    const uint64_t bits = static_cast<uint64_t>(totalSize) * 8;
    for (int k = 7; k >= 0; --k) out.push_back(static_cast<uint8_t>(bits >> (8 * k)));
    return out;
}

}  // namespace

std::array<uint8_t, 32> Sha256(const uint8_t* data, size_t size) {
    // Step 1: whole blocks straight from the input.
    std::array<uint32_t, 8> state = kInitialHash;
    const size_t wholeBlocks = size / 64;
    for (size_t b = 0; b < wholeBlocks; ++b) Compress(&state, data + 64 * b);
    // Step 2: padded tail.
    const std::vector<uint8_t> tail =
        PaddedTail(data + 64 * wholeBlocks, size - 64 * wholeBlocks, size);
    for (size_t b = 0; b < tail.size(); b += 64) Compress(&state, tail.data() + b);
    // Step 3: big-endian digest bytes.
    std::array<uint8_t, 32> digest{};
    for (size_t k = 0; k < 32; ++k)
        digest[k] = static_cast<uint8_t>(state[k / 4] >> (24 - 8 * (k % 4)));
    return digest;
}

std::string Sha256Hex(const uint8_t* data, size_t size) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string hex;
    for (uint8_t byte : Sha256(data, size)) {
        hex.push_back(kHex[byte >> 4]);
        hex.push_back(kHex[byte & 15]);
    }
    return hex;
}

}  // namespace pem::base
