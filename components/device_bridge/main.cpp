// SPDX-License-Identifier: Apache-2.0
#include "components/Processes.hpp"

int main(int argc, char** argv) { return flatsat::device_bridge::runProcess(argc, argv); }
