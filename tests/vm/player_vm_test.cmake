# player_vm_test(NAME <name> COMMAND <command> [<arg>...]
#                [SHARES <dir>...] [TIMEOUT <seconds>] [MEM <megabytes>]
#                [WORKING_DIRECTORY <dir>] [LABELS <label>...] [ENVIRONMENT <VAR=value>...])
#
# Adds the ctest test vm.<name>: COMMAND runs as root in a QEMU guest (tools/vm/run) on the kernel
# the vm.kernel fixture builds, with vkms, gpio-sim, vivid and uinput. Generator expressions such as
# $<TARGET_FILE:hal_tests> work in COMMAND. The guest sees this machine's `/` read-only; each of
# SHARES is read-write at its own path, and so is a per-test folder,
# ${PLAYER_TEST_OUTPUT_DIR}/vm/<name>, emptied before each run, whose path the command finds in
# PLAYER_VM_OUTPUT. TIMEOUT (default 600) bounds the guest; the ctest timeout is 120 s more.
# MEM defaults to 2048. WORKING_DIRECTORY (default: the calling folder's build folder) must be
# readable in the guest; it is writable only if it lies in a share. Exit 77 from the runner (no
# QEMU, no kernel) is a skip. Tests carry the label vm (plus LABELS) and the resource lock vm:
# one guest at a time.
#
# Include this file where you call it: include(${CMAKE_SOURCE_DIR}/tests/vm/player_vm_test.cmake)
include_guard(GLOBAL)

set(PLAYER_VM_RUN ${CMAKE_SOURCE_DIR}/tools/vm/run)

function(player_vm_test)
  cmake_parse_arguments(PARSE_ARGV 0 VM "" "NAME;TIMEOUT;MEM;WORKING_DIRECTORY" "COMMAND;SHARES;LABELS;ENVIRONMENT")
  if(NOT VM_NAME OR NOT VM_COMMAND)
    message(FATAL_ERROR "player_vm_test: NAME and COMMAND are required")
  endif()
  if(VM_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "player_vm_test(${VM_NAME}): unknown arguments: ${VM_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT VM_TIMEOUT)
    set(VM_TIMEOUT 600)
  endif()
  if(NOT VM_MEM)
    set(VM_MEM 2048)
  endif()
  if(NOT VM_WORKING_DIRECTORY)
    set(VM_WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  endif()
  if(NOT PLAYER_TEST_OUTPUT_DIR)
    set(PLAYER_TEST_OUTPUT_DIR ${CMAKE_BINARY_DIR}/test-output)
  endif()
  set(share_args --output ${PLAYER_TEST_OUTPUT_DIR}/vm/${VM_NAME})
  foreach(dir IN LISTS VM_SHARES)
    list(APPEND share_args --share ${dir})
  endforeach()
  add_test(NAME vm.${VM_NAME}
           COMMAND ${PLAYER_VM_RUN} --timeout ${VM_TIMEOUT} --mem ${VM_MEM} ${share_args} -- ${VM_COMMAND}
           WORKING_DIRECTORY ${VM_WORKING_DIRECTORY})
  math(EXPR ctest_timeout "${VM_TIMEOUT} + 120")
  set_tests_properties(vm.${VM_NAME} PROPERTIES
    LABELS "vm;${VM_LABELS}"
    FIXTURES_REQUIRED vm_kernel
    RESOURCE_LOCK vm
    # Started first: the guests run one after another for minutes, and begun last they would leave
    # the other core idle at the end of the run.
    COST 1000
    SKIP_RETURN_CODE 77
    TIMEOUT ${ctest_timeout})
  if(VM_ENVIRONMENT)
    set_tests_properties(vm.${VM_NAME} PROPERTIES ENVIRONMENT "${VM_ENVIRONMENT}")
  endif()
endfunction()
