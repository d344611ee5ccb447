// The systemd notifications (player/app/src/service_notify.*) against a datagram socket the test
// listens on, as systemd's manager would: the notifier under an injected clock, then `player play`
// end to end with NOTIFY_SOCKET, WATCHDOG_USEC and WATCHDOG_PID set as systemd sets them.
#include "service_notify.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace std::chrono_literals;
using app::ServiceNotifier;
using Nanos = std::chrono::nanoseconds;

// The manager's end: a datagram socket bound to an abstract name unique to this process and test.
class Listener {
 public:
  Listener() {
    static int count = 0;
    name_ = "@ssao-player-test-" + std::to_string(getpid()) + "-" + std::to_string(count++);
    fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::memcpy(address.sun_path + 1, name_.data() + 1, name_.size() - 1);
    const socklen_t length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + name_.size());
    if (fd_ < 0 || bind(fd_, reinterpret_cast<const sockaddr*>(&address), length) != 0)
      ADD_FAILURE() << "cannot bind " << name_ << ": " << std::strerror(errno);
  }
  ~Listener() { close(fd_); }
  const std::string& name() const { return name_; }
  int fd() const { return fd_; }

  // Every datagram waiting now, each as it came.
  std::vector<std::string> take() {
    std::vector<std::string> messages;
    char buffer[4096];
    for (;;) {
      const ssize_t length = recv(fd_, buffer, sizeof buffer, MSG_DONTWAIT);
      if (length < 0) break;
      messages.emplace_back(buffer, static_cast<size_t>(length));
    }
    return messages;
  }

 private:
  std::string name_;
  int fd_ = -1;
};

ServiceNotifier::Config config_for(const Listener& listener, Nanos watchdog) {
  ServiceNotifier::Config config;
  config.socket = listener.name();
  config.watchdog = watchdog;
  return config;
}

// What was sent, and the injected time of the call that sent it.
struct Sent {
  Nanos at;
  std::string message;
};

// Frames presented every `step` from 0 to `until`, the listener read after each.
std::vector<Sent> present_frames(ServiceNotifier& notifier, Listener& listener, Nanos step, Nanos until) {
  std::vector<Sent> sent;
  for (Nanos now{0}; now <= until; now += step) {
    notifier.frame_presented(now);
    for (std::string& message : listener.take()) sent.push_back({now, std::move(message)});
  }
  return sent;
}

TEST(Notifier, WithoutNotifySocketEveryCallDoesNothing) {
  ServiceNotifier notifier(ServiceNotifier::Config{});
  EXPECT_FALSE(notifier.enabled());
  EXPECT_EQ(notifier.error(), "");
  notifier.state("playing");
  notifier.frame_presented(Nanos{0});
  notifier.frame_presented(Nanos{std::chrono::seconds(100)});
  notifier.stopping();
  EXPECT_FALSE(notifier.ready_sent());
}

TEST(Notifier, ReadyOnceOnTheFirstFrameThenWatchdogEveryHalfInterval) {
  Listener listener;
  const Nanos watchdog = 10s;
  ServiceNotifier notifier(config_for(listener, watchdog));
  ASSERT_TRUE(notifier.enabled()) << notifier.error();
  // 60 s of frames at 60 Hz (a step that does not divide 5 s) from t = 0.
  const Nanos step = std::chrono::duration_cast<Nanos>(std::chrono::duration<double>(1.0 / 60.0));
  const std::vector<Sent> sent = present_frames(notifier, listener, step, 60s);

  ASSERT_FALSE(sent.empty());
  EXPECT_EQ(sent.front().message, "READY=1");
  EXPECT_EQ(sent.front().at, Nanos{0});  // the first frame presented, not a later one
  EXPECT_EQ(std::count_if(sent.begin(), sent.end(), [](const Sent& s) { return s.message == "READY=1"; }), 1);
  Nanos last = sent.front().at;
  int pings = 0;
  for (size_t i = 1; i < sent.size(); ++i) {
    EXPECT_EQ(sent[i].message, "WATCHDOG=1") << "message " << i;
    // Never closer than half the interval (READY=1 starts systemd's timer), and sent by the first
    // frame after that: at most one frame later.
    EXPECT_GE(sent[i].at - last, watchdog / 2) << "message " << i;
    EXPECT_LT(sent[i].at - last, watchdog / 2 + step) << "message " << i;
    last = sent[i].at;
    ++pings;
  }
  EXPECT_EQ(pings, 11);  // 60 s / (5 s and a part of a frame)
}

