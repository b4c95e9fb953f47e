# The plotting scripts as the README and the programs tell a user to run them: `python3 scripts/X.py` with the
# python3 on PATH (often not the system Python: pyenv, conda, a venv), on what the programs just wrote; each must
# leave its PNGs. Included by tests/CMakeLists.txt; the driver is examples/run_plot.cmake.
find_program(BLOCKDEM_USER_PYTHON NAMES python3 python DOC "the python3 a user's shell starts")
if(NOT BLOCKDEM_USER_PYTHON)
  return()
endif()
set(scripts "${PROJECT_SOURCE_DIR}/scripts")
set(plots "${CMAKE_CURRENT_BINARY_DIR}/plots")
set(run_plot "${CMAKE_CURRENT_SOURCE_DIR}/examples/run_plot.cmake")

# blockdem_plot_test(NAME SCRIPT script.py ARGS ... PNGS ... [PRODUCE_1 ...] [PYTHON p | VENV dir] [SCRIPT_ENV ...]
#                    [EXPECT_EXIT n] [OUTPUT_MATCHES regex] [NEEDS test-that-writes-the-input])
function(blockdem_plot_test name)
  cmake_parse_arguments(arg "" "SCRIPT;PYTHON;VENV;EXPECT_EXIT;OUTPUT_MATCHES;NEEDS"
                        "ARGS;PNGS;PRODUCE_1;PRODUCE_2;PRODUCE_3;SCRIPT_ENV" ${ARGN})
  if(NOT arg_PYTHON)
    set(arg_PYTHON "${BLOCKDEM_USER_PYTHON}")
  endif()
  set(defines "")
  foreach(key PRODUCE_1 PRODUCE_2 PRODUCE_3 ARGS PNGS SCRIPT_ENV)
    string(REPLACE ";" "\\;" value "${arg_${key}}")
    set(key_name ${key})
    if(key STREQUAL "ARGS")
      set(key_name SCRIPT_ARGS)
    endif()
    list(APPEND defines "-D${key_name}=${value}")
  endforeach()
  add_test(NAME plot.${name} COMMAND ${CMAKE_COMMAND} -DWORK=${plots}/${name} "-DPYTHON=${arg_PYTHON}"
    "-DVENV=${arg_VENV}" "-DSCRIPT=${arg_SCRIPT}" "-DEXPECT_EXIT=${arg_EXPECT_EXIT}"
    "-DOUTPUT_MATCHES=${arg_OUTPUT_MATCHES}" ${defines} -P ${run_plot})
  set_tests_properties(plot.${name} PROPERTIES SKIP_REGULAR_EXPRESSION "SKIPPED:" TIMEOUT 300)
  if(arg_NEEDS)
    set_tests_properties(plot.${name} PROPERTIES FIXTURES_REQUIRED ${arg_NEEDS})
  endif()
endfunction()

# The damping-ratio curves of maxwell_fit --curve (the paper's Fig. 10-12).
blockdem_plot_test(damping_curve SCRIPT ${scripts}/plot_damping_curve.py
  PRODUCE_1 $<TARGET_FILE:maxwell_fit> --zeta 0.04 --curve curve.csv
  ARGS curve.csv --band 1 40 --out curve.png PNGS ${plots}/damping_curve/curve.png)
# The joint's stress-displacement curves of joint_test --csv.
blockdem_plot_test(joint_curve SCRIPT ${scripts}/plot_joint_curve.py
  PRODUCE_1 $<TARGET_FILE:joint_test> --path cyclic-tension --steps 2000 --csv tension.csv
  PRODUCE_2 $<TARGET_FILE:joint_test> --path cyclic-shear --cycles 3 --csv shear.csv
  ARGS tension.csv shear.csv --out joints.png PNGS ${plots}/joint_curve/joints.png)
# A record, its spectrum, its wavelet truncation and pulse (the paper's Fig. 21).
blockdem_plot_test(record SCRIPT ${scripts}/plot_record.py
  PRODUCE_1 $<TARGET_FILE:ground_motion> process --synthetic --out record.csv
  PRODUCE_2 $<TARGET_FILE:ground_motion> spectrum --synthetic --out spectrum.csv
  PRODUCE_3 $<TARGET_FILE:ground_motion> truncate --synthetic --method wavelet --out cut.csv --pulse-out pulse.csv
  ARGS record.csv --spectrum spectrum.csv --cut cut.csv --pulse pulse.csv --out record.png
  PNGS ${plots}/record/record.png)
# The vault, rendered from cross_vault --geometry-only --vtk.
blockdem_plot_test(render_vault SCRIPT ${scripts}/render_vault.py
  PRODUCE_1 $<TARGET_FILE:cross_vault> --geometry-only --vtk vault.vtu
  ARGS vault.vtu vault.png PNGS ${plots}/render_vault/vault.png)
