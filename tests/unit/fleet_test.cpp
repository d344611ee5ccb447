// The fleet agent's pure parts: its configuration as an operator writes it (and the errors they
// see), the topics a player answers on, and what Home Assistant's discovery is told. The agent
// against a real broker is tests/cli/fleet.sh.
#include "fleet/fleet.h"
#include "screenshot.h"  // player/fleet/src: the agent's PNG-to-JPEG step

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <png.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <random>
#include <set>

namespace {

fleet::Config parsed(const std::string& text, const std::string& machine_id = "0123abcd") {
  fleet::Config config;
  std::string error;
  EXPECT_TRUE(fleet::parse_config(text, "fleet.toml", machine_id, config, error)) << error;
  return config;
}

std::string refusal(const std::string& text, const std::string& machine_id = "0123abcd") {
  fleet::Config config;
  std::string error;
  EXPECT_FALSE(fleet::parse_config(text, "fleet.toml", machine_id, config, error)) << text;
  return error;
}

TEST(FleetConfig, TheIssuesExampleReadsAsWritten) {
  const fleet::Config c = parsed(R"(broker = "mqtts://broker.example:8883"
client_id = "kiosk-12"
prefix = "ssao-player"
username = "kiosk-12"
password_file = "/etc/ssao-player/fleet.password"
ca_file = "/etc/ssl/certs/fleet-ca.pem"
status_file = "/run/ssao-player/status.json"
control = "/run/ssao-player/control"
status_period_s = 5
)");
  EXPECT_TRUE(c.tls);
  EXPECT_EQ(c.host, "broker.example");
  EXPECT_EQ(c.port, 8883);
  EXPECT_EQ(c.client_id, "kiosk-12");
  EXPECT_EQ(c.username, "kiosk-12");
  EXPECT_EQ(c.password_file, "/etc/ssao-player/fleet.password");
  EXPECT_EQ(c.ca_file, "/etc/ssl/certs/fleet-ca.pem");
  EXPECT_FALSE(c.insecure);
  EXPECT_EQ(c.status_period_s, 5.0);
  EXPECT_EQ(c.name, "kiosk-12");
}

TEST(FleetConfig, OnlyTheBrokerIsRequiredAndTheMachineIdNamesThePlayer) {
  const fleet::Config c = parsed("broker = \"mqtt://10.0.0.2\"\n", "4f1e9a");
  EXPECT_FALSE(c.tls);
  EXPECT_EQ(c.host, "10.0.0.2");
  EXPECT_EQ(c.port, 1883);
  EXPECT_EQ(c.client_id, "4f1e9a");
  EXPECT_EQ(c.prefix, "ssao-player");
  EXPECT_EQ(c.status_file, "/run/ssao-player/status.json");
  EXPECT_EQ(c.control, "/run/ssao-player/control");
  EXPECT_EQ(c.status_period_s, 5.0);
  EXPECT_EQ(c.keepalive_s, 30);
  EXPECT_EQ(c.discovery_prefix, "homeassistant");
  EXPECT_EQ(parsed("broker = \"mqtts://b\"\n").port, 8883);
  EXPECT_EQ(refusal("broker = \"mqtt://b\"\n", ""),
            "fleet.toml:1:1: client_id: expected a name (this machine has no /etc/machine-id to stand in), got nothing");
}

TEST(FleetConfig, BrokerAddressesAsPeopleWriteThem) {
  EXPECT_EQ(parsed("broker = \"mqtt://[::1]:1884\"\n").host, "::1");
  EXPECT_EQ(parsed("broker = \"mqtt://[::1]:1884\"\n").port, 1884);
  EXPECT_EQ(parsed("broker = \"mqtt://broker.local:65535/\"\n").port, 65535);
  for (const char* bad : {"broker.example:1883", "http://broker", "mqtt://", "mqtt://b:0", "mqtt://b:65536",
                          "mqtt://b:", "mqtt://b:1x", "mqtt://user@b", "mqtt://[::1", "mqtt://[::1]x"})
    EXPECT_EQ(refusal(std::string("broker = \"") + bad + "\"\n"),
              std::string("fleet.toml:1:10: broker: expected mqtt://HOST[:PORT] or mqtts://HOST[:PORT], got '") + bad + "'");
}

TEST(FleetConfig, ErrorsNameTheLineTheKeyAndWhatWasExpected) {
  EXPECT_EQ(refusal("broker = \"mqtt://b\"\nstatus_period_s = \"five\"\n"),
            "fleet.toml:2:19: status_period_s: expected seconds in 0.2..3600, got 'five'");
  EXPECT_EQ(refusal("broker = \"mqtt://b\"\nstatus_period_s = 0.1\n"),
            "fleet.toml:2:19: status_period_s: expected seconds in 0.2..3600, got 0.1");
  EXPECT_EQ(refusal("broker = \"mqtt://b\"\nkeepalive_s = 7.5\n"),
            "fleet.toml:2:15: keepalive_s: expected whole seconds in 5..3600, got 7.5");
  EXPECT_EQ(refusal("broker = \"mqtt://b\"\nbroker_url = \"x\"\n"),
            "fleet.toml:2:1: broker_url: unknown key (expected one of broker, client_id, prefix, username, password_file, "
            "ca_file, insecure, status_file, control, status_period_s, keepalive_s, reconnect_max_s, discovery_prefix, name, "
            "screenshot_max_kb)");
  EXPECT_EQ(refusal("broker = \"mqtt://b\"\nca_file = \"/ca.pem\"\n"),
            "fleet.toml:2:11: ca_file: expected nothing for a broker without TLS (mqtt://); use mqtts://, got '/ca.pem'");
  EXPECT_EQ(refusal("broker = \"mqtts://b\"\npassword_file = \"/pw\"\n"),
            "fleet.toml:1:1: username: expected a user name to go with password_file, got nothing");
  EXPECT_EQ(refusal("broker = \"mqtt://b\"\nstatus_file = \"\"\n"), "fleet.toml:2:15: status_file: expected a path, got ''");
  EXPECT_EQ(refusal("broker = \n"), "fleet.toml:1:10: Error while parsing key-value pair: expected value, saw '\\n'");
}

TEST(FleetConfig, TopicLevelsRefuseWildcardsAndTheFleetWideName) {
  for (const char* id : {"a/b", "a+", "#", "all", ""})
    EXPECT_NE(
        refusal(std::string("broker = \"mqtt://b\"\nclient_id = \"") + id + "\"\n").find("client_id: expected a name without"),
        std::string::npos)
        << id;
  for (const char* prefix : {"/x", "x/", "a//b", "a/+/b", "#", ""})
    EXPECT_NE(refusal(std::string("broker = \"mqtt://b\"\nprefix = \"") + prefix + "\"\n").find("prefix: expected topic levels"),
              std::string::npos)
        << prefix;
  EXPECT_EQ(parsed("broker = \"mqtt://b\"\nprefix = \"museum/hall-3\"\n").prefix, "museum/hall-3");
  EXPECT_NE(refusal("broker = \"mqtt://b\"\ndiscovery_prefix = \"home/assistant\"\n")
                .find("discovery_prefix: expected one topic level"),
            std::string::npos);
}

TEST(FleetConfig, TlsWithoutChecksMustBeWrittenOut) {
  const fleet::Config checked = parsed("broker = \"mqtts://b\"\n");
  EXPECT_FALSE(checked.insecure);
  EXPECT_TRUE(checked.ca_file.empty());  // the system's certificates
  EXPECT_TRUE(parsed("broker = \"mqtts://b\"\ninsecure = true\n").insecure);
  EXPECT_EQ(refusal("broker = \"mqtts://b\"\ninsecure = \"yes\"\n"),
            "fleet.toml:2:12: insecure: expected true or false, got 'yes'");
}

TEST(FleetTopics, APlayerTakesItsOwnCommandsAndTheFleetsAsControlMessages) {
  const fleet::Config c = parsed("broker = \"mqtt://b\"\nclient_id = \"k1\"\nprefix = \"museum/players\"\n");
  EXPECT_EQ(fleet::command_subscriptions(c), (std::vector<std::string>{"museum/players/k1/cmd/+", "museum/players/all/cmd/+"}));
  EXPECT_EQ(fleet::state_topic(c), "museum/players/k1/state");
  EXPECT_EQ(fleet::availability_topic(c), "museum/players/k1/availability");
  std::string message, error;
  ASSERT_TRUE(fleet::command_of(c, "museum/players/k1/cmd/next", "", message, error)) << error;
  EXPECT_EQ(message, "next");
  ASSERT_TRUE(fleet::command_of(c, "museum/players/all/cmd/item", "2", message, error)) << error;
  EXPECT_EQ(message, "item 2");
  ASSERT_TRUE(fleet::command_of(c, "museum/players/all/cmd/display", "off", message, error)) << error;
  EXPECT_EQ(message, "display off");
  // Home Assistant's buttons press with "PRESS" unless told otherwise.
  ASSERT_TRUE(fleet::command_of(c, "museum/players/k1/cmd/check", "PRESS", message, error)) << error;
  EXPECT_EQ(message, "check");
  EXPECT_FALSE(fleet::command_of(c, "museum/players/k2/cmd/next", "", message, error));
  EXPECT_EQ(error, "'museum/players/k2/cmd/next' is not a command topic of this player");
  EXPECT_FALSE(fleet::command_of(c, "museum/players/k1/cmd/", "", message, error));
  EXPECT_FALSE(fleet::command_of(c, "museum/players/k1/cmd/format", "", message, error));
  EXPECT_NE(error.find("format"), std::string::npos);
  EXPECT_FALSE(fleet::command_of(c, "museum/players/k1/cmd/next", "now", message, error));
  EXPECT_FALSE(fleet::command_of(c, "museum/players/k1/cmd/item", "", message, error));
}

TEST(FleetDiscovery, EveryEntityCarriesWhatHomeAssistantRequires) {
  const fleet::Config c = parsed("broker = \"mqtt://b\"\nclient_id = \"kiosk.12\"\nname = \"Hall 3\"\n");
  const std::vector<fleet::Message> messages = fleet::discovery_messages(c, "1.2.3");
  std::set<std::string> unique_ids, components;
  for (const fleet::Message& m : messages) {
    SCOPED_TRACE(m.topic);
    EXPECT_TRUE(m.retain);
    // <prefix>/<component>/<node id>/<object id>/config, the ids of [a-zA-Z0-9_-] only.
    ASSERT_EQ(m.topic.rfind("homeassistant/", 0), 0u);
    ASSERT_EQ(m.topic.substr(m.topic.size() - 7), "/config");
    const std::string component = m.topic.substr(14, m.topic.find('/', 14) - 14);
    components.insert(component);
    EXPECT_NE(m.topic.find("/ssao_player_kiosk_12/"), std::string::npos);
    const nlohmann::json j = nlohmann::json::parse(m.payload);
    ASSERT_TRUE(j.contains("unique_id"));
    EXPECT_TRUE(unique_ids.insert(j["unique_id"].get<std::string>()).second) << "unique_id twice";
    EXPECT_EQ(j["availability"][0]["topic"], "ssao-player/kiosk.12/availability");
    EXPECT_EQ(j["device"]["identifiers"][0], "ssao-player-kiosk.12");
    EXPECT_EQ(j["device"]["name"], "Hall 3");
    EXPECT_EQ(j["device"]["sw_version"], "1.2.3");
    ASSERT_TRUE(j.contains("name"));
    if (component == "sensor" || component == "binary_sensor") {
      EXPECT_EQ(j["state_topic"], "ssao-player/kiosk.12/state");
      EXPECT_TRUE(j.contains("value_template"));
    } else if (component == "button") {
      EXPECT_EQ(j["command_topic"].get<std::string>().rfind("ssao-player/kiosk.12/cmd/", 0), 0u);
    } else if (component == "camera") {
      // The presented frame, and what the check camera sees of it.
      const std::string topic = j["topic"];
      EXPECT_TRUE(topic == "ssao-player/kiosk.12/screenshot/rendered" || topic == "ssao-player/kiosk.12/screenshot/camera")
          << topic;
    } else {
      ADD_FAILURE() << "a component Home Assistant was not meant to get: " << component;
    }
  }
  EXPECT_EQ(components, (std::set<std::string>{"sensor", "binary_sensor", "button", "camera"}));
  // Each button's verb is one the player takes.
  for (const fleet::Message& m : messages)
    if (m.topic.find("/button/") != std::string::npos) {
      std::string message, error;
      const std::string topic = nlohmann::json::parse(m.payload)["command_topic"];
      EXPECT_TRUE(fleet::command_of(c, topic, "PRESS", message, error)) << topic << ": " << error;
    }
}

TEST(FleetDiscovery, RemovalEmptiesEveryTopicDiscoveryFilled) {
  const fleet::Config c = parsed("broker = \"mqtt://b\"\nclient_id = \"k1\"\n");
  const std::vector<fleet::Message> made = fleet::discovery_messages(c, "1"), removed = fleet::discovery_removal(c);
  ASSERT_EQ(made.size(), removed.size());
  for (std::size_t i = 0; i < made.size(); ++i) {
    EXPECT_EQ(made[i].topic, removed[i].topic);
    EXPECT_TRUE(removed[i].payload.empty());
    EXPECT_TRUE(removed[i].retain);
  }
  EXPECT_TRUE(fleet::discovery_messages(parsed("broker = \"mqtt://b\"\ndiscovery_prefix = \"\"\n"), "1").empty());
}

TEST(FleetScreenshot, AFrameTooLargeForTheCapIsHalvedUntilItFits) {
  // Noise: JPEG cannot make it small, so only fewer pixels can.
  const int width = 320, height = 240;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * height * 3);
  std::minstd_rand random(7);
  for (std::uint8_t& v : rgb) v = static_cast<std::uint8_t>(random());
  const std::string path = (std::filesystem::temp_directory_path() / "fleet-screenshot-test.png").string();
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = width;
  image.height = height;
  image.format = PNG_FORMAT_RGB;
  ASSERT_NE(png_image_write_to_file(&image, path.c_str(), 0, rgb.data(), 0, nullptr), 0) << image.message;
  std::string jpeg, error;
  int w = 0, h = 0;
  ASSERT_TRUE(fleet::jpeg_within(path, 1u << 20, jpeg, w, h, error)) << error;
  EXPECT_EQ(w, width);  // under the cap: the whole frame
  EXPECT_EQ(h, height);
  ASSERT_GE(jpeg.size(), 3u);
  EXPECT_EQ(static_cast<unsigned char>(jpeg[0]), 0xff);
  EXPECT_EQ(static_cast<unsigned char>(jpeg[1]), 0xd8);
  const std::size_t full = jpeg.size();
  ASSERT_TRUE(fleet::jpeg_within(path, full / 3, jpeg, w, h, error)) << error;
  EXPECT_LE(jpeg.size(), full / 3);
  EXPECT_LT(w, width);
  EXPECT_EQ(w * height, h * width);  // halved, the shape kept
  EXPECT_FALSE(fleet::jpeg_within(path, 16, jpeg, w, h, error));
  EXPECT_NE(error.find("over the 16 bytes allowed"), std::string::npos) << error;
  EXPECT_FALSE(fleet::jpeg_within(path + ".missing", 1u << 20, jpeg, w, h, error));
  std::filesystem::remove(path);
}

}  // namespace
