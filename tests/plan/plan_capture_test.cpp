// The plan table checks, not mirrors: every rrc-bench configuration runs at
// the table's small size, on both paths, through the bench's own code
// (bench/interop_run.cpp, bench/standalone_run.cpp) and the library's public
// API, under the Khronos validation layer.  An observer installed in the
// library (plugin/plan_observer.h) sees each call's plan and wraps the
// device's function table (volk), so every command the context records is
// captured.  The test fails where a context records anything but its plan's
// steps, with the resources the context mapped (the barriers' stages,
// accesses, buffers and layouts, the clears' words, the copies, the bound
// sets, the dispatch sizes and indirect buffers); where a plan differs from
// the checked-in table (tests/plan/plan_table.txt); and where a table entry
// is never recorded.  It prints the captured commands once per distinct
// shape (docs/design/frame-plan.md).
#include "plan/plan_table.h"
#include "rrc_interop.h"

#include "bench_images.h"    // bench/
#include "interop_run.h"
#include "scene.h"
#include "standalone_run.h"
#include "plan_observer.h"   // plugin/
#include "vulkan_device.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace {

struct Command {
    std::string name;
    VkPipelineStageFlags src = 0, dst = 0;
    std::vector<VkMemoryBarrier> memory;
    std::vector<VkBufferMemoryBarrier> buffers;
    std::vector<VkImageMemoryBarrier> images;
    VkBuffer buffer = VK_NULL_HANDLE;  // update, copy, indirect dispatch
    VkImage image = VK_NULL_HANDLE;    // copy, clear
    VkDeviceSize offset = 0, size = 0;
    std::vector<uint32_t> words;       // update
    VkDescriptorSet set = VK_NULL_HANDLE;
    uint32_t x = 0, y = 0, z = 0;
    std::string label;
};

// The one capture in progress (the test records on one thread).
std::vector<Command>* g_log = nullptr;
std::map<const rrc::VulkanDevice*, std::pair<VolkDeviceTable, rrc::InstanceFunctions>> g_real;
const std::pair<VolkDeviceTable, rrc::InstanceFunctions>* g_current = nullptr;

void log(Command c) {
    if (g_log) g_log->push_back(std::move(c));
}