TEST(Notifier, SlowFramesFeedTheWatchdogOnEveryFrameThatIsLateEnough) {
  Listener listener;
  ServiceNotifier notifier(config_for(listener, 2s));
  // A frame every 1.5 s: more than half the interval apart, so each one after READY=1 pings.
  const std::vector<Sent> sent = present_frames(notifier, listener, 1500ms, 6s);
  ASSERT_EQ(sent.size(), 5u);
  EXPECT_EQ(sent[0].message, "READY=1");
  for (size_t i = 1; i < sent.size(); ++i) EXPECT_EQ(sent[i].message, "WATCHDOG=1");
}

TEST(Notifier, NoWatchdogIntervalMeansReadyAlone) {
  Listener listener;
  ServiceNotifier notifier(config_for(listener, Nanos{0}));
  const std::vector<Sent> sent = present_frames(notifier, listener, 100ms, 60s);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].message, "READY=1");
}

TEST(Notifier, StatusOnEachChangeOnly) {
  Listener listener;
  ServiceNotifier notifier(config_for(listener, 10s));
  notifier.state("starting");
  notifier.state("starting");
  notifier.state("loading");
  notifier.state("playing");
  notifier.state("playing");
  notifier.state("paused");
  notifier.state("playing");
  EXPECT_EQ(listener.take(),
            (std::vector<std::string>{"STATUS=starting", "STATUS=loading", "STATUS=playing", "STATUS=paused", "STATUS=playing"}));
  // A text longer than the buffer is cut, and the cut text counts as the same state next time.
  const std::string long_text(300, 'x');
  notifier.state(long_text);
  notifier.state(long_text);
  const std::vector<std::string> sent = listener.take();
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].rfind("STATUS=xxx", 0), 0u);
  EXPECT_EQ(sent[0].size(), 128u);
}

TEST(Notifier, StoppingIsTheLastMessage) {
  Listener listener;
  ServiceNotifier notifier(config_for(listener, 2s));
  notifier.state("playing");
  notifier.frame_presented(Nanos{0});
  notifier.stopping();
  notifier.state("error");
  notifier.frame_presented(Nanos{std::chrono::seconds(10)});
  notifier.stopping();
  EXPECT_EQ(listener.take(), (std::vector<std::string>{"STATUS=playing", "READY=1", "STOPPING=1\nSTATUS=stopping"}));
}

// The manager not reading: its queue fills, and the notifier neither blocks the frame nor loses
// READY=1 or a ping, which go out on the next frame once there is room.
TEST(Notifier, AFullQueueNeitherBlocksNorLosesReadyOrThePing) {
  Listener listener;
  const int filler = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::memcpy(address.sun_path + 1, listener.name().data() + 1, listener.name().size() - 1);
  const socklen_t length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + listener.name().size());
  int queued = 0;
  while (sendto(filler, "x", 1, MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&address), length) == 1) ++queued;
  ASSERT_EQ(errno, EAGAIN);
  ASSERT_GT(queued, 0);

  ServiceNotifier notifier(config_for(listener, 2s));
  notifier.frame_presented(Nanos{0});  // would block here if it waited for room
  EXPECT_FALSE(notifier.ready_sent());
  listener.take();
  notifier.frame_presented(Nanos{16ms});
  EXPECT_TRUE(notifier.ready_sent());
  EXPECT_EQ(listener.take(), std::vector<std::string>{"READY=1"});

  while (sendto(filler, "x", 1, MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&address), length) == 1) {
  }
  notifier.frame_presented(Nanos{1100ms});  // due, not taken
  listener.take();
  notifier.frame_presented(Nanos{1116ms});  // the next frame sends it
  EXPECT_EQ(listener.take(), std::vector<std::string>{"WATCHDOG=1"});
  notifier.frame_presented(Nanos{1200ms});  // and the half interval counts from there
  EXPECT_EQ(listener.take(), std::vector<std::string>{});
  close(filler);
}

