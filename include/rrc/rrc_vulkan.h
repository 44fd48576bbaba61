/*
 * rrc Vulkan interop: run rrc inside the host engine's own Vulkan device and
 * command buffers.  C99; include after <rrc/rrc.h>.  Vulkan types come from
 * <vulkan/vulkan.h> (define VK_NO_PROTOTYPES first if you use volk: this
 * header calls no Vulkan function).
 *
 * Model (docs/guide/integration.md has the full walk-through, docs/reference/api.md an input table)
 * ---------------------------------------------------------------------
 *   rrc_vulkan_context_create()  once, on the host's instance/device
 *   rrc_vulkan_record_frame()    per frame: records barriers and one dispatch
 *                                into the host's command buffer
 *   rrc_context_destroy()        after the host has waited for the device
 *
 * The library never submits, waits, or touches a queue.  It cannot know when
 * the GPU has finished a frame, so the host declares max_frames_in_flight:
 * it may record a new frame while up to that many earlier recorded frames are
 * still pending (descriptor sets are used in a ring of max_frames_in_flight + 1).  Frames must be submitted in the order
 * they were recorded, on the queue family given at creation.  Queue-family
 * ownership transfers (async compute) are the host's job.
 *
 * Every host image is passed with the layout it is in when the recorded
 * commands start and the layout it must be left in; the library's barriers
 * make the host's earlier writes (any stage) visible, and its own writes
 * visible to any later stage.  History, age and previous depth are owned by
 * the library (ping-pong; rrc_get_memory_usage reports the bytes).
 *
 * Device requirements: rrc_vulkan_get_requirements (0.11) returns them: the
 * Vulkan version, the features to enable, the device extensions (none) and
 * the limits rrc needs; creation checks them against the physical device.
 */
#ifndef RRC_RRC_VULKAN_H
#define RRC_RRC_VULKAN_H

#include <rrc/rrc.h>
#include <vulkan/vulkan.h>