VKAPI_ATTR void VKAPI_CALL cap_barrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkPipelineStageFlags dst, VkDependencyFlags dep,
                                       uint32_t nm, const VkMemoryBarrier* m, uint32_t nb, const VkBufferMemoryBarrier* b, uint32_t ni,
                                       const VkImageMemoryBarrier* i) {
    Command c{"barrier"};
    c.src = src, c.dst = dst;
    c.memory.assign(m, m + nm);
    c.buffers.assign(b, b + nb);
    c.images.assign(i, i + ni);
    log(c);
    g_current->first.vkCmdPipelineBarrier(cmd, src, dst, dep, nm, m, nb, b, ni, i);
}
VKAPI_ATTR void VKAPI_CALL cap_update(VkCommandBuffer cmd, VkBuffer buffer, VkDeviceSize offset, VkDeviceSize size, const void* data) {
    Command c{"update buffer"};
    c.buffer = buffer, c.offset = offset, c.size = size;
    c.words.resize(size / 4);
    std::memcpy(c.words.data(), data, c.words.size() * 4);
    log(c);
    g_current->first.vkCmdUpdateBuffer(cmd, buffer, offset, size, data);
}
VKAPI_ATTR void VKAPI_CALL cap_bind_pipeline(VkCommandBuffer cmd, VkPipelineBindPoint point, VkPipeline pipeline) {
    log(Command{"bind pipeline"});
    g_current->first.vkCmdBindPipeline(cmd, point, pipeline);
}
VKAPI_ATTR void VKAPI_CALL cap_bind_sets(VkCommandBuffer cmd, VkPipelineBindPoint point, VkPipelineLayout layout, uint32_t first, uint32_t n,
                                         const VkDescriptorSet* sets, uint32_t nd, const uint32_t* dyn) {
    Command c{"bind set"};
    c.set = n == 1 ? sets[0] : VK_NULL_HANDLE;
    log(c);
    g_current->first.vkCmdBindDescriptorSets(cmd, point, layout, first, n, sets, nd, dyn);
}
VKAPI_ATTR void VKAPI_CALL cap_push(VkCommandBuffer cmd, VkPipelineLayout layout, VkShaderStageFlags stages, uint32_t offset, uint32_t size,
                                    const void* data) {
    log(Command{"push constants"});
    g_current->first.vkCmdPushConstants(cmd, layout, stages, offset, size, data);
}
VKAPI_ATTR void VKAPI_CALL cap_dispatch(VkCommandBuffer cmd, uint32_t x, uint32_t y, uint32_t z) {
    Command c{"dispatch"};
    c.x = x, c.y = y, c.z = z;
    log(c);
    g_current->first.vkCmdDispatch(cmd, x, y, z);
}
VKAPI_ATTR void VKAPI_CALL cap_indirect(VkCommandBuffer cmd, VkBuffer buffer, VkDeviceSize offset) {
    Command c{"dispatch indirect"};
    c.buffer = buffer, c.offset = offset;
    log(c);
    g_current->first.vkCmdDispatchIndirect(cmd, buffer, offset);
}
VKAPI_ATTR void VKAPI_CALL cap_to_image(VkCommandBuffer cmd, VkBuffer src, VkImage dst, VkImageLayout layout, uint32_t n,
                                        const VkBufferImageCopy* r) {
    Command c{"copy buffer to image"};
    c.buffer = src, c.image = dst, c.offset = n ? r[0].bufferOffset : 0;
    log(c);
    g_current->first.vkCmdCopyBufferToImage(cmd, src, dst, layout, n, r);
}
VKAPI_ATTR void VKAPI_CALL cap_to_buffer(VkCommandBuffer cmd, VkImage src, VkImageLayout layout, VkBuffer dst, uint32_t n,
                                         const VkBufferImageCopy* r) {
    Command c{"copy image to buffer"};
    c.buffer = dst, c.image = src, c.offset = n ? r[0].bufferOffset : 0;
    log(c);
    g_current->first.vkCmdCopyImageToBuffer(cmd, src, layout, dst, n, r);
}
VKAPI_ATTR void VKAPI_CALL cap_clear(VkCommandBuffer cmd, VkImage image, VkImageLayout layout, const VkClearColorValue* colour, uint32_t n,
                                     const VkImageSubresourceRange* r) {
    Command c{"clear image"};
    c.image = image;
    log(c);
    g_current->first.vkCmdClearColorImage(cmd, image, layout, colour, n, r);
}
VKAPI_ATTR void VKAPI_CALL cap_begin_label(VkCommandBuffer cmd, const VkDebugUtilsLabelEXT* label) {
    Command c{"begin label"};
    c.label = label->pLabelName;
    log(c);
    g_current->second.CmdBeginDebugUtilsLabelEXT(cmd, label);
}
VKAPI_ATTR void VKAPI_CALL cap_end_label(VkCommandBuffer cmd) {
    log(Command{"end label"});
    g_current->second.CmdEndDebugUtilsLabelEXT(cmd);
}

// One recorded call: its plan, what the context mapped, what it recorded.
struct Call {
    rrc::FramePlan plan;
    rrc::PlanResources res;
    rrc::ContextConfig config;
    bool labels = false;
    std::vector<Command> commands;
    // The images of res.inputs and res.outputs, taken while they live.
    std::vector<std::pair<VkImage, VkDeviceSize>> inputs, outputs;
};

