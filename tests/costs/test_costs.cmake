# The suite's long tests and their seconds, so that `ctest -j` starts them
# first: without a cost file of its own (a fresh build directory has none)
# ctest starts tests in the order they are registered, and a long test
# registered last (bench_smoke) ran alone at the end of both runs of
# .ci/test.  Read by ctest (tests/costs/CMakeLists.txt); a name no longer
# registered, or one a run leaves out (-LE), is ignored.  Once a build
# directory has run its tests, ctest's own measured costs
# (Testing/Temporary/CTestCostData.txt) take over.
#
# Seconds: a release run's own times, one test per GoogleTest suite
# (cmake/RrcGTestSuites.cmake; `ctest -j2 --timeout 900` in a build directory
# without a cost file, on the 2-core machine of docs/measurements/PERFORMANCE.md,
# "The test suite's time").  Only the order matters; the sanitizer run uses the same.
set(_rrc_test_costs
  spirv_disabled_features_cost_nothing 87
  rrc_visibility_test/Cases/HitTestRecall 39
  rrc_sweep_test/Sweep 38
  documented_commands 29
  rrc_plan_capture_test/PlanCapture 37
  bench_smoke 20
  rrc_sweep_test/RectifyStudy 17
  rrc_stability_long_test/LambdaSweep 16
  rrc_kernel_reference_test/Cases/KernelVsReference 15
  rrc_visibility_test/Cases/ThinCard 14
  rrc_sample_test/RrcSample 13
  rrc_stability_test/Cases/DepthPrecision 12
  rrc_stability_long_test/AgeCap 11
  rrc_shading_cache_test/Policies/SplitVsFusedReuseOnly 8
  rrc_bias_regions_test/BiasMaps 7
  rrc_shading_cache_test/ShadingCacheRefresh 7
  rrc_cache_test/RrcCache 7
  rrc_interop_shading_cache_test/InteropShadingCache 7)
while(_rrc_test_costs)
  list(POP_FRONT _rrc_test_costs _rrc_name _rrc_seconds)
  set_tests_properties(${_rrc_name} PROPERTIES COST ${_rrc_seconds})
endwhile()
