#include "common/security/machine_permissions.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

using namespace mcnc;
using security::Role;
using ::testing::Contains;
using ::testing::IsEmpty;
using ::testing::Not;

namespace {

const std::string kSourceDir = MCNC_SOURCE_DIR;

config::MachineConfig twin_turret() {
  return config::load_machine_file(kSourceDir + "/launch/machines/twin_turret.yaml");
}

const security::Identity& identity(const std::vector<security::Identity>& all,
                                   const std::string& name) {
  const security::Identity* found = security::find_identity(all, name);
  if (found == nullptr) {
    throw std::runtime_error("no identity " + name);
  }
  return *found;
}

// The identities that may write `topic`, by name.
std::vector<std::string> writers_of(const std::vector<security::Identity>& all,
                                    const std::string& topic) {
  std::vector<std::string> names;
  for (const security::Identity& i : all) {
    if (std::find(i.publishes.begin(), i.publishes.end(), topic) != i.publishes.end()) {
      names.push_back(i.name);
    }
  }
  return names;
}

}  // namespace

TEST(MachinePermissions, EveryProcessOfTheMachineHasAnIdentityAndTheViewerToo) {
  const auto all = security::machine_identities(twin_turret());
  for (const char* name : {"CH1", "CH2", "CH3", "X1", "Z1", "A1", "S1", "X2", "Z2", "S2", "X3",
                           "Z3", "PLC", "hmi", "launch", "viewer"}) {
    EXPECT_NE(security::find_identity(all, name), nullptr) << name;
  }
  EXPECT_EQ(identity(all, "CH1").role, Role::channel);
  EXPECT_EQ(identity(all, "X1").role, Role::axis_node);
  EXPECT_EQ(identity(all, "viewer").role, Role::viewer);
  EXPECT_EQ(security::find_identity(all, "C1"), nullptr);  // a C axis has no node of its own
}

TEST(MachinePermissions, AChannelWritesItsStatusItsCoordinationAndTheSetpointsOfAxesItMayOwn) {
  const auto all = security::machine_identities(twin_turret());
  const auto& ch1 = identity(all, "CH1").publishes;
  EXPECT_THAT(ch1, Contains("mcnc/ChannelStatus/CH1"));
  EXPECT_THAT(ch1, Contains("mcnc/CoordinationEvent"));
  EXPECT_THAT(ch1, Contains("mcnc/AxisSetpoint/X1"));
  EXPECT_THAT(ch1, Contains("mcnc/AxisSetpoint/A1"));
  EXPECT_THAT(ch1, Contains("mcnc/AxisSetpoint/S1"));  // its spindle, and C1 on S1's node
  EXPECT_THAT(ch1, Not(Contains("mcnc/ChannelStatus/CH2")));
  EXPECT_THAT(ch1, Not(Contains("mcnc/AxisSetpoint/X2")));
  EXPECT_THAT(ch1, Not(Contains("mcnc/OperatorCommand")));
  EXPECT_THAT(ch1, Not(Contains("mcnc/RunControl")));
  EXPECT_THAT(ch1, Not(Contains("mcnc/AxisFeedback/X1")));
  // CH2 may take A1 with G141: it may write A1's setpoints, never X1's.
  const auto& ch2 = identity(all, "CH2").publishes;
  EXPECT_THAT(ch2, Contains("mcnc/AxisSetpoint/A1"));
  EXPECT_THAT(ch2, Not(Contains("mcnc/AxisSetpoint/X1")));
  EXPECT_EQ(writers_of(all, "mcnc/AxisSetpoint/X1"), std::vector<std::string>{"CH1"});
  EXPECT_EQ(writers_of(all, "mcnc/AxisSetpoint/A1"), (std::vector<std::string>{"CH1", "CH2"}));
  EXPECT_EQ(writers_of(all, "mcnc/ChannelStatus/CH3"), std::vector<std::string>{"CH3"});
}

TEST(MachinePermissions, AnAxisNodeWritesItsOwnFeedbackAndItsAnswersOnly) {
  const auto all = security::machine_identities(twin_turret());
  EXPECT_EQ(identity(all, "X1").publishes,
            (std::vector<std::string>{"mcnc/ProcessState", "mcnc/Alarm", "mcnc/AxisFeedback/X1",
                                      "mcnc/OperatorAnswer"}));
  EXPECT_EQ(writers_of(all, "mcnc/AxisFeedback/S2"), std::vector<std::string>{"S2"});
}