# The arch as built and collapsed, in elevation, from arch --vtk.
blockdem_plot_test(blocks_elevation SCRIPT ${scripts}/plot_blocks_elevation.py
  PRODUCE_1 $<TARGET_FILE:arch> --lambda 0 --vtk built
  PRODUCE_2 $<TARGET_FILE:arch> --lambda 0.4 --vtk collapsed
  ARGS built_blocks.vtu collapsed_blocks.vtu --titles built collapsed --out arch.png PNGS ${plots}/blocks_elevation/arch.png)
# The vault study's figures from the short run of program.cross_vault.run (the fixture vault_run).
set(vault_run "${CMAKE_CURRENT_BINARY_DIR}/vault_run")
blockdem_plot_test(vault SCRIPT ${scripts}/plot_vault.py NEEDS vault_run ARGS ${vault_run} --out ${plots}/vault
  PNGS ${plots}/vault/displacement_oc1.png ${plots}/vault/displacement_oc2_oc4.png
       ${plots}/vault/acceleration_acc18.png ${plots}/vault/damage_map.png ${plots}/vault/timing.png)
# Any study's figures (scripts/plot_study.py) from the same run, and the pushover curve of a block (b/h = 0.3).
blockdem_plot_test(study SCRIPT ${scripts}/plot_study.py NEEDS vault_run ARGS ${vault_run} --out ${plots}/study --points OC1,ACC18
  PNGS ${plots}/study/histories.png ${plots}/study/accelerations.png ${plots}/study/damage_by_group.png)
blockdem_plot_test(pushover SCRIPT ${scripts}/plot_study.py
  PRODUCE_1 $<TARGET_FILE:blockdem_program> run ${PROJECT_SOURCE_DIR}/examples/models/block_pushover.json --out pushed --quiet
  ARGS pushed --out . PNGS ${plots}/pushover/pushover.png)
# A sweep's figures from the small sweep of program.cross_vault.sweep.
set_tests_properties(program.cross_vault.sweep PROPERTIES FIXTURES_SETUP vault_sweep)
blockdem_plot_test(sweep SCRIPT ${scripts}/plot_sweep.py NEEDS vault_sweep
  ARGS ${CMAKE_CURRENT_BINARY_DIR}/vault_sweep/farm --out ${plots}/sweep
  PNGS ${plots}/sweep/sweep_table3.png ${plots}/sweep/sweep_heatmaps.png)

# Started by an interpreter that lacks matplotlib (a venv without the system's packages, as pyenv, conda or a venv
# would be): the script says so on one line, runs again under the system Python, and writes its PNG.
blockdem_plot_test(foreign_python SCRIPT ${scripts}/plot_damping_curve.py VENV ${plots}/foreign_python/venv
  PRODUCE_1 $<TARGET_FILE:maxwell_fit> --curve curve.csv
  ARGS curve.csv --out curve.png PNGS ${plots}/foreign_python/curve.png
  OUTPUT_MATCHES "plot_damping_curve.py: [^\n]*/venv/bin/python has no numpy or matplotlib; running with /usr/bin/python3, which has them")
# Neither that interpreter nor the system Python has them: the message names each one, what it lacks and the command
# that installs it, and nothing is written.
blockdem_plot_test(no_python SCRIPT ${scripts}/plot_damping_curve.py VENV ${plots}/no_python/venv
  SCRIPT_ENV BLOCKDEM_SYSTEM_PYTHON=/nonexistent/python3
  ARGS curve.csv --out curve.png EXPECT_EXIT 1
  OUTPUT_MATCHES "plot_damping_curve.py: needs numpy and matplotlib, and no Python here has them all; install them for either:\n  [^\n]*/venv/bin/python \\(the python3 running this script\\) has no numpy or matplotlib: [^\n]*/venv/bin/python -m pip install numpy matplotlib\n  there is no system Python at /nonexistent/python3: [^\n]*install-deps.sh --plots \\(Debian's python3-numpy python3-matplotlib\\)")
# MINPACK's LM from scipy on the problem of bench_maxwell_fit (benchmarks/minpack_reference.py): an independent
# implementation reaching the optimum maxwell_fit reports for 4 % over 1-40 Hz (1 + sum alpha = 1.3947, -2.256 % /
# +1.048 %; program.maxwell_fit tests the same figures from blockdem's fit).
blockdem_plot_test(minpack_reference SCRIPT ${PROJECT_SOURCE_DIR}/benchmarks/minpack_reference.py
  OUTPUT_MATCHES "1 \\+ sum alpha = 1\\.3947, relative error -2\\.256 % / \\+1\\.048 %")
