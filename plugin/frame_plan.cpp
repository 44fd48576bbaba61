#include "frame_plan.h"

#include <rrc/rrc_vulkan.h>

#include <cstdio>
#include <cstring>

namespace rrc {
namespace {

uint32_t all_channels(const ContextConfig& c) { return (1u << c.channels.size()) - 1u; }

PlanStep dispatch(uint32_t pass, PlanSet set, PlanGrid grid) {
    PlanStep s;
    s.kind = PlanStep::Kind::Dispatch;
    s.variant.pass = pass;
    s.set = set;
    s.grid = grid;
    return s;
}

PlanStep barrier(PlanResource resource, VkPipelineStageFlags src_stages, VkAccessFlags src_access, VkPipelineStageFlags dst_stages,
                 VkAccessFlags dst_access, VkImageLayout old_layout = VK_IMAGE_LAYOUT_UNDEFINED,
                 VkImageLayout new_layout = VK_IMAGE_LAYOUT_UNDEFINED) {
    PlanStep s;
    s.kind = PlanStep::Kind::Barrier;
    s.resource = resource;
    s.src_stages = src_stages, s.src_access = src_access;
    s.dst_stages = dst_stages, s.dst_access = dst_access;
    s.old_layout = old_layout, s.new_layout = new_layout;
    return s;
}

PlanStep step(PlanStep::Kind kind, PlanResource resource = PlanResource::Memory) {
    PlanStep s;
    s.kind = kind;
    s.resource = resource;
    return s;
}

constexpr VkPipelineStageFlags kCompute = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, kTransfer = VK_PIPELINE_STAGE_TRANSFER_BIT,
                               kIndirect = VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT, kAll = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                               kHost = VK_PIPELINE_STAGE_HOST_BIT;
constexpr VkAccessFlags kRead = VK_ACCESS_SHADER_READ_BIT, kWrite = VK_ACCESS_SHADER_WRITE_BIT,
                        kIndirectRead = VK_ACCESS_INDIRECT_COMMAND_READ_BIT, kTransferWrite = VK_ACCESS_TRANSFER_WRITE_BIT,
                        kMemory = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;

// A buffer's first words written before the passes: the earlier use of
// those bytes (`src`: any stage, or the previous frame's passes and indirect
// read) finishes first, and the passes see the words.
void clear(std::vector<PlanStep>& steps, PlanResource buffer, std::vector<uint32_t> words, VkPipelineStageFlags src_stages,
           VkAccessFlags src_access) {
    steps.push_back(barrier(buffer, src_stages, src_access, kTransfer, kTransferWrite));
    PlanStep c = step(PlanStep::Kind::Clear, buffer);
    c.words = std::move(words);
    steps.push_back(c);
    steps.push_back(barrier(buffer, kTransfer, kTransferWrite, kCompute, kRead | kWrite));
}

// What each pass reads and writes (compute/rrc_module_*.comp); brackets:
// only when the configuration or the frame has it.
const char* pass_bindings(uint32_t pass, bool all_reuse) {
    switch (pass) {
        case RRC_PASS_FUSED:
            return "reads depth, reprojection, [nocache, ids], samples, [confidence, base], previous depth, history, age, [weight, previous "
                   "ids]; writes history, age, [weight], mask, [depth and id copies, host outputs, fill list]";
        case RRC_PASS_CLASSIFY:
            return all_reuse ? "reads depth, reprojection, [nocache, ids], previous depth, history, age, [previous ids]; writes mask, "
                               "[depth and id copies]; at HITs history, age, [weight, host outputs, fill list]"
                             : "reads depth, reprojection, [nocache, ids], previous depth, [history ages for refresh, previous ids]; "
                               "writes mask, [depth and id copies]";
        case RRC_PASS_LIST: return "reads mask; writes quad list";
        case RRC_PASS_RESOLVE:
            return "reads mask, samples, [confidence, base], history, age, [weight]; writes history, age, [weight], mask, [host outputs, "
                   "fill list]";
        case RRC_PASS_RESOLVE_LISTED:
            return "reads quad list, mask, samples, [confidence]; at listed pixels that are not HITs writes history, age, [weight], mask, "
                   "[host outputs, fill list]";
        case RRC_PASS_COPY_OUT: return "reads this frame's history, age, mask; writes host outputs, [host ages, host mask]";
        case RRC_PASS_FILL: return "reads fill list, this frame's history, age, depth, [fallback or base]; writes displayed values";
    }
    return "?";
}

}  // namespace

const char* pass_name(uint32_t pass) {
    switch (pass) {
        case RRC_PASS_FUSED: return "FUSED";
        case RRC_PASS_CLASSIFY: return "CLASSIFY";
        case RRC_PASS_LIST: return "LIST";
        case RRC_PASS_RESOLVE: return "RESOLVE";
        case RRC_PASS_FILL: return "FILL";
        case RRC_PASS_RESOLVE_LISTED: return "RESOLVE_LISTED";
        case RRC_PASS_COPY_OUT: return "COPY_OUT";
    }
    return "?";
}

bool all_reuse(const ContextConfig& c) {
    for (const ChannelConfig& ch : c.channels)
        if (ch.blend != RRC_BLEND_REUSE) return false;
    return !c.channels.empty();
}

FramePlan make_plan(const ContextConfig& c, const PlanRequest& r) {
    FramePlan plan;
    auto& steps = plan.steps;
    if (r.call == PlanCall::Initialise) {
        PlanStep label = step(PlanStep::Kind::BeginLabel);
        label.label = "rrc: initialise";
        steps.push_back(label);
        steps.push_back(step(PlanStep::Kind::Initialise, PlanResource::LibraryImages));
        steps.push_back(step(PlanStep::Kind::EndLabel));
        return plan;
    }
    const bool reuse = all_reuse(c), fill = c.fill_mask() != 0;
    // The host's outputs on the Vulkan path; on the standalone path a fill's or a residual's displayed values.
    const uint32_t outputs = r.interop ? all_channels(c) : c.displayed_mask();
    const uint32_t split_outputs = r.interop && r.split_outputs ? all_channels(c) : r.interop ? 0u : c.displayed_mask();
    const uint32_t split_ages = r.interop && r.split_outputs ? r.host_age_mask : 0u;
    // The passes, then what the sets bind (below).
    std::vector<PlanStep> passes;
    auto pass_barrier = [&](bool to_indirect) {
        // The previous pass's writes to the next pass's reads (and, to an indirect dispatch, its indirect read).
        passes.push_back(barrier(PlanResource::Memory, kCompute, kWrite, kCompute | (to_indirect ? kIndirect : 0),
                                 kRead | kWrite | (to_indirect ? kIndirectRead : 0)));
    };
    // A frame that counts its image operations (rrc_vulkan_frame_desc.count_io) counts them in its
    // per-pixel passes, the frame's and the fill's, into the statistics buffer.
    const bool count_io = r.stats && r.count_io && r.call == PlanCall::Run;
    auto add_fill = [&]() {
        if (!fill) return;
        pass_barrier(true);
        PlanStep s = dispatch(RRC_PASS_FILL, PlanSet::Next, PlanGrid::FillList);
        s.variant.count_io = count_io;
        passes.push_back(s);
    };
    auto counted = [&](PlanStep s) {
        s.variant.stats = r.stats;
        s.variant.count_io = count_io;
        return s;
    };
    // Classify writes its mask into the host's image when the host asks for
    // it after classify (split_outputs), else into the library's; the list
    // pass reads it there.
    const bool host_classified = r.interop && r.split_outputs && r.host_mask;
    bool frame_set_host_mask = false, clears_fill_list = false;
    auto add_list = [&]() {
        pass_barrier(false);
        PlanStep list = dispatch(RRC_PASS_LIST, PlanSet::Frame, PlanGrid::Quads);
        list.variant.mask_in_place = true;
        passes.push_back(list);
    };
    switch (r.call) {
        case PlanCall::Initialise: break;
        case PlanCall::Run: {
            frame_set_host_mask = r.host_mask;
            clears_fill_list = fill;
            PlanStep s = counted(dispatch(RRC_PASS_FUSED, PlanSet::Frame, PlanGrid::Pixels));
            s.variant.host_out_mask = outputs;
            s.variant.host_age_mask = r.host_age_mask;
            passes.push_back(s);
            add_fill();
            break;
        }
        case PlanCall::Classify: {
            frame_set_host_mask = host_classified;
            clears_fill_list = reuse && fill;
            PlanStep s = counted(dispatch(RRC_PASS_CLASSIFY, PlanSet::Frame, PlanGrid::Pixels));
            if (reuse) s.variant.host_out_mask = split_outputs, s.variant.host_age_mask = split_ages;
            passes.push_back(s);
            add_list();
            break;
        }
        case PlanCall::Resolve: {
            if (!reuse) {
                frame_set_host_mask = r.host_mask;
                clears_fill_list = fill;
                PlanStep s = counted(dispatch(RRC_PASS_RESOLVE, PlanSet::Frame, PlanGrid::Pixels));
                s.variant.mask_in_place = !r.host_mask || host_classified;  // else classify's mask is the library's, read through a sampler
                s.variant.host_out_mask = outputs;
                s.variant.host_age_mask = r.host_age_mask;
                passes.push_back(s);
                add_fill();
                break;
            }
            // Only the listed pixels that are not HITs (classify wrote the HITs).
            frame_set_host_mask = host_classified;
            PlanStep s = counted(dispatch(RRC_PASS_RESOLVE_LISTED, PlanSet::Frame, PlanGrid::QuadList));
            s.variant.mask_in_place = true;
            s.variant.host_out_mask = split_outputs;
            s.variant.host_age_mask = split_ages;
            passes.push_back(s);
            if (r.interop && !r.split_outputs) {
                // The host's images get every pixel: a copy of the library's results.
                pass_barrier(false);
                PlanStep copy = dispatch(RRC_PASS_COPY_OUT, PlanSet::Next, PlanGrid::Pixels);
                copy.variant.host_out_mask = all_channels(c);
                copy.variant.host_age_mask = r.host_age_mask;
                copy.variant.copy_mask = r.host_mask;
                passes.push_back(copy);
            }
            add_fill();
            break;
        }
    }

    // What each set binds: the host's images where a pass bound with it writes
    // them, the mask where the plan puts it, the inputs the call reads.
    PlanSetContents& frame = plan.sets[(int)PlanSet::Frame];
    frame.host_mask = frame_set_host_mask;
    frame.channel_inputs = r.call != PlanCall::Classify;
    for (const ChannelConfig& ch : c.channels) frame.fallbacks = frame.fallbacks || ch.residual;
    frame.stats = r.stats;
    plan.sets[(int)PlanSet::Next].stats = count_io;  // the fill counts into the same buffer
    plan.count_io = count_io;
    frame.quad_list = r.call == PlanCall::Classify || (r.call == PlanCall::Resolve && reuse);
    plan.sets[(int)PlanSet::Next].fallbacks = true;
    for (const PlanStep& s : passes) {
        if (s.kind != PlanStep::Kind::Dispatch) continue;
        PlanSetContents& set = plan.sets[(int)s.set];
        set.used = true;
        set.host_outputs |= s.variant.host_out_mask | (s.variant.pass == RRC_PASS_FILL ? c.fill_mask() : 0u);
        set.host_ages |= s.variant.host_age_mask;
        set.host_mask = set.host_mask || s.variant.copy_mask;
    }

    // The whole call, in order.
    PlanStep label = step(PlanStep::Kind::BeginLabel);
    label.label = r.call == PlanCall::Classify  ? "rrc: classify"
                  : r.call == PlanCall::Resolve ? "rrc: resolve"
                                                : "rrc: reproject + accumulate";
    steps.push_back(label);
    if (r.first_use) steps.push_back(step(PlanStep::Kind::Initialise, PlanResource::LibraryImages));
    // The previous frame's passes (and, standalone, its copies) wrote what
    // this one reads and read what this one overwrites.
    const VkPipelineStageFlags prior = kCompute | (r.interop ? 0 : kTransfer);
    steps.push_back(barrier(PlanResource::Memory, prior, kWrite | (r.interop ? 0 : kTransferWrite), kCompute | kIndirect,
                            kRead | kWrite | kIndirectRead));
    if (r.interop) {
        // The host's images come over (from any stage, in the host's layouts).
        steps.push_back(barrier(PlanResource::HostImagesIn, kAll, 0, kCompute, 0));
    } else {
        // The call's inputs from staging; their old contents are discarded.
        steps.push_back(barrier(PlanResource::Inputs, prior, 0, kTransfer, kTransferWrite, VK_IMAGE_LAYOUT_UNDEFINED,
                                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL));
        steps.push_back(step(PlanStep::Kind::Upload, PlanResource::Inputs));
        steps.push_back(barrier(PlanResource::Inputs, kTransfer, kTransferWrite, kCompute, kRead, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                VK_IMAGE_LAYOUT_GENERAL));
    }
    // The frame's counters start at zero, `pixels` at its size; resolve adds
    // its counts (invalid samples) to classify's.
    if (r.stats && r.call != PlanCall::Resolve) {
        rrc_vulkan_frame_stats start{};
        start.pixels = c.width * c.height;
        std::vector<uint32_t> words(sizeof start / sizeof(uint32_t));
        std::memcpy(words.data(), &start, sizeof start);
        if (count_io) words.resize(words.size() + sizeof(rrc_vulkan_io_counts) / sizeof(uint32_t), 0u);
        clear(steps, PlanResource::Stats, words, kAll, kMemory);
    }
    // Classify's list starts empty with a dispatch of {0, 1, 1}; the host's
    // earlier use of those bytes (its indirect dispatch of a frame before) finishes first.
    if (r.call == PlanCall::Classify) clear(steps, PlanResource::QuadList, {0, 0, 1, 1}, kAll, kMemory);
    // The frame's camera for the view lobe: written by the calls that carry a
    // frame (resolve reads what classify wrote), after the previous frame's
    // passes finish reading it.
    if (c.view_lobe() && r.call != PlanCall::Resolve) {
        steps.push_back(barrier(PlanResource::ViewBuffer, kCompute, kRead, kTransfer, kTransferWrite));
        steps.push_back(step(PlanStep::Kind::WriteView, PlanResource::ViewBuffer));
        steps.push_back(barrier(PlanResource::ViewBuffer, kTransfer, kTransferWrite, kCompute, kRead));
    }
    // The fill list starts empty, after the previous frame's fill (its indirect read and its loads).
    if (clears_fill_list) {
        // The dispatch {0, 1, 1} and every sub-list's count 0 (rrc_kernel_interface.h).
        std::vector<uint32_t> header(RRC_FILL_LIST_FIRST, 0u);
        header[RRC_FILL_LIST_DISPATCH + 1] = header[RRC_FILL_LIST_DISPATCH + 2] = 1;
        clear(steps, PlanResource::FillList, std::move(header), kCompute | kIndirect, kRead | kWrite | kIndirectRead);
    }
    steps.insert(steps.end(), passes.begin(), passes.end());
    // The list to the host: its indirect dispatch and miss shader (rrc_vulkan.h), or the CPU.
    if (r.call == PlanCall::Classify)
        steps.push_back(r.interop ? barrier(PlanResource::QuadList, kCompute, kWrite, kIndirect | kCompute, kIndirectRead | kRead)
                                  : barrier(PlanResource::QuadList, kCompute, kWrite, kHost, VK_ACCESS_HOST_READ_BIT));
    if (r.interop) {
        // The kernel's writes to whatever the host does next.
        steps.push_back(barrier(PlanResource::HostImagesOut, kCompute, 0, kAll, 0));
        // The counters to the host (after its fence) and to any later command.
        if (r.stats) steps.push_back(barrier(PlanResource::Stats, kCompute, kWrite, kAll | kHost, VK_ACCESS_HOST_READ_BIT | kMemory));
    } else {
        // What the host asked for (and the mask, for the statistics) is copied
        // out, then back to GENERAL: the next frame reads it as history.
        steps.push_back(barrier(PlanResource::Outputs, kCompute, kWrite, kTransfer, VK_ACCESS_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
        steps.push_back(step(PlanStep::Kind::Readback, PlanResource::Outputs));
        steps.push_back(barrier(PlanResource::Outputs, kTransfer, 0, kCompute, kRead | kWrite, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                VK_IMAGE_LAYOUT_GENERAL));
        steps.push_back(barrier(PlanResource::Memory, kTransfer, kTransferWrite, kHost, VK_ACCESS_HOST_READ_BIT));
    }
    steps.push_back(step(PlanStep::Kind::EndLabel));
    return plan;
}


namespace {

std::string flag_names(uint32_t flags, std::initializer_list<std::pair<uint32_t, const char*>> names) {
    std::string out;
    for (const auto& n : names)
        if (flags & n.first) out += (out.empty() ? "" : "|") + std::string(n.second);
    return out.empty() ? "0" : out;
}

std::string stages(VkPipelineStageFlags f) {
    return flag_names(f, {{kAll, "ALL_COMMANDS"}, {kIndirect, "DRAW_INDIRECT"}, {kCompute, "COMPUTE"}, {kTransfer, "TRANSFER"}, {kHost, "HOST"}});
}

std::string accesses(VkAccessFlags f) {
    return flag_names(f, {{VK_ACCESS_INDIRECT_COMMAND_READ_BIT, "INDIRECT_READ"},
                          {kRead, "SHADER_READ"},
                          {kWrite, "SHADER_WRITE"},
                          {VK_ACCESS_TRANSFER_READ_BIT, "TRANSFER_READ"},
                          {kTransferWrite, "TRANSFER_WRITE"},
                          {VK_ACCESS_HOST_READ_BIT, "HOST_READ"},
                          {VK_ACCESS_MEMORY_READ_BIT, "MEMORY_READ"},
                          {VK_ACCESS_MEMORY_WRITE_BIT, "MEMORY_WRITE"}});
}

const char* layout_name(VkImageLayout l) {
    switch (l) {
        case VK_IMAGE_LAYOUT_UNDEFINED: return "UNDEFINED";
        case VK_IMAGE_LAYOUT_GENERAL: return "GENERAL";
        case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL: return "TRANSFER_SRC";
        case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL: return "TRANSFER_DST";
        default: return "?";
    }
}

const char* resource_name(PlanResource r) {
    switch (r) {
        case PlanResource::Memory: return "memory";
        case PlanResource::LibraryImages: return "library images";
        case PlanResource::FillList: return "fill list";
        case PlanResource::ViewBuffer: return "view buffer";
        case PlanResource::QuadList: return "quad list";
        case PlanResource::Stats: return "statistics buffer";
        case PlanResource::HostImagesIn: return "host images (host layouts -> kernel's)";
        case PlanResource::HostImagesOut: return "host images (kernel's -> final layouts)";
        case PlanResource::Inputs: return "inputs";
        case PlanResource::Outputs: return "outputs";
    }
    return "?";
}

std::string set_text(const PlanSetContents& s) {
    char line[160];
    std::snprintf(line, sizeof line, "%s%s%s mask; host outputs 0x%x, host ages 0x%x%s%s", s.channel_inputs ? "channel inputs, " : "",
                  s.fallbacks ? "fallbacks, " : "", s.host_mask ? "host's" : "library's", s.host_outputs, s.host_ages,
                  s.stats ? ", statistics buffer" : "", s.quad_list ? ", quad list" : "");
    return line;
}

}  // namespace


std::string describe_plan(const FramePlan& plan, const ContextConfig& c) {
    std::string out;
    char line[512];
    const uint32_t gx = AccumulatePipeline::kGroupX, w = c.width, h = c.height, qw = (w + 1) / 2, qh = (h + 1) / 2;
    for (int set = 0; set < 2; ++set)
        if (plan.sets[set].used) out += std::string("  set ") + (set == 0 ? "frame" : "next") + " binds: " + set_text(plan.sets[set]) + "\n";
    for (const PlanStep& s : plan.steps) {
        switch (s.kind) {
            case PlanStep::Kind::BeginLabel: out += std::string("  begin label \"") + s.label + "\"\n"; break;
            case PlanStep::Kind::EndLabel: out += "  end label\n"; break;
            case PlanStep::Kind::Initialise: out += "  initialise library images: UNDEFINED -> GENERAL, cleared to 0\n"; break;
            case PlanStep::Kind::Barrier: {
                std::string layouts;
                if (s.resource == PlanResource::Inputs || s.resource == PlanResource::Outputs)
                    layouts = std::string(", ") + layout_name(s.old_layout) + " -> " + layout_name(s.new_layout);
                std::snprintf(line, sizeof line, "  barrier %s: %s %s -> %s %s%s\n", resource_name(s.resource), stages(s.src_stages).c_str(),
                              accesses(s.src_access).c_str(), stages(s.dst_stages).c_str(), accesses(s.dst_access).c_str(), layouts.c_str());
                out += line;
                break;
            }
            case PlanStep::Kind::Clear: {
                std::string words;
                // A run of one value is written once, with its length: "0 x269".
                for (size_t i = 0, n; i < s.words.size(); i += n) {
                    for (n = 1; i + n < s.words.size() && s.words[i + n] == s.words[i];) ++n;
                    words += (words.empty() ? "" : ", ") + std::to_string(s.words[i]) + (n > 3 ? " x" + std::to_string(n) : "");
                    if (n <= 3) n = 1;
                }
                out += std::string("  clear ") + resource_name(s.resource) + " {" + words + "}\n";
                break;
            }
            case PlanStep::Kind::WriteView: out += "  write view buffer from the frame's camera\n"; break;
            case PlanStep::Kind::Upload: out += "  upload inputs from staging (one copy an image)\n"; break;
            case PlanStep::Kind::Readback: out += "  read back outputs into staging (one copy an image)\n"; break;
            case PlanStep::Kind::Dispatch: {
                const KernelVariant& v = s.variant;
                std::string grid;
                if (s.grid == PlanGrid::Pixels)
                    grid = std::to_string((w + gx - 1) / gx) + "x" + std::to_string(h) + " groups (pixels)";
                else if (s.grid == PlanGrid::Quads)
                    grid = std::to_string((qw + gx - 1) / gx) + "x" + std::to_string(qh) + " groups (2x2 quads)";
                else if (s.grid == PlanGrid::QuadList)
                    grid = "indirect (quad list, " + std::to_string(RRC_QUADS_PER_GROUP) + " quads a group)";
                else
                    grid = "indirect (fill list, " + std::to_string(RRC_FILL_LIST_PER_GROUP) + " pixels a group)";
                std::snprintf(line, sizeof line, "  %s over %s; set %s; host outputs 0x%x, host ages 0x%x%s%s%s%s\n    %s\n", pass_name(v.pass),
                              grid.c_str(), s.set == PlanSet::Frame ? "frame" : "next", v.host_out_mask, v.host_age_mask,
                              v.stats ? "; statistics" : "", v.count_io ? "; counts image operations" : "", v.copy_mask ? "; copies the mask" : "", v.mask_in_place ? "; reads the mask in place" : "",
                              pass_bindings(v.pass, all_reuse(c)));
                out += line;
                break;
            }
        }
    }
    return out;
}

}  // namespace rrc