TEST(MachinePermissions, OnlyTheHmiAndTheLauncherCommandAndTheViewerWritesNothing) {
  const auto all = security::machine_identities(twin_turret());
  EXPECT_EQ(writers_of(all, "mcnc/OperatorCommand"), (std::vector<std::string>{"hmi", "launch"}));
  EXPECT_EQ(writers_of(all, "mcnc/RunControl"), std::vector<std::string>{"launch"});
  EXPECT_THAT(identity(all, "viewer").publishes, IsEmpty());
  EXPECT_EQ(writers_of(all, "mcnc/AuxAck"), std::vector<std::string>{"PLC"});
}

TEST(MachinePermissions, TheProcessesThatServeOperatorCommandsAnswerThemAndNoOneElse) {
  const auto machine = twin_turret();
  const auto all = security::machine_identities(machine);
  const auto answering = writers_of(all, "mcnc/OperatorAnswer");
  EXPECT_EQ(answering.size(), machine.channels.size() + machine.axes.size());
  EXPECT_THAT(answering, Contains("CH1"));
  EXPECT_THAT(answering, Contains("X1"));
  for (const char* other : {"hmi", "launch", "viewer", "PLC"}) {
    EXPECT_THAT(answering, Not(Contains(other))) << other;
  }
}

TEST(MachinePermissions, AMachineOfSeveralHostsHasALauncherIdentityPerHost) {
  const auto machine = config::load_machine_file(kSourceDir + "/launch/machines/cell_3ncu.yaml");
  ASSERT_FALSE(machine.hosts.empty());
  const auto all = security::machine_identities(machine);
  for (const config::HostConfig& host : machine.hosts) {
    const security::Identity* launcher = security::find_identity(all, "launch-" + host.name);
    ASSERT_NE(launcher, nullptr) << host.name;
    EXPECT_THAT(launcher->publishes, Contains("mcnc/RunControl"));
  }
}

TEST(MachinePermissions, ThePermissionsGrantEachSubjectItsTopicsAndDenyTheRest) {
  const auto machine = twin_turret();
  const auto all = security::machine_identities(machine);
  const std::string xml =
      security::permissions_xml(machine.name, all, {"2026-01-01T00:00:00", "2027-01-01T00:00:00"});
  const auto grant_start = xml.find("<grant name=\"viewer\">");
  ASSERT_NE(grant_start, std::string::npos);
  const std::string viewer =
      xml.substr(grant_start, xml.find("</grant>", grant_start) - grant_start);
  EXPECT_THAT(viewer, ::testing::HasSubstr("<subject_name>CN=viewer.twin_turret</subject_name>"));
  EXPECT_THAT(viewer, Not(::testing::HasSubstr("<publish>")));
  EXPECT_THAT(viewer, ::testing::HasSubstr("<default>DENY</default>"));
  EXPECT_THAT(xml, ::testing::HasSubstr("<not_after>2027-01-01T00:00:00</not_after>"));
  EXPECT_THAT(xml, ::testing::HasSubstr("<topic>mcnc/AxisFeedback/X1</topic>"));
  // Cyclone DDS 0.10 refuses the whole document for a domain above 230.
  EXPECT_THAT(xml, ::testing::HasSubstr("<id_range><min>0</min><max>230</max></id_range>"));
}

TEST(MachinePermissions, TheGovernanceRefusesUnauthenticatedParticipantsAndChecksEveryWrite) {
  const std::string sign = security::governance_xml(security::Protection::sign);
  EXPECT_THAT(
      sign, ::testing::HasSubstr(
                "<allow_unauthenticated_participants>false</allow_unauthenticated_participants>"));
  EXPECT_THAT(
      sign, ::testing::HasSubstr("<enable_join_access_control>true</enable_join_access_control>"));
  EXPECT_THAT(sign, ::testing::HasSubstr(
                        "<enable_write_access_control>true</enable_write_access_control>"));
  EXPECT_THAT(sign,
              ::testing::HasSubstr("<metadata_protection_kind>SIGN</metadata_protection_kind>"));
  EXPECT_THAT(security::governance_xml(security::Protection::access_control),
              ::testing::HasSubstr("<metadata_protection_kind>NONE</metadata_protection_kind>"));
  EXPECT_THAT(security::governance_xml(security::Protection::encrypt),
              ::testing::HasSubstr("<metadata_protection_kind>ENCRYPT</metadata_protection_kind>"));
}