TEST(Notifier, APathSocketWorksLikeAnAbstractOne) {
  const std::filesystem::path folder = std::filesystem::path(SERVICE_TEST_OUTPUT_DIR) / "notify-path";
  std::filesystem::create_directories(folder);
  const std::string path = (folder / ("notify-" + std::to_string(getpid()))).string();
  unlink(path.c_str());
  const int fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::memcpy(address.sun_path, path.c_str(), path.size() + 1);
  ASSERT_EQ(bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0) << std::strerror(errno);
  ServiceNotifier::Config config;
  config.socket = path;
  ServiceNotifier notifier(config);
  notifier.frame_presented(Nanos{0});
  char buffer[64];
  const ssize_t got = recv(fd, buffer, sizeof buffer, MSG_DONTWAIT);
  EXPECT_EQ(std::string(buffer, static_cast<size_t>(std::max<ssize_t>(got, 0))), "READY=1");
  close(fd);
  unlink(path.c_str());
}

TEST(Notifier, ARelativeSocketPathIsAnErrorNamingTheVariable) {
  ServiceNotifier::Config config;
  config.socket = "run/notify";
  ServiceNotifier notifier(config);
  EXPECT_FALSE(notifier.enabled());
  EXPECT_EQ(notifier.error(),
            "NOTIFY_SOCKET='run/notify': expected an absolute path or '@' and an abstract name, shorter than 108 bytes; "
            "systemd is not told the player is ready");
}

// Environment variables for one test, restored after it.
class Environment {
 public:
  void set(const char* name, const std::string& value) {
    const char* old = std::getenv(name);
    saved_.push_back({name, old != nullptr, old != nullptr ? old : ""});
    setenv(name, value.c_str(), 1);
  }
  ~Environment() {
    for (auto it = saved_.rbegin(); it != saved_.rend(); ++it)
      if (it->had)
        setenv(it->name, it->value.c_str(), 1);
      else
        unsetenv(it->name);
  }

 private:
  struct Saved {
    const char* name;
    bool had;
    std::string value;
  };
  std::vector<Saved> saved_;
};

TEST(NotifierEnvironment, ReadsTheSocketAndTheWatchdogForThisProcess) {
  Environment environment;
  environment.set("NOTIFY_SOCKET", "@x");
  environment.set("WATCHDOG_USEC", "3000000");
  environment.set("WATCHDOG_PID", std::to_string(getpid()));
  const ServiceNotifier::Config config = ServiceNotifier::from_environment();
  EXPECT_EQ(config.socket, "@x");
  EXPECT_EQ(config.watchdog, Nanos{3s});
  EXPECT_EQ(config.problem, "");
}

TEST(NotifierEnvironment, AWatchdogForAnotherProcessIsNotOurs) {
  Environment environment;
  environment.set("WATCHDOG_USEC", "3000000");
  environment.set("WATCHDOG_PID", std::to_string(getpid() + 1));
  const ServiceNotifier::Config config = ServiceNotifier::from_environment();
  EXPECT_EQ(config.watchdog, Nanos{0});
  EXPECT_EQ(config.problem, "");
}

TEST(NotifierEnvironment, AMalformedIntervalIsAProblemNamingTheVariable) {
  Environment environment;
  environment.set("WATCHDOG_USEC", "ten seconds");
  environment.set("WATCHDOG_PID", std::to_string(getpid()));
  const ServiceNotifier::Config config = ServiceNotifier::from_environment();
  EXPECT_EQ(config.watchdog, Nanos{0});
  EXPECT_EQ(config.problem.rfind("WATCHDOG_USEC='ten seconds', WATCHDOG_PID='", 0), 0u) << config.problem;
  EXPECT_NE(config.problem.find("expected microseconds above 0"), std::string::npos) << config.problem;
}

// `player play` as systemd runs it: the messages a manager would get, in order.
struct PlayRun {
  int status = -1;
  std::vector<std::string> lines;  // every datagram's lines, in order
  std::string output;              // the player's stdout and stderr
};

