// The public enumerations (include/rrc/rrc_values.h, the lists rrc.h makes
// its C enums of) and the kernel interface (rrc_kernel_interface.h) for the
// GLSL kernels: every value is written once, in those two headers.
#ifndef RRC_VALUES_GLSL
#define RRC_VALUES_GLSL

#include "rrc/rrc_values.h"
#include "rrc_kernel_interface.h"

#define RRC_GLSL_UINT(name, value) const uint name = uint(value);
RRC_DEPTH_MODE_VALUES(RRC_GLSL_UINT)
RRC_REPROJECTION_VALUES(RRC_GLSL_UINT)
RRC_BLEND_VALUES(RRC_GLSL_UINT)
RRC_HISTORY_FILTER_VALUES(RRC_GLSL_UINT)
RRC_MASK_VALUES(RRC_GLSL_UINT)
RRC_REFRESH_POLICY_VALUES(RRC_GLSL_UINT)
#undef RRC_GLSL_UINT

#endif
