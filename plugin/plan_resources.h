// What a plan's resource ids (frame_plan.h, PlanResource) stand for in one
// call: a context's images, buffers and descriptor sets.  A context fills it
// from the plan (what each set binds); the core adds its own buffers and
// records the plan's steps against it (AccumulatorCore::record_call).
#pragma once

#include "accumulate_pipeline.h"
#include "gpu_resources.h"

#include <vector>

namespace rrc {

struct PlanBuffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize offset = 0, size = VK_WHOLE_SIZE;
};

// One image copied between staging and a library image (Upload, Readback).
struct PlanCopy {
    const GpuImage* image = nullptr;
    VkDeviceSize offset = 0;  // in the staging buffer
};

struct PlanResources {
    DescriptorSets frame, next;                 // PlanSet::Frame, PlanSet::Next
    PlanBuffer quad_list, stats;                // QuadList, Stats
    PlanBuffer fill_list, view_buffer;          // FillList, ViewBuffer: the core's own, filled by the core
    std::vector<GpuImage*> initialise;          // LibraryImages: the context's own images beside the core's (the core adds its own)
    std::vector<VkImageMemoryBarrier> host_in;  // HostImagesIn: each host image to the kernel's layout
    std::vector<VkImageMemoryBarrier> host_out; // HostImagesOut: back to the host's final layout
    VkBuffer staging_in = VK_NULL_HANDLE, staging_out = VK_NULL_HANDLE;
    std::vector<PlanCopy> inputs, outputs;      // Inputs (uploaded), Outputs (read back)
};

}  // namespace rrc