class Capture : public rrc::PlanObserver {
public:
    Capture() { rrc::set_plan_observer(this); }
    ~Capture() override {
        rrc::set_plan_observer(nullptr);
        g_log = nullptr;
    }
    void recording(const rrc::FramePlan& plan, const rrc::PlanResources& res, const rrc::ContextConfig& config,
                   rrc::VulkanDevice& dev) override {
        if (!g_real.count(&dev) || dev.vk.vkCmdDispatch != &cap_dispatch) {
            g_real[&dev] = {dev.vk, dev.fi};
            dev.vk.vkCmdPipelineBarrier = &cap_barrier;
            dev.vk.vkCmdUpdateBuffer = &cap_update;
            dev.vk.vkCmdBindPipeline = &cap_bind_pipeline;
            dev.vk.vkCmdBindDescriptorSets = &cap_bind_sets;
            dev.vk.vkCmdPushConstants = &cap_push;
            dev.vk.vkCmdDispatch = &cap_dispatch;
            dev.vk.vkCmdDispatchIndirect = &cap_indirect;
            dev.vk.vkCmdCopyBufferToImage = &cap_to_image;
            dev.vk.vkCmdCopyImageToBuffer = &cap_to_buffer;
            dev.vk.vkCmdClearColorImage = &cap_clear;
            if (dev.fi.CmdBeginDebugUtilsLabelEXT) dev.fi.CmdBeginDebugUtilsLabelEXT = &cap_begin_label;
            if (dev.fi.CmdEndDebugUtilsLabelEXT) dev.fi.CmdEndDebugUtilsLabelEXT = &cap_end_label;
        }
        g_current = &g_real[&dev];
        calls.push_back(Call{plan, res, config, g_current->second.CmdBeginDebugUtilsLabelEXT != nullptr, {}, {}, {}});
        for (const rrc::PlanCopy& c : res.inputs) calls.back().inputs.push_back({c.image->image, c.offset});
        for (const rrc::PlanCopy& c : res.outputs) calls.back().outputs.push_back({c.image->image, c.offset});
        g_log = &calls.back().commands;
    }
    // A context's device goes away with it: its table is never called again.
    void forget() {
        g_log = nullptr;
        g_current = nullptr;
        g_real.clear();
    }
    std::vector<Call> calls;
};

std::string hex(uint64_t v) {
    char b[32];
    std::snprintf(b, sizeof b, "0x%llx", (unsigned long long)v);
    return b;
}

