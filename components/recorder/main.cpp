// SPDX-License-Identifier: Apache-2.0
#include "analysis/RunFigures.hpp"
#include "components/Processes.hpp"

int main(int argc, char** argv) {
  flatsat::analysis::recordRunFigures();  // the summary's figures, accumulated as the samples are stored
  return flatsat::recorder::runProcess(argc, argv);
}
