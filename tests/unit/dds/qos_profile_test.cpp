// The QoS profiles file is really applied (Fast DDS silently ignores it when a participant is
// created from the default QoS): the lease decides how fast a killed process is noticed.
#include "idl/dds_participant.hpp"

#include <gtest/gtest.h>

TEST(QosProfile, ParticipantLeaseComesFromTheProfile) {
  mcnc::dds::Participant participant(231, "qos-test");
  EXPECT_EQ(mcnc::dds::participant_lease(participant), std::chrono::seconds(3));
}