// Compares one call's commands with its plan, step by step; returns "" or what differs.
std::string compare(const Call& call) {
    const std::vector<Command>& cmds = call.commands;
    const rrc::PlanResources& res = call.res;
    size_t at = 0;
    auto next = [&](const char* name) -> const Command* {
        if (at >= cmds.size()) return nullptr;
        const Command* c = &cmds[at];
        if (c->name != name) return nullptr;
        ++at;
        return c;
    };
    auto buffer_of = [&](rrc::PlanResource r) -> const rrc::PlanBuffer& {
        switch (r) {
            case rrc::PlanResource::FillList: return res.fill_list;
            case rrc::PlanResource::ViewBuffer: return res.view_buffer;
            case rrc::PlanResource::Stats: return res.stats;
            default: return res.quad_list;
        }
    };
    const uint32_t gx = rrc::AccumulatePipeline::kGroupX, w = call.config.width, h = call.config.height;
    for (size_t i = 0; i < call.plan.steps.size(); ++i) {
        const rrc::PlanStep& s = call.plan.steps[i];
        const std::string where = "step " + std::to_string(i) + ": ";
        switch (s.kind) {
            case rrc::PlanStep::Kind::BeginLabel: {
                if (!call.labels) break;
                const Command* c = next("begin label");
                if (!c || c->label != s.label) return where + "no label \"" + s.label + "\"";
                break;
            }
            case rrc::PlanStep::Kind::EndLabel:
                if (call.labels && !next("end label")) return where + "no end of label";
                break;
            case rrc::PlanStep::Kind::Initialise: {
                const Command* b = next("barrier");
                if (!b || b->images.empty() || b->images.size() < res.initialise.size()) return where + "no initialising barrier";
                for (size_t k = 0; k < b->images.size(); ++k) {
                    const Command* c = next("clear image");
                    if (!c || c->image != b->images[k].image) return where + "image " + std::to_string(k) + " not cleared";
                }
                if (!next("barrier")) return where + "no barrier after the clears";
                break;
            }
            case rrc::PlanStep::Kind::Barrier: {
                const bool images = s.resource == rrc::PlanResource::Inputs || s.resource == rrc::PlanResource::Outputs;
                const auto& list = s.resource == rrc::PlanResource::Inputs ? call.inputs : call.outputs;
                if (images && list.empty()) break;  // nothing to hand over: no command
                const Command* c = next("barrier");
                if (!c) return where + "no barrier";
                if (c->src != s.src_stages || c->dst != s.dst_stages)
                    return where + "stages " + hex(c->src) + " -> " + hex(c->dst) + ", the plan's " + hex(s.src_stages) + " -> " + hex(s.dst_stages);
                switch (s.resource) {
                    case rrc::PlanResource::Memory:
                        if (c->memory.size() != 1 || !c->buffers.empty() || !c->images.empty()) return where + "not one memory barrier";
                        if (c->memory[0].srcAccessMask != s.src_access || c->memory[0].dstAccessMask != s.dst_access)
                            return where + "memory barrier's accesses";
                        break;
                    case rrc::PlanResource::HostImagesIn:
                    case rrc::PlanResource::HostImagesOut: {
                        const auto& want = s.resource == rrc::PlanResource::HostImagesIn ? res.host_in : res.host_out;
                        if (c->images.size() != want.size() || !c->memory.empty() || !c->buffers.empty())
                            return where + std::to_string(c->images.size()) + " host image barriers, mapped " + std::to_string(want.size());
                        for (size_t k = 0; k < want.size(); ++k)
                            if (c->images[k].image != want[k].image || c->images[k].newLayout != want[k].newLayout)
                                return where + "host image " + std::to_string(k);
                        break;
                    }
                    case rrc::PlanResource::Inputs:
                    case rrc::PlanResource::Outputs:
                        if (c->images.size() != list.size()) return where + "image barrier count";
                        for (size_t k = 0; k < list.size(); ++k) {
                            const VkImageMemoryBarrier& b = c->images[k];
                            if (b.image != list[k].first || b.oldLayout != s.old_layout || b.newLayout != s.new_layout ||
                                b.srcAccessMask != s.src_access || b.dstAccessMask != s.dst_access)
                                return where + "image barrier " + std::to_string(k) + ": " + hex((uint64_t)b.image) + " " + hex(b.oldLayout) + "->" +
                                       hex(b.newLayout) + " " + hex(b.srcAccessMask) + "->" + hex(b.dstAccessMask) + ", the plan's " +
                                       hex((uint64_t)list[k].first) + " " + hex(s.old_layout) + "->" + hex(s.new_layout) + " " +
                                       hex(s.src_access) + "->" + hex(s.dst_access);
                        }
                        break;
                    case rrc::PlanResource::LibraryImages: return where + "a barrier over the library's images";
                    default: {
                        const rrc::PlanBuffer& buf = buffer_of(s.resource);
                        if (c->buffers.size() != 1 || !c->memory.empty() || !c->images.empty()) return where + "not one buffer barrier";
                        const VkBufferMemoryBarrier& b = c->buffers[0];
                        if (b.buffer != buf.buffer || b.offset != buf.offset || b.size != buf.size || b.srcAccessMask != s.src_access ||
                            b.dstAccessMask != s.dst_access)
                            return where + "buffer barrier (buffer, range or accesses)";
                    }
                }
                break;
            }
            case rrc::PlanStep::Kind::Clear: {
                const Command* c = next("update buffer");
                const rrc::PlanBuffer& buf = buffer_of(s.resource);
                if (!c || c->buffer != buf.buffer || c->offset != buf.offset || c->words != s.words) return where + "clear";
                break;
            }
            case rrc::PlanStep::Kind::WriteView: {
                const Command* c = next("update buffer");
                if (!c || c->buffer != res.view_buffer.buffer || c->offset != 0 || c->words.empty()) return where + "view buffer write";
                break;
            }
            case rrc::PlanStep::Kind::Upload:
            case rrc::PlanStep::Kind::Readback: {
                const bool up = s.kind == rrc::PlanStep::Kind::Upload;
                for (const auto& copy : up ? call.inputs : call.outputs) {
                    const Command* c = next(up ? "copy buffer to image" : "copy image to buffer");
                    if (!c || c->image != copy.first || c->offset != copy.second || c->buffer != (up ? res.staging_in : res.staging_out))
                        return where + (up ? "upload" : "readback");
                }
                break;
            }
            case rrc::PlanStep::Kind::Dispatch: {
                const uint32_t module = rrc::module_of(s.variant.pass);
                const VkDescriptorSet set = (s.set == rrc::PlanSet::Frame ? res.frame : res.next).module[module];
                if (!next("bind pipeline")) return where + "no pipeline bound";
                const Command* b = next("bind set");
                if (!b || b->set != set) return where + "not the plan's set";
                if (!next("push constants")) return where + "no push constants";
                if (s.grid == rrc::PlanGrid::Pixels || s.grid == rrc::PlanGrid::Quads) {
                    const uint32_t gw = s.grid == rrc::PlanGrid::Quads ? (w + 1) / 2 : w, gh = s.grid == rrc::PlanGrid::Quads ? (h + 1) / 2 : h;
                    const Command* d = next("dispatch");
                    if (!d || d->x != (gw + gx - 1) / gx || d->y != gh || d->z != 1) return where + "dispatch size";
                } else {
                    const Command* d = next("dispatch indirect");
                    const bool quads = s.grid == rrc::PlanGrid::QuadList;
                    const VkBuffer want = quads ? res.quad_list.buffer : res.fill_list.buffer;
                    const VkDeviceSize offset = quads ? res.quad_list.offset + 4 * RRC_QUAD_LIST_DISPATCH : 4 * RRC_FILL_LIST_DISPATCH;
                    if (!d || d->buffer != want || d->offset != offset) return where + "indirect dispatch (buffer or offset)";
                }
                break;
            }
        }
    }
    if (at != cmds.size()) return "a command the plan lacks: " + cmds[at].name + " (command " + std::to_string(at) + ")";
    return "";
}

