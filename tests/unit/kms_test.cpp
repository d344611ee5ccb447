// The kms platform's decisions on plain data, as the kernel would report a display: which connector
// and mode --drm-connector and --drm-mode choose, what the errors list, and which uevents are a
// hotplug of the device the player drives.
#include "kms_output.h"
#include "uevent.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace platform {
namespace {

using kms::Connector;
using kms::ConnectorState;
using kms::Mode;
using kms::ModeRequest;

Mode mode(int w, int h, double hz, bool preferred = false, bool interlaced = false) {
  Mode m;
  m.width = w;
  m.height = h;
  m.refresh_hz = hz;
  m.preferred = preferred;
  m.interlaced = interlaced;
  return m;
}

// A TV on HDMI that prefers 1080p60 but also offers 4K30 and 1080i, a switched-off second HDMI.
std::vector<Connector> tv() {
  Connector hdmi1{1,
                  "HDMI-A-1",
                  ConnectorState::connected,
                  {mode(1920, 1080, 60.0, true), mode(3840, 2160, 30.0), mode(1920, 1080, 59.94), mode(1920, 1080, 50.0),
                   mode(1920, 1080, 60.0, false, true), mode(1280, 720, 60.0), mode(640, 480, 59.94)}};
  Connector hdmi2{2, "HDMI-A-2", ConnectorState::disconnected, {}};
  return {hdmi2, hdmi1};
}

TEST(KmsMode, ParsesEveryFormMpvTakes) {
  ModeRequest request;
  std::string error;
  ASSERT_TRUE(kms::parse_mode_request("preferred", request, error));
  EXPECT_EQ(request.kind, ModeRequest::Kind::preferred);
  ASSERT_TRUE(kms::parse_mode_request("highest", request, error));
  EXPECT_EQ(request.kind, ModeRequest::Kind::highest);
  ASSERT_TRUE(kms::parse_mode_request("1280x720", request, error));
  EXPECT_EQ(request.kind, ModeRequest::Kind::size);
  EXPECT_EQ(request.width, 1280);
  EXPECT_EQ(request.height, 720);
  EXPECT_EQ(request.refresh_hz, 0.0);
  ASSERT_TRUE(kms::parse_mode_request("1920x1080@59.94", request, error));
  EXPECT_DOUBLE_EQ(request.refresh_hz, 59.94);
  EXPECT_EQ(kms::to_string(request), "1920x1080@59.94");
}

TEST(KmsMode, RefusesWhatIsNotAMode) {
  for (const char* text : {"", "best", "1920", "1920x", "x1080", "0x1080", "1920x1080@", "1920x1080@0", "1920x1080@abc", "-1x5",
                           "1920x1080x3", "1920 x1080", "1920x1080@60Hz", "99999999999x1"}) {
    ModeRequest request;
    std::string error;
    EXPECT_FALSE(kms::parse_mode_request(text, request, error)) << text;
    EXPECT_EQ(error, "--drm-mode: expected preferred, highest or WxH[@R] (e.g. 1920x1080@60), got '" + std::string(text) + "'");
  }
}

TEST(KmsMode, ChoosesAsTheRequestSays) {
  const Connector hdmi = tv()[1];
  std::string error;
  auto choose = [&](const char* text) {
    ModeRequest request;
    EXPECT_TRUE(kms::parse_mode_request(text, request, error));
    return kms::choose_mode(hdmi, request, error);
  };
  EXPECT_EQ(choose("preferred"), 0);
  EXPECT_EQ(choose("highest"), 1);    // most pixels, whatever the refresh
  EXPECT_EQ(choose("1920x1080"), 0);  // the highest refresh at that size, progressive
  EXPECT_EQ(choose("1920x1080@50"), 3);
  EXPECT_EQ(choose("1920x1080@59.94"), 2);  // the nearest within half a hertz, not 60
  EXPECT_EQ(choose("1920x1080@60"), 0);
  EXPECT_EQ(choose("640x480@60"), 6);  // 59.94 is what a user means by 60
  EXPECT_EQ(choose("1280x720@50"), -1);
  EXPECT_EQ(error,
            "--drm-mode: HDMI-A-1 offers no mode 1280x720@50 (it offers 1920x1080@60.00 (preferred), 3840x2160@30.00, "
            "1920x1080@59.94, 1920x1080@50.00, 1920x1080i@60.00, 1280x720@60.00, 640x480@59.94)");
}

TEST(KmsMode, WithoutAPreferredModeTheFirstIsTaken) {
  Connector panel{7, "DSI-1", ConnectorState::connected, {mode(800, 480, 60.0), mode(640, 480, 60.0)}};
  ModeRequest request;
  std::string error;
  EXPECT_EQ(kms::choose_mode(panel, request, error), 0);
  request.kind = ModeRequest::Kind::highest;
  EXPECT_EQ(kms::choose_mode(panel, request, error), 0);
}

TEST(KmsConnector, AutoTakesTheFirstConnectedOne) {
  bool waiting = true;
  std::string error;
  EXPECT_EQ(kms::choose_connector(tv(), "auto", waiting, error), 1);
  EXPECT_FALSE(waiting);
  EXPECT_EQ(kms::choose_connector(tv(), "HDMI-A-1", waiting, error), 1);
}

TEST(KmsConnector, ADisconnectedDisplayIsWaitedFor) {
  bool waiting = false;
  std::string error;
  std::vector<Connector> off = tv();
  off[1].state = ConnectorState::disconnected;
  EXPECT_EQ(kms::choose_connector(off, "auto", waiting, error), -1);
  EXPECT_TRUE(waiting);
  EXPECT_EQ(kms::choose_connector(tv(), "HDMI-A-2", waiting, error), -1);
  EXPECT_TRUE(waiting);
  EXPECT_TRUE(error.empty());
}

TEST(KmsConnector, UnknownStateWithModesCounts) {
  // Some boards' DSI panels and HDMI without a hotplug line answer "unknown".
  std::vector<Connector> panel{{3, "DSI-1", ConnectorState::unknown, {mode(800, 480, 60.0, true)}}};
  bool waiting = true;
  std::string error;
  EXPECT_EQ(kms::choose_connector(panel, "auto", waiting, error), 0);
}

TEST(KmsConnector, AWrongNameListsTheConnectors) {
  bool waiting = true;
  std::string error;
  EXPECT_EQ(kms::choose_connector(tv(), "HDMI-1", waiting, error), -1);
  EXPECT_FALSE(waiting);
  EXPECT_EQ(error, "--drm-connector: no connector named 'HDMI-1' (expected auto, help or one of: HDMI-A-2 HDMI-A-1)");
}

TEST(KmsConnector, TheListingNamesStateAndModes) {
  std::vector<Connector> connectors = tv();
  connectors[1].modes.resize(2);
  EXPECT_EQ(kms::describe_connectors("/dev/dri/card1", connectors),
            "/dev/dri/card1: 2 connector(s)\n"
            "  HDMI-A-2: disconnected; no modes\n"
            "  HDMI-A-1: connected; 1920x1080@60.00 (preferred), 3840x2160@30.00\n");
}

// The one choice the start and every hotplug make: connector, then mode, with what each outcome says.
TEST(KmsChoice, ConnectorThenModeWithOneOutcome) {
  ModeRequest preferred;
  kms::Choice choice = kms::choose_output(tv(), "auto", preferred);
  EXPECT_EQ(choice.outcome, kms::Choice::Outcome::chosen);
  EXPECT_EQ(choice.connector, 1);
  EXPECT_EQ(choice.mode, 0);

  std::vector<Connector> off = tv();
  off[1].state = ConnectorState::disconnected;
  choice = kms::choose_output(off, "auto", preferred);
  EXPECT_EQ(choice.outcome, kms::Choice::Outcome::waiting);
  EXPECT_EQ(choice.why, "no display connected");
  choice = kms::choose_output(off, "HDMI-A-2", preferred);
  EXPECT_EQ(choice.outcome, kms::Choice::Outcome::waiting);
  EXPECT_EQ(choice.why, "no display connected to HDMI-A-2");

  choice = kms::choose_output(tv(), "HDMI-1", preferred);
  EXPECT_EQ(choice.outcome, kms::Choice::Outcome::no_such_connector);
  EXPECT_EQ(choice.why, "--drm-connector: no connector named 'HDMI-1' (expected auto, help or one of: HDMI-A-2 HDMI-A-1)");

  ModeRequest unknown;
  std::string error;
  ASSERT_TRUE(kms::parse_mode_request("1280x720@50", unknown, error));
  choice = kms::choose_output(tv(), "HDMI-A-1", unknown);
  EXPECT_EQ(choice.outcome, kms::Choice::Outcome::no_such_mode);
  EXPECT_EQ(choice.connector, 1);
  EXPECT_EQ(choice.mode, -1);
  EXPECT_EQ(choice.why.rfind("--drm-mode: HDMI-A-1 offers no mode 1280x720@50 (it offers ", 0), 0u);
}

TEST(KmsConnector, StatesHaveTheirNames) {
  EXPECT_EQ(kms::to_string(ConnectorState::connected), "connected");
  EXPECT_EQ(kms::to_string(ConnectorState::disconnected), "disconnected");
  EXPECT_EQ(kms::to_string(ConnectorState::unknown), "unknown");
  ModeRequest request;
  request.kind = ModeRequest::Kind::highest;
  EXPECT_EQ(kms::to_string(request), "highest");
  request.kind = ModeRequest::Kind::preferred;
  EXPECT_EQ(kms::to_string(request), "preferred");
}

// A message as the kernel sends it: fields separated by NULs (the literal's own NUL left out).
template <size_t N>
std::vector<char> raw(const char (&text)[N]) {
  return {text, text + N - 1};
}

TEST(Uevent, AKernelHotplugOfTheCardIsSeen) {
  const auto message =
      raw("change@/devices/platform/vkms/drm/card0\0ACTION=change\0DEVPATH=/devices/platform/vkms/drm/card0\0"
          "SUBSYSTEM=drm\0HOTPLUG=1\0DEVNAME=dri/card0\0DEVTYPE=drm_minor\0SEQNUM=1234\0MAJOR=226\0MINOR=0");
  uevent::Message parsed;
  ASSERT_TRUE(uevent::parse(message, parsed));
  EXPECT_EQ(parsed.action, "change");
  EXPECT_EQ(parsed.subsystem, "drm");
  EXPECT_EQ(parsed.devname, "dri/card0");
  EXPECT_TRUE(parsed.hotplug);
  EXPECT_TRUE(uevent::is_drm_change_of(parsed, "/dev/dri/card0"));
  EXPECT_FALSE(uevent::is_drm_change_of(parsed, "/dev/dri/card1"));
}

TEST(Uevent, ASyntheticHotplugWrittenToSysfsIsSeen) {
  // echo "change $(uuid) HOTPLUG=1" > /sys/class/drm/card0/uevent: the kernel prefixes the argument.
  const auto message =
      raw("change@/devices/platform/vkms/drm/card0\0ACTION=change\0DEVPATH=/devices/platform/vkms/drm/card0\0"
          "SUBSYSTEM=drm\0SYNTH_UUID=1c2a\0SYNTH_ARG_HOTPLUG=1\0DEVNAME=dri/card0\0SEQNUM=9\0");
  uevent::Message parsed;
  ASSERT_TRUE(uevent::parse(message, parsed));
  EXPECT_TRUE(parsed.hotplug);
  EXPECT_TRUE(uevent::is_drm_change_of(parsed, "/dev/dri/card0"));
}

TEST(Uevent, OtherDevicesAndUdevCopiesAreNot) {
  uevent::Message parsed;
  ASSERT_TRUE(
      uevent::parse(raw("add@/devices/virtual/input/input5\0ACTION=add\0SUBSYSTEM=input\0DEVNAME=input/event3\0"), parsed));
  EXPECT_FALSE(uevent::is_drm_change_of(parsed, "/dev/dri/card0"));
  ASSERT_TRUE(
      uevent::parse(raw("remove@/devices/platform/vkms/drm/card0\0ACTION=remove\0SUBSYSTEM=drm\0DEVNAME=dri/card0\0"), parsed));
  EXPECT_FALSE(uevent::is_drm_change_of(parsed, "/dev/dri/card0"));
  EXPECT_FALSE(uevent::parse(raw("libudev\0\xfe\xed\xca\xfe"), parsed));
  EXPECT_FALSE(uevent::parse(raw("garbage without fields"), parsed));
  EXPECT_FALSE(uevent::parse({}, parsed));
}

TEST(Uevent, TruncatedMessagesAreReadSafely) {
  // Every prefix of a message: fields cut short are read as far as they go, never past the end.
  const std::vector<char> full = raw("change@/x\0ACTION=change\0SUBSYSTEM=drm\0DEVNAME=dri/card0\0HOTPLUG=1");
  for (size_t length = 0; length <= full.size(); ++length) {
    uevent::Message parsed;
    const std::vector<char> cut(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(length));
    const bool parsed_ok = uevent::parse(cut, parsed);
    const std::string_view text(full.data(), full.size());
    const size_t action_ends = text.find("ACTION=") + 8, devname_ends = text.find("dri/card0") + 9;
    EXPECT_EQ(parsed_ok, length >= action_ends) << length;
    EXPECT_EQ(parsed.hotplug, length == full.size()) << length;
    EXPECT_EQ(uevent::is_drm_change_of(parsed, "/dev/dri/card0"), length >= devname_ends) << length;
  }
}

}  // namespace
}  // namespace platform
