// SPDX-License-Identifier: Apache-2.0
#pragma once
// The in-process transport of a composed rig (architecture, "Composed
// mode"): Writer<Def>::write hands the sample to every Reader<Def> of the
// topic in the same process, synchronously, on the writer's thread. No DDS
// participant, no serialization, no middleware hop. What the nodes rely on
// from DDS is mirrored: matched counts are the endpoints present on the
// topic, delivery is reliable and in order, and a transient-local writer
// keeps its last samples (the depth of its QoS preset) for a reader that
// is created later.
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <vector>

#include "bus/Qos.hpp"

namespace flatsat::bus {

class LocalChannelBase {
 public:
  virtual ~LocalChannelBase() = default;
  /// No reader joins from now on: writers stop keeping samples for late ones.
  virtual void seal() = 0;
};

/// One topic's endpoints in the process.
template <class Def>
class LocalChannel final : public LocalChannelBase {
 public:
  using Sample = typename Def::Type;
  using Callback = std::function<void(const Sample&)>;

  explicit LocalChannel(QosKind kind) {
    const auto qos = writerQos(kind);
    if (qos.durability().kind == eprosima::fastdds::dds::TRANSIENT_LOCAL_DURABILITY_QOS) {
      depth_ = static_cast<std::size_t>(qos.history().depth);
    }
  }

  std::size_t addWriter() {
    writers_.push_back({true, {}, 0});
    return writers_.size() - 1;
  }
  /// A deleted writer's history goes with it, as in DDS.
  void removeWriter(std::size_t id) { writers_[id] = {false, {}, 0}; }

  void seal() override {
    sealed_ = true;
    for (auto& w : writers_) w.history = {};
  }

  /// Hands the new reader what each live writer still keeps, oldest first.
  std::size_t addReader(const Callback* callback) {
    if (sealed_) {
      throw std::logic_error("a reader joined a composed rig after it started: it would miss the samples "
                             "a transient-local writer keeps for late readers");
    }
    for (const auto& w : writers_) {
      for (std::size_t i = 0; i < w.history.size(); ++i) {
        (*callback)(w.history[(w.next + i) % w.history.size()]);
      }
    }
    readers_.push_back(callback);
    return readers_.size() - 1;
  }
  void removeReader(std::size_t id) { readers_[id] = nullptr; }

  void write(std::size_t writer, const Sample& sample) {
    if (depth_ > 0 && !sealed_) keep(writers_[writer], sample);
    // By index: a callback may add a reader (the vector grows, never shrinks).
    for (std::size_t i = 0; i < readers_.size(); ++i) {
      if (readers_[i] != nullptr) (*readers_[i])(sample);
    }
  }

  int writers() const { return count(writers_, [](const WriterSlot& w) { return w.live; }); }
  int readers() const { return count(readers_, [](const Callback* r) { return r != nullptr; }); }

 private:
  struct WriterSlot {
    bool live;
    std::vector<Sample> history;  // a ring of at most depth_ samples
    std::size_t next;             // oldest sample (where the next one goes) once full
  };

  void keep(WriterSlot& w, const Sample& sample) {
    if (w.history.size() < depth_) {
      w.history.push_back(sample);
      return;
    }
    w.history[w.next] = sample;
    w.next = (w.next + 1) % depth_;
  }

  template <class Slots, class Live>
  static int count(const Slots& slots, Live live) {
    int n = 0;
    for (const auto& s : slots) n += live(s) ? 1 : 0;
    return n;
  }

  std::size_t depth_ = 0;  // [samples] kept per writer for late readers; 0: volatile
  bool sealed_ = false;    // no late reader can come: nothing kept
  std::vector<WriterSlot> writers_;
  std::vector<const Callback*> readers_;
};

/// The topics of one composed rig, by name. Not thread-safe: every endpoint
/// on a hub is created, used and deleted from one thread (the composed
/// scheduler's), which is also what makes the delivery order deterministic.
class LocalHub {
 public:
  /// The channel of that topic; throws std::logic_error when the name is
  /// already bound to another type (the registry binds one type per name).
  template <class Def>
  LocalChannel<Def>& channel(const Def& def) {
    auto it = channels_.find(def.name);
    if (it == channels_.end()) {
      it = channels_.emplace(std::string(def.name), std::make_unique<LocalChannel<Def>>(def.qos))
               .first;
    }
    auto* typed = dynamic_cast<LocalChannel<Def>*>(it->second.get());
    if (typed == nullptr) {
      throw std::logic_error("topic " + std::string(def.name) + ": already bound to another type than " +
                             typeid(typename Def::Type).name());
    }
    if (sealed_) typed->seal();
    return *typed;
  }

  /// Every reader of the rig exists (its nodes started): from now on a write
  /// copies its sample to the readers only, not also into a writer's history
  /// for late readers, which was a copy of every sample of every step. A
  /// reader created after this throws std::logic_error.
  void seal() {
    sealed_ = true;
    for (auto& [name, channel] : channels_) channel->seal();
  }

 private:
  bool sealed_ = false;
  std::map<std::string, std::unique_ptr<LocalChannelBase>, std::less<>> channels_;
};

}  // namespace flatsat::bus