// The captured commands as text, handles replaced by what the plan's ids map to.
std::string shape(const Call& call) {
    std::string out;
    auto buffer_name = [&](VkBuffer b) -> std::string {
        return b == call.res.fill_list.buffer     ? "fill list"
               : b == call.res.view_buffer.buffer ? "view buffer"
               : b == call.res.quad_list.buffer   ? "quad list"
               : b == call.res.stats.buffer       ? "statistics buffer"
               : b == call.res.staging_in         ? "upload staging"
               : b == call.res.staging_out        ? "readback staging"
                                                  : "?";
    };
    for (const Command& c : call.commands) {
        out += "  " + c.name;
        if (c.name == "barrier") {
            out += " " + hex(c.src) + " -> " + hex(c.dst) + ":";
            for (const VkMemoryBarrier& m : c.memory) out += " memory " + hex(m.srcAccessMask) + " -> " + hex(m.dstAccessMask);
            for (const VkBufferMemoryBarrier& b : c.buffers)
                out += " " + buffer_name(b.buffer) + " " + hex(b.srcAccessMask) + " -> " + hex(b.dstAccessMask);
            if (!c.images.empty()) out += " " + std::to_string(c.images.size()) + " image(s)";
        } else if (c.name == "update buffer" || c.name == "dispatch indirect") {
            out += " " + buffer_name(c.buffer) + " at " + std::to_string(c.offset);
        } else if (c.name == "copy buffer to image" || c.name == "copy image to buffer") {
            out += " " + buffer_name(c.buffer);
        } else if (c.name == "bind set") {
            for (int s = 0; s < 2; ++s)
                for (VkDescriptorSet set : (s ? call.res.next : call.res.frame).module)
                    if (set && set == c.set) out += s ? " next" : " frame";
        } else if (c.name == "dispatch") {
            out += " " + std::to_string(c.x) + "x" + std::to_string(c.y) + "x" + std::to_string(c.z);
        } else if (c.name == "begin label") {
            out += " \"" + c.label + "\"";
        }
        out += "\n";
    }
    return out;
}

// The table's key of a captured call (plan_table.h): its path, call and statistics.
std::string key_of(const std::string& config, const Call& call) {
    bool interop = false;
    std::string name;
    for (const rrc::PlanStep& s : call.plan.steps) {
        interop = interop || s.resource == rrc::PlanResource::HostImagesIn;
        if (s.kind == rrc::PlanStep::Kind::BeginLabel) name = s.label;
    }
    const std::string call_name = name == "rrc: initialise" ? "initialise" : name == "rrc: classify" ? "classify" : name == "rrc: resolve" ? "resolve" : "frame";
    return config + (interop ? "/interop/" : "/standalone/") + call_name + (call.plan.sets[0].stats ? "+stats" : "");
}

