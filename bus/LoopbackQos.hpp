// SPDX-License-Identifier: Apache-2.0
#pragma once
#include <cstdint>

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

namespace flatsat::bus {

/// The participant of the rig's default network (NetworkProfile::kLoopback): UDP on
/// 127.0.0.1 (and shared memory), unicast discovery to the first participants of the
/// domain on 127.0.0.1, no multicast. Transports set in code, from a default QoS
/// (Bus.cpp says why). Exposed for programs that use Fast DDS without the bus, on the
/// same network: `flatsat bench`'s plain graph.
eprosima::fastdds::dds::DomainParticipantQos loopbackParticipantQos(std::uint32_t domain, bool shared_memory,
                                                                   bool acks_over_shm);

}  // namespace flatsat::bus
