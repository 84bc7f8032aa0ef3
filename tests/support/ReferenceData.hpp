// SPDX-License-Identifier: Apache-2.0
#pragma once
// The shipped reference files (data/, with their provenance) that the unit
// tests read; FLATSAT_DATA_DIR comes from the tests' CMakeLists.
#include <string>

inline const std::string kDataDir = FLATSAT_DATA_DIR;
inline const std::string kIgrfFile = kDataDir + "/igrf/igrf14coeffs.txt";