// describe_plan without the host's first-use initialisation (the table states it once).
std::string without_initialise(std::string text) {
    const std::string line = "  initialise library images: UNDEFINED -> GENERAL, cleared to 0\n";
    const size_t at = text.find(line);
    if (at != std::string::npos && text.find("\"rrc: initialise\"") == std::string::npos) text.erase(at, line.size());
    return text;
}

TEST(PlanCapture, EveryBenchConfigurationRecordsItsPlanOnBothPaths) {
    // Validation is on by the bench's own means on both paths (the host's
    // instance, the standalone descriptor); the test environment's
    // RRC_VALIDATION=1 would only add the interop context's warning that it
    // does not apply there, which the bench's log counts.
    unsetenv("RRC_VALIDATION");
    const std::map<std::string, std::string> table = rrc_plan::plan_texts();
    std::set<std::string> seen;
    std::vector<std::pair<std::string, std::vector<std::string>>> shapes;  // captured text, its calls
    rrc_bench::LogCounter log;
    rrc_host::BootstrapOptions bo;
    bo.application = "rrc-plan-capture";
    bo.validation = true;
    bo.features = rrc_host::rrc_features();  // what rrc needs (rrc_vulkan_get_requirements)
    rrc_host::VulkanBootstrap vk(bo);
    Capture capture;
    size_t checked = 0;
    for (rrc_bench::Config config : rrc_bench::full_sweep()) {
        config.width = rrc_plan::kWidth, config.height = rrc_plan::kHeight;
        std::fprintf(stderr, "plan capture: %s\n", config.name.c_str());
        capture.calls.clear();
        {
            const rrc_bench::SceneInputs scene = rrc_bench::make_scene(config);
            rrc_bench::StandaloneBench standalone(config, scene, log, "", /*validation=*/true);
            standalone.step(false);
            EXPECT_EQ(standalone.result().validation_messages, 0u) << config.name;
            capture.forget();  // the standalone device goes with its context
            rrc_bench::BenchImages images = rrc_bench::create_images(vk, config, scene);
            {
                rrc_bench::InteropBench interop(vk, config, scene, images, log);
                interop.prime(1);
                interop.finish(false);
            }
            rrc_bench::destroy_images(vk, images);
            capture.forget();
        }
        for (const Call& call : capture.calls) {
            const std::string key = key_of(config.name, call);
            seen.insert(key);
            ++checked;
            EXPECT_EQ(compare(call), "") << key;
            auto row = table.find(key);
            if (row == table.end()) {
                ADD_FAILURE() << key << ": no such call in the plan table";
                continue;
            }
            EXPECT_EQ(without_initialise(rrc::describe_plan(call.plan, call.config)), row->second)
                << key << ": the plan the context recorded is not the table's (cmake --build <build> --target regenerate_plan_table)";
            const std::string text = shape(call);
            auto found = std::find_if(shapes.begin(), shapes.end(), [&](const auto& s) { return s.first == text; });
            if (found == shapes.end()) shapes.push_back({text, {key}});
            else found->second.push_back(key);
        }
    }
    EXPECT_EQ(log.messages.load(), 0u) << "the library reported warnings or validation messages";
    EXPECT_EQ(vk.message_count(), 0u) << "validation messages on the host's device";
    for (const auto& row : table) EXPECT_TRUE(seen.count(row.first)) << row.first << ": in the table, never recorded";
    // The captured commands, once per distinct shape.
    std::printf("%zu calls captured, %zu distinct command lists\n", checked, shapes.size());
    for (const auto& s : shapes) {
        std::printf("\n## %s", s.second[0].c_str());
        if (s.second.size() > 1) std::printf(" and %zu more", s.second.size() - 1);
        std::printf("\n%s", s.first.c_str());
    }
}

}  // namespace
