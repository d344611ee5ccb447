#include "mqtt_link.h"

#include "base/read_file.h"

#include <mosquitto.h>

#include <poll.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <random>

namespace fleet {
namespace {

// libmosquitto's global state (OpenSSL's), made once for the process.
void init_library() {
  static const int initialised = mosquitto_lib_init();
  (void)initialised;
}

std::string where(const Config& config) {
  return (config.tls ? "mqtts://" : "mqtt://") + config.host + ":" + std::to_string(config.port);
}

}  // namespace

MqttLink::MqttLink(const Config& config, const Message& will, std::ostream& log) : config_(config), log_(log), will_(will) {
  init_library();
}

MqttLink::~MqttLink() {
  if (client_ != nullptr) mosquitto_destroy(client_);
}

bool MqttLink::configure(std::string& error) {
  client_ = mosquitto_new(config_.client_id.c_str(), true, this);
  if (client_ == nullptr) {
    error = "cannot make an MQTT client (out of memory)";
    return false;
  }
  mosquitto_connect_callback_set(client_, &MqttLink::on_connect);
  mosquitto_message_callback_set(client_, &MqttLink::on_message);
  mosquitto_publish_callback_set(client_, [](mosquitto*, void* self, int) { ++static_cast<MqttLink*>(self)->acknowledged_; });
  mosquitto_disconnect_callback_set(client_,
                                    [](mosquitto*, void* self, int) { static_cast<MqttLink*>(self)->socket_closed_ = true; });
  mosquitto_log_callback_set(client_, &MqttLink::on_log);
  if (!config_.username.empty()) {
    std::string password;
    if (!config_.password_file.empty()) {
      if (!base::read_regular_file(config_.password_file, "password file", 4 * base::kKiB, password, error)) {
        error = config_.source + ": password_file: " + error;
        return false;
      }
      // A password file ends with a newline as editors write it; the password does not.
      while (!password.empty() && (password.back() == '\n' || password.back() == '\r')) password.pop_back();
    }
    if (mosquitto_username_pw_set(client_, config_.username.c_str(),
                                  config_.password_file.empty() ? nullptr : password.c_str()) != MOSQ_ERR_SUCCESS) {
      error = config_.source + ": username: libmosquitto refused it (not UTF-8?)";
      return false;
    }
  }
  if (config_.tls) {
    // Without a CA file, the system's certificates (ca-certificates) vouch for the broker.
    const char* ca_file = config_.ca_file.empty() ? nullptr : config_.ca_file.c_str();
    const int rc =
        mosquitto_tls_set(client_, ca_file, ca_file == nullptr ? "/etc/ssl/certs" : nullptr, nullptr, nullptr, nullptr);
    if (rc != MOSQ_ERR_SUCCESS) {
      error = config_.source + ": ca_file: " + (config_.ca_file.empty() ? "/etc/ssl/certs" : config_.ca_file) +
              " cannot be used: " + mosquitto_strerror(rc);
      return false;
    }
    if (config_.insecure) {
      mosquitto_tls_opts_set(client_, 0 /* SSL_VERIFY_NONE */, nullptr, nullptr);
      mosquitto_tls_insecure_set(client_, true);
    }
  }
  if (mosquitto_will_set(client_, will_.topic.c_str(), static_cast<int>(will_.payload.size()), will_.payload.data(), 1,
                         will_.retain) != MOSQ_ERR_SUCCESS) {
    error = "the last will on '" + will_.topic + "' was refused by libmosquitto";
    return false;
  }
  return true;
}

void MqttLink::poll(int wait_ms, int wake_fd) {
  const Clock::time_point now = Clock::now();
  if (!socket_open_ && now >= next_try_) try_connect(now);
  pollfd fds[2] = {{wake_fd, POLLIN, 0}, {-1, 0, 0}};
  if (socket_open_) {
    fds[1] = {mosquitto_socket(client_), static_cast<short>(POLLIN | (mosquitto_want_write(client_) ? POLLOUT : 0)), 0};
  } else {
    const auto until_try = std::chrono::duration_cast<std::chrono::milliseconds>(next_try_ - now).count();
    wait_ms = static_cast<int>(std::clamp<long long>(until_try, 0, wait_ms));
  }
  // Woken by the broker's socket or the caller's own events (a command's reply), never later than
  // wait_ms: the keepalive's pings are due on time.
  ::poll(fds, socket_open_ ? 2 : 1, wait_ms);
  if (!socket_open_) return;
  // What is there (TLS records already decrypted included), what waits to be written, the keepalive.
  const int rc = mosquitto_loop(client_, 0, 1);
  if (rc != MOSQ_ERR_SUCCESS)
    lost((connected_ ? "" : "cannot connect: ") +
             (last_library_error_.empty() ? std::string(mosquitto_strerror(rc)) : last_library_error_),
         Clock::now());
}

void MqttLink::try_connect(Clock::time_point now) {
  last_library_error_.clear();
  const int rc = mosquitto_connect(client_, config_.host.c_str(), config_.port, config_.keepalive_s);
  if (rc == MOSQ_ERR_SUCCESS) {
    socket_open_ = true;  // the broker's CONNACK decides (on_connect)
    return;
  }
  lost("cannot connect: " + (last_library_error_.empty() ? std::string(mosquitto_strerror(rc)) : last_library_error_), now);
}

void MqttLink::lost(const std::string& why, Clock::time_point now) {
  if (connected_) {
    log_ << "fleet: lost " << where(config_) << ": " << why << "\n";
    failures_ = 0;
  } else if (why != last_failure_) {
    log_ << "fleet: " << where(config_) << ": " << why << "\n";
  }
  last_failure_ = why;
  connected_ = false;
  if (socket_open_) mosquitto_disconnect(client_);
  socket_open_ = false;
  // 1 s, 2 s, 4 s ... up to reconnect_max_s, each ±20% so that a fleet does not return in step.
  ++failures_;
  static thread_local std::minstd_rand jitter(std::random_device{}());
  const double base = std::min(config_.reconnect_max_s, std::ldexp(1.0, std::min(failures_ - 1, 20)));
  const double delay = base * std::uniform_real_distribution<double>(0.8, 1.2)(jitter);
  next_try_ = now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(delay));
}

