# Measured run times (s) of the longest tests, read by CTest after each test directory's discovered
# GoogleTest tests (stickslip_add_gtest appends this file to the directory's TEST_INCLUDE_FILES).
# CTest starts the tests in decreasing COST; a fresh build tree has no timing history
# (Testing/Temporary/CTestCostData.txt), so without these the longest tests may start last and
# leave one core idle at the end of a suite. Values: the AddressSanitizer + UBSan suite of the
# clean-clone run at 0049500 (Clang 14, 2 cores; the tests of 1.5 s and more), where the spread is
# widest; a test missing from this list costs 0, and a name that no longer exists is ignored by
# CTest.
set_tests_properties("ObserverIndependence.EvaluatingForcesAtSamplesLeavesEveryIntegratorsRunBitwiseUnchanged" PROPERTIES COST 21.1)
set_tests_properties("SteadyStateContinuation.LinearTwoDofFrequencyResponseIsTheReceptance" PROPERTIES COST 6.7)
set_tests_properties("SteadyStateBlade.OrbitEqualsTheLongTransientAtThreePreloads" PROPERTIES COST 4.7)
set_tests_properties("EnergyAudit.ResidualAtIntegrationErrorAndShrinksWithTolerance" PROPERTIES COST 4.5)
set_tests_properties("SplitContinuation.DuffingBranchCutBetweenTheFoldsJoinsOnlyWhereTheBranchRunsOnInOneDirection" PROPERTIES COST 4.4)
set_tests_properties("MixedLaws.ThreeDampersOnThreeMembersPassTheEnergyAudit" PROPERTIES COST 3.9)
set_tests_properties("LongRun.TenThousandPeriodsStuckDamperDoesNotDriftAndTheResidualStaysBounded" PROPERTIES COST 3.8)
set_tests_properties("Regimes/ExponentialRun.SameEventsTipHistoryAndClosedEnergyAuditAsDopriAtRtol1e12/N0_26dN  # GetParam() = 2.6" PROPERTIES COST 3.8)
set_tests_properties("SplitContinuation.LinearTwoDofCurveInPartsUpAndDownIsTheReceptanceWithEveryPartJoined" PROPERTIES COST 3.7)
set_tests_properties("SpeedParameters/Fryba.MidspanHistoryAndPeakAmplificationMatchSeries/0.1" PROPERTIES COST 3.5)
set_tests_properties("ExactLinearStepperFrozen.StiffMovingPointRefreshesOnlyWhenTheRemainderLimitsTheStep" PROPERTIES COST 3.4)
set_tests_properties("PerDamperContactPoint.AMovingDamperThatNeverSlipsIsTheFixedContactScene" PROPERTIES COST 3.3)
set_tests_properties("RungeKutta4Clock.StepsOnTheGridKeepTheBeltOscillatorOnItsClosedForm" PROPERTIES COST 3.0)
set_tests_properties("FixedStep.UncheckedFarAboveTheStabilityLimitStopsButTheCauseIsMisnamed" PROPERTIES COST 2.5)
set_tests_properties("ModelAllocation.RunThroughSwitchesAllocatesNothingInsideRhs" PROPERTIES COST 2.4)
set_tests_properties("ExactLinearStepperExponential.NoStabilityLimitFromTheLinearPart" PROPERTIES COST 2.2)
set_tests_properties("SimplifiedModels.MovingAndFixedContactDifferByLittle" PROPERTIES COST 2.2)
set_tests_properties("ExactLinearStepper.LinearSceneMatchesTheClosedFormModalSolution" PROPERTIES COST 2.1)
set_tests_properties("CoulombConditions.HoldAtEverySampleAndEverySwitch" PROPERTIES COST 2.0)
set_tests_properties("SimplifiedModels.InertialNormalLoadTendsToConstantAsDamperMassVanishes" PROPERTIES COST 2.0)
set_tests_properties("ExactLinearStepper.ClosedFormQuadraturesMatchTheClosedFormModalSolution" PROPERTIES COST 1.9)
set_tests_properties("TradeStudy.ModelVariantOnTheTFrameMatchesAHandComparison" PROPERTIES COST 1.7)
set_tests_properties("StuckLimit.AllDampersStuckMatchClosedFormOfRitzStuckSystem" PROPERTIES COST 1.7)
set_tests_properties("PerDamperContactPoint.FixedDamperKeepsItsPointWhileTheOtherSlidesAndTheAuditCloses" PROPERTIES COST 1.6)
