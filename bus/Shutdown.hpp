// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <atomic>

namespace flatsat::bus {

/// Installs SIGINT/SIGTERM handlers that only set the flag below.
void installShutdownHandlers();
/// True once SIGINT or SIGTERM arrived.
bool shutdownRequested();
/// For tests hosting several nodes in one process: ask them all to stop.
void requestShutdown();
/// For such a test once its nodes stopped: the next test's nodes may run.
void clearShutdownRequest();

}  // namespace flatsat::bus
