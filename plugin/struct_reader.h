// How the library reads the tagged structs of the public headers, whatever
// minor version the caller compiled against: the rules of include/rrc/rrc.h
// "Versioning" in code, and the only place that knows them.  Header-only and
// device-free (the descriptor fuzzer compiles it without Vulkan calls).
#pragma once

#include "error.h"

#include <rrc/rrc.h>
#include <rrc/rrc_vulkan.h>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace rrc {

// Per struct: its tag and its first published (0.1) size, the smallest a
// caller may pass.  A struct that grows in a later version names the first
// appended member here.
template <typename T>
struct StructInfo;
#define RRC_STRUCT_INFO(T, tag, first_size)            \
    template <>                                        \
    struct StructInfo<T> {                             \
        static constexpr rrc_struct_type type = tag;   \
        static constexpr size_t size_0_1 = first_size; \
    }
RRC_STRUCT_INFO(rrc_context_desc, RRC_STRUCT_TYPE_CONTEXT_DESC, offsetof(rrc_context_desc, depth_test));
RRC_STRUCT_INFO(rrc_channel_desc, RRC_STRUCT_TYPE_CHANNEL_DESC, offsetof(rrc_channel_desc, rectify));  // 0.4 appends
RRC_STRUCT_INFO(rrc_frame_desc, RRC_STRUCT_TYPE_FRAME_DESC, offsetof(rrc_frame_desc, object_id));
RRC_STRUCT_INFO(rrc_channel_input, RRC_STRUCT_TYPE_CHANNEL_INPUT, offsetof(rrc_channel_input, fallback));  // 0.4 appends
RRC_STRUCT_INFO(rrc_frame_output, RRC_STRUCT_TYPE_FRAME_OUTPUT, offsetof(rrc_frame_output, refreshed));
RRC_STRUCT_INFO(rrc_channel_output, RRC_STRUCT_TYPE_CHANNEL_OUTPUT, sizeof(rrc_channel_output));
RRC_STRUCT_INFO(rrc_vulkan_device_desc, RRC_STRUCT_TYPE_VULKAN_DEVICE_DESC, offsetof(rrc_vulkan_device_desc, enabled_features));  // 0.11 appends
RRC_STRUCT_INFO(rrc_vulkan_frame_desc, RRC_STRUCT_TYPE_VULKAN_FRAME_DESC, offsetof(rrc_vulkan_frame_desc, stats_buffer));
RRC_STRUCT_INFO(rrc_vulkan_channel_images, RRC_STRUCT_TYPE_VULKAN_CHANNEL_IMAGES, offsetof(rrc_vulkan_channel_images, age));
// 0.3: first published with the shading cache.
RRC_STRUCT_INFO(rrc_classify_output, RRC_STRUCT_TYPE_CLASSIFY_OUTPUT, sizeof(rrc_classify_output));
RRC_STRUCT_INFO(rrc_resolve_desc, RRC_STRUCT_TYPE_RESOLVE_DESC, sizeof(rrc_resolve_desc));
RRC_STRUCT_INFO(rrc_vulkan_quad_list, RRC_STRUCT_TYPE_VULKAN_QUAD_LIST, offsetof(rrc_vulkan_quad_list, buffer_size));  // 0.10 appends
// 0.11: first published with the requirements query and the first extension.
RRC_STRUCT_INFO(rrc_vulkan_requirements, RRC_STRUCT_TYPE_VULKAN_REQUIREMENTS, sizeof(rrc_vulkan_requirements));
RRC_STRUCT_INFO(rrc_vulkan_image_extents, RRC_STRUCT_TYPE_EXT_VULKAN_IMAGE_EXTENTS, sizeof(rrc_vulkan_image_extents));
#undef RRC_STRUCT_INFO

