// SPDX-License-Identifier: BSD-3-Clause
#include "geaware/bridge/dds_node.hpp"

#include <stdexcept>

namespace geaware::bridge {
namespace {

[[noreturn]] void fail(const std::string& what, dds_return_t rc) {
  throw std::runtime_error("DDS: " + what + ": " + dds_strretcode(rc));
}

dds_qos_t* qosOf(TopicQos q) {
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, q.reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT,
                       DDS_SECS(1));
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, q.depth);
  dds_qset_durability(qos, DDS_DURABILITY_VOLATILE);
  dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos, 1, &xcdr1);
  return qos;
}

dds_entity_t topicOf(const DdsParticipant& p, const std::string& name,
                     const dds_topic_descriptor_t* type) {
  const dds_entity_t t = dds_create_topic(p.id(), type, name.c_str(), nullptr, nullptr);
  if (t < 0) fail("topic " + name + " (" + type->m_typename + ")", t);
  return t;
}

}  // namespace

std::string cycloneConfig(const DdsSettings& s) {
  std::string xml = "<CycloneDDS><Domain id=\"any\"><General>";
  if (!s.interface_address.empty()) {
    const bool address = s.interface_address.find_first_of("0123456789") == 0;
    xml += "<Interfaces><NetworkInterface " + std::string(address ? "address" : "name") + "=\"" +
           s.interface_address + "\"/></Interfaces>";
  }
  xml += std::string("<AllowMulticast>") + (s.multicast ? "default" : "false") + "</AllowMulticast>";
  xml += "</General><Discovery><ParticipantIndex>auto</ParticipantIndex>"
         "<MaxAutoParticipantIndex>60</MaxAutoParticipantIndex>";
  if (!s.peers.empty()) {
    xml += "<Peers>";
    for (const auto& peer : s.peers) xml += "<Peer address=\"" + peer + "\"/>";
    xml += "</Peers>";
  }
  xml += "</Discovery></Domain></CycloneDDS>";
  return xml;
}

std::string px4Topic(const DdsSettings& s, const char* direction, const char* name) {
  std::string t = "rt/";
  if (!s.px4_namespace.empty()) t += s.px4_namespace + "/";
  return t + "fmu/" + direction + "/" + name;
}

DdsParticipant::DdsParticipant(const DdsSettings& s) {
  const std::string config = cycloneConfig(s);
  domain_ = dds_create_domain(s.domain_id, config.c_str());
  if (domain_ < 0) fail("domain " + std::to_string(s.domain_id) + " with " + config, domain_);
  participant_ = dds_create_participant(s.domain_id, nullptr, nullptr);
  if (participant_ < 0) fail("participant in domain " + std::to_string(s.domain_id), participant_);
  publisher_ = dds_create_publisher(participant_, nullptr, nullptr);
  if (publisher_ < 0) fail("publisher", publisher_);
}

DdsParticipant::~DdsParticipant() {
  if (participant_ > 0) dds_delete(participant_);
  if (domain_ > 0) dds_delete(domain_);
}

dds_entity_t makeWriter(const DdsParticipant& p, const std::string& topic,
                        const dds_topic_descriptor_t* type, TopicQos q) {
  dds_qos_t* qos = qosOf(q);
  const dds_entity_t w = dds_create_writer(p.publisher(), topicOf(p, topic, type), qos, nullptr);
  dds_delete_qos(qos);
  if (w < 0) fail("writer of " + topic, w);
  return w;
}

dds_entity_t makeReader(const DdsParticipant& p, const std::string& topic,
                        const dds_topic_descriptor_t* type, TopicQos q) {
  dds_qos_t* qos = qosOf(q);
  const dds_entity_t r = dds_create_reader(p.id(), topicOf(p, topic, type), qos, nullptr);
  dds_delete_qos(qos);
  if (r < 0) fail("reader of " + topic, r);
  return r;
}

std::int32_t matchedReaders(dds_entity_t writer) noexcept {
  dds_publication_matched_status_t st{};
  if (dds_get_publication_matched_status(writer, &st) < 0) return 0;
  return static_cast<std::int32_t>(st.current_count);
}

std::int32_t matchedWriters(dds_entity_t reader) noexcept {
  dds_subscription_matched_status_t st{};
  if (dds_get_subscription_matched_status(reader, &st) < 0) return 0;
  return static_cast<std::int32_t>(st.current_count);
}

}  // namespace geaware::bridge
