# Included by ctest after the discovered tests (TEST_INCLUDE_FILES): a test of the Fast DDS
# subset runs on the DDS domain and the CAN groups of its twin on the default middleware, so
# the two never run at once (two machines on one domain would hear each other).
foreach(fastdds_test IN LISTS mcnc_fastdds_twins)
  string(REPLACE "integration.fastdds." "integration." twin "${fastdds_test}")
  set_tests_properties("${fastdds_test}" "${twin}" PROPERTIES RESOURCE_LOCK "${twin}")
endforeach()
