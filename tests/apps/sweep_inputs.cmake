# SPDX-License-Identifier: BSD-3-Clause
# Bad input to the sweep-file commands and to `fly --learned-vehicle` (included by
# CMakeLists.txt): each refused or warned of before any flight, with the file and what was
# expected. That nothing in the directory changes is hostile_inputs_test.py's check.

# A directory with a results.json and no sweep.sha256 is not a sweep's: refused, not overwritten.
set(foreign_sweep_dir ${CMAKE_CURRENT_BINARY_DIR}/foreign_sweep_dir)
file(WRITE ${foreign_sweep_dir}/results.json "{\"mine\": true}\n")
geaware_cli_test(app_sweep_refuses_a_foreign_directory EXIT 1
  STDERR_CONTAINS "geaware: error: --out '${foreign_sweep_dir}': holds ${foreign_sweep_dir}/results.json and no sweep.sha256"
                  "expected a new or empty directory (nothing was changed)"
  LABELS app sweep COMMAND $<TARGET_FILE:geaware> sweep tests/sweep/sweep64.yaml --out ${foreign_sweep_dir} --quiet)

# The learned vehicle file cannot go to standard output, which carries the flight's summary.
geaware_cli_test(app_fly_learned_vehicle_not_stdout EXIT 1
  STDERR_CONTAINS "--learned-vehicle '-'"
  LABELS app COMMAND $<TARGET_FILE:geaware> fly --trajectory hover-descent --from-height 0.6 --height 0.1
                     --speed 0.2 --controller recommended+learn0 --quiet --learned-vehicle -)
