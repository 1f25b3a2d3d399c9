# The unit tests' labels beyond `unit`, read by ctest after each executable's list of discovered
# tests (<executable>_TESTS, from gtest_discover_tests) and the list of executables.
#   threaded  the modules whose threads meet: the worker pool, the server's pipelined loop, the
#             clients, the renderer and the gateway (scripts/test.sh --sanitize thread runs these)
#   long      a long physics scene, over 30 s each under AddressSanitizer (a minute or more of
#             simulated cloth); CI's sanitizer run (.ci/run) leaves these out, as the same
#             kernels run there in the other tests, and scripts/test.sh --sanitize address runs all
set(threaded_executables parallel_tests service_tests client_tests render_tests gateway_tests)
set(long_tests
  CollisionCulling.EveryPairThatComesWithinHIsACandidate
  ImplicitEuler.StiffFlagAtLargeStepsLosesEnergyWhereSymplecticEulerBlowsUp
  Obstacles.AFlagOnAShortPoleInStillAirEndsUpOnTheGroundAndLiesThere
  ScenePresets.HangingDrapesNearThePoleWithin10SecondsAndSleeps
  SelfCollision.AGaleNeverTakesTheFlagIntoThePoleOrThroughItself
  SelfCollision.CalmAirNeverTakesTheFlagIntoThePoleOrThroughItself
  SelfCollision.TheBreezeNeverCrossesItself
  SelfCollision.TheSameStatesAtAnyThreadCount
  Session.KeysEditedDuringPlayMakeNoJump
  Session.SubstepsAreFixedPerSegmentForItsStiffestSetting
  Simulation.AFlagAtRestInCalmAirSleepsAndWindWakesIt
  Simulation.FlagAtRestInStillAirSettles
  Simulation.OnlyAChangeOfControlsWakesTheFlag
  Simulation.TheGuardKeepsStableIntegratorsSoundAtTheLargestStep
  Bending.TheBreezesCurvatureDoesNotGrowAsTheGridRefines
  FrameDefect.TheEstimateTracksTheMeasuredErrorWithinAFactorOfTwo
  AutoModel.MeetsTheBudgetAtThePresetsViewAndCostsFarLessTenTimesFarther
  ModelGovernor.SwitchesAreJournaledAndReplayBitForBit
  InputsLog.AServersOwnRecordReplaysBitForBit
  InputsLog.AServerResumedFromItsRecordStepsOnAsTheOriginal)

foreach(executable IN LISTS unit_executables)  # every flagsim_test (tests/CMakeLists.txt)
  foreach(test IN LISTS ${executable}_TESTS)
    set(labels unit)
    list(FIND threaded_executables "${executable}" threaded)
    if(threaded GREATER -1)
      list(APPEND labels threaded)
    endif()
    list(FIND long_tests "${test}" long)
    if(long GREATER -1)
      list(APPEND labels long)
    endif()
    set_tests_properties("${test}" PROPERTIES LABELS "${labels}")
  endforeach()
endforeach()
