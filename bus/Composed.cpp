// SPDX-License-Identifier: Apache-2.0
#include "bus/Composed.hpp"

#include <exception>
#include <string>

#include "bus/Shutdown.hpp"

namespace flatsat::bus {

namespace {

/// Runs f for the named node; anything it throws becomes a NodeFailure
/// naming the node (a node's own failures already name it).
template <class F>
auto on(const Node& node, F&& f) {
  try {
    return f();
  } catch (const NodeFailure&) {
    throw;
  } catch (const std::exception& e) {
    throw NodeFailure(node.name() + ": " + e.what());
  }
}

}  // namespace

ComposedScheduler::ComposedScheduler(TimeMaster& master, std::vector<Component*> components)
    : master_(master), order_(std::move(components)) {}

void ComposedScheduler::run(const std::function<void(std::uint64_t)>& after_step) {
  start();
  for (std::uint64_t k = 0; k <= master_.finalStep(); ++k) {
    step(k);
    if (after_step) after_step(k);
  }
  stop();
}

void ComposedScheduler::start() {
  for (Component* c : order_) on(*c, [c] { c->start(); });
  on(master_, [this] { master_.start(); });
}

void ComposedScheduler::step(std::uint64_t k) {
  if (shutdownRequested()) throw NodeFailure("interrupted at step " + std::to_string(k));
  runStep(k);
}

void ComposedScheduler::stop() {
  on(master_, [this] { master_.stop(); });
  for (Component* c : order_) {
    if (on(*c, [c] { return c->turn(); }) != Component::Turn::kStopped) {
      throw NodeFailure(c->name() + ": did not take the stop grant");
    }
    on(*c, [c] { c->finish(); });
  }
}

void ComposedScheduler::runStep(std::uint64_t k) {
  on(master_, [this, k] { master_.beginStep(k); });
  // Every component holds this step's grant; each takes exactly one turn.
  went_.clear();
  done_.assign(order_.size(), false);
  while (went_.size() < order_.size()) {
    const std::size_t before = went_.size();
    std::string blocked;
    for (std::size_t i = 0; i < order_.size(); ++i) {
      if (done_[i]) continue;
      Component* c = order_[i];
      const auto turn = on(*c, [c] { return c->turn(); });
      if (turn == Component::Turn::kStepped) {
        done_[i] = true;
        went_.push_back(c);
      } else {
        blocked += " " + c->name() + (turn == Component::Turn::kBlocked ? " (inputs)" : " (no grant)");
      }
    }
    if (went_.size() == before) {
      throw NodeFailure("step " + std::to_string(k) + ": no component can go on:" + blocked);
    }
  }
  order_.swap(went_);
  on(master_, [this, k] { master_.endStep(k); });
}

}  // namespace flatsat::bus