PlayRun run_player(const std::vector<std::string>& arguments, bool watchdog_for_player, const std::string& log_name) {
  Listener listener;
  PlayRun run;
  const std::string log = (std::filesystem::path(SERVICE_TEST_OUTPUT_DIR) / log_name).string();
  std::vector<std::string> argv_text{PLAYER_BINARY, "play"};
  argv_text.insert(argv_text.end(), arguments.begin(), arguments.end());
  const pid_t child = fork();
  if (child == 0) {
    std::vector<char*> argv;
    for (std::string& argument : argv_text) argv.push_back(argument.data());
    argv.push_back(nullptr);
    const int out = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(out, 1);
    dup2(out, 2);
    setenv("NOTIFY_SOCKET", listener.name().c_str(), 1);
    // 200 ms: a ping at least every 100 ms of the run, several over the frames paced below.
    setenv("WATCHDOG_USEC", "200000", 1);
    setenv("WATCHDOG_PID", std::to_string(watchdog_for_player ? getpid() : getppid()).c_str(), 1);
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  for (;;) {
    pollfd wake{listener.fd(), POLLIN, 0};
    poll(&wake, 1, 100);
    for (const std::string& message : listener.take()) {
      std::istringstream lines(message);
      for (std::string line; std::getline(lines, line);) run.lines.push_back(line);
    }
    const pid_t done = waitpid(child, &status, WNOHANG);
    if (done == child) break;
  }
  for (const std::string& message : listener.take()) {
    std::istringstream lines(message);
    for (std::string line; std::getline(lines, line);) run.lines.push_back(line);
  }
  run.status = status;
  std::ifstream in(log);
  run.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return run;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

TEST(ServicePlay, ReadyAfterTheFirstFrameThenWatchdogStatusAndStopping) {
  // 30 frames paced at 30 fps take at least 29/30 s of real time: with pings due every 100 ms
  // that is several, whatever the machine's speed (a slower machine only sends more).
  const PlayRun run =
      run_player({"--platform", "egl", "--size", "64x48", "--frames", "30", "--fps", "30"}, true, "service-play.log");
  ASSERT_TRUE(WIFEXITED(run.status) && WEXITSTATUS(run.status) == 0) << run.output;
  const std::vector<std::string>& lines = run.lines;
  SCOPED_TRACE("messages:\n" + joined(lines) + "player output:\n" + run.output);

  const auto ready = std::find(lines.begin(), lines.end(), "READY=1");
  ASSERT_NE(ready, lines.end());
  EXPECT_EQ(std::count(lines.begin(), lines.end(), "READY=1"), 1);
  const auto first_ping = std::find(lines.begin(), lines.end(), "WATCHDOG=1");
  EXPECT_LT(ready, first_ping);
  EXPECT_GE(std::count(lines.begin(), lines.end(), "WATCHDOG=1"), 3);

  // The states as the status file names them, each a change from the one before; starting first.
  std::vector<std::string> states;
  for (const std::string& line : lines)
    if (line.rfind("STATUS=", 0) == 0) states.push_back(line.substr(7));
  ASSERT_GE(states.size(), 3u);
  EXPECT_EQ(states.front(), "starting");
  for (size_t i = 0; i < states.size(); ++i) {
    EXPECT_TRUE(states[i] == "starting" || states[i] == "loading" || states[i] == "playing" || states[i] == "stopping")
        << states[i];
    if (i > 0) {
      EXPECT_NE(states[i], states[i - 1]);
    }
  }
  // The first frame presented shows the item, loading or playing: not the state before the loop.
  const auto last_status = std::find_if(std::make_reverse_iterator(ready), lines.rend(),
                                        [](const std::string& line) { return line.rfind("STATUS=", 0) == 0; });
  ASSERT_NE(last_status, lines.rend());
  EXPECT_TRUE(*last_status == "STATUS=loading" || *last_status == "STATUS=playing") << *last_status;
  EXPECT_NE(std::find(lines.begin(), lines.end(), "STATUS=playing"), lines.end());
  // Stopping last.
  ASSERT_GE(lines.size(), 2u);
  EXPECT_EQ(lines[lines.size() - 2], "STOPPING=1");
  EXPECT_EQ(lines.back(), "STATUS=stopping");
  EXPECT_NE(run.output.find("played 30 frames, 0 error(s)"), std::string::npos);
}

TEST(ServicePlay, AWatchdogMeantForAnotherProcessIsNotFed) {
  const PlayRun run =
      run_player({"--platform", "egl", "--size", "64x48", "--frames", "10", "--fps", "30"}, false, "service-pid.log");
  ASSERT_TRUE(WIFEXITED(run.status) && WEXITSTATUS(run.status) == 0) << run.output;
  SCOPED_TRACE("messages:\n" + joined(run.lines));
  ASSERT_FALSE(run.lines.empty());
  EXPECT_EQ(std::count(run.lines.begin(), run.lines.end(), "READY=1"), 1);
  EXPECT_EQ(std::count(run.lines.begin(), run.lines.end(), "WATCHDOG=1"), 0);
  EXPECT_EQ(run.lines.back(), "STATUS=stopping");
}

}  // namespace
