# Measured run times (s) of the longest tests, read by CTest after each test directory's discovered
# GoogleTest tests (stickslip_add_gtest appends this file to the directory's TEST_INCLUDE_FILES).
# CTest starts the tests in decreasing COST; a fresh build tree has no timing history
# (Testing/Temporary/CTestCostData.txt), so without these the longest tests may start last and
# leave one core idle at the end of a suite. Values: the AddressSanitizer + UBSan suite of the
# clean-clone run at e27b54a (Clang 14, 2 cores), where the spread is widest; a test missing from
# this list costs 0, and a name that no longer exists is ignored by CTest.
set_tests_properties("SteadyStateBlade.OrbitEqualsTheLongTransientAtThreePreloads" PROPERTIES COST 42)
set_tests_properties("SteadyStateContinuation.LinearTwoDofFrequencyResponseIsTheReceptance" PROPERTIES COST 30)
set_tests_properties("OptimalPreload.MinMaxAmplitudeOfAMaxwellDamperIsTheFixedPoint" PROPERTIES COST 13)  # helper's measurement
set_tests_properties("MixedLaws.ThreeDampersOnThreeMembersPassTheEnergyAudit" PROPERTIES COST 16)
set_tests_properties("ExactLinearStepperFrozen.StiffMovingPointRefreshesOnlyWhenTheRemainderLimitsTheStep" PROPERTIES COST 10)
set_tests_properties("EnergyAudit.ResidualAtIntegrationErrorAndShrinksWithTolerance" PROPERTIES COST 7)
set_tests_properties("LongRun.TenThousandPeriodsStuckDamperDoesNotDriftAndTheResidualStaysBounded" PROPERTIES COST 6)
set_tests_properties("PerDamperContactPoint.AMovingDamperThatNeverSlipsIsTheFixedContactScene" PROPERTIES COST 5)
set_tests_properties("ModelAllocation.RunThroughSwitchesAllocatesNothingInsideRhs" PROPERTIES COST 5)
set_tests_properties("SpeedParameters/Fryba.MidspanHistoryAndPeakAmplificationMatchSeries/0.1" PROPERTIES COST 4)
set_tests_properties("RungeKutta4Clock.StepsOnTheGridKeepTheBeltOscillatorOnItsClosedForm" PROPERTIES COST 4)
set_tests_properties("PerDamperContactPoint.FixedDamperKeepsItsPointWhileTheOtherSlidesAndTheAuditCloses" PROPERTIES COST 3)
set_tests_properties("CoulombConditions.HoldAtEverySampleAndEverySwitch" PROPERTIES COST 3)
set_tests_properties("FixedStep.UncheckedFarAboveTheStabilityLimitStopsButTheCauseIsMisnamed" PROPERTIES COST 3)
set_tests_properties("ExactLinearStepperExponential.NoStabilityLimitFromTheLinearPart" PROPERTIES COST 3)
set_tests_properties("SimplifiedModels.MovingAndFixedContactDifferByLittle" PROPERTIES COST 3)
set_tests_properties("TradeStudy.ModelVariantOnTheTFrameMatchesAHandComparison" PROPERTIES COST 3)
set_tests_properties("SimplifiedModels.InertialNormalLoadTendsToConstantAsDamperMassVanishes" PROPERTIES COST 3)
set_tests_properties("StuckLimit.AllDampersStuckMatchClosedFormOfRitzStuckSystem" PROPERTIES COST 3)
set_tests_properties("ExactLinearStepper.LinearSceneMatchesTheClosedFormModalSolution" PROPERTIES COST 3)
set_tests_properties("StaticPreloadStart.ARunWithoutLoadsStaysAtRestWhereTheStepStartOscillates" PROPERTIES COST 3)
set_tests_properties("Stops.ExtrapolatePolicyContinuesPastTheMemberEnd" PROPERTIES COST 3)
set_tests_properties("FrictionlessLimit.MuZeroLeavesDampersAtRestAndStructureLinear" PROPERTIES COST 2)
set_tests_properties("SteadyStateContinuation.DuffingBranchPassesBothFoldsWithStabilityChangeThroughPlusOne" PROPERTIES COST 2)
set_tests_properties("DamperStatistics.StickSlipMatchesTheEventLogAndAFineSampling" PROPERTIES COST 2)
set_tests_properties("ExactLinearStepper.ClosedFormQuadraturesMatchTheClosedFormModalSolution" PROPERTIES COST 2)
set_tests_properties("SimultaneousSwitches.MirrorDampersSwitchTogether" PROPERTIES COST 2)
set_tests_properties("SimplifiedModels.ConstantLoadFixedContactMatchesIndependentSingleDamperSystem" PROPERTIES COST 2)
