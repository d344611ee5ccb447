#include "control/control.h"
#include "fleet/fleet.h"

#include <nlohmann/json.hpp>

#include <algorithm>

namespace fleet {
namespace {

std::string base_topic(const Config& config) {
  return config.prefix + "/" + config.client_id;
}

// Home Assistant's node and object ids allow [a-zA-Z0-9_-] only.
std::string discovery_id(std::string_view text) {
  std::string id(text);
  std::replace_if(
      id.begin(), id.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_'; }, '_');
  return id;
}

struct Entity {
  std::string_view component, key, name;
  // The rest of the entity's payload, over the common part.
  nlohmann::json extra;
};

std::vector<Entity> entities(const Config& config) {
  const std::string state = state_topic(config), commands = base_topic(config) + "/cmd/";
  const auto sensor = [&](std::string_view key, std::string_view name, std::string_view value, nlohmann::json more = {}) {
    nlohmann::json extra = {{"state_topic", state}, {"value_template", value}};
    if (!more.is_null()) extra.update(more);
    return Entity{"sensor", key, name, extra};
  };
  const auto button = [&](std::string_view verb, std::string_view name) {
    return Entity{"button", verb, name, {{"command_topic", commands + std::string(verb)}, {"payload_press", ""}}};
  };
  return {
      sensor("state", "State", "{{ value_json.state }}"),
      sensor("item", "Item", "{{ value_json.item }}"),
      sensor("fps", "Frame rate", "{{ value_json.fps | round(1) }}",
             {{"unit_of_measurement", "fps"}, {"state_class", "measurement"}}),
      sensor("frame_ms_p99", "Frame time p99", "{{ value_json.frame_ms_p99 | round(1) }}",
             {{"unit_of_measurement", "ms"}, {"state_class", "measurement"}}),
      sensor("errors", "Errors", "{{ value_json.errors | count }}", {{"state_class", "measurement"}}),
      Entity{"binary_sensor",
             "display",
             "Display connected",
             {{"state_topic", state},
              {"device_class", "connectivity"},
              {"value_template", "{{ 'OFF' if value_json.state == 'no display' else 'ON' }}"}}},
      Entity{"binary_sensor",
             "self_check",
             "Self-check passed",
             {{"state_topic", state},
              {"value_template", "{{ 'ON' if value_json.self_check and value_json.self_check.passed else 'OFF' }}"}}},
      button("next", "Next"),
      button("previous", "Previous"),
      button("pause", "Pause"),
      button("resume", "Resume"),
      button("check", "Self-check"),
      button("reload", "Reload"),
      Entity{"camera", "screenshot", "Screenshot", {{"topic", screenshot_topic(config)}}},
      Entity{"camera", "camera_view", "Check camera's view", {{"topic", camera_topic(config)}}},
  };
}

std::string discovery_topic(const Config& config, const Entity& entity) {
  return config.discovery_prefix + "/" + std::string(entity.component) + "/" + discovery_id("ssao_player_" + config.client_id) +
         "/" + std::string(entity.key) + "/config";
}

}  // namespace

std::string state_topic(const Config& config) {
  return base_topic(config) + "/state";
}
std::string availability_topic(const Config& config) {
  return base_topic(config) + "/availability";
}
std::string reply_topic(const Config& config) {
  return base_topic(config) + "/reply";
}
std::string screenshot_topic(const Config& config) {
  return base_topic(config) + "/screenshot/rendered";
}
std::string camera_topic(const Config& config) {
  return base_topic(config) + "/screenshot/camera";
}

std::vector<std::string> command_subscriptions(const Config& config) {
  return {base_topic(config) + "/cmd/+", config.prefix + "/all/cmd/+"};
}

bool command_of(const Config& config, std::string_view topic, std::string_view payload, std::string& message,
                std::string& error) {
  std::string_view verb;
  for (const std::string& target : {base_topic(config), config.prefix + "/all"}) {
    const std::string start = target + "/cmd/";
    if (topic.size() > start.size() && topic.substr(0, start.size()) == start) verb = topic.substr(start.size());
  }
  if (verb.empty()) {
    error = "'" + std::string(topic) + "' is not a command topic of this player";
    return false;
  }
  // A Home Assistant button presses with "PRESS" unless told otherwise: the same as nothing.
  if (payload == "PRESS") payload = {};
  message = std::string(verb) + (payload.empty() ? "" : " " + std::string(payload));
  control::Command command;
  if (!control::parse_command(message, command, error)) return false;
  message = control::format_command(command);
  return true;
}

std::vector<Message> discovery_messages(const Config& config, const std::string& version) {
  std::vector<Message> messages;
  if (config.discovery_prefix.empty()) return messages;
  const std::string device_id = "ssao-player-" + config.client_id;
  const nlohmann::json device = {{"identifiers", {device_id}},
                                 {"name", config.name},
                                 {"manufacturer", "ssao-player"},
                                 {"model", "ssao-player kiosk"},
                                 {"sw_version", version}};
  for (const Entity& entity : entities(config)) {
    nlohmann::json payload = {{"name", entity.name},
                              {"unique_id", discovery_id(device_id + "-" + std::string(entity.key))},
                              {"availability", {{{"topic", availability_topic(config)}}}},
                              {"device", device}};
    payload.update(entity.extra);
    messages.push_back({discovery_topic(config, entity), payload.dump(), true});
  }
  return messages;
}

std::vector<Message> discovery_removal(const Config& config) {
  std::vector<Message> messages;
  if (!config.discovery_prefix.empty())
    for (const Entity& entity : entities(config)) messages.push_back({discovery_topic(config, entity), "", true});
  return messages;
}

}  // namespace fleet
