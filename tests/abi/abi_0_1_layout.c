/* Compiled against ONLY the verbatim 0.1 headers (tests/abi/rrc_0_1): the
 * sizes and member offsets a 0.1 caller's compiler gave each public struct. */
#include <rrc/rrc.h>
#include <rrc/rrc_vulkan.h>

#include "abi_0_1_layout.h"

/* The 0.1 headers and nothing newer: RRC_API_VERSION must be 0.1.0 here (a
 * negative array size otherwise), and 0.2's additions must be absent. */
typedef char rrc_abi_header_is_0_1_0[(RRC_API_VERSION == RRC_MAKE_VERSION(0, 1, 0)) ? 1 : -1];
#if defined(RRC_MAX_CHAIN) || defined(RRC_STRUCT_TYPE_EXT_FIRST)
#error "abi_0_1_layout.c must be compiled against the 0.1 headers (tests/abi/rrc_0_1), not include/"
#endif
const rrc_abi_entry rrc_abi_0_1_layout[] = {
#include "abi_0_1_entries.inc"
};

const uint32_t rrc_abi_0_1_header_version = RRC_API_VERSION;
