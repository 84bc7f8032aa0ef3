// SPDX-License-Identifier: Apache-2.0
#include "bus/Shutdown.hpp"

#include <csignal>

namespace flatsat::bus {

namespace {
std::atomic<bool> g_shutdown{false};
extern "C" void onSignal(int) { g_shutdown.store(true); }
}  // namespace

void installShutdownHandlers() {
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool shutdownRequested() { return g_shutdown.load(); }
void requestShutdown() { g_shutdown.store(true); }
void clearShutdownRequest() { g_shutdown.store(false); }

}  // namespace flatsat::bus
