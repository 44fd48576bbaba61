#include "frame_plan.h"

#include <cstdio>

namespace rrc {
namespace {

uint32_t all_channels(const ContextConfig& c) { return (1u << c.channels.size()) - 1u; }

PlanStep dispatch(uint32_t phase, PlanSet set, PlanGrid grid) {
    PlanStep s;
    s.op = PlanStep::Op::Dispatch;
    s.variant.phase = phase;
    s.set = set;
    s.grid = grid;
    return s;
}

PlanStep barrier(bool to_indirect) {
    PlanStep s;
    s.op = PlanStep::Op::Barrier;
    s.to_indirect = to_indirect;
    return s;
}

PlanStep clear_fill_list() {
    PlanStep s;
    s.op = PlanStep::Op::ClearFillList;
    return s;
}

PlanStep write_view() {
    PlanStep s;
    s.op = PlanStep::Op::WriteView;
    return s;
}

const char* phase_name(uint32_t phase) {
    switch (phase) {
        case RRC_PHASE_FUSED: return "FUSED";
        case RRC_PHASE_CLASSIFY: return "CLASSIFY";
        case RRC_PHASE_LIST: return "LIST";
        case RRC_PHASE_RESOLVE: return "RESOLVE";
        case RRC_PHASE_FILL: return "FILL";
        case RRC_PHASE_RESOLVE_LISTED: return "RESOLVE_LISTED";
        case RRC_PHASE_COPY_OUT: return "COPY_OUT";
    }
    return "?";
}

// What each pass reads and writes (compute/rrc_pass_*.comp); brackets:
// only when the configuration or the frame has it.
const char* phase_bindings(uint32_t phase, bool all_reuse) {
    switch (phase) {
        case RRC_PHASE_FUSED:
            return "reads depth, reprojection, [nocache, ids], samples, [confidence, base], previous depth, history, age, [weight, previous "
                   "ids]; writes history, age, [weight], mask, [depth and id copies, host outputs, fill list]";
        case RRC_PHASE_CLASSIFY:
            return all_reuse ? "reads depth, reprojection, [nocache, ids], previous depth, history, age, [previous ids]; writes mask, "
                               "[depth and id copies]; at HITs history, age, [weight, host outputs, fill list]"
                             : "reads depth, reprojection, [nocache, ids], previous depth, [history ages for refresh, previous ids]; "
                               "writes mask, [depth and id copies]";
        case RRC_PHASE_LIST: return "reads mask; writes quad list";
        case RRC_PHASE_RESOLVE:
            return "reads mask, samples, [confidence, base], history, age, [weight]; writes history, age, [weight], mask, [host outputs, "
                   "fill list]";
        case RRC_PHASE_RESOLVE_LISTED:
            return "reads quad list, mask, samples, [confidence]; at listed pixels that are not HITs writes history, age, [weight], mask, "
                   "[host outputs, fill list]";
        case RRC_PHASE_COPY_OUT: return "reads this frame's history, age, mask; writes host outputs, [host ages, host mask]";
        case RRC_PHASE_FILL: return "reads fill list, this frame's history, age, depth, [fallback or base]; writes displayed values";
    }
    return "?";
}

}  // namespace

bool all_reuse(const ContextConfig& c) {
    for (const ChannelConfig& ch : c.channels)
        if (ch.blend != RRC_BLEND_REUSE) return false;
    return !c.channels.empty();
}

bool FramePlan::uses(PlanSet set) const {
    for (const PlanStep& s : steps)
        if (s.op == PlanStep::Op::Dispatch && s.set == set) return true;
    return false;
}

FramePlan make_plan(const ContextConfig& c, const PlanRequest& r) {
    FramePlan plan;
    auto& steps = plan.steps;
    const bool reuse = all_reuse(c), fill = c.fill_mask() != 0;
    // The host's outputs on the Vulkan path; on the standalone path a fill's or a residual's displayed values.
    const uint32_t outputs = r.interop ? all_channels(c) : c.displayed_mask();
    const uint32_t split_outputs = r.interop && r.split_outputs ? all_channels(c) : r.interop ? 0u : c.displayed_mask();
    const uint32_t split_ages = r.interop && r.split_outputs ? r.host_age_mask : 0u;
    auto add_fill = [&]() {
        if (!fill) return;
        steps.push_back(barrier(true));
        steps.push_back(dispatch(RRC_PHASE_FILL, PlanSet::Next, PlanGrid::FillList));
    };
    auto counted = [&](PlanStep s) {
        s.variant.stats = r.stats;
        return s;
    };
    // Classify writes its mask into the host's image when the host asks for
    // it after classify (split_outputs), else into the library's; the list
    // pass reads it there.
    const bool host_classified = r.interop && r.split_outputs && r.host_mask;
    auto add_list = [&]() {
        steps.push_back(barrier(false));
        PlanStep list = dispatch(RRC_PHASE_LIST, PlanSet::Frame, PlanGrid::Quads);
        list.variant.mask_in_place = true;
        steps.push_back(list);
    };

    // The frame's camera for the view lobe: written by the calls that carry a
    // frame (resolve reads what classify wrote).
    if (c.view_lobe() && r.call != PlanCall::Resolve) steps.push_back(write_view());
    switch (r.call) {
        case PlanCall::Run: {
            plan.frame_set_host_mask = r.host_mask;
            if (fill) steps.push_back(clear_fill_list());
            PlanStep s = counted(dispatch(RRC_PHASE_FUSED, PlanSet::Frame, PlanGrid::Pixels));
            s.variant.host_out_mask = outputs;
            s.variant.host_age_mask = r.host_age_mask;
            steps.push_back(s);
            add_fill();
            break;
        }
        case PlanCall::Classify: {
            plan.frame_set_host_mask = host_classified;
            if (reuse && fill) steps.push_back(clear_fill_list());
            PlanStep s = counted(dispatch(RRC_PHASE_CLASSIFY, PlanSet::Frame, PlanGrid::Pixels));
            if (reuse) s.variant.host_out_mask = split_outputs, s.variant.host_age_mask = split_ages;
            steps.push_back(s);
            add_list();
            break;
        }
        case PlanCall::Resolve: {
            if (!reuse) {
                plan.frame_set_host_mask = r.host_mask;
                if (fill) steps.push_back(clear_fill_list());
                PlanStep s = counted(dispatch(RRC_PHASE_RESOLVE, PlanSet::Frame, PlanGrid::Pixels));
                s.variant.mask_in_place = !r.host_mask || host_classified;  // else classify's mask is the library's, read through a sampler
                s.variant.host_out_mask = outputs;
                s.variant.host_age_mask = r.host_age_mask;
                steps.push_back(s);
                add_fill();
                break;
            }
            // Only the listed pixels that are not HITs (classify wrote the HITs).
            plan.frame_set_host_mask = host_classified;
            PlanStep s = counted(dispatch(RRC_PHASE_RESOLVE_LISTED, PlanSet::Frame, PlanGrid::QuadList));
            s.variant.mask_in_place = true;
            s.variant.host_out_mask = split_outputs;
            s.variant.host_age_mask = split_ages;
            steps.push_back(s);
            if (r.interop && !r.split_outputs) {
                // The host's images get every pixel: a copy of the library's results.
                steps.push_back(barrier(false));
                PlanStep copy = dispatch(RRC_PHASE_COPY_OUT, PlanSet::Next, PlanGrid::Pixels);
                copy.variant.host_out_mask = all_channels(c);
                copy.variant.host_age_mask = r.host_age_mask;
                copy.variant.copy_mask = r.host_mask;
                steps.push_back(copy);
            }
            add_fill();
            break;
        }
    }
    return plan;
}

std::string describe_plan(const FramePlan& plan, const ContextConfig& c) {
    std::string out;
    char line[512];
    const uint32_t gx = AccumulatePipeline::kGroupX, w = c.width, h = c.height, qw = (w + 1) / 2, qh = (h + 1) / 2;
    for (const PlanStep& s : plan.steps) {
        switch (s.op) {
            case PlanStep::Op::ClearFillList: out += "  clear fill list {0, 0, 1, 1} (transfer; barriers before and after)\n"; break;
            case PlanStep::Op::WriteView: out += "  write view buffer from the frame's camera (transfer; barriers before and after)\n"; break;
            case PlanStep::Op::Barrier:
                out += s.to_indirect ? "  barrier: compute writes -> compute reads and indirect command read\n"
                                     : "  barrier: compute writes -> compute reads\n";
                break;
            case PlanStep::Op::Dispatch: {
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
                const char* set = s.set == PlanSet::Frame ? "frame" : "next";
                std::snprintf(line, sizeof line, "  %s over %s; set %s%s; host outputs 0x%x, host ages 0x%x%s%s%s\n    %s\n",
                              phase_name(v.phase), grid.c_str(), set,
                              s.set == PlanSet::Frame ? (plan.frame_set_host_mask ? " (mask: host's)" : " (mask: library's)") : "",
                              v.host_out_mask, v.host_age_mask, v.stats ? "; statistics" : "", v.copy_mask ? "; copies the mask" : "",
                              v.mask_in_place ? "; reads the mask in place" : "",
                              phase_bindings(v.phase, all_reuse(c)));
                out += line;
                break;
            }
        }
    }
    return out;
}

}  // namespace rrc
