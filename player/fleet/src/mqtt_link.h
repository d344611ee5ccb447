#pragma once
// One connection to the broker through libmosquitto, driven from the agent's own loop (no thread of
// libmosquitto's): connect, reconnect with backoff, publish only while connected, so that a broker
// away for hours queues nothing.
#include "fleet/fleet.h"

#include <chrono>
#include <deque>
#include <string>

struct mosquitto;
struct mosquitto_message;

namespace fleet {

class MqttLink {
 public:
  using Clock = std::chrono::steady_clock;

  // `will`: published by the broker when this client vanishes without saying goodbye.
  MqttLink(const Config& config, const Message& will, std::ostream& log);
  ~MqttLink();
  MqttLink(const MqttLink&) = delete;
  MqttLink& operator=(const MqttLink&) = delete;

  // Credentials and TLS as configured. False and why (a password file that cannot be read, a CA
  // file libmosquitto refuses).
  bool configure(std::string& error);
  // Connects when it is time to (at once, then after each failure later, doubling up to
  // reconnect_max_s), reads and writes what is due, and waits at most `wait_ms` for the socket or
  // `wake_fd` (-1: none) to be readable.
  void poll(int wait_ms, int wake_fd = -1);
  // True between the broker's CONNACK and the connection's loss. `fresh()` is true once per
  // connection: the caller then announces itself (retained messages, subscriptions).
  bool connected() const { return connected_; }
  bool fresh() {
    const bool was = fresh_;
    fresh_ = false;
    return was;
  }
  // Dropped (false) while not connected: nothing waits for the broker.
  bool publish(const Message& message, int qos);
  bool subscribe(const std::string& pattern);
  // Messages received, oldest first; at most kMaxPending are kept (the oldest are dropped).
  std::deque<Message>& received() { return received_; }
  // A clean goodbye: the messages given, each acknowledged (up to `flush_ms`), then DISCONNECT (so no will).
  void close(const std::vector<Message>& last, int flush_ms);
  // Connections made, counted for logs and tests.
  int connections() const { return connections_; }

  static constexpr std::size_t kMaxPending = 64;

 private:
  void try_connect(Clock::time_point now);
  void lost(const std::string& why, Clock::time_point now);
  static void on_connect(mosquitto*, void* self, int rc);
  static void on_message(mosquitto*, void* self, const mosquitto_message* message);
  static void on_log(mosquitto*, void* self, int level, const char* text);

  const Config& config_;
  std::ostream& log_;
  mosquitto* client_ = nullptr;
  bool socket_open_ = false, connected_ = false, fresh_ = false;
  int connections_ = 0, failures_ = 0;
  long long acknowledged_ = 0;  // QoS 1 messages the broker confirmed
  bool socket_closed_ = false;  // libmosquitto's disconnect callback ran
  Clock::time_point next_try_{};
  std::string last_library_error_;  // what libmosquitto logged last as an error (TLS details)
  std::string last_failure_;        // logged once until it changes
  std::deque<Message> received_;
  Message will_;
};

}  // namespace fleet
