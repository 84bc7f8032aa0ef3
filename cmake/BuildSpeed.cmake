# SPDX-License-Identifier: Apache-2.0
# flatsat_unity_group(<target> <group> <file>...): compiles those sources of
# the target as one file (a unity build), so the headers and the inline code
# they share (CLI11, nlohmann-json, Fast DDS, fmt) are compiled once for the
# group instead of once per file. A cold build (CI builds a clean clone) is
# then much cheaper; an edit recompiles the whole group.
# Files of one group share one translation unit: names in their anonymous
# namespaces must differ (a clash is a compile error). A constant several
# files define each belongs in a header, defined once; a file whose own
# helper merely shares a name stays out of the group. Files in no group are
# compiled alone.
# -DFLATSAT_UNITY=OFF compiles every file alone.
function(flatsat_unity_group target group)
  if(NOT FLATSAT_UNITY)
    return()
  endif()
  set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_MODE GROUP)
  set_source_files_properties(${ARGN} TARGET_DIRECTORY ${target}
                              PROPERTIES UNITY_GROUP ${target}_${group})
endfunction()

# flatsat_unity_batches(<target> <size>): the target's sources compiled <size>
# to a file. For targets of many small files that parse the same headers
# again each (Catch2's single header, Eigen, the generated topic types).
# Results do not change: the same IEEE operations are compiled, only where a
# function is inlined may differ (no -ffast-math, no FMA contraction on x86-64).
function(flatsat_unity_batches target size)
  if(NOT FLATSAT_UNITY)
    return()
  endif()
  set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_MODE BATCH
                        UNITY_BUILD_BATCH_SIZE ${size})
endfunction()
