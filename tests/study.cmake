# Studies as data: the study file's checks, its plan of jobs and their ids, a merge of hand-written
# rows (no GL).
penumbra_add_test(test_study ${CMAKE_CURRENT_SOURCE_DIR}/study_test.cpp LIBS penumbra_study penumbra_compare penumbra_core)
# A study run end to end with the real binary (tests/study_run_test.sh MODE): locally with -j 2,
# in shards, killed mid-job, through GNU parallel, with the axes beyond the product (light scales,
# parts, scene variants, shading modes, profiled frames) and through a real Slurm started on
# localhost.
foreach(mode local shards failed kill parallel axes slurm)
  add_test(NAME study_run_${mode} COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/study_run_test.sh $<TARGET_FILE:penumbra>
           $<TARGET_FILE:exr_diff> ${PROJECT_SOURCE_DIR} ${mode})
  set_tests_properties(study_run_${mode} PROPERTIES SKIP_RETURN_CODE 77 LABELS gl)
endforeach()
# Under the sanitizers too (6 s there): the runner, the frame files and the merge, failed jobs
# beside done ones.
set_tests_properties(study_run_failed PROPERTIES LABELS "gl;sanitize")
# (slurm: eight array tasks at once on the node, and daemons of its own: alone.)
set_tests_properties(study_run_slurm PROPERTIES RUN_SERIAL TRUE)
