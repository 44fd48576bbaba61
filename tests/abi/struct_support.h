// Struct-size helpers of the ABI tests: tagged structs copied into byte
// buffers with a chosen `size`, extension tails, garbage beyond the size,
// guard bytes after, and arrays strided by their elements' size.
#pragma once

#include "abi_0_1_layout.h"

#include <rrc/rrc.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace rrc_abi {

// The size a 0.1 caller's compiler gave a struct (abi_0_1_layout.c).
inline size_t size01(const char* struct_name) {
    for (const rrc_abi_entry* e = rrc_abi_0_1_layout; e->struct_name; ++e)
        if (!e->member && std::strcmp(e->struct_name, struct_name) == 0) return e->offset;
    throw std::runtime_error(std::string("no 0.1 layout for ") + struct_name);
}

// How a struct is laid into its buffer:
//   [0, min(size, sizeof))   the struct's bytes
//   [sizeof, size)           an extension tail: zero (a newer header's members, unset)
//   [max(size, 24), alloc)   `beyond` (garbage a truncated reader must not use, or guard bytes)
// then `nonzero_at` (if >= 0) is set to 0x01 and the size field to `size`.
struct Shape {
    uint32_t size = 0;  // 0: sizeof
    size_t alloc = 0;   // 0: max(size, sizeof); exactly `size` for a truncated struct lets ASan catch over-reads
    unsigned char beyond = 0;
    long nonzero_at = -1;
};

// Heap bytes (operator new: aligned for any struct) with a snapshot of how
// they were filled, so a test can tell which bytes the library wrote.
class Blob {
public:
    Blob() = default;
    explicit Blob(size_t n) : bytes_(new unsigned char[n ? n : 1]()), n_(n) {}
    unsigned char* data() { return bytes_.get(); }
    const unsigned char* data() const { return bytes_.get(); }
    size_t size() const { return n_; }
    template <typename T>
    T* as() {
        return reinterpret_cast<T*>(bytes_.get());
    }
    void snapshot() { original_.assign(bytes_.get(), bytes_.get() + n_); }
    // True if [from, to) is as it was at snapshot().
    bool untouched(size_t from, size_t to) const {
        to = std::min(to, n_);
        for (size_t i = from; i < to; ++i)
            if (bytes_[i] != original_[i]) return false;
        return true;
    }

private:
    std::unique_ptr<unsigned char[]> bytes_;
    size_t n_ = 0;
    std::vector<unsigned char> original_;
};

inline void set_size_field(unsigned char* p, uint32_t size) {
    // Every tagged struct starts {type; next; size} (rule 1).
    struct Header {
        rrc_struct_type type;
        const void* next;
        uint32_t size;
    };
    std::memcpy(p + offsetof(Header, size), &size, sizeof size);
}

template <typename T>
Blob pack(const T& s, const Shape& sh) {
    const uint32_t size = sh.size ? sh.size : (uint32_t)sizeof(T);
    const size_t alloc = sh.alloc ? sh.alloc : std::max<size_t>(size, sizeof(T));
    Blob b(std::max<size_t>(alloc, 24));
    std::memcpy(b.data(), &s, std::min(alloc, sizeof(T)));
    for (size_t i = std::max<size_t>(size, 24); i < alloc; ++i) b.data()[i] = sh.beyond;  // the header stays intact
    if (sh.nonzero_at >= 0) b.data()[sh.nonzero_at] = 1;
    set_size_field(b.data(), size);
    b.snapshot();
    return b;
}

// Elements strided by `stride` (each element's [sizeof, stride) zero), each
// size field = stride unless `sizes` overrides it per element; `guard` bytes
// of `guard_fill` after the last element; nonzero_at: a byte index in the buffer.
template <typename T>
Blob pack_array(const std::vector<T>& v, uint32_t stride, const std::vector<uint32_t>& sizes = {}, size_t guard = 32,
                unsigned char guard_fill = 0xCD, long nonzero_at = -1) {
    Blob b(v.size() * stride + guard);
    for (size_t i = 0; i < v.size(); ++i) {
        unsigned char* e = b.data() + i * stride;
        std::memcpy(e, &v[i], std::min<size_t>(stride, sizeof(T)));
        set_size_field(e, sizes.empty() ? stride : sizes[i]);
    }
    for (size_t i = v.size() * stride; i < b.size(); ++i) b.data()[i] = guard_fill;
    if (nonzero_at >= 0) b.data()[nonzero_at] = 1;
    b.snapshot();
    return b;
}

// An extension-chain node: the header every chained struct starts with.
struct ChainNode {
    rrc_struct_type type;
    const void* next;
    uint32_t size;
    uint32_t payload[6];
};

inline ChainNode node(rrc_struct_type type, const void* next = nullptr) {
    ChainNode n;
    std::memset(&n, 0, sizeof n);
    n.type = type;
    n.next = next;
    n.size = sizeof n;
    return n;
}

// A tag no version of rrc defines (outside the base tags and the extension range).
constexpr rrc_struct_type kUnknownExtension = 0x525243EFu;

}  // namespace rrc_abi