// Tags of base structs: never valid inside a `next` chain.
inline bool is_base_struct_type(rrc_struct_type t) {
    return (t >= RRC_STRUCT_TYPE_CONTEXT_DESC && t <= RRC_STRUCT_TYPE_RESOLVE_DESC) ||
           (t >= RRC_STRUCT_TYPE_VULKAN_DEVICE_DESC && t <= RRC_STRUCT_TYPE_VULKAN_REQUIREMENTS);
}

// Rule 5's table: the extensions each parent struct takes.
struct ExtensionRule {
    rrc_struct_type parent, extension;
};
constexpr ExtensionRule kExtensionRules[] = {
    {RRC_STRUCT_TYPE_VULKAN_FRAME_DESC, RRC_STRUCT_TYPE_EXT_VULKAN_IMAGE_EXTENTS},
};
inline bool is_known_extension(rrc_struct_type t) {
    for (const ExtensionRule& r : kExtensionRules)
        if (r.extension == t) return true;
    return false;
}
inline bool parent_takes(rrc_struct_type parent, rrc_struct_type t) {
    for (const ExtensionRule& r : kExtensionRules)
        if (r.parent == parent && r.extension == t) return true;
    return false;
}

inline rrc_struct_header read_header(const void* p) {
    rrc_struct_header h;
    std::memcpy(&h, p, sizeof h);
    return h;
}

// Rule 5: walks a `next` chain.  Its shape is checked first (length, base
// tags, a type twice), then each element's type against the parent's
// extensions (kExtensionRules); the extensions themselves are read by
// find_extension.
inline void check_chain(const void* next, rrc_struct_type parent, const std::string& what) {
    int length = 0;
    std::vector<rrc_struct_type> seen;
    for (const void* p = next; p; p = read_header(p).next, ++length) {
        if (length >= RRC_MAX_CHAIN)
            fail(RRC_ERROR_INVALID_STRUCT, "%s.next: the chain is longer than %d structs (a cycle?)", what.c_str(), RRC_MAX_CHAIN);
        const rrc_struct_header h = read_header(p);
        if (is_base_struct_type(h.type))
            fail(RRC_ERROR_INVALID_STRUCT, "%s.next[%d].type is 0x%08x, the tag of a base struct, not of an extension", what.c_str(),
                 length, (unsigned)h.type);
        if (std::find(seen.begin(), seen.end(), h.type) != seen.end())
            fail(RRC_ERROR_INVALID_STRUCT, "%s.next[%d].type 0x%08x is in the chain twice", what.c_str(), length, (unsigned)h.type);
        seen.push_back(h.type);
    }
    length = 0;
    for (const void* p = next; p; p = read_header(p).next, ++length) {
        const rrc_struct_type t = read_header(p).type;
        if (!is_known_extension(t))
            fail(RRC_ERROR_UNSUPPORTED, "%s.next[%d].type is 0x%08x: an extension this library (%u.%u.%u) does not know", what.c_str(), length,
                 (unsigned)t, RRC_VERSION_MAJOR(RRC_API_VERSION), RRC_VERSION_MINOR(RRC_API_VERSION), RRC_VERSION_PATCH(RRC_API_VERSION));
        if (!parent_takes(parent, t))
            fail(RRC_ERROR_INVALID_STRUCT, "%s.next[%d].type is 0x%08x: an extension %s does not take", what.c_str(), length, (unsigned)t,
                 what.c_str());
    }
}

// Rule 2's cap: a size no struct of any version has is refused before the
// tail beyond the known struct is scanned (or an array strided by it).
inline void check_size_cap(uint32_t size, const std::string& what) {
    if (size > RRC_MAX_STRUCT_SIZE)
        fail(RRC_ERROR_INVALID_STRUCT, "%s.size is %u, above RRC_MAX_STRUCT_SIZE (%u): not a size of any version of the struct",
             what.c_str(), (unsigned)size, (unsigned)RRC_MAX_STRUCT_SIZE);
}

