# The suite's long tests and their seconds, so that `ctest -j` starts them
# first: without a cost file of its own (a fresh build directory has none)
# ctest starts tests in the order they are registered, and a long test
# registered last (bench_smoke) ran alone at the end of both runs of
# .ci/test.  Read by ctest (tests/costs/CMakeLists.txt); a name no longer
# registered, or one a run leaves out (-LE), is ignored.  Once a build
# directory has run its tests, ctest's own measured costs
# (Testing/Temporary/CTestCostData.txt) take over.
#
# Seconds: `bash .ci/test` at commit 9de67d0 (2026-12-03, 2-core AMD EPYC VM,
# Mesa 22.3.6 lavapipe, otherwise idle), the sanitizer run's time where the
# test runs there, else the release run's.  Only the order matters.
set(_rrc_test_costs
  spirv_disabled_features_cost_nothing 60
  Sweep.EstimatorsAreUnbiasedAndAccumulationBeatsOneFrame 47
  bench_smoke 42
  documented_commands 31
  LambdaSweep.BiasAndVarianceOver10000Frames 23
  RectifyStudy.TheMovingLightChangesTargetsAndRectificationCutsTheLag 19
  AgeCap.SaturatesAtTheTypeMaximumWithoutWrapping 15
  BlenderPresetTau.HitAndFalseHitRates 15
  RrcCache.MissShaderCoversTheListAndRefreshTradesErrorForWork 12
  CacheRefresh.EveryPixelOnceEveryNFramesOnAStaticScene 11
  ShadingCacheRefresh.OncePerPeriodFromNear2To40AndBalancedRandom 11
  BiasMaps.UnderMotionTheBiasSitsWhereTheTargetChanged 8
  BiasMaps.NothingMovingNoTargetChangesAndNoBias 7
  RrcSample.DefaultDepthTestRecallAndNoFalseHits 7
  RrcCache.OctavesChangeTheShadingAndStayFiniteAt64 7
  NonFiniteSamples.TenThousandFrames 7
  ApiVulkanDepth.ImageFormatDisagreesWithDepthFormat 6)
while(_rrc_test_costs)
  list(POP_FRONT _rrc_test_costs _rrc_name _rrc_seconds)
  set_tests_properties(${_rrc_name} PROPERTIES COST ${_rrc_seconds})
endwhile()