#ifdef __cplusplus
extern "C" {
#endif

#define RRC_STRUCT_TYPE_VULKAN_DEVICE_DESC 0x52524310u
#define RRC_STRUCT_TYPE_VULKAN_FRAME_DESC 0x52524311u
#define RRC_STRUCT_TYPE_VULKAN_CHANNEL_IMAGES 0x52524312u
#define RRC_STRUCT_TYPE_VULKAN_QUAD_LIST 0x52524313u /* 0.3 */
#define RRC_STRUCT_TYPE_VULKAN_REQUIREMENTS 0x52524314u /* 0.11 */
#define RRC_STRUCT_TYPE_EXT_VULKAN_IMAGE_EXTENTS 0x525243E0u /* 0.11, on rrc_vulkan_frame_desc.next */

/** What rrc needs of the host's Vulkan device, whatever the context
 *  description (0.11).  Written by rrc_vulkan_get_requirements up to the
 *  caller's `size`. */
typedef struct rrc_vulkan_requirements {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_VULKAN_REQUIREMENTS */
    const void* next;     /* NULL */
    uint32_t size;        /* sizeof(rrc_vulkan_requirements) */
    uint32_t api_version; /* written: the lowest VkApplicationInfo.apiVersion / device version, VK_API_VERSION_1_1 */
    /* Written: VK_TRUE for each feature the host must enable at vkCreateDevice
     * (OR it into its own VkPhysicalDeviceFeatures or VkPhysicalDeviceFeatures2.features),
     * VK_FALSE for the rest: shaderStorageImageWriteWithoutFormat. */
    VkPhysicalDeviceFeatures features;
    uint32_t device_extension_count;           /* written: the device extensions rrc needs: 0 */
    const char* const* device_extensions;      /* written: their names (NULL when none); static storage */
    uint32_t max_per_stage_storage_images;     /* written: the maxPerStageDescriptorStorageImages rrc needs: 64 */
    const char* optional_instance_extension;   /* written: VK_EXT_DEBUG_UTILS_EXTENSION_NAME: with it rrc labels its
                                                  commands (rrc_vulkan_device_desc.debug_utils_enabled) */
} rrc_vulkan_requirements;

/** Fills `out` (its type and size set by the caller).  Needs no context, no
 *  device and no Vulkan call: call it before creating the host's device. */
RRC_API rrc_result rrc_vulkan_get_requirements(rrc_vulkan_requirements* out);

/** The host's Vulkan objects.  The library uses them and destroys none. */
typedef struct rrc_vulkan_device_desc {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_VULKAN_DEVICE_DESC */
    const void* next;     /* NULL or an extension chain (rrc.h Versioning, rule 5) */
    uint32_t size;        /* sizeof(rrc_vulkan_device_desc) */
    VkInstance instance;
    VkPhysicalDevice physical_device;
    VkDevice device;
    uint32_t queue_family_index;                      /* the family whose command buffers the host passes */
    uint32_t vulkan_api_version;                      /* what the host's device was created with; at least VK_API_VERSION_1_1 */
    PFN_vkGetInstanceProcAddr get_instance_proc_addr; /* required: the host's loader entry */
    PFN_vkGetDeviceProcAddr get_device_proc_addr;     /* optional: NULL = from get_instance_proc_addr */
    VkPipelineCache pipeline_cache;                   /* optional */
    const VkAllocationCallbacks* allocator;           /* optional, used for every object the library makes */
    uint32_t max_frames_in_flight;                    /* recorded frames pending at once; 0 = 2, at most 16 */
    uint32_t debug_utils_enabled;                     /* non-zero: VK_EXT_debug_utils is enabled on the instance; dispatches get labels */
    /* ---- 0.11 (a 0.10 caller's size ends before this: read as NULL) ---- */
    /* Optional: the features the host enabled on `device` (what it passed as
     * VkDeviceCreateInfo.pEnabledFeatures or VkPhysicalDeviceFeatures2.features),
     * which Vulkan cannot report.  Non-NULL: creation is refused
     * (RRC_ERROR_UNSUPPORTED, naming the feature) unless every feature of
     * rrc_vulkan_requirements.features is VK_TRUE in it.  NULL: not stated,
     * unchecked.  Either way creation checks that the physical device
     * supports them, its API version and its limits. */
    const VkPhysicalDeviceFeatures* enabled_features;
} rrc_vulkan_device_desc;

/** One host image as the kernel sees it.  What Vulkan cannot report, the host
 *  gets right and rrc cannot check (docs/guide/integration.md, "What rrc checks and
 *  what it cannot"): its usage (SAMPLED for inputs, STORAGE for outputs, ages and
 *  the mask), its extent (the context's; state it with rrc_vulkan_image_extents
 *  to have it checked), no aliasing of another image's memory. */
typedef struct rrc_vulkan_image {
    VkImage image;
    VkImageView view;           /* 2D, one mip, one layer; for depth formats a view of the DEPTH aspect only
                                   (D32_SFLOAT_S8_UINT counts as D32); Vulkan cannot report a view's aspects */
    VkFormat format;            /* the view's format */
    VkImageLayout layout;       /* its layout when the recorded commands start, whatever it is (an attachment
                                   layout straight out of a render pass too; UNDEFINED discards an output's
                                   contents, for its first frame): rrc's barriers move it and cover any
                                   earlier stage's writes */
    VkImageLayout final_layout; /* the layout to leave it in; VK_IMAGE_LAYOUT_UNDEFINED = `layout` */
} rrc_vulkan_image;

typedef struct rrc_vulkan_channel_images {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_VULKAN_CHANNEL_IMAGES */
    const void* next;
    uint32_t size;
    rrc_vulkan_image samples;    /* required, SAMPLED usage, any float format: .r (1 component) or .rgba */
    rrc_vulkan_image confidence; /* required iff the channel has confidence: SAMPLED, weight in .r */
    rrc_vulkan_image output;     /* required, STORAGE usage, a float format: receives the accumulated value
                                    (with a fill, the displayed value: rrc.h rrc_channel_output.values) */
    /* ---- 0.2 (a 0.1 caller's size ends before this: read as zero) ---- */
    rrc_vulkan_image age; /* optional (image = NULL: none), STORAGE R16_UINT: the channel's age n after this frame */
    /* ---- 0.4 ---- */
    rrc_vulkan_image fallback; /* required iff the channel's fill_prior > 0 or residual (0.9, the base): SAMPLED, any float format, .r or .rgba */
} rrc_vulkan_channel_images;

/** What the kernel writes at rrc_vulkan_frame_desc.stats_buffer + stats_offset
 *  (std430: eight uint32 counters, 32 bytes): the same counts rrc_frame_stats
 *  reports on the standalone path.  Valid once the host's own fence (or a
 *  later barrier) says the recorded frame has finished. */
typedef struct rrc_vulkan_frame_stats {
    uint32_t hits;
    uint32_t misses; /* non-background pixels that are neither hits nor refreshed */
    uint32_t background;
    uint32_t invalid_samples;  /* pixels with RRC_MASK_INVALID_SAMPLE */
    uint32_t invalid_geometry; /* pixels with RRC_MASK_INVALID_GEOMETRY */
    uint32_t refreshed;        /* pixels with RRC_MASK_REFRESHED */
    uint32_t pixels;           /* width * height of the frame */
    uint32_t reserved;         /* 0 */
} rrc_vulkan_frame_stats;

typedef struct rrc_vulkan_frame_desc {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_VULKAN_FRAME_DESC */
    const void* next;
    uint32_t size;
    VkCommandBuffer command_buffer; /* recording, outside a render pass, of the context's queue family (Vulkan
                                       reports no command buffer state: unchecked); at most max_frames_in_flight
                                       recorded frames pending, and the context destroyed only after they finished */
    uint64_t frame_index;
    uint32_t reset;
    rrc_vulkan_image depth;        /* required, SAMPLED: D16/D24/D32 (depth view) or a colour format with depth in .r */
    rrc_vulkan_image reprojection; /* SAMPLED, float: PREV_CLIP rgba, MOTION rg, MOTION_DEPTH rgb; unused for CAMERA */
    rrc_vulkan_image nocache;      /* SAMPLED R8_UINT, required iff use_nocache_mask */
    rrc_vulkan_image mask;         /* optional (image = NULL: none), STORAGE R8_UINT: the RRC_MASK_* bits */
    double view_proj[16];          /* as rrc_frame_desc */
    double prev_view_proj[16];
    float jitter[2];
    float prev_jitter[2];
    uint32_t channel_count;                    /* the context's */
    const rrc_vulkan_channel_images* channels; /* strided by channels[0].size (rrc.h Versioning, rule 3) */
    /* ---- 0.2 (a 0.1 caller's size ends before this: read as zero) ---- */
    /* Optional (VK_NULL_HANDLE: none): a host buffer with STORAGE_BUFFER and
     * TRANSFER_DST usage; the recorded commands clear and fill an
     * rrc_vulkan_frame_stats at stats_offset (a multiple of the device's
     * minStorageBufferOffsetAlignment; 256 always is) and make it visible to
     * the host (HOST_READ) and to any later command.  Give each frame in
     * flight its own offset to read N frames' statistics after one wait. */
    VkBuffer stats_buffer;
    VkDeviceSize stats_offset;
    /* Required iff the context's use_object_id: SAMPLED R16_UINT or R32_UINT,
     * each pixel's object id (rrc_frame_desc.object_id). */
    rrc_vulkan_image object_id;
    /* Non-zero: this frame's depth, reprojection, nocache, samples and
     * confidence images also have STORAGE usage and are in the formats the
     * kernel loads directly: depth R32_SFLOAT (a colour image), reprojection
     * R32G32B32A32_SFLOAT (every source that reads it), nocache R8_UINT,
     * samples R32_SFLOAT (1 component) or R32G32B32A32_SFLOAT (4),
     * confidence R32_SFLOAT.  The kernel then reads them with storage loads,
     * not through samplers: on lavapipe a sampler fetch costs several
     * storage loads (docs/measurements/PERFORMANCE.md, "Sampled or storage inputs").
     * Zero: any sampled format, as above.  Object ids are sampled either way. */
    uint32_t storage_inputs;
    /* ---- 0.3 ---- */
    uint32_t view;           /* as rrc_frame_desc.view */
    uint32_t reproject_from; /* as rrc_frame_desc.reproject_from */
    /* ---- 0.5 ---- */
    /* The shading cache's split frame (below).  Zero: classify writes none of
     * the host's images (read right after classify, the mask image still
     * holds what the last resolve or frame wrote); resolve writes the output,
     * age and mask images at every pixel.  Non-zero: classify also writes the
     * mask image at every pixel (every bit but INVALID_SAMPLE, which resolve
     * adds at the listed quads' pixels) and, when every channel is REUSE, the
     * output and age images at every HIT; resolve then writes them only at
     * the listed quads' pixels, so the images are complete after resolve
     * without a full-frame copy (docs/guide/integration.md, "The shading cache").
     * Classify then moves the output, age and mask images as resolve does.
     * rrc_vulkan_record_frame ignores it. */
    uint32_t split_outputs;
    /* ---- 0.7 ---- */
    double camera_position[3];      /* as rrc_frame_desc.camera_position */
    double prev_camera_position[3]; /* as rrc_frame_desc.prev_camera_position */
    /* ---- 0.8 ---- */
    float lighting_turn; /* as rrc_frame_desc.lighting_turn (rrc.h) */
    /* ---- 0.10 ---- */
    /* The stats buffer's size in bytes (its VkBufferCreateInfo.size), which
     * Vulkan cannot report.  Non-zero: stats_offset +
     * sizeof(rrc_vulkan_frame_stats) must lie within it, else the frame is
     * refused (RRC_ERROR_SIZE_MISMATCH) and nothing is recorded.  Zero: not
     * stated (a caller before 0.10), unchecked: then a range past the
     * buffer's end is written (docs/guide/integration.md, "What rrc checks and
     * what it cannot"). */
    VkDeviceSize stats_buffer_size;
    /* ---- 0.13 ---- */
    /* Non-zero: rrc_vulkan_record_frame also counts the image loads and
     * stores its dispatches make, and writes an rrc_vulkan_io_counts (below)
     * right after the statistics, at stats_offset + sizeof(rrc_vulkan_frame_stats).
     * Needs stats_buffer (else refused, RRC_ERROR_INVALID_ARGUMENT); with
     * stats_buffer_size, the range checked is both structs.  For measuring
     * only: the frame runs a counting variant of its pipelines, with atomics
     * at every pixel, whose outputs equal the plain frame's but whose time
     * does not.  rrc_vulkan_record_classify and _resolve count nothing (the
     * checks above still apply). */
    uint32_t count_io;
} rrc_vulkan_frame_desc;

/** What a frame with count_io writes after its rrc_vulkan_frame_stats
 *  (std430: five uint64 counters, 40 bytes, each written as two 32-bit
 *  words, low word first): the image operations of the frame's per-pixel
 *  dispatches (the frame and, with a spatial fill, the fill) at the pixels
 *  inside the frame.  A load is one imageLoad, texelFetch or textureGather;
 *  `texels_loaded` counts a gather's four texels.  Bytes are each texel's
 *  size in the format the kernel reads or writes: the library's own images
 *  in their formats, the host's inputs as rrc-bench's roof counts them
 *  (depth 4, reprojection 16 or, MOTION through a sampler, 8, samples 4 a
 *  component, confidence 4, object ids 4, a fallback 4 a component) and the
 *  host's outputs at the channel's history precision
 *  (docs/measurements/PERFORMANCE.md, "What a pixel moves").
 *  Divide by rrc_vulkan_frame_stats.pixels for figures a pixel. */
typedef struct rrc_vulkan_io_counts {
    uint64_t loads;         /* load instructions */
    uint64_t texels_loaded; /* texels they read */
    uint64_t bytes_loaded;
    uint64_t stores;        /* imageStore instructions (one texel each) */
    uint64_t bytes_stored;
} rrc_vulkan_io_counts;

/* ---- Image extents (0.11): what Vulkan cannot report -------------------- *
 * An extension on rrc_vulkan_frame_desc.next (rrc.h Versioning, rule 5) for
 * rrc_vulkan_record_frame, _classify and _resolve: the host states the extent
 * it created its images with (VkImageCreateInfo.extent).  With it, every
 * image the frame binds must be listed, and each must be the context's width
 * x height: else the call is refused (RRC_ERROR_INVALID_ARGUMENT for an image
 * not listed or listed twice with two extents, RRC_ERROR_SIZE_MISMATCH for
 * an extent other than the context's) and nothing is recorded.  Images
 * listed but not bound are ignored, so one table of all the host's images
 * serves every frame.  Without it, extents are unchecked: an image larger
 * than the context is written only in its top-left corner, a smaller one
 * reads garbage (docs/guide/integration.md, "What rrc checks and what it cannot"). */
typedef struct rrc_vulkan_image_extent {
    VkImage image;
    uint32_t width, height;
} rrc_vulkan_image_extent;

typedef struct rrc_vulkan_image_extents {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_EXT_VULKAN_IMAGE_EXTENTS */
    const void* next;     /* the rest of the chain */
    uint32_t size;        /* sizeof(rrc_vulkan_image_extents) */
    uint32_t count;       /* 1..RRC_MAX_IMAGE_EXTENTS */
    const rrc_vulkan_image_extent* images;
} rrc_vulkan_image_extents;
#define RRC_MAX_IMAGE_EXTENTS 4096u

/** Creates a context on the host's device (no device of its own). */
RRC_API rrc_result rrc_vulkan_context_create(const rrc_context_desc* desc, const rrc_vulkan_device_desc* device, rrc_context** out_context);

/** Records one frame into frame->command_buffer: barriers, one dispatch,
 *  barriers.  The frame becomes the "previous frame" of the next call.  On
 *  error nothing is recorded.  Only for contexts made by rrc_vulkan_context_create. */
RRC_API rrc_result rrc_vulkan_record_frame(rrc_context* context, const rrc_vulkan_frame_desc* frame);

/* ---- The shading cache in the host's command buffer (0.3) --------------- *
 * The split frame of rrc.h ("The shading cache"), recorded:
 *
 *   rrc_vulkan_record_classify(ctx, &frame, &list)
 *   vkCmdDispatchIndirect(cmd, list.buffer, list.offset + 4 * RRC_QUAD_LIST_DISPATCH)
 *       the host's miss shader: workgroup g shades quads g*RRC_QUADS_PER_GROUP..
 *       of the list, every pixel of each, into the channels' `samples` images
 *   rrc_vulkan_record_resolve(ctx, &frame)
 *
 * Both calls take the same frame descriptor (the same frame_index; resolve
 * reads the channels, classify does not).  Each call moves every host image
 * it uses from `layout` to `final_layout`: pass layout == final_layout, or
 * give resolve the layouts classify left.  The quad list buffer is the
 * host's: classify clears and fills it and ends with a barrier from its
 * writes to DRAW_INDIRECT (INDIRECT_COMMAND_READ) and COMPUTE_SHADER
 * (SHADER_READ), so a compute miss shader may read it at once; a graphics
 * miss pass adds its own barrier from COMPUTE_SHADER / SHADER_WRITE to its
 * stages.  Resolve's barriers make the host's writes to the samples images
 * (any stage) visible to it, as rrc_vulkan_record_frame's do.  Resolve
 * reads the list too: in a context of REUSE channels only it runs on the
 * listed quads alone (an indirect dispatch from the list; classify computed
 * the HITs), so neither the host's shader nor anything else may write the
 * list between classify and resolve.  A list must not be overwritten (by
 * the next frame's classify) before the host's dispatch and resolve that
 * read it have run: one list per frame in flight, or the same one, since
 * recorded commands run in order on one queue.  What each call writes of the
 * host's images: rrc_vulkan_frame_desc.split_outputs. */

typedef struct rrc_vulkan_quad_list {
    rrc_struct_type type; /* RRC_STRUCT_TYPE_VULKAN_QUAD_LIST */
    const void* next;
    uint32_t size;
    VkBuffer buffer;     /* STORAGE_BUFFER, INDIRECT_BUFFER and TRANSFER_DST usage */
    VkDeviceSize offset; /* a multiple of minStorageBufferOffsetAlignment (256 always is);
                            RRC_QUAD_LIST_BYTES(width, height) bytes from it are written */
    /* ---- 0.10 ---- */
    /* The buffer's size in bytes (VkBufferCreateInfo.size).  Non-zero: offset +
     * RRC_QUAD_LIST_BYTES(width, height) must lie within it, else classify is
     * refused (RRC_ERROR_SIZE_MISMATCH) and nothing is recorded.  Zero: not
     * stated (a caller before 0.10), unchecked. */
    VkDeviceSize buffer_size;
} rrc_vulkan_quad_list;

/** Records classify: barriers, the list's clear, one dispatch, barriers.
 *  The frame's statistics buffer (if any) is cleared and receives every
 *  count but invalid_samples, which resolve adds.  History does not change. */
RRC_API rrc_result rrc_vulkan_record_classify(rrc_context* context, const rrc_vulkan_frame_desc* frame, const rrc_vulkan_quad_list* list);

/** Records resolve for the frame classify recorded last: the frame becomes
 *  the "previous frame" of the next.  Without a classified frame of the same
 *  frame_index: RRC_ERROR_INVALID_ARGUMENT, nothing recorded. */
RRC_API rrc_result rrc_vulkan_record_resolve(rrc_context* context, const rrc_vulkan_frame_desc* frame);

#ifdef __cplusplus
}
#endif

#endif /* RRC_RRC_VULKAN_H */
