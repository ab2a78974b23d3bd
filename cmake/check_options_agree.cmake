# The command line, a scenario file and calibration resolve the same settings to the same
# AnalysisOptions (glint … --print-options prints them as JSON and loads nothing).
#   -DGLINT=path/to/glint -DDATA=tests/data -DWORKDIR=dir
function(glint_print out_var)
  execute_process(COMMAND ${GLINT} ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "glint ${ARGN}: exit ${code}\nstdout:\n${out}\nstderr:\n${err}")
  endif()
  string(STRIP "${out}" out)
  set(${out_var} "${out}" PARENT_SCOPE)
endfunction()

set(scenario ${DATA}/scenarios/options_equivalence.toml)
glint_print(cli sweep ${DATA}/cube.obj ${DATA}/cube.obj --register --loss huber --fit-roi sphere:0,0,0,5 --symmetric
            --samples 3000 --plan sphere:12 --zoom 0.05,0.1 --supersample 3 --metric rgb --max-incidence 70
            --threshold-deg 12.5 --noise-k 5 --min-region-vertices 4 --rule normal -o ${WORKDIR}/unused --print-options)
glint_print(from_scenario run ${scenario} -o ${WORKDIR}/unused --print-options)
glint_print(from_calibrate calibrate ${scenario} -o ${WORKDIR}/unused.json --print-options)
if(NOT cli STREQUAL from_scenario)
  message(FATAL_ERROR "sweep flags and the scenario file resolve differently:\n--- command line\n${cli}\n--- scenario\n${from_scenario}")
endif()
if(NOT from_calibrate STREQUAL from_scenario)
  message(FATAL_ERROR "calibrate and run read the scenario differently:\n--- calibrate\n${from_calibrate}\n--- run\n${from_scenario}")
endif()
# The defaults agree too: a bare sweep with --register and an empty scenario with only the
# reference resolve alike.
file(WRITE ${WORKDIR}/defaults.toml "[reference]\nmesh = \"${DATA}/cube.obj\"\n")
glint_print(cli_defaults sweep ${DATA}/cube.obj ${DATA}/cube.obj --register -o ${WORKDIR}/unused --print-options)
glint_print(scenario_defaults run ${WORKDIR}/defaults.toml -o ${WORKDIR}/unused --print-options)
if(NOT cli_defaults STREQUAL scenario_defaults)
  message(FATAL_ERROR "defaults differ:\n--- command line\n${cli_defaults}\n--- scenario\n${scenario_defaults}")
endif()
# And they are not trivially equal: a changed option shows.
glint_print(other sweep ${DATA}/cube.obj ${DATA}/cube.obj --register --size 300 -o ${WORKDIR}/unused --print-options)
if(other STREQUAL cli_defaults)
  message(FATAL_ERROR "--size 300 did not change the printed options")
endif()
