# Studies as data: the study file's checks, its plan of jobs and their ids (no GL).
penumbra_add_test(test_study ${CMAKE_CURRENT_SOURCE_DIR}/study_test.cpp LIBS penumbra_study penumbra_core)
