# Read by CTest after the tests are discovered: the slowest tests, started first. Without a
# cost CTest runs tests in the order they were defined, and on a clean tree (no cost data of
# an earlier run) a two-minute test started last leaves one core idle while it finishes. The
# costs are seconds measured under the sanitizers (2026-11-29, the grasp map's and the partial
# series' 2026-12-02; the Slurm test's in Release,
# where alone it runs); only their order matters, and a name that is no longer a test's is
# passed over.
set(handlab_slow_tests
  "Slurm.StudiesAndAPowerPointAsJobArraysMergedAndACancelledTaskRerun=110"
  "CliMerge.ShardsMergedEqualTheStudyRunInOneProcess=103"
  "CliSim.GraspMapsAClosingThatHoldsAndOneThatLosesTheCube=94"
  "Hardening.ASeriesWithAPartialMergeIsUnfinishedUntilItsMergeJobRunsAgain=79"
  "GroupAssignment.ShardsAndTheirMergeHoldTheGroupsOfTheWholeStudy=71"
  "CliSensitivity.MorrisEffectsOfTheModelsParametersOnWholeStudies=68"
  "SimulatedParticipantBlinding.EveryPhaseSwappedConditionsSameFramesMemoryAndAnswers=68"
  "CliMerge.KilledAtAnyMomentLeavesNoOutputAndItsInputsIntact=44"
  "CliStudy.CreateEnrolRunStatusExportAnalyze=40"
  "SoftHandWorld.PinchesLiftsAndReleasesTheCubeByContact=39"
  "ParticipantMemory.ASessionStoppedAndResumedGoesOnWithWhatItLearnt=36"
  "PinchSkin.TheCubesEdgesDoNotSinkIntoTheSkinBetweenNodes=34"
  "CliSim.ReplayDrivesTheSoftHandByARecording=33"
  "CrashTest.SigkillAtRandomMomentsLosesNoTrialAndResumesInOrder=32"
  "PinchRobustness.HoldsTheHeavyCubeForAnySqueeze=22"
  "PinchRobustness.HoldsTheLightCubeForAnySqueeze=17"
  "PinchDeterminism.TheSameRunGivesTheSameStates=30"
  "CliMerge.RefusalsSayWhichFileAndWhyAndChangeNothing=30")
foreach(entry IN LISTS handlab_slow_tests)
  string(REPLACE "=" ";" pair "${entry}")
  list(GET pair 0 test_name)
  list(GET pair 1 test_cost)
  set_tests_properties("${test_name}" PROPERTIES COST ${test_cost})
endforeach()