bool MqttLink::publish(const Message& message, int qos) {
  if (!connected_) return false;
  return mosquitto_publish(client_, nullptr, message.topic.c_str(), static_cast<int>(message.payload.size()),
                           message.payload.data(), qos, message.retain) == MOSQ_ERR_SUCCESS;
}

bool MqttLink::subscribe(const std::string& pattern) {
  return connected_ && mosquitto_subscribe(client_, nullptr, pattern.c_str(), 1) == MOSQ_ERR_SUCCESS;
}

void MqttLink::close(const std::vector<Message>& last, int flush_ms) {
  if (!connected_) return;
  // Each message acknowledged by the broker (QoS 1) before DISCONNECT: a socket closed earlier
  // loses what libmosquitto had not written yet.
  const long long expected = acknowledged_ + static_cast<long long>(last.size());
  for (const Message& message : last) publish(message, 1);
  const Clock::time_point end = Clock::now() + std::chrono::milliseconds(flush_ms);
  while (acknowledged_ < expected && Clock::now() < end)
    if (mosquitto_loop(client_, 50, 1) != MOSQ_ERR_SUCCESS) break;
  socket_closed_ = false;
  if (mosquitto_disconnect(client_) == MOSQ_ERR_SUCCESS)
    while (!socket_closed_ && Clock::now() < end + std::chrono::milliseconds(500))
      if (mosquitto_loop(client_, 50, 1) != MOSQ_ERR_SUCCESS) break;
  connected_ = socket_open_ = false;
}

void MqttLink::on_connect(mosquitto*, void* self, int rc) {
  auto& link = *static_cast<MqttLink*>(self);
  if (rc != 0) {
    // Refused (a bad password, an unknown user): the broker closes the connection and poll() finds it.
    link.last_library_error_ = std::string("the broker refused the connection: ") + mosquitto_connack_string(rc);
    return;
  }
  link.connected_ = link.fresh_ = true;
  link.failures_ = 0;
  link.last_library_error_.clear();
  link.last_failure_.clear();
  ++link.connections_;
  link.log_ << "fleet: connected to " << where(link.config_) << " as " << link.config_.client_id << "\n";
}

void MqttLink::on_message(mosquitto*, void* self, const mosquitto_message* message) {
  auto& link = *static_cast<MqttLink*>(self);
  if (link.received_.size() >= kMaxPending) link.received_.pop_front();
  link.received_.push_back(
      {message->topic,
       std::string(static_cast<const char*>(message->payload), static_cast<std::size_t>(std::max(0, message->payloadlen))),
       message->retain});
}

void MqttLink::on_log(mosquitto*, void* self, int level, const char* text) {
  if (level == MOSQ_LOG_ERR) static_cast<MqttLink*>(self)->last_library_error_ = text;
}

}  // namespace fleet
