/* The layout of the 0.1 public structs as a caller compiled against the 0.1
 * headers sees it (abi_0_1_layout.c, compiled against ONLY tests/abi/rrc_0_1).
 * Plain C; no rrc header is included here, so both versions can use it. */
#ifndef RRC_TESTS_ABI_0_1_LAYOUT_H
#define RRC_TESTS_ABI_0_1_LAYOUT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct rrc_abi_entry {
    const char* struct_name;
    const char* member; /* NULL: the struct itself (offset = sizeof, tag = its type tag) */
    size_t offset;      /* offsetof(member), or sizeof(struct) */
    size_t member_size; /* sizeof(member), or 0 */
    uint32_t tag;       /* the struct's RRC_STRUCT_TYPE_*, 0 for untagged structs and for members */
} rrc_abi_entry;

/* Every entry of abi_0_1_layout.inc, in order, terminated by struct_name NULL. */
extern const rrc_abi_entry rrc_abi_0_1_layout[];
/* RRC_API_VERSION of the headers that TU was compiled against. */
extern const uint32_t rrc_abi_0_1_header_version;

#ifdef __cplusplus
}
#endif

#endif
