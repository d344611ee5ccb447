#include "base/read_file.h"
#include "base/toml_fields.h"
#include "fleet/fleet.h"

#include <algorithm>
#include <charconv>

namespace fleet {
namespace {

// A topic level of ours: MQTT's wildcards and the separator would change what it means.
bool plain_level(std::string_view text) {
  return !text.empty() && text.find_first_of("+#/") == std::string_view::npos &&
         std::none_of(text.begin(), text.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; });
}

// mqtt://host[:port] or mqtts://host[:port], the host a name, an IPv4 address or [IPv6].
bool parse_broker(std::string_view url, Config& config) {
  constexpr std::string_view plain = "mqtt://", secure = "mqtts://";
  if (url.substr(0, plain.size()) == plain) {
    url.remove_prefix(plain.size());
    config.tls = false;
    config.port = 1883;
  } else if (url.substr(0, secure.size()) == secure) {
    url.remove_prefix(secure.size());
    config.tls = true;
    config.port = 8883;
  } else {
    return false;
  }
  if (!url.empty() && url.back() == '/') url.remove_suffix(1);
  std::string_view host = url, port;
  if (!url.empty() && url.front() == '[') {
    const std::size_t close = url.find(']');
    if (close == std::string_view::npos) return false;
    host = url.substr(1, close - 1);
    const std::string_view rest = url.substr(close + 1);
    if (!rest.empty()) {
      if (rest.front() != ':') return false;
      port = rest.substr(1);
    }
  } else if (const std::size_t colon = url.rfind(':'); colon != std::string_view::npos) {
    host = url.substr(0, colon);
    port = url.substr(colon + 1);
  }
  if (host.empty() || host.find_first_of("/@ ") != std::string_view::npos) return false;
  if (!port.empty() || url.back() == ':') {
    int number = 0;
    const auto [end, status] = std::from_chars(port.data(), port.data() + port.size(), number);
    if (status != std::errc() || end != port.data() + port.size() || number < 1 || number > 65535) return false;
    config.port = number;
  }
  config.host = std::string(host);
  return true;
}

}  // namespace

bool parse_config(std::string_view text, const std::string& source, const std::string& machine_id, Config& config,
                  std::string& error) {
  Config read;
  read.source = source;
  const auto fill = [&](const toml::table& table) {
    const base::TomlFields f(table, source);
    f.only({"broker", "client_id", "prefix", "username", "password_file", "ca_file", "insecure", "status_file", "control",
            "status_period_s", "keepalive_s", "reconnect_max_s", "discovery_prefix", "name", "screenshot_max_kb"});
    if (!f.has("broker") || !parse_broker(f.string("broker", ""), read))
      f.fail("broker", "mqtt://HOST[:PORT] or mqtts://HOST[:PORT]");
    read.client_id = f.string("client_id", machine_id);
    if (!plain_level(read.client_id) || read.client_id == "all")
      f.fail("client_id", f.has("client_id") ? "a name without '/', '+', '#' or control characters, other than 'all'"
                                             : "a name (this machine has no /etc/machine-id to stand in)");
    read.prefix = f.string("prefix", read.prefix);
    const std::string_view prefix = read.prefix;
    bool prefix_ok = !prefix.empty() && prefix.front() != '/' && prefix.back() != '/';
    for (std::size_t start = 0; prefix_ok && start <= prefix.size();) {
      const std::size_t end = std::min(prefix.find('/', start), prefix.size());
      prefix_ok = plain_level(prefix.substr(start, end - start));
      start = end + 1;
    }
    if (!prefix_ok) f.fail("prefix", "topic levels separated by '/', without '+', '#' or empty levels");
    read.username = f.string("username", "");
    read.password_file = f.string("password_file", "");
    if (!read.password_file.empty() && read.username.empty()) f.fail("username", "a user name to go with password_file");
    read.ca_file = f.string("ca_file", "");
    read.insecure = f.boolean("insecure", false);
    if (!read.tls && (f.has("ca_file") || f.has("insecure")))
      f.fail(f.has("ca_file") ? "ca_file" : "insecure", "nothing for a broker without TLS (mqtt://); use mqtts://");
    read.status_file = f.string("status_file", read.status_file);
    read.control = f.string("control", read.control);
    if (read.status_file.empty()) f.fail("status_file", "a path");
    if (read.control.empty()) f.fail("control", "a path");
    read.status_period_s = f.number("status_period_s", read.status_period_s, 0.2, 3600.0, "seconds");
    read.keepalive_s = static_cast<int>(f.number("keepalive_s", read.keepalive_s, 5, 3600, "whole seconds"));
    if (f.has("keepalive_s") && !table.get("keepalive_s")->is_integer()) f.fail("keepalive_s", "whole seconds in 5..3600");
    read.reconnect_max_s = f.number("reconnect_max_s", read.reconnect_max_s, 1.0, 3600.0, "seconds");
    read.discovery_prefix = f.string("discovery_prefix", read.discovery_prefix);
    if (!read.discovery_prefix.empty() && !plain_level(read.discovery_prefix))
      f.fail("discovery_prefix", "one topic level (Home Assistant's is 'homeassistant'), or \"\" for no discovery");
    read.name = f.string("name", read.client_id);
    read.screenshot_max_kb = static_cast<int>(f.number("screenshot_max_kb", read.screenshot_max_kb, 16, 16384, "KiB"));
  };
  if (!base::read_toml(text, source, fill, error)) return false;
  config = std::move(read);
  return true;
}

bool load_config(const std::string& path, Config& config, std::string& error) {
  std::string text, machine_id;
  if (!base::read_regular_file(path, "fleet configuration", 64 * base::kKiB, text, error)) return false;
  std::string ignored;
  if (base::read_regular_file("/etc/machine-id", "machine id", base::kKiB, machine_id, ignored))
    machine_id.erase(std::remove_if(machine_id.begin(), machine_id.end(), [](char c) { return c == '\n' || c == ' '; }),
                     machine_id.end());
  return parse_config(text, path, machine_id, config, error);
}

}  // namespace fleet
