# cmake -P script: the installed tree works by itself. Installs into a scratch
# prefix and runs the installed pronk from a directory outside the source tree,
# with no plugin path given: every shipped scenario validates, the main job
# (forward jump with the shipped policy) runs, and `pronk bench` finds its
# scenarios. Only files git tracks are installed.
file(REMOVE_RECURSE ${PREFIX} ${WORK})
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX}
  RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "cmake --install failed: ${rc}")
endif()

set(pronk ${PREFIX}/bin/pronk)
set(data ${PREFIX}/share/pronk)
# The environment of a user who has only the prefix.
set(clean_env ${CMAKE_COMMAND} -E env --unset=PRONK_PLUGIN_PATH --unset=PRONK_DATA_DIR)

function(run_installed what)
  execute_process(COMMAND ${clean_env} ${ARGN} WORKING_DIRECTORY ${WORK}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc)
    message(FATAL_ERROR "${what} failed (exit ${rc}) from the installed tree:\n${out}${err}")
  endif()
  set(last_output "${out}${err}" PARENT_SCOPE)
endfunction()

# Every shipped scenario, as a user of the prefix would name it.
file(GLOB_RECURSE scenarios ${data}/scenarios/*.xml)
list(LENGTH scenarios count)
if(count LESS 40)
  message(FATAL_ERROR "only ${count} scenario files installed under ${data}/scenarios")
endif()
run_installed("pronk validate of the ${count} installed scenarios" ${pronk} validate ${scenarios})

# The plugin comes from the prefix's own plugin directory.
run_installed("pronk plugins" ${pronk} plugins)
if(NOT last_output MATCHES "${PREFIX}/lib[^/]*/pronk/plugins")
  message(FATAL_ERROR "pronk plugins did not load the prefix's plugin:\n${last_output}")
endif()

# The main job with the installed policy.
run_installed("the forward jump with the shipped policy" ${pronk} run ${data}/scenarios/go1/forward.xml
  --policy ${data}/assets/policies/go1_flat_aim.json --out ${WORK}/forward)
if(NOT EXISTS ${WORK}/forward/results.json)
  message(FATAL_ERROR "the installed run wrote no results.json")
endif()

# bench finds its default scenarios in the prefix.
run_installed("pronk bench" ${pronk} bench --repeats 1)

# The man page and the bash completion, generated from the command line.
foreach(page share/man/man1/pronk.1 share/bash-completion/completions/pronk)
  if(NOT EXISTS ${PREFIX}/${page})
    message(FATAL_ERROR "not installed: ${PREFIX}/${page}")
  endif()
endforeach()

# Nothing but tracked files (when the source is a git checkout).
execute_process(COMMAND git -C ${SOURCE_DIR} ls-files -- scenarios assets
  OUTPUT_VARIABLE tracked RESULT_VARIABLE git_rc ERROR_QUIET)
if(git_rc EQUAL 0 AND tracked)
  string(REPLACE "\n" ";" tracked "${tracked}")
  file(GLOB_RECURSE installed RELATIVE ${data} ${data}/*)
  foreach(file IN LISTS installed)
    list(FIND tracked "${file}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "installed but not tracked by git: share/pronk/${file}")
    endif()
  endforeach()
endif()