// Rules 1 and 2: a copy of the caller's struct with every member beyond
// its `size` zero (its `next` untouched).  Throws rrc::Error naming `what`.
template <typename T>
T read_members(const void* p, const std::string& what) {
    using Info = StructInfo<T>;
    if (!p) fail(RRC_ERROR_INVALID_ARGUMENT, "%s is NULL", what.c_str());
    const rrc_struct_header h = read_header(p);
    if (h.type != Info::type)
        fail(RRC_ERROR_INVALID_STRUCT, "%s.type is 0x%08x, expected 0x%08x", what.c_str(), (unsigned)h.type, (unsigned)Info::type);
    if (h.size < Info::size_0_1)
        fail(RRC_ERROR_INVALID_STRUCT, "%s.size is %u, smaller than its first version's %zu", what.c_str(), (unsigned)h.size,
             Info::size_0_1);
    check_size_cap(h.size, what);
    T out;
    std::memset(&out, 0, sizeof out);
    std::memcpy(&out, p, std::min<size_t>(h.size, sizeof out));
    const unsigned char* tail = static_cast<const unsigned char*>(p) + sizeof out;
    for (size_t i = sizeof out; i < h.size; ++i, ++tail)
        if (*tail)
            fail(RRC_ERROR_UNSUPPORTED,
                 "%s.size is %u and byte %zu is non-zero: a member of a newer header than this library's (%zu bytes) knows", what.c_str(),
                 (unsigned)h.size, i, sizeof out);
    return out;
}

// Rules 1, 2 and 5: the struct's members, and its chain checked.
template <typename T>
T read_struct(const void* p, const std::string& what) {
    T out = read_members<T>(p, what);
    check_chain(out.next, StructInfo<T>::type, what);
    return out;
}

// Rule 5: extension E on a chain check_chain accepted, read by rules 1-2;
// false when the chain does not hold it.
template <typename E>
bool find_extension(const void* next, const std::string& what, E& out) {
    for (const void* p = next; p; p = read_header(p).next)
        if (read_header(p).type == StructInfo<E>::type) {
            out = read_members<E>(p, what);
            return true;
        }
    return false;
}

// Rule 3: element i of a caller's array strided by element 0's size, whose
// own size must equal that stride.  The size is checked before anything
// else is read: an element larger than the stride would be read beyond the
// caller's array.
// `name`: what messages call the element ("frame", "channels[2]").
template <typename T>
T* strided_element(T* base, uint32_t i, const std::string& what, const std::string& name) {
    using Byte = typename std::conditional<std::is_const<T>::value, const unsigned char, unsigned char>::type;
    const uint32_t stride = read_header(base).size;
    check_size_cap(stride, what + "[0]");
    T* element = reinterpret_cast<T*>(reinterpret_cast<Byte*>(base) + (size_t)i * stride);
    const uint32_t size = read_header(element).size;
    if (size != stride)
        fail(RRC_ERROR_INVALID_STRUCT, "%s.size is %u but %s[0].size is %u: every element of an array has one size", name.c_str(),
             (unsigned)size, what.c_str(), (unsigned)stride);
    return element;
}

// Rule 3 for a whole array, each element read by rules 1, 2 and 5.
template <typename T>
std::vector<T> read_array(const T* base, uint32_t count, const std::string& what) {
    std::vector<T> out;
    if (count == 0) return out;
    if (!base) fail(RRC_ERROR_INVALID_ARGUMENT, "%s is NULL", what.c_str());
    for (uint32_t i = 0; i < count; ++i) {
        const std::string name = what + "[" + std::to_string(i) + "]";
        out.push_back(read_struct<T>(strided_element(base, i, what, name), name));
    }
    return out;
}

// Rule 4: writes one member of a caller's output struct only if the
// caller's `size` covers it.
template <typename T, typename M>
void write_member(T* caller, size_t offset, const M& value) {
    if (caller->size >= offset + sizeof(M)) std::memcpy(reinterpret_cast<unsigned char*>(caller) + offset, &value, sizeof(M));
}

}  // namespace rrc
