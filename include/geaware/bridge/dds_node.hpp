// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A thin C++ layer over Cyclone DDS's C API for the bridge and the simulator: one participant in
// its own domain configuration (unicast to the given peers, multicast off by default), typed
// writers and readers of the idlc-generated structs, samples taken into preallocated memory.
// QoS: keep-last history of a fixed depth, volatile, XCDR1 data representation (ROS 2's).

#include <cstdint>
#include <string>
#include <vector>

#include <dds/dds.h>

namespace geaware::bridge {

/// Where the participant talks (docs/bridge.md, "Network").
struct DdsSettings {
  std::uint32_t domain_id = 0;            ///< DDS domain (ROS_DOMAIN_ID) [-]
  std::string interface_address = "127.0.0.1";  ///< the network interface, by address or name
  std::vector<std::string> peers{"127.0.0.1"};  ///< unicast discovery peers
  bool multicast = false;                 ///< multicast discovery and data (off: unicast only)
  std::string px4_namespace;              ///< PX4's uXRCE-DDS namespace, e.g. "px4_1" (topics rt/px4_1/fmu/...)
};

/// The Cyclone DDS configuration XML for `s`.
[[nodiscard]] std::string cycloneConfig(const DdsSettings& s);
/// "rt/fmu/out/<name>" (with the namespace: "rt/<ns>/fmu/out/<name>"); `direction` "in" or "out".
[[nodiscard]] std::string px4Topic(const DdsSettings& s, const char* direction, const char* name);

/// Owns the domain and the participant; throws std::runtime_error naming what failed.
class DdsParticipant {
 public:
  explicit DdsParticipant(const DdsSettings& s);
  ~DdsParticipant();
  DdsParticipant(const DdsParticipant&) = delete;
  DdsParticipant& operator=(const DdsParticipant&) = delete;
  [[nodiscard]] dds_entity_t id() const noexcept { return participant_; }
  [[nodiscard]] dds_entity_t publisher() const noexcept { return publisher_; }

 private:
  dds_entity_t domain_ = 0;
  dds_entity_t participant_ = 0;
  dds_entity_t publisher_ = 0;
};

/// Reliable or best effort, and the history depth of a writer or reader.
struct TopicQos {
  bool reliable = true;
  std::int32_t depth = 1;
};

/// Creates the topic (or finds it) and a writer or reader; throws on failure.
dds_entity_t makeWriter(const DdsParticipant& p, const std::string& topic,
                        const dds_topic_descriptor_t* type, TopicQos qos);
dds_entity_t makeReader(const DdsParticipant& p, const std::string& topic,
                        const dds_topic_descriptor_t* type, TopicQos qos);

/// Number of readers (writers) matched with `entity` right now.
[[nodiscard]] std::int32_t matchedReaders(dds_entity_t writer) noexcept;
[[nodiscard]] std::int32_t matchedWriters(dds_entity_t reader) noexcept;

/// Takes up to N samples of T into preallocated storage (no allocation by us); valid samples only.
template <class T, int N>
class TakeBuffer {
 public:
  TakeBuffer() noexcept {
    for (int i = 0; i < N; ++i) ptrs_[i] = &samples_[i];
  }
  /// Takes what the reader holds (at most N); returns the number of valid samples, packed first.
  int take(dds_entity_t reader) noexcept {
    const dds_return_t n = dds_take(reader, ptrs_, infos_, N, N);
    if (n <= 0) return 0;
    int valid = 0;
    for (int i = 0; i < n; ++i) {
      if (!infos_[i].valid_data) continue;
      if (valid != i) samples_[valid] = samples_[i];
      ++valid;
    }
    return valid;
  }
  [[nodiscard]] const T& operator[](int i) const noexcept { return samples_[i]; }

 private:
  T samples_[N]{};
  void* ptrs_[N]{};
  dds_sample_info_t infos_[N]{};
};

}  // namespace geaware::bridge
