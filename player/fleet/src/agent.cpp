// The agent's loop: the broker's link polled, the status file carried to the state topic every
// status period, commands carried to the control socket one at a time with their replies sent back.
#include "base/read_file.h"
#include "command_carrier.h"
#include "control/control.h"
#include "fleet/fleet.h"
#include "mqtt_link.h"

#include <sys/stat.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <optional>
#include <ostream>

namespace fleet {
namespace {

volatile std::sig_atomic_t g_stop = 0;
void request_stop(int) {
  g_stop = 1;
}

using Clock = std::chrono::steady_clock;

// The player writes its status at least every two seconds: a file older than this is a player that
// stopped (or hangs), which the state must say rather than repeat the last words of.
constexpr double kStaleStatusS = 20.0;
std::string not_running(const std::string& reason) {
  return nlohmann::json{{"state", "not running"}, {"reason", reason}}.dump();
}

// The status file as the state topic's payload: its JSON as the player wrote it, or "not running"
// and why.
std::string read_state(const Config& config) {
  std::string text, error;
  if (!base::read_regular_file(config.status_file, "status file", base::kMiB, text, error)) return not_running(error);
  nlohmann::json status = nlohmann::json::parse(text, nullptr, false);
  if (status.is_discarded() || !status.is_object())
    return not_running(config.status_file + ": not the player's status (JSON object)");
  struct stat info {};
  if (stat(config.status_file.c_str(), &info) == 0) {
    const double age = static_cast<double>(time(nullptr) - info.st_mtim.tv_sec);
    if (age > kStaleStatusS) {
      status["reason"] = "the status file was last written " + std::to_string(static_cast<long long>(age)) + " s ago";
      status["state"] = "not running";
    }
  }
  return status.dump();
}

class Agent {
 public:
  Agent(const Config& config, const std::string& version, std::ostream& out)
      : config_(config), version_(version), out_(out), link_(config, {availability_topic(config), "offline", true}, out) {}

  bool start(std::string& error) { return link_.configure(error); }

  void run(double duration_s) {
    const Clock::time_point end =
        Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(duration_s));
    Clock::time_point next_state{};
    while (g_stop == 0 && (duration_s <= 0.0 || Clock::now() < end)) {
      link_.poll(100, carrier_.fd());
      if (link_.fresh()) announce(next_state);
      while (!link_.received().empty()) {
        carrier_.push(std::move(link_.received().front()));
        link_.received().pop_front();
      }
      while (std::optional<CommandCarrier::Done> done = carrier_.take()) publish_done(*done);
      if (link_.connected() && Clock::now() >= next_state) {
        link_.publish({state_topic(config_), read_state(config_), true}, 0);
        next_state =
            Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(config_.status_period_s));
      }
    }
    link_.close({{availability_topic(config_), "offline", true}}, 2000);
    out_ << "fleet: stopped\n";
  }

  // `player fleet --remove`: the broker forgets this player (Home Assistant its device).
  bool remove(double timeout_s) {
    const Clock::time_point end =
        Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s));
    while (!link_.connected() && Clock::now() < end && g_stop == 0) link_.poll(100);
    if (!link_.connected()) return false;
    std::vector<Message> empty = discovery_removal(config_);
    for (const std::string& topic :
         {state_topic(config_), availability_topic(config_), screenshot_topic(config_), camera_topic(config_)})
      empty.push_back({topic, "", true});
    link_.close(empty, 3000);
    out_ << "fleet: removed " << empty.size() << " retained topics of " << config_.client_id << "\n";
    return true;
  }

 private:
  // Each connection, new or again: who we are, retained, so that a broker that restarted without
  // persistence has it all back.
  void announce(Clock::time_point& next_state) {
    link_.publish({availability_topic(config_), "online", true}, 1);
    for (const Message& message : discovery_messages(config_, version_)) link_.publish(message, 1);
    for (const std::string& pattern : command_subscriptions(config_)) link_.subscribe(pattern);
    next_state = Clock::time_point{};
  }

  // A command's outcome, from the carrier's thread: its reply published, the state with it (the
  // player changed or refused: the status says so at once, not a period later).
  void publish_done(CommandCarrier::Done& done) {
    out_ << "fleet: " << done.topic << (done.payload.empty() ? "" : " '" + done.payload + "'") << ": " << done.reply << "\n";
    if (!done.jpeg.empty()) link_.publish({screenshot_topic(config_), std::move(done.jpeg), true}, 0);
    if (!done.camera_jpeg.empty()) link_.publish({camera_topic(config_), std::move(done.camera_jpeg), true}, 0);
    link_.publish(
        {reply_topic(config_),
         nlohmann::json{{"command", done.command}, {"ok", control::reply_ok(done.reply)}, {"reply", done.reply}}.dump(), false},
        1);
    link_.publish({state_topic(config_), read_state(config_), true}, 0);
  }

  const Config& config_;
  const std::string version_;
  std::ostream& out_;
  MqttLink link_;
  CommandCarrier carrier_{config_};
};

}  // namespace

int run_fleet(const Options& options, const std::string& version, std::ostream& out, std::ostream& err) {
  out << std::unitbuf;  // each line as it happens: a journal or a test reads along
  Config config;
  std::string error;
  if (!load_config(options.config, config, error)) {
    err << "error: " << error << "\n";
    return 2;
  }
  struct sigaction action {};
  action.sa_handler = request_stop;
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGINT, &action, nullptr);
  std::signal(SIGPIPE, SIG_IGN);
  g_stop = 0;
  Agent agent(config, version, out);
  if (!agent.start(error)) {
    err << "error: " << error << "\n";
    return 2;
  }
  out << (options.check ? "ok: " + options.config + ": " : std::string("fleet: ")) << config.client_id << " on "
      << (config.tls ? "mqtts://" : "mqtt://") << config.host << ":" << config.port << ", topics " << config.prefix << "/"
      << config.client_id << "/..., status " << config.status_file << ", control " << config.control << std::endl;
  if (options.check) return 0;
  if (options.remove) {
    if (agent.remove(options.duration_s > 0.0 ? options.duration_s : 30.0)) return 0;
    err << "error: the broker could not be reached to remove " << config.client_id << "\n";
    return 1;
  }
  agent.run(options.duration_s);
  return 0;
}

}  // namespace fleet
