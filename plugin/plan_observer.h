// A test's window on the recording: before the core records a call, an
// installed observer sees the call's plan, the resources its ids stand for,
// the context's configuration and the device whose function table records it, so that a test can
// capture the commands and compare them with the plan (tests/plan,
// plan_capture_test.cpp).  Nothing is installed in a program that links the
// library: the observer is internal, never exported.
#pragma once

#include "frame_plan.h"
#include "plan_resources.h"

namespace rrc {

class VulkanDevice;

class PlanObserver {
public:
    virtual ~PlanObserver() = default;
    virtual void recording(const FramePlan& plan, const PlanResources& resources, const ContextConfig& config, VulkanDevice& device) = 0;
};

// Process-wide; NULL (the default) observes nothing.
void set_plan_observer(PlanObserver* observer);
PlanObserver* plan_observer();

}  // namespace rrc
