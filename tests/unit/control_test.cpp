// The control socket: its commands as text, and the player's end against real sockets (a client
// connects, sends, and reads the reply, as `player ctl` does).
#include "control/control.h"
#include "control/server.h"

#include <gtest/gtest.h>

#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using control::Command;
using control::Verb;

namespace {

TEST(ControlCommand, EachVerbReadsAndWritesBack) {
  for (const char* text : {"next", "previous", "pause", "resume", "check", "reload", "restart", "item 0", "item 12", "screenshot",
                           "display on", "display off"}) {
    Command command;
    std::string error;
    ASSERT_TRUE(control::parse_command(text, command, error)) << text << ": " << error;
    EXPECT_EQ(control::format_command(command), text);
  }
  Command command;
  std::string error;
  ASSERT_TRUE(control::parse_command("item 3\n", command, error)) << "one trailing newline, as echo sends";
  EXPECT_EQ(command.verb, Verb::item);
  EXPECT_EQ(command.item, 3);
}

TEST(ControlCommand, AMalformedCommandSaysWhatWasExpected) {
  const struct {
    std::string text, error;
  } cases[] = {
      {"",
       "unknown command '' (expected one of next, previous, pause, resume, check, reload, restart, item N, screenshot, display "
       "on|off)"},
      {"jump",
       "unknown command 'jump' (expected one of next, previous, pause, resume, check, reload, restart, item N, screenshot, "
       "display on|off)"},
      {"Next",
       "unknown command 'Next' (expected one of next, previous, pause, resume, check, reload, restart, item N, screenshot, "
       "display on|off)"},
      {"next ", "next: takes no argument, got ''"},
      {"pause now", "pause: takes no argument, got 'now'"},
      {"item", "item: expected an item number from 0 (as the status file counts), got ''"},
      {"item -1", "item: expected an item number from 0 (as the status file counts), got '-1'"},
      {"item 2x", "item: expected an item number from 0 (as the status file counts), got '2x'"},
      {"item 1000001", "item: expected an item number from 0 (as the status file counts), got '1000001'"},
      {"next\n\n",
       "unknown command 'next\\x0a' (expected one of next, previous, pause, resume, check, reload, restart, item N, screenshot, "
       "display on|off)"},
      {"a\x01'b\\",
       "unknown command 'a\\x01\\x27b\\x5c' (expected one of next, previous, pause, resume, check, reload, restart, item N, "
       "screenshot, display on|off)"},
      {"display", "display: expected on or off, got ''"},
      {"display dim", "display: expected on or off, got 'dim'"},
      {"display on off", "display: expected on or off, got 'on off'"},
  };
  for (const auto& c : cases) {
    Command command;
    std::string error;
    EXPECT_FALSE(control::parse_command(c.text, command, error)) << c.text;
    EXPECT_EQ(error, c.error);
  }
  Command command;
  std::string error;
  EXPECT_TRUE(
      control::parse_command(std::string(control::kMaxMessage, 'x').replace(0, 5, "next\n").substr(0, 5), command, error));
  EXPECT_FALSE(control::parse_command("next" + std::string(control::kMaxMessage - 3, ' '), command, error));
  EXPECT_EQ(error, "a command of 257 bytes, more than 256");
}

TEST(ControlCommand, LongTextIsShownCut) {
  Command command;
  std::string error;
  EXPECT_FALSE(control::parse_command(std::string(100, 'z'), command, error));
  EXPECT_EQ(
      error,
      "unknown command '" + std::string(64, 'z') +
          "'... (expected one of next, previous, pause, resume, check, reload, restart, item N, screenshot, display on|off)");
}

TEST(ControlCommand, AReplyIsOkOnlyWhenItSaysSo) {
  EXPECT_TRUE(control::reply_ok("ok"));
  EXPECT_TRUE(control::reply_ok("ok: next"));
  EXPECT_FALSE(control::reply_ok("okay"));
  EXPECT_FALSE(control::reply_ok("error: ok"));
  EXPECT_FALSE(control::reply_ok(""));
}

// A folder of its own per test, removed after.
class ControlServer : public testing::Test {
 protected:
  void SetUp() override {
    // Under /tmp rather than the test's TempDir: a socket's path must fit sun_path's 107 bytes.
    char name[] = "/tmp/control-test-XXXXXX";
    ASSERT_NE(mkdtemp(name), nullptr);
    dir_ = name;
    path_ = dir_ + "/control";
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A client's connection with its message sent, not yet answered.
  static int connect_and_send(const std::string& path, std::string_view message) {
    const int fd = socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::memcpy(address.sun_path, path.data(), path.size());
    EXPECT_EQ(connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0) << std::strerror(errno);
    if (!message.empty()) {
      EXPECT_EQ(send(fd, message.data(), message.size(), 0), static_cast<ssize_t>(message.size()));
    }
    return fd;
  }
  static std::string reply_of(int fd) {
    pollfd wait{fd, POLLIN, 0};
    char buffer[1024];
    const ssize_t n = poll(&wait, 1, 5000) == 1 ? recv(fd, buffer, sizeof buffer, 0) : -1;
    close(fd);
    return n > 0 ? std::string(buffer, static_cast<std::size_t>(n)) : std::string("(no reply)");
  }

  // Serves once, recording what reaches the handler and what is logged.
  void serve(control::Server& server, double now = 0.0) {
    server.serve(
        now,
        [&](const Command& c, const control::Server::Peer& peer) {
          handled_.push_back(control::format_command(c));
          peers_.push_back(peer);
          return "ok: " + control::format_command(c);
        },
        [&](const std::string& line) { log_.push_back(line); });
  }

  std::string dir_, path_;
  std::vector<std::string> handled_, log_;
  std::vector<control::Server::Peer> peers_;
};

TEST_F(ControlServer, ACommandIsDoneAndAnsweredWithThePeerNamed) {
  control::Server server;
  std::string error;
  ASSERT_TRUE(server.open(path_, {}, error)) << error;
  struct stat st {};
  ASSERT_EQ(lstat(path_.c_str(), &st), 0);
  EXPECT_TRUE(S_ISSOCK(st.st_mode));
  EXPECT_EQ(st.st_mode & 0777, 0660u) << "only the owner and the control group may connect";
  const int a = connect_and_send(path_, "item 2");
  const int b = connect_and_send(path_, "pause\n");
  serve(server);
  EXPECT_EQ(reply_of(a), "ok: item 2");
  EXPECT_EQ(reply_of(b), "ok: pause");
  EXPECT_EQ(handled_, (std::vector<std::string>{"item 2", "pause"}));
  ASSERT_EQ(peers_.size(), 2u);
  EXPECT_EQ(peers_[0].uid, geteuid());
  EXPECT_EQ(peers_[0].pid, getpid());
  EXPECT_TRUE(log_.empty());
}

TEST_F(ControlServer, TheClientSendsAndReadsTheReply) {
  control::Server server;
  std::string error;
  ASSERT_TRUE(server.open(path_, {}, error)) << error;
  // The client waits for its reply while the server serves, as a player's loop does beside it.
  const pid_t child = fork();
  if (child == 0) {
    std::string reply, why;
    const bool sent = control::send_command(path_, "restart", 5000, reply, why);
    _exit(sent && reply == "ok: restart" ? 0 : 1);
  }
  for (int i = 0; i < 500 && handled_.empty(); ++i) {
    std::vector<int> fds;
    server.fds(fds);
    std::vector<pollfd> wait;
    for (int fd : fds) wait.push_back({fd, POLLIN, 0});
    poll(wait.data(), wait.size(), 10);
    serve(server);
  }
  int status = -1;
  waitpid(child, &status, 0);
  EXPECT_EQ(handled_, std::vector<std::string>{"restart"});
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

// A screenshot waits for the next frame: its reply is put off, then given, or an error after a while.
TEST_F(ControlServer, AReplyPutOffIsGivenLaterOrTimesOut) {
  control::Server server;
  std::string error;
  control::Server::Limits limits;
  limits.reply_wait_s = 10.0;
  ASSERT_TRUE(server.open(path_, limits, error)) << error;
  const auto later = [&](double now) {
    server.serve(
        now, [&](const Command& c, const control::Server::Peer&) { return c.verb == Verb::screenshot ? std::string() : "ok"; },
        [&](const std::string& line) { log_.push_back(line); });
  };
  int first = connect_and_send(path_, "screenshot");
  const int other = connect_and_send(path_, "next");
  later(0.0);
  EXPECT_EQ(reply_of(other), "ok") << "the other commands are answered at once";
  EXPECT_TRUE(server.answers_pending());
  std::vector<int> fds;
  server.fds(fds);
  EXPECT_EQ(fds.size(), 1u) << "a connection waiting for its reply is not polled";
  pollfd wait{first, POLLIN, 0};
  EXPECT_EQ(poll(&wait, 1, 0), 0) << "no reply before the frame";
  server.answer_later("ok: frame 7 written to /x/screenshot.png");
  EXPECT_EQ(reply_of(first), "ok: frame 7 written to /x/screenshot.png");
  EXPECT_FALSE(server.answers_pending());

  first = connect_and_send(path_, "screenshot");
  later(20.0);
  later(29.0);
  wait = {first, POLLIN, 0};
  EXPECT_EQ(poll(&wait, 1, 0), 0) << "within the 10 s, still waiting";
  later(30.5);
  EXPECT_EQ(reply_of(first), "error: not done within 10 s (no frame was drawn)");
  ASSERT_EQ(log_.size(), 1u);
  EXPECT_NE(log_[0].find("was not done within 10 s"), std::string::npos) << log_[0];
}

TEST_F(ControlServer, MalformedAndOversizedCommandsAreRefusedAndLogged) {
  control::Server server;
  std::string error;
  ASSERT_TRUE(server.open(path_, {}, error)) << error;
  const int bad = connect_and_send(path_, "format c:");
  const int big = connect_and_send(path_, "next" + std::string(1000, ' '));
  serve(server);
  EXPECT_EQ(reply_of(bad),
            "error: unknown command 'format c:' (expected one of next, previous, pause, resume, check, reload, restart, "
            "item N, screenshot, display on|off)");
  EXPECT_EQ(reply_of(big), "error: a command of 1004 bytes, more than 256");
  EXPECT_TRUE(handled_.empty());
  ASSERT_EQ(log_.size(), 2u);
  EXPECT_NE(log_[0].find("control: refused a command from pid "), std::string::npos) << log_[0];
  EXPECT_NE(log_[1].find("more than 256"), std::string::npos) << log_[1];
}

TEST_F(ControlServer, ABurstPastTheRateIsRefusedThenTheRateRefills) {
  control::Server server;
  std::string error;
  control::Server::Limits limits;
  limits.burst = 3;
  limits.per_second = 1;
  ASSERT_TRUE(server.open(path_, limits, error)) << error;
  std::vector<int> clients;
  for (int i = 0; i < 5; ++i) clients.push_back(connect_and_send(path_, "next"));
  serve(server, 100.0);
  std::vector<std::string> replies;
  for (int fd : clients) replies.push_back(reply_of(fd));
  EXPECT_EQ(handled_.size(), 3u);
  for (int i = 3; i < 5; ++i)
    EXPECT_EQ(replies[static_cast<std::size_t>(i)],
              "error: too many commands (more than 3 at once, then 1 a second): this one was ignored");
  EXPECT_EQ(log_.size(), 2u);
  // A second later one more is taken, not two.
  clients = {connect_and_send(path_, "next"), connect_and_send(path_, "next")};
  serve(server, 101.0);
  EXPECT_EQ(reply_of(clients[0]), "ok: next");
  EXPECT_NE(reply_of(clients[1]).find("too many"), std::string::npos);
  EXPECT_EQ(handled_.size(), 4u);
}

TEST_F(ControlServer, AConnectionThatSendsNothingWaitsThenIsClosed) {
  control::Server server;
  std::string error;
  control::Server::Limits limits;
  limits.message_wait_s = 2.0;
  ASSERT_TRUE(server.open(path_, limits, error)) << error;
  const int silent = connect_and_send(path_, "");
  serve(server, 10.0);
  std::vector<int> fds;
  server.fds(fds);
  EXPECT_EQ(fds.size(), 2u) << "the listener and the connection waiting for its command";
  serve(server, 11.9);
  fds.clear();
  server.fds(fds);
  EXPECT_EQ(fds.size(), 2u);
  serve(server, 12.1);
  fds.clear();
  server.fds(fds);
  EXPECT_EQ(fds.size(), 1u);
  EXPECT_EQ(reply_of(silent), "error: no command within 2 s");
  ASSERT_EQ(log_.size(), 1u);
  EXPECT_NE(log_[0].find("sent no command"), std::string::npos);
}

TEST_F(ControlServer, MoreWaitingConnectionsThanTheLimitAreRefused) {
  control::Server server;
  std::string error;
  ASSERT_TRUE(server.open(path_, {}, error)) << error;
  // Accepted in two serves, so the backlog never holds more than it may.
  std::vector<int> silent;
  for (std::size_t i = 0; i < control::Server::kMaxWaiting; ++i) {
    silent.push_back(connect_and_send(path_, ""));
    serve(server, 0.0);
  }
  const int extra = connect_and_send(path_, "next");
  serve(server, 0.0);
  EXPECT_EQ(reply_of(extra), "error: busy: 8 connections wait for their command already");
  EXPECT_TRUE(handled_.empty());
  for (int fd : silent) close(fd);
}

TEST_F(ControlServer, ASocketLeftByAPlayerThatIsGoneIsReplacedOneInUseIsNot) {
  {
    control::Server first;
    std::string error;
    ASSERT_TRUE(first.open(path_, {}, error)) << error;
    control::Server second;
    EXPECT_FALSE(second.open(path_, {}, error));
    EXPECT_EQ(error, "control: another player listens on " + path_ + " (give this one its own with --control PATH)");
    // The first one still serves.
    const int fd = connect_and_send(path_, "next");
    serve(first);
    EXPECT_EQ(reply_of(fd), "ok: next");
  }
  EXPECT_FALSE(fs::exists(path_)) << "a player removes its socket when it stops";
  // A socket file nobody listens on (a player killed outright) is taken over.
  {
    const int stale = socket(AF_UNIX, SOCK_SEQPACKET, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::memcpy(address.sun_path, path_.data(), path_.size());
    ASSERT_EQ(bind(stale, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
    close(stale);
  }
  control::Server server;
  std::string error;
  ASSERT_TRUE(server.open(path_, {}, error)) << error;
  const int fd = connect_and_send(path_, "check");
  serve(server);
  EXPECT_EQ(reply_of(fd), "ok: check");
}

TEST_F(ControlServer, AFileThatIsNotASocketIsLeftAsItIs) {
  std::ofstream(path_) << "notes";
  control::Server server;
  std::string error;
  EXPECT_FALSE(server.open(path_, {}, error));
  EXPECT_EQ(error, "control: " + path_ + " exists and is not a socket; it is left as it is");
  std::ifstream in(path_);
  std::string text;
  in >> text;
  EXPECT_EQ(text, "notes");
  EXPECT_FALSE(server.open(dir_ + "/" + std::string(120, 'p'), {}, error));
  EXPECT_NE(error.find("is empty or longer than 107 bytes"), std::string::npos) << error;
}

TEST_F(ControlServer, NoPlayerListeningIsSaidPlainly) {
  std::string reply, error;
  EXPECT_FALSE(control::send_command(path_, "next", 1000, reply, error));
  EXPECT_EQ(error, path_ +
                       ": No such file or directory (no player listens there: is it running, with --control or the "
                       "board's control = \"" +
                       path_ + "\"?)");
}

// Another user, neither root nor in ssao-player-control, is refused before its command is read.
TEST_F(ControlServer, AnotherUserIsRefused) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root, to connect as another user (nobody); CI runs the suite as root";
  control::Server server;
  std::string error;
  ASSERT_TRUE(server.open(path_, {}, error)) << error;
  chmod(dir_.c_str(), 0755);
  chmod(path_.c_str(), 0666);  // the permission check aside, so the peer check is what refuses
  int pipe_fds[2];
  ASSERT_EQ(pipe(pipe_fds), 0);
  const pid_t child = fork();
  if (child == 0) {
    close(pipe_fds[0]);
    if (setgid(65534) != 0 || setuid(65534) != 0) _exit(3);
    const int fd = connect_and_send(path_, "next");
    const std::string reply = reply_of(fd);
    write(pipe_fds[1], reply.data(), reply.size());
    _exit(0);
  }
  close(pipe_fds[1]);
  for (int i = 0; i < 500; ++i) {
    serve(server);
    pollfd wait{pipe_fds[0], POLLIN, 0};
    if (poll(&wait, 1, 10) == 1) break;
  }
  char buffer[512];
  const ssize_t n = read(pipe_fds[0], buffer, sizeof buffer);
  close(pipe_fds[0]);
  int status = -1;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_EQ(std::string(buffer, n > 0 ? static_cast<std::size_t>(n) : 0).substr(0, 20), "error: not allowed: ");
  EXPECT_TRUE(handled_.empty());
  ASSERT_EQ(log_.size(), 1u);
  EXPECT_NE(log_[0].find("uid 65534 is not root, not the player's user and not in the group ssao-player-control"),
            std::string::npos)
      << log_[0];
}

}  // namespace
