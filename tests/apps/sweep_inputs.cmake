# SPDX-License-Identifier: BSD-3-Clause
# Bad input to the sweep-file commands and to `fly --learned-vehicle` (included by
# CMakeLists.txt): each refused or warned of before any flight, with the file and what was
# expected. That nothing in the directory changes is hostile_inputs_test.py's check.

# A directory with a results.json and no sweep.sha256 is not a sweep's: refused, not overwritten.
set(foreign_sweep_dir ${CMAKE_CURRENT_BINARY_DIR}/foreign_sweep_dir)
file(WRITE ${foreign_sweep_dir}/results.json "the results of another program\n")
geaware_cli_test(app_sweep_refuses_a_foreign_directory EXIT 1
  STDERR_CONTAINS "geaware: error: --out '${foreign_sweep_dir}': holds ${foreign_sweep_dir}/results.json and no sweep.sha256"
                  "expected a new or empty directory (nothing was changed)"
  LABELS app sweep COMMAND $<TARGET_FILE:geaware> sweep tests/sweep/sweep64.yaml --out ${foreign_sweep_dir} --quiet)

# A grid of hours (2 cases × 100,000 seeds of exp 1's lemniscate) is warned of, naming the file,
# the flights and the hours, before any flight: here the run then stops at its bad --json path
# (`sweep` at its --out, a file), so nothing is flown.
set(long_grid ${CMAKE_CURRENT_BINARY_DIR}/long_grid.yaml)
file(READ ${PROJECT_SOURCE_DIR}/tests/sweep/suites/faults_small.yaml long_grid_text)
string(REPLACE "count: 1}" "count: 100000}" long_grid_text "${long_grid_text}")
file(WRITE ${long_grid} "${long_grid_text}")
geaware_cli_test(app_bench_warns_of_a_long_grid EXIT 1
  STDERR_LINE_REGEX "^geaware: warning: .*long_grid\\.yaml: 200000 flights, [0-9]+ h of simulated flight, a long run; "
  STDERR_CONTAINS "bench keeps its flights in memory" "no_such_dir"
  LABELS app sweep COMMAND $<TARGET_FILE:geaware> bench --suite faults --sweep ${long_grid} --quiet
                           --json ${CMAKE_CURRENT_BINARY_DIR}/no_such_dir/out.json)
geaware_cli_test(app_sweep_warns_of_a_long_grid EXIT 1
  STDERR_LINE_REGEX "^geaware: warning: .*long_grid\\.yaml: 200000 flights, [0-9]+ h of simulated flight, a long run; "
  STDERR_CONTAINS "run the same command again to go on" "exists and is not a directory"
  LABELS app sweep COMMAND $<TARGET_FILE:geaware> sweep ${long_grid} --out ${long_grid} --quiet)

# The learned vehicle file cannot go to standard output, which carries the flight's summary.
geaware_cli_test(app_fly_learned_vehicle_not_stdout EXIT 1
  STDERR_CONTAINS "--learned-vehicle '-'"
  LABELS app COMMAND $<TARGET_FILE:geaware> fly --trajectory hover-descent --from-height 0.6 --height 0.1
                     --speed 0.2 --controller recommended+learn0 --quiet --learned-vehicle -)
