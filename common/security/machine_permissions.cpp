#include "common/security/machine_permissions.hpp"

#include "common/config/cyclic_routes.hpp"
#include "common/security/identity_files.hpp"
#include "common/text/markup_escape.hpp"
#include "idl/topics.hpp"

#include <algorithm>

namespace mcnc::security {

namespace {

template <class T>
std::string topic() {
  return dds::TopicTraits<T>::name;
}

template <class T>
std::string topic_of(const std::string& key) {
  return dds::keyed_topic(dds::TopicTraits<T>::name, key);
}

void add_once(std::vector<std::string>& topics, std::string topic) {
  if (std::find(topics.begin(), topics.end(), topic) == topics.end()) {
    topics.push_back(std::move(topic));
  }
}

// Every process of the machine says how it is and raises its alarms.
std::vector<std::string> process_topics() {
  return {topic<ProcessState>(), topic<Alarm>()};
}

Identity channel_identity(const config::MachineConfig& machine,
                          const config::ChannelConfig& channel) {
  Identity identity{channel.name, Role::channel, process_topics()};
  add_once(identity.publishes, topic_of<ChannelStatus>(channel.name));
  add_once(identity.publishes, topic<CoordinationEvent>());
  add_once(identity.publishes, topic<OperatorAnswer>());  // answers the operator's commands
  // The setpoints of the axes it may own: its own, those it may take with G141, its spindles'
  // C axes (on the spindle's node) and its spindles.
  std::vector<std::string> commanded = channel.program_axes();
  commanded.insert(commanded.end(), channel.spindles.begin(), channel.spindles.end());
  for (const std::string& name : commanded) {
    if (const config::AxisConfig* axis = machine.find_axis(name)) {
      add_once(identity.publishes, topic_of<AxisSetpoint>(config::node_key(*axis)));
    }
  }
  return identity;
}

Identity launcher_identity(std::string name) {
  Identity identity{std::move(name), Role::launcher, process_topics()};
  for (std::string t : {topic<RunControl>(), topic<OperatorCommand>(), topic<ClockProbe>(),
                        topic<ClockEcho>(), topic<HostClock>(), topic<RunRequest>(),
                        topic<RunOutcome>(), topic<TraceChunk>(), topic<TraceReceipt>()}) {
    add_once(identity.publishes, std::move(t));
  }
  return identity;
}

// Every domain a secured machine may run on: the CA, not the domain, tells machines apart, and
// MCNC_DOMAIN moves a machine to another domain (decision 70).
const std::string kAllDomains = "<domains><id_range><min>0</min><max>" +
                                std::to_string(kMaxSecuredDomain) + "</max></id_range></domains>";

const char* protection_kind(Protection protection) {
  switch (protection) {
    case Protection::access_control:
      return "NONE";
    case Protection::sign:
      return "SIGN";
    case Protection::encrypt:
      return "ENCRYPT";
  }
  return "NONE";
}

}  // namespace

std::vector<Identity> machine_identities(const config::MachineConfig& machine) {
  std::vector<Identity> identities;
  for (const config::ChannelConfig& channel : machine.channels) {
    identities.push_back(channel_identity(machine, channel));
  }
  for (const config::AxisConfig& axis : machine.axes) {
    Identity identity{axis.name, Role::axis_node, process_topics()};
    add_once(identity.publishes, topic_of<AxisFeedback>(config::node_key(axis)));
    add_once(identity.publishes, topic<OperatorAnswer>());  // answers the operator's resets
    identities.push_back(std::move(identity));
  }
  if (machine.plc.present) {
    Identity identity{"PLC", Role::plc, process_topics()};
    add_once(identity.publishes, topic<PlcStatus>());
    add_once(identity.publishes, topic<AuxAck>());
    identities.push_back(std::move(identity));
  }
  identities.push_back(Identity{"hmi", Role::hmi, {topic<OperatorCommand>()}});
  identities.push_back(launcher_identity("launch"));
  for (const config::HostConfig& host : machine.hosts) {
    identities.push_back(launcher_identity("launch-" + host.name));
  }
  identities.push_back(Identity{kViewerIdentity, Role::viewer, {}});
  return identities;
}

const Identity* find_identity(const std::vector<Identity>& identities, const std::string& name) {
  const auto it = std::find_if(identities.begin(), identities.end(),
                               [&](const Identity& identity) { return identity.name == name; });
  return it == identities.end() ? nullptr : &*it;
}

std::string common_name(const std::string& machine, const std::string& identity) {
  return identity + "." + machine;
}

std::string subject_name(const std::string& machine, const std::string& identity) {
  return "CN=" + common_name(machine, identity);
}

const char* protection_name(Protection protection) noexcept {
  switch (protection) {
    case Protection::access_control:
      return "access";
    case Protection::sign:
      return "sign";
    case Protection::encrypt:
      return "encrypt";
  }
  return "access";
}

std::string governance_xml(Protection protection) {
  // Every topic alike (docs/operations.md, "Security", says why per topic): writes are checked
  // against the permissions, reads are not (what a machine reports is no secret from its own
  // identities), and the protection kind covers each submessage on the network. Shared memory
  // between the processes of one host carries the cyclic samples outside of it.
  std::string xml =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\">\n"
      "  <domain_access_rules>\n"
      "    <domain_rule>\n      ";
  xml += kAllDomains;
  xml +=
      "\n"
      "      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>\n"
      "      <enable_join_access_control>true</enable_join_access_control>\n"
      "      <discovery_protection_kind>NONE</discovery_protection_kind>\n"
      "      <liveliness_protection_kind>NONE</liveliness_protection_kind>\n"
      "      <rtps_protection_kind>NONE</rtps_protection_kind>\n"
      "      <topic_access_rules>\n"
      "        <topic_rule>\n"
      "          <topic_expression>*</topic_expression>\n"
      "          <enable_discovery_protection>false</enable_discovery_protection>\n"
      "          <enable_liveliness_protection>false</enable_liveliness_protection>\n"
      "          <enable_read_access_control>false</enable_read_access_control>\n"
      "          <enable_write_access_control>true</enable_write_access_control>\n"
      "          <metadata_protection_kind>";
  xml += protection_kind(protection);
  xml +=
      "</metadata_protection_kind>\n"
      "          <data_protection_kind>NONE</data_protection_kind>\n"
      "        </topic_rule>\n"
      "      </topic_access_rules>\n"
      "    </domain_rule>\n"
      "  </domain_access_rules>\n"
      "</dds>\n";
  return xml;
}

std::string permissions_xml(const std::string& machine, const std::vector<Identity>& identities,
                            const Validity& validity) {
  std::string xml =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\">\n"
      "  <permissions>\n";
  for (const Identity& identity : identities) {
    xml += "    <grant name=\"" + text::markup_escaped(identity.name) + "\">\n";
    xml += "      <subject_name>" + text::markup_escaped(subject_name(machine, identity.name)) +
           "</subject_name>\n";
    xml += "      <validity><not_before>" + validity.not_before + "</not_before><not_after>" +
           validity.not_after + "</not_after></validity>\n";
    xml += "      <allow_rule>\n        ";
    xml += kAllDomains;
    xml += "\n";
    if (!identity.publishes.empty()) {
      xml += "        <publish><topics>\n";
      for (const std::string& t : identity.publishes) {
        xml += "          <topic>" + text::markup_escaped(t) + "</topic>\n";
      }
      xml += "        </topics></publish>\n";
    }
    xml += "        <subscribe><topics><topic>*</topic></topics></subscribe>\n";
    xml += "      </allow_rule>\n";
    xml += "      <default>DENY</default>\n";
    xml += "    </grant>\n";
  }
  xml +=
      "  </permissions>\n"
      "</dds>\n";
  return xml;
}

}  // namespace mcnc::security
